"""Issue 19: atlases at scale -- ``gearkit atlas`` writes a queryable dataset (a file per cell, an
index, a contact sheet), resumable and deterministic, on a local process pool and on a Dask cluster
started here (the same cell function)."""
import json
import os
import re
import signal
import subprocess
import sys
import time

import numpy as np
import pytest

from gearkit.checks import check_pair
from gearkit.cli import main
from gearkit.pair import PairSpec

ARGS = ["atlas", "--z1", "12,20", "--z2", "30,40", "--tol", "1e-3"]


def _files(root):
    return {p.relative_to(root).as_posix(): p.read_bytes() for p in sorted(root.rglob("*")) if p.is_file()}


@pytest.fixture(scope="module")
def local(tmp_path_factory):
    out = tmp_path_factory.mktemp("atlas") / "a"
    assert main(ARGS + ["-o", str(out), "--workers", "2", "--no-progress"]) == 0
    return out


def test_dataset_is_queryable(local):
    index = json.loads((local / "index.json").read_text())
    assert [(c["z1"], c["z2"]) for c in index["cells"]] == [(12, 30), (12, 40), (20, 30), (20, 40)]
    assert not [p for p in local.rglob("*") if ".part" in p.name]
    assert (local / "atlas.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    row = next(c for c in index["cells"] if (c["z1"], c["z2"]) == (12, 40))
    cell = json.loads((local / row["file"]).read_text())
    assert cell["contour"]["pair"]["z1"] == 12 and not cell["contour"]["region"]["empty"]
    for row in index["cells"]:  # every cell's recommendation is a pair check_pair passes
        assert row["passes"] and check_pair(PairSpec(row["z1"], row["z2"], 1.0, row["x1"], row["x2"])).ok


def test_deterministic_and_resumable(local, tmp_path, capsys, monkeypatch):
    """One worker writes the same bytes as two; a run that lost a cell (interrupted) computes only it."""
    again = tmp_path / "b"
    assert main(ARGS + ["-o", str(again), "--workers", "1", "--no-progress"]) == 0
    assert _files(again) == _files(local)
    (again / "cells" / "z1-020_z2-030.json").unlink()
    (again / "index.json").unlink()
    capsys.readouterr()
    from gearkit.progress import Progress

    monkeypatch.setattr(Progress, "delay", 0.0)  # draw at once (a bar waits half a second of work)
    assert main(["--progress"] + ARGS + ["-o", str(again)]) == 0
    assert "1/1 cells" in capsys.readouterr().err  # the progress bar: one cell left to compute
    assert _files(again) == _files(local)


def test_on_a_dask_cluster_the_same_files(local, tmp_path):
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(n_workers=1, threads_per_worker=1, processes=False, protocol="tcp",
                                  host="127.0.0.1", dashboard_address=None) as cluster:
        out = tmp_path / "d"
        assert main(ARGS + ["-o", str(out), "--scheduler", cluster.scheduler_address, "--no-progress"]) == 0
    assert _files(out) == _files(local)


def test_bad_input_and_other_options(local, capsys):
    assert main(["atlas", "--z1", "10:5:0", "--z2", "30", "-o", str(local)]) == 2
    assert main(["atlas", "--z1", "12,20", "--z2", "2", "-o", str(local)]) == 2
    # the directory holds an atlas at another tolerance: refused, nothing overwritten
    before = _files(local)
    assert main(["atlas", "--z1", "12,20", "--z2", "30,40", "--tol", "1e-4", "-o", str(local)]) == 2
    assert "another template or options" in capsys.readouterr().err
    assert _files(local) == before


def test_internal_atlas_names_cells_that_are_no_pair(tmp_path):
    out = tmp_path / "ring"
    assert main(["atlas", "--z1", "20,50", "--z2", "49", "--internal", "--cutter-teeth", "20", "--tol", "1e-3",
                 "-o", str(out), "--no-progress", "--workers", "1"]) == 0
    rows = {(c["z1"], c["z2"]): c for c in json.loads((out / "index.json").read_text())["cells"]}
    assert rows[(50, 49)]["status"] == "error" and "teeth" in rows[(50, 49)]["error"]
    assert rows[(20, 49)]["status"] == "ok"



def test_contact_sheet_title_is_not_cut_off(local):
    """The 2 x 2 sheet is narrower than its title: the title is wrapped to the figure, so no ink
    touches the image's left or right edge (a cut-off title runs through both)."""
    from matplotlib.image import imread

    img = imread(local / "atlas.png")[..., :3]
    ink = img.min(axis=2) < 0.5  # dark pixels: text and outlines
    assert not ink[:, 0].any() and not ink[:, -1].any()
    assert ink[: img.shape[0] // 5].any()  # the title is there, at the top


def test_contact_sheet_of_one_row_is_cropped_to_its_drawing(tmp_path):
    """A 9 x 1 sheet (the README's ring atlas: z1 20..60 step 5 on z2 49) has no empty bands above and
    below its drawing (its 3.2-inch minimum height left 0.9 inch of white on each side), and its title
    is not cut: the first and last rows of ink lie within 0.15 inch of the image's edges."""
    from matplotlib.image import imread

    from gearkit.blocking.plot import contact_sheet

    z1s = list(range(20, 61, 5))
    records = [{"z1": z, "z2": 49, "error": "the ring needs more teeth than the pinion"} for z in z1s]
    contact_sheet(records, z1s, [49], tmp_path / "sheet.png", PairSpec(20, 49, 1.0))
    img = imread(tmp_path / "sheet.png")[..., :3]
    rows = np.flatnonzero((img.min(axis=2) < 0.5).any(axis=1))  # rows with dark ink: text, frame, crosses
    pad = 15  # pixels: 0.15 inch at the sheet's 100 dpi
    assert rows[0] <= pad and img.shape[0] - 1 - rows[-1] <= pad


def test_bad_contour_options_and_an_absent_scheduler_write_nothing(tmp_path, capsys, monkeypatch):
    """A tolerance out of range (or NaN) is one error before any work (it wrote a dataset of failed
    cells, or crashed on NaN), an unreachable scheduler too (it left the folder behind); an empty
    range says it is empty."""
    from gearkit.blocking import atlas

    monkeypatch.setattr(atlas, "DASK_TIMEOUT", 0.5)
    for extra, field in ((["--tol", "5"], "tol"), (["--tol", "nan"], "tol"),
                         (["--scheduler", "tcp://127.0.0.1:1"], "scheduler")):
        out = tmp_path / "a"
        assert main(ARGS + extra + ["-o", str(out), "--no-progress"]) == 2
        err = capsys.readouterr().err.strip().splitlines()
        assert len(err) == 1 and err[0].startswith(f"gearkit atlas: error: {field}:"), err
        assert not out.exists()
    assert main(["atlas", "--z1", "10:5:1", "--z2", "30", "-o", str(tmp_path / "a")]) == 2
    assert "'10:5:1' is empty" in capsys.readouterr().err
    assert main(["atlas", "--z1", "10:20:0", "--z2", "30", "-o", str(tmp_path / "a")]) == 2
    assert "the step must be a positive integer" in capsys.readouterr().err


#: ``gearkit`` with the atlas' cell function replaced: every cell but z1 = 12 runs ten minutes
SLOW_CELLS = """
import signal, sys, time
# Ctrl-C as a terminal delivers it: a test run started in the background inherits SIGINT ignored
signal.signal(signal.SIGINT, signal.default_int_handler)
import gearkit.blocking.atlas as atlas
real = atlas.atlas_cell
def cell(template, z1, z2, options, criterion="balanced"):
    if z1 != 12:
        time.sleep(600)
    return real(template, z1, z2, options, criterion)
atlas.atlas_cell = cell
from gearkit.cli import main
sys.exit(main(sys.argv[1:]))
"""


@pytest.mark.parametrize("group", [True, False], ids=["ctrl-c", "sigint-to-the-parent"])
def test_an_interrupt_stops_every_cell_and_the_run_resumes(tmp_path, group):
    """Ctrl-C (SIGINT to the process group) or SIGINT to the parent alone, once the first cell is on
    disk while the workers run ten-minute cells: exit 130 with one line saying what is kept, the
    workers stopped (the pool ran every queued cell on before exiting), no partial file, no index or
    sheet; the same command then computes only the missing cells."""
    out = tmp_path / "a"
    args = ["atlas", "--z1", "12,13,14,15", "--z2", "30", "--tol", "1e-3", "--workers", "2", "-o", str(out)]
    proc = subprocess.Popen([sys.executable, "-c", SLOW_CELLS, *args], stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True, start_new_session=True)
    first = out / "cells" / "z1-012_z2-030.json"
    try:
        for _ in range(2400):  # the first cell (its worker starts the slow ones next)
            if first.exists() or proc.poll() is not None:
                break
            time.sleep(0.05)
        assert first.exists()
        (os.killpg if group else os.kill)(proc.pid, signal.SIGINT)
        _, err = proc.communicate(timeout=60)  # not ten minutes: the cells running are stopped
    finally:
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait()
    assert proc.returncode == 130
    assert err.strip().splitlines() == [f"gearkit atlas: interrupted; 1 of 4 cells are in {out / 'cells'}/ "
                                        "(the same command resumes)"]
    assert sorted(p.relative_to(out).as_posix() for p in out.rglob("*")) == [
        "atlas.json", "cells", "cells/z1-012_z2-030.json"]
    kept = first.stat().st_mtime_ns
    assert main(args[:-4] + ["--workers", "1", "--no-progress", "-o", str(out)]) == 0
    assert first.stat().st_mtime_ns == kept
    assert len(json.loads((out / "index.json").read_text())["cells"]) == 4


def test_only_the_parent_draws_the_bar(tmp_path):
    """Workers forked while the bar is open draw none (each drew its stale copy, '0/4 cells', between
    the parent's): the counts on stderr only grow, and no cell's own bar shows."""
    script = ("import sys\nfrom gearkit.progress import Progress\nProgress.delay = 0.0\n"
              "from gearkit.cli import main\nsys.exit(main(sys.argv[1:]))")
    r = subprocess.run([sys.executable, "-c", script, "--progress", *ARGS, "--workers", "2",
                        "-o", str(tmp_path / "a")], capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stderr
    counts = [int(n) for n in re.findall(r"\] (\d+)/4 cells", r.stderr)]
    assert counts and counts == sorted(counts) and counts[-1] == 4, r.stderr
    assert "blocking [" not in r.stderr
