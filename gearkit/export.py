"""Reading design files and writing results to files: atomically, in the formats users load elsewhere.

:func:`read_toml` reads every TOML file gearkit accepts (designs, scenes, racks, cams): a missing,
unreadable, binary or non-UTF-8 file is one ``SpecError`` naming it.

Every writer goes through :func:`atomic_write`: the file is written to a temporary file in
the target directory and renamed over the target only when complete, so a failed export
never leaves a partial or corrupt file behind.

2D formats: SVG (a closed path, y up, viewBox in mm), DXF (a closed polyline in mm, R2010),
CSV (x,y per line, mm) and JSON (points and key values). Numbers in every JSON output (files and
``--json``) go through :func:`json_number`.
"""
from __future__ import annotations

import math
import os
from pathlib import Path

import numpy as np

from gearkit.errors import SpecError
from gearkit.progress import Progress

PROFILE_FORMATS = ("svg", "dxf", "csv", "json")


def text_number(v, spec: str = "g", infinite: str = "unbounded") -> str:
    """``v`` formatted by ``spec`` for a text report, the twin of :func:`json_number`: a zero prints
    without a sign (no ``-0.0000``, no ``-0``), an infinite value as the word ``infinite`` (say what it
    means: ``"none"`` for an absent pitch, ``"unbounded"`` by default), NaN as ``"undefined"`` and None
    as ``"-"``; words are right-aligned to the width of ``spec``.

    Examples
    --------
    >>> text_number(-1e-17, ".4f"), text_number(-0.0), text_number(-2.5, "8.3f"), text_number(1e-17, ".4f")
    ('0.0000', '0', '  -2.500', '0.0000')
    >>> text_number(float("inf"), "10.3f", "none"), text_number(float("nan")), text_number(None, "4g")
    ('      none', 'undefined', '   -')
    """
    import re

    if v is None or isinstance(v, float) and not math.isfinite(v):
        word = "-" if v is None else "undefined" if v != v else infinite if v > 0 else f"-{infinite}"
        width = re.match(r"[<>^]?\+?(\d*)", spec.lstrip("0") or "").group(1)
        return word.rjust(int(width)) if width else word
    text = format(v, spec)
    mantissa = text.split("e")[0].split("E")[0]
    if "-" in mantissa and not any(c in "123456789" for c in mantissa):  # a zero (or round-off of one)
        text = text.replace("-", " " if spec[:1].isdigit() else "", 1)
        text = text if spec[:1].isdigit() else text.lstrip()
    return text


def json_number(v):
    """``v`` as a JSON-safe number: non-finite values (unbounded quantities) become ``None``.

    Examples
    --------
    >>> json_number(1), json_number(float("inf")), json_number(None), json_number(True)
    (1.0, None, None, True)
    """
    if v is None:
        return None
    if isinstance(v, bool):
        return v
    v = float(v)
    return v if math.isfinite(v) else None


def read_toml(path, field: str = "design") -> dict:
    """The tables of a TOML file; any problem reading it is one :class:`SpecError` naming the file.

    Examples
    --------
    >>> read_toml("/nonexistent.toml")
    Traceback (most recent call last):
    ...
    gearkit.errors.SpecError: design: cannot read '/nonexistent.toml': No such file or directory
    """
    try:
        import tomllib as toml
    except ImportError:  # Python 3.10
        try:
            import tomli as toml
        except ImportError:
            raise SpecError(field, "reading TOML on Python 3.10 needs the 'tomli' package") from None
    try:
        with open(path, "rb") as fh:
            return toml.load(fh)
    except OSError as exc:
        raise SpecError(field, f"cannot read {str(path)!r}: {exc.strerror or exc}") from None
    except UnicodeDecodeError:
        raise SpecError(field, f"{str(path)!r} is not a TOML text file (not UTF-8)") from None
    except toml.TOMLDecodeError as exc:
        raise SpecError(field, f"{str(path)!r} is not valid TOML: {exc}") from None


def check_output_path(path, field: str = "-o") -> Path:
    """Raise ``SpecError`` unless a file can be written at ``path``: checked before any work.

    The path must not be a directory, and its folder must exist and be writable.

    Examples
    --------
    >>> check_output_path(".")
    Traceback (most recent call last):
    ...
    gearkit.errors.SpecError: -o: '.' is a directory; give a file name
    >>> check_output_path("/nonexistent-folder/x.svg")
    Traceback (most recent call last):
    ...
    gearkit.errors.SpecError: -o: directory '/nonexistent-folder' does not exist
    """
    target = Path(path)
    if str(path) == "" or target.is_dir():
        raise SpecError(field, f"{str(path)!r} is a directory; give a file name")
    directory = target.parent if str(target.parent) else Path(".")
    if not directory.is_dir():
        what = "is not a directory" if directory.exists() else "does not exist"
        raise SpecError(field, f"directory {str(directory)!r} {what}")
    _require_writable(directory, field)
    return target


def _require_writable(directory, field: str) -> None:
    """Raise ``SpecError`` unless a file can be created in ``directory``: a real probe (a private
    empty file, removed at once), since permission bits do not stop root and say nothing of a
    read-only or pseudo file system."""
    if not os.access(directory, os.W_OK | os.X_OK):
        raise SpecError(field, f"directory {str(directory)!r} is not writable")
    probe = os.path.join(directory, f".gearkit-probe-{os.urandom(8).hex()}.part")  # a name no one else holds
    try:
        os.close(os.open(probe, os.O_WRONLY | os.O_CREAT | os.O_EXCL | getattr(os, "O_NOFOLLOW", 0), 0o600))
    except OSError as exc:
        raise SpecError(field, f"directory {str(directory)!r} is not writable ({exc.strerror or exc})") from None
    finally:  # removed whatever happens (an interrupt between the open and here included)
        if os.path.lexists(probe):
            os.unlink(probe)


def check_output_dir(path, field: str = "--out-dir") -> Path:
    """Raise ``SpecError`` unless ``path`` is a directory, or can be made one (not a file)."""
    target = Path(path)
    probe = target
    while not probe.exists():
        if probe.parent == probe:
            break
        probe = probe.parent
    if not probe.is_dir():
        raise SpecError(field, f"{str(probe)!r} is a file, not a directory")
    _require_writable(probe, field)
    return target


def atomic_write(path, write) -> Path:
    """Call ``write(tmp_path)`` then rename the temporary file over ``path``.

    The temporary file lives in the target's folder (``.NAME.*.part``); it is removed whatever
    happens (an error, Ctrl-C, SIGTERM through the CLI's handler), so a failed or interrupted
    export leaves nothing behind. The written file gets the usual permissions (0644 under the
    common umask 022).

    Parameters
    ----------
    path : str or Path
    write : callable taking the temporary file's path (str); it writes the whole file.

    Raises whatever ``write`` raises, after removing the temporary file; ``SpecError`` when the
    path cannot be written (:func:`check_output_path`).
    """
    target = check_output_path(path, "output")
    directory = target.parent if str(target.parent) else Path(".")
    tmp = None
    try:
        # a new private file (0600, 16 random hex digits), as the standard library's secure temporary
        # file is made but without importing tempfile; its name is held before it exists, so an
        # interrupt at any point leaves nothing behind
        for _ in range(100):
            tmp = os.path.join(directory, f".{target.name}.{os.urandom(8).hex()}.part")
            try:
                os.close(os.open(tmp, os.O_RDWR | os.O_CREAT | os.O_EXCL | getattr(os, "O_NOFOLLOW", 0), 0o600))
                break
            except FileExistsError:  # another file has that name: not ours to remove
                tmp = None
        else:
            raise FileExistsError(f"no free temporary name in {str(directory)!r}")
        write(tmp)
        umask = os.umask(0)  # temporary files are private; the result gets the usual permissions
        os.umask(umask)
        os.chmod(tmp, 0o666 & ~umask)
        os.replace(tmp, target)
    except BaseException:
        if tmp is not None and os.path.exists(tmp):
            os.unlink(tmp)
        raise
    return target


def profile_format(path) -> str:
    """The 2D format named by a file's extension, or a SpecError listing the allowed ones."""
    ext = Path(path).suffix.lower().lstrip(".")
    if ext not in PROFILE_FORMATS:
        raise SpecError("output", f"unknown 2D format {ext!r} for {str(path)!r}; allowed: "
                        + ", ".join("." + f for f in PROFILE_FORMATS))
    return ext


#: points formatted at once by the 2D writers: bounds their temporaries and paces their progress bars
CHUNK = 1 << 15


def _points(loops) -> int:
    return sum(len(lp) for lp in loops)


def _svg(loops, tmp):
    allpts = np.concatenate(loops)
    lo, hi = allpts.min(axis=0), allpts.max(axis=0)
    pad = 0.02 * float((hi - lo).max())
    w, h = hi - lo + 2 * pad
    with open(tmp, "w") as fh, Progress("SVG", _points(loops), unit="points") as bar:
        fh.write(f'<svg xmlns="http://www.w3.org/2000/svg" width="{w:.6g}mm" height="{h:.6g}mm" '
                 f'viewBox="{lo[0] - pad:.9g} {-hi[1] - pad:.9g} {w:.9g} {h:.9g}">\n'
                 f'<g fill="none" stroke="black" stroke-width="{max(w, h) / 1000:.3g}" fill-rule="evenodd">\n')
        for k, loop in enumerate(loops):
            flipped = loop * (1.0, -1.0)  # y up
            fh.write(("\n" if k else "") + '<path d="M %.9g %.9g' % tuple(flipped[0]))
            for s in range(1, len(flipped), CHUNK):
                block = flipped[s:s + CHUNK]
                fh.write((" L %.9g %.9g" * len(block)) % tuple(block.ravel().tolist()))
                bar.step(len(block))
            fh.write(' Z"/>')
            bar.step(1)
        fh.write("\n</g>\n</svg>\n")


class _CountedWrites:
    """A text stream that advances a progress bar by one step per write (a writer that writes tag by tag)."""

    def __init__(self, stream, bar):
        self.stream, self.bar, self.writes = stream, bar, 0

    def write(self, text):
        self.writes += 1
        if not self.writes & 0xFFF:
            self.bar.update(self.writes)
        return self.stream.write(text)


def _dxf(loops, tmp):
    import ezdxf

    doc = ezdxf.new("R2010")
    doc.units = ezdxf.units.MM
    msp = doc.modelspace()
    for loop in loops:
        # in bulk: appending vertex by vertex copies the vertex array each time (quadratic)
        vertices = np.zeros((len(loop), 5))  # x, y, start width, end width, bulge
        vertices[:, :2] = loop
        pl = msp.add_lwpolyline([], close=True)
        pl.lwpoints.set(vertices)
    # the writer writes a piece at a time: one per vertex, and about 1500 for the rest of the document
    with open(tmp, "wt", encoding=doc.output_encoding, errors="dxfreplace") as fh, \
            Progress("DXF", _points(loops) + 1500) as bar:
        doc.write(_CountedWrites(fh, bar))


def _csv(loops, tmp):
    with open(tmp, "w") as fh, Progress("CSV", _points(loops), unit="points") as bar:
        fh.write("loop,x_mm,y_mm\n")
        for k, lp in enumerate(loops):
            for s in range(0, len(lp), CHUNK):
                block = lp[s:s + CHUNK]
                fh.write((f"{k},%.12g,%.12g\n" * len(block)) % tuple(block.ravel().tolist()))
                bar.step(len(block))


def _json(loops, info, tmp):
    """One JSON object: ``info``'s keys, then ``loops`` (lists of [x, y]), written a chunk at a time."""
    import json

    head = json.dumps({k: v for k, v in info.items() if k != "loops"}, allow_nan=False)
    with open(tmp, "w") as fh, Progress("JSON", _points(loops), unit="points") as bar:
        fh.write(head[:-1] + (", " if len(head) > 2 else "") + '"loops": [')
        for k, lp in enumerate(loops):
            fh.write((", " if k else "") + "[")
            for s in range(0, len(lp), CHUNK):
                block = lp[s:s + CHUNK]
                fh.write((", " if s else "") + json.dumps(block.tolist(), allow_nan=False)[1:-1])
                bar.step(len(block))
            fh.write("]")
        fh.write("]}")


def write_profile(path, loops, info: dict | None = None) -> Path:
    """Write closed 2D loops (each an ``(n, 2)`` array, mm) in the format of ``path``'s extension."""
    fmt = profile_format(path)
    loops = [np.asarray(lp, dtype=float) for lp in loops]
    if not loops or any(lp.ndim != 2 or lp.shape[1] != 2 or len(lp) < 3 for lp in loops):
        raise SpecError("output", "nothing to write: a profile needs closed loops of at least 3 points")
    if not all(np.isfinite(lp).all() for lp in loops):
        raise SpecError("output", "the profile has non-finite points; nothing was written")
    writer = {"svg": _svg, "dxf": _dxf, "csv": _csv, "json": lambda lp, tmp: _json(lp, info or {}, tmp)}[fmt]
    return atomic_write(path, lambda tmp: writer(loops, tmp))
