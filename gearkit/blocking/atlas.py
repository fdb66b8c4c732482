"""An atlas of blocking contours: one contour per (z1, z2) cell, computed in parallel.

Printed atlases cover a grid of tooth numbers for one tool; :func:`blocking_atlas` computes the
same grid for any pair template (tool, pressure angle, helix angle, external or internal) on a
pool of local processes (:class:`multiprocessing.pool.Pool`: Ctrl-C or an error stops it at once,
no cell runs on). Each cell is the contour
:func:`~gearkit.blocking.blocking_contour` returns for the template with ``teeth1 = z1``,
``teeth2 = z2``; a worker sends it back without its evaluation caches (they are rebuilt on demand).

:func:`write_atlas` writes an atlas as a dataset on disk: one JSON file per cell (its contour and
recommendation, :func:`atlas_cell`), ``index.json`` (one summary row per cell) and a contact sheet
``atlas.png``. It is resumable (cells already on disk are skipped) and deterministic (the same
input gives byte-identical files). The cells run on a local process pool or, given the address
of a scheduler, on a Dask cluster (``dask.distributed``, imported only then); both run the same
:func:`atlas_cell`.

>>> atlas = blocking_atlas([13], [16], workers=1, lines=["undercut.1"])
>>> sorted(atlas.cells), atlas.errors
([(13, 16)], {})
"""
from __future__ import annotations

import json
import os
import signal
import time
from dataclasses import dataclass, replace
from pathlib import Path

from gearkit.errors import GearkitError, SpecError, require
from gearkit.pair.spec import PairSpec
from gearkit.progress import Progress

__all__ = ["BlockingAtlas", "blocking_atlas", "atlas_cell", "write_atlas", "cell_name"]

FORMAT = 1  #: version of the dataset's layout (index.json says it)


@dataclass(frozen=True)
class BlockingAtlas:
    """Result of :func:`blocking_atlas`.

    Attributes
    ----------
    cells : dict
        ``(z1, z2) -> BlockingContour`` for every cell whose pair exists.
    errors : dict
        ``(z1, z2) -> str``: why a cell has no contour (e.g. an internal pair with z2 <= z1).
    seconds : float
        Wall time of the whole atlas.
    workers : int
        Processes used (1: computed in this process).
    """

    cells: dict
    errors: dict
    seconds: float
    workers: int

    def __getitem__(self, key):
        return self.cells[key]

    def to_dict(self) -> dict:
        """JSON-ready: one entry per cell (its :meth:`~gearkit.blocking.BlockingContour.to_dict`) or error."""
        return {"seconds": self.seconds, "workers": self.workers,
                "cells": [{"z1": z1, "z2": z2, "contour": c.to_dict()} for (z1, z2), c in sorted(self.cells.items())],
                "errors": [{"z1": z1, "z2": z2, "error": e} for (z1, z2), e in sorted(self.errors.items())]}


def _cell(template: PairSpec, z1: int, z2: int, options: dict):
    """One cell (runs in a worker): ``(z1, z2, contour or None, error or None)``."""
    from gearkit.blocking.contour import blocking_contour

    try:
        spec = replace(template, teeth1=int(z1), teeth2=int(z2))
        return z1, z2, blocking_contour(spec, **options), None
    except GearkitError as exc:
        return z1, z2, None, str(exc)


def blocking_atlas(z1s, z2s, template: PairSpec | None = None, *, workers: int | None = 2,
                   **options) -> BlockingAtlas:
    """Blocking contours of every pair ``(z1, z2)`` of ``z1s`` x ``z2s``, computed in ``workers`` processes.

    Parameters
    ----------
    z1s, z2s : iterable of int
        Pinion and wheel (ring) tooth numbers.
    template : PairSpec or None
        Everything but the tooth numbers (tools, module, pressure and helix angle, kind); its teeth
        and shifts are ignored. None: external spur pair, module 1, the 20 degree basic rack.
    workers : int or None
        Worker processes (default 2; None: one per CPU; 1: no pool, computed in this process).
    **options
        Keyword arguments of :func:`~gearkit.blocking.blocking_contour` (``window``, ``xtol``,
        ``points``, ``lines``, ``tip_levels`` ...), the same for every cell.

    Returns
    -------
    BlockingAtlas
        A cell whose pair does not exist (e.g. a ring with too few teeth) is listed in ``errors``
        with the reason, not left out silently.
    """
    t0 = time.perf_counter()
    z1s = [int(z) for z in z1s]
    z2s = [int(z) for z in z2s]
    require(z1s and z2s, "z1s", "give at least one tooth number for each gear")
    template = PairSpec(20, 40, 1.0) if template is None else template
    require(isinstance(template, PairSpec), "template", "must be a PairSpec")
    n = (os.cpu_count() or 1) if workers is None else workers
    require(isinstance(n, int) and n >= 1, "workers", f"{workers!r} must be a positive integer or None")
    _check_options(options)
    jobs = [(z1, z2) for z1 in z1s for z2 in z2s]
    results = {}
    with Progress("atlas", len(jobs), unit="cells") as bar:
        def sink(result):
            results[result[:2]] = result
            bar.step()
        _run_local(_cell, [(template, z1, z2, options) for z1, z2 in jobs], n, sink)
    cells, errors = {}, {}
    for z1, z2, contour, err in (results[job] for job in jobs):
        if contour is None:
            errors[(z1, z2)] = err
        else:
            cells[(z1, z2)] = contour
    if not cells and errors:
        raise SpecError("z1s", "no cell of the atlas is a valid pair: " + next(iter(errors.values())))
    return BlockingAtlas(cells, errors, time.perf_counter() - t0, n)


def cell_name(z1: int, z2: int) -> str:
    """File name of a cell in the dataset: ``z1-013_z2-016.json``."""
    return f"z1-{int(z1):03d}_z2-{int(z2):03d}.json"


def atlas_cell(template: PairSpec, z1: int, z2: int, options: dict, criterion: str = "balanced") -> dict:
    """One cell of a dataset atlas (runs in a worker, local or remote): a JSON-ready record with the
    contour (no timing: the same on every run), its recommendation, or the reason it has none."""
    from gearkit.blocking.contour import blocking_contour

    out = {"z1": int(z1), "z2": int(z2)}
    try:
        spec = replace(template, teeth1=int(z1), teeth2=int(z2))
        contour = blocking_contour(spec, **options)
        rec = contour.recommend(criterion)
        out["contour"] = contour.to_dict(rec, timing=False)
    except GearkitError as exc:
        out["error"] = str(exc)
    return out


def _summary(record: dict, file: str) -> dict:
    row = {"z1": record["z1"], "z2": record["z2"], "file": file}
    if "error" in record:
        row.update(status="error", error=record["error"])
        return row
    c = record["contour"]
    rec = c.get("recommendation") or {}
    row.update(status="ok", empty=c["region"]["empty"], area=c["region"]["area"],
               x1=rec.get("x1"), x2=rec.get("x2"), passes=rec.get("passes"))
    return row


def _dump(obj) -> str:
    return json.dumps(obj, sort_keys=True, allow_nan=False, separators=(",", ":"))


def _worker_start() -> None:
    """Start of a local worker process: Ctrl-C and termination are the parent's to handle (it stops
    the pool: a worker ignores SIGINT and ends quietly on SIGTERM), and a progress bar the parent
    had open when it forked is the parent's (the worker draws none)."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    Progress.forget()


def _call(job):
    fn, args = job
    return fn(*args)


def _run_local(fn, jobs, workers: int, sink) -> None:
    """``sink(fn(*args))`` for every ``args`` of ``jobs``: in this process when ``workers`` is 1 or
    there is one job, else on a pool of ``workers`` local processes, each result as it comes (in any
    order). Ctrl-C, termination, an error in a job or in ``sink`` stops the pool at once (its workers
    are terminated: no job runs on after the exception) and is raised here.

    >>> out = []
    >>> _run_local(pow, [(2, 3), (3, 2)], 2, out.append)
    >>> sorted(out)
    [8, 9]
    """
    if workers == 1 or len(jobs) <= 1:
        for args in jobs:
            sink(fn(*args))
        return
    import multiprocessing

    pool = multiprocessing.Pool(min(workers, len(jobs)), initializer=_worker_start)
    try:
        for result in pool.imap_unordered(_call, [(fn, args) for args in jobs]):
            sink(result)
        pool.close()
    except BaseException:
        pool.terminate()
        raise
    finally:
        pool.join()


def _dask_client(scheduler):
    try:
        from distributed import Client
    except ImportError:
        raise SpecError("scheduler", "the distributed path needs dask.distributed: pip install 'gearkit[dask]'") from None
    try:
        return Client(scheduler, timeout=DASK_TIMEOUT)
    except (OSError, TimeoutError) as exc:
        raise SpecError("scheduler", f"no Dask scheduler answers at {scheduler!r} ({exc})") from None


def _run_dask(jobs, template, options, criterion, client, sink):
    from distributed import as_completed as dask_completed

    futures = client.map(atlas_cell, [template] * len(jobs), [z for z, _ in jobs], [z for _, z in jobs],
                         [options] * len(jobs), [criterion] * len(jobs), pure=False)
    try:
        for fut in dask_completed(futures):
            sink(fut.result())
    finally:
        client.cancel(futures)  # an interrupt leaves nothing running on the cluster


DASK_TIMEOUT = 10  #: seconds to reach the scheduler


def write_atlas(z1s, z2s, out_dir, template: PairSpec | None = None, *, workers: int = 2,
                scheduler: str | None = None, criterion: str = "balanced", progress=None, **options) -> dict:
    """Write the atlas of ``z1s`` x ``z2s`` to ``out_dir`` (see the module notes); returns the index.

    Parameters
    ----------
    z1s, z2s : iterable of int
    out_dir : str or Path
        Created if missing. Cells already there (from an interrupted run with the same template and
        options) are kept; ``index.json`` and ``atlas.png`` are written last.
    template : PairSpec or None
        As for :func:`blocking_atlas`.
    workers : int
        Local worker processes (1: this process). Ignored with ``scheduler``.
    scheduler : str or None
        Address of a Dask scheduler (``tcp://host:8786``): the cells run on its workers.
    criterion : str
        Recommendation criterion of every cell.
    progress : bool, file or None
        A progress bar (:class:`gearkit.progress.Progress`) on stderr (True) or the given stream;
        False: none; None: as the command line says (``Progress.mode``).
    **options
        Keyword arguments of :func:`~gearkit.blocking.blocking_contour` (``tol``, ``window`` ...).
    """
    z1s = sorted({int(z) for z in z1s})
    z2s = sorted({int(z) for z in z2s})
    require(z1s and z2s, "z1s", "give at least one tooth number for each gear")
    template = PairSpec(20, 40, 1.0) if template is None else template
    require(isinstance(template, PairSpec), "template", "must be a PairSpec")
    require(isinstance(workers, int) and workers >= 1, "workers", f"{workers!r} must be a positive integer")
    require(criterion in ("balanced", "strength"), "criterion", f"{criterion!r} is not one of balanced, strength")
    _check_options(options)
    client = _dask_client(scheduler) if scheduler else None  # before anything is written
    try:
        return _write(z1s, z2s, Path(out_dir), template, workers, client, criterion, progress, options)
    finally:
        if client is not None:
            client.close()


def _check_options(options) -> None:
    """The contour options every cell shares, checked once before any work or file (bad input is
    one error, not a dataset of failed cells)."""
    from gearkit.blocking.contour import check_options

    check_options(**{k: options[k] for k in ("tol", "points", "window") if k in options})


def _write(z1s, z2s, out, template, workers, client, criterion, progress, options) -> dict:
    from gearkit.export import atomic_write

    cells_dir = out / "cells"
    try:
        cells_dir.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise SpecError("output", f"cannot create {str(cells_dir)!r}: {exc.strerror}") from None
    head = {"format": FORMAT, "template": _template_dict(template), "criterion": criterion,
            "options": {k: (list(v) if isinstance(v, tuple) else v) for k, v in sorted(options.items())}}
    index_path = out / "index.json"
    if (out / "atlas.json").exists():
        try:
            old = json.loads((out / "atlas.json").read_text())
        except (OSError, ValueError):
            old = None
        if old is not None and old != json.loads(_dump(head)):
            raise SpecError("output", f"{str(out)!r} holds an atlas of another template or options; "
                            "give a new directory")
    atomic_write(out / "atlas.json", lambda tmp: Path(tmp).write_text(_dump(head)))
    jobs = [(z1, z2) for z1 in z1s for z2 in z2s if not (cells_dir / cell_name(z1, z2)).exists()]
    enabled = None if progress is None else bool(progress)
    stream = progress if progress not in (None, True, False) else None
    with Progress("atlas", len(jobs), unit="cells", enabled=enabled, stream=stream) as bar:
        def sink(record):
            name = cell_name(record["z1"], record["z2"])
            atomic_write(cells_dir / name, lambda tmp: Path(tmp).write_text(_dump(record)))
            bar.step()
        if jobs and client is not None:
            _run_dask(jobs, template, options, criterion, client, sink)
        elif jobs:
            _run_local(atlas_cell, [(template, z1, z2, options, criterion) for z1, z2 in jobs], workers, sink)
    rows = []
    records = []
    for z1 in z1s:
        for z2 in z2s:
            name = cell_name(z1, z2)
            record = json.loads((cells_dir / name).read_text())
            records.append(record)
            rows.append(_summary(record, f"cells/{name}"))
    index = dict(head, cells=rows)
    atomic_write(index_path, lambda tmp: Path(tmp).write_text(json.dumps(index, sort_keys=True, indent=1)))
    from gearkit.blocking.plot import contact_sheet
    contact_sheet(records, z1s, z2s, out / "atlas.png", template)
    return index


def _template_dict(t: PairSpec) -> dict:
    from dataclasses import asdict

    from gearkit.families.involute import tool_label

    # the tools as every output spells them, and every parameter (the template's identity on resume)
    params = [{k: v for k, v in asdict(tool).items() if k != "name"} for tool in t.tools]
    return {"kind": t.kind, "module": t.module, "pressure_angle_deg": t.alpha_n_deg,
            "helix_angle_deg": t.helix_angle_deg, "addendum": t.addendum, "tip_rule": t.tip_rule,
            "tools": [tool_label(tool) for tool in t.tools], "tool_parameters": params}
