"""What every ``gearkit`` command gets by construction: exit codes, one-line errors, signals,
output paths checked before any work and bounded work (the progress bar is :mod:`gearkit.progress`).

Exit status: 0 ok, 1 a design check fails, 2 bad input or a file problem (one line naming the
file or field), 130 interrupted (Ctrl-C), 143 terminated (SIGTERM), 70 an internal error (a bug:
one line and a hint to rerun with ``--debug`` for the traceback).

Examples
--------
>>> describe_os_error(FileNotFoundError(2, "No such file or directory", "/nope/a.toml"))
"'/nope/a.toml': No such file or directory"
>>> refuse_size("--tol", 3.2e7, 2e6, "points", "--max-points")
Traceback (most recent call last):
...
gearkit.errors.SpecError: --tol: this needs about 3.2e+07 points (limit 2e+06); raise --max-points to compute it anyway
"""
from __future__ import annotations

import _signal  # the built-in module under signal, whose enum wrappers a command never needs
import os
import sys

from gearkit.errors import GearkitError, SpecError
from gearkit.progress import line_break

EXIT_OK, EXIT_FAILS, EXIT_INPUT, EXIT_INTERNAL, EXIT_INTERRUPTED, EXIT_TERMINATED = 0, 1, 2, 70, 130, 143

#: argparse destinations that name a file a command writes, and those that name a folder (a command
#: whose ``-o`` is a folder sets ``output_is_folder=True`` in its defaults)
OUTPUT_DESTS = ("output", "plot")
OUTPUT_DIR_DESTS = ("out_dir",)


class Terminated(BaseException):
    """SIGTERM turned into an exception, so temporary files are removed on the way out."""


def describe_os_error(exc: OSError) -> str:
    """One line for a file problem: the file's name and what is wrong."""
    name = exc.filename if exc.filename is not None else ""
    reason = exc.strerror or str(exc)
    return f"{str(name)!r}: {reason}" if name != "" else reason


#: the ``--max-points`` override of every size limit (None: each limit's default)
MAX_POINTS: list = [None]


def bound(field: str, estimate: float, default_limit: float, unit: str) -> None:
    """Refuse (exit 2) work whose estimated size exceeds the limit (``--max-points N`` overrides it).

    Examples
    --------
    >>> bound("--steps", 1e6, 1e5, "mesh positions")
    Traceback (most recent call last):
    ...
    gearkit.errors.SpecError: --steps: this needs about 1e+06 mesh positions (limit 1e+05); raise --max-points to compute it anyway
    """
    limit = MAX_POINTS[0] if MAX_POINTS[0] is not None else default_limit
    refuse_size(field, estimate, limit, unit, "--max-points")


def refuse_size(field: str, estimate: float, limit: float, unit: str, override: str) -> None:
    """Raise ``SpecError`` when an output's estimated size exceeds ``limit``, naming the override."""
    if estimate > limit:
        raise SpecError(field, f"this needs about {estimate:.2g} {unit} (limit {limit:.2g}); "
                               f"raise {override} to compute it anyway")


#: default limit of a STEP file's B-rep faces (``--max-points`` raises it): about a minute of work (each
#: face is made, sewn, checked and written: about 4 ms of CPU per face; a spur gear has 8 faces per tooth)
MAX_STEP_FACES = 10_000


def bound_step(path, parts) -> None:
    """Refuse (exit 2) a STEP file of more than :data:`MAX_STEP_FACES` B-rep faces, estimated from the
    parts' recipes before any is built (no-op for any other format)."""
    from gearkit.solids.export import mesh_format

    if mesh_format(path) in ("step", "stp"):
        from gearkit.solids.step import estimate_faces

        bound("-o", estimate_faces(parts), MAX_STEP_FACES, "B-rep faces in the STEP file")


def write_solids(path, parts, ascii: bool = False):
    """Write solids (:func:`~gearkit.solids.write_mesh`), a STEP file bounded first (:func:`bound_step`)."""
    from gearkit.solids.export import write_mesh

    parts = list(parts)
    bound_step(path, parts)
    return write_mesh(path, parts, ascii=ascii)


def output_paths(args) -> list:
    """``(flag, path, is_folder)`` for every output a parsed command line names."""
    found = []
    folder_output = bool(getattr(args, "output_is_folder", False))  # a command whose -o is a folder says so
    for dest in OUTPUT_DESTS + OUTPUT_DIR_DESTS:
        value = getattr(args, dest, None)
        for path in (value if isinstance(value, list) else [value]):
            if isinstance(path, str):
                flag = "--" + dest.replace("_", "-") if dest != "output" else "-o"
                found.append((flag, path, dest in OUTPUT_DIR_DESTS or (dest == "output" and folder_output)))
    return found


def check_outputs(args) -> None:
    """Check every output path before the command does any work (exit 2 on a bad one)."""
    from gearkit.export import check_output_dir, check_output_path

    for flag, path, folder in output_paths(args):
        (check_output_dir if folder else check_output_path)(path, flag)


def _on_sigterm(signum, frame):
    raise Terminated()


def run_guarded(args, debug: bool = False) -> int:
    """Run ``args.run(args)`` and turn every way it can end into an exit status and at most one line."""
    prefix = f"gearkit {getattr(args, 'command', '')}".rstrip()
    previous = None
    try:
        previous = _signal.signal(_signal.SIGTERM, _on_sigterm)
    except ValueError:  # not the main thread: leave signals alone
        previous = None
    tee = _Tee(sys.stdout)
    try:
        check_outputs(args)
        before = {path: _stamp(path) for _, path, folder in output_paths(args) if not folder}
        sys.stdout = tee
        try:
            code = int(args.run(args) or 0)
        finally:
            sys.stdout = tee.stream
        for path, stamp in before.items():  # every command says what it wrote
            if _stamp(path) not in (None, stamp) and f"wrote {path}" not in tee.seen:
                print(f"{prefix}: wrote {path}", file=sys.stderr)
        return code
    except GearkitError as exc:
        print(f"{prefix}: error: {exc}", file=sys.stderr)
        return EXIT_INPUT
    except BrokenPipeError:  # output piped into a reader that stopped early (e.g. `| head`)
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return EXIT_OK
    except OSError as exc:
        if debug:
            raise
        print(f"{prefix}: error: {describe_os_error(exc)}", file=sys.stderr)
        return EXIT_INPUT
    except KeyboardInterrupt:
        print(f"{line_break()}{prefix}: interrupted", file=sys.stderr)
        return EXIT_INTERRUPTED
    except Terminated:
        print(f"{prefix}: terminated", file=sys.stderr)
        return EXIT_TERMINATED
    except MemoryError:
        print(f"{prefix}: error: out of memory; ask for less (a coarser --tol, fewer steps or teeth)",
              file=sys.stderr)
        return EXIT_INPUT
    except Exception as exc:  # a bug: one line, the traceback only on request
        if debug:
            raise
        text = str(exc).splitlines()[0] if str(exc) else ""
        print(f"{prefix}: internal error: {type(exc).__name__}: {text} (a bug; rerun with "
              f"'gearkit --debug {getattr(args, 'command', '')} ...' for the traceback)", file=sys.stderr)
        return EXIT_INTERNAL
    finally:
        if previous is not None:
            _signal.signal(_signal.SIGTERM, previous)


def _stamp(path):
    """A file's identity and modification time (None if there is none), to see whether a run wrote it."""
    try:
        st = os.stat(path)
    except (OSError, ValueError):
        return None
    return (st.st_ino, st.st_mtime_ns, st.st_size)


class _Tee:
    """Stand-in for stdout that remembers what a command printed (to tell whether it said "wrote")."""

    def __init__(self, stream):
        self.stream, self.seen = stream, ""

    def write(self, text):
        if len(self.seen) < 1_000_000:
            self.seen += text
        return self.stream.write(text)

    def __getattr__(self, name):
        return getattr(self.stream, name)
