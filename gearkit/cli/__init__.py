"""The ``gearkit`` command line: a thin shell over the public API.

Every command lives in its own module ``gearkit.cli.<name>`` exposing
``register(subparsers)``; heavy imports happen inside the command's run function.
The parser is lazy: ``gearkit <cmd> ...`` imports and registers only the module of
``<cmd>`` (:data:`COMMANDS` lists the modules, :data:`MODULE_OF` names the module of a
command whose name differs from it), so a command pays only for what it uses. A plain line
(every flag spelled in full, every value valid) is read without argparse at all
(:mod:`gearkit.cli.lean`); help, errors and anything else go to the full parser
(:mod:`gearkit.cli.parser`: every module for ``gearkit --help`` and unknown commands), which
prints every help text and error message.

The command runs numpy's BLAS on one thread (:data:`BLAS_THREAD_VARIABLES`, set before numpy
loads unless the user set them): starting the BLAS thread pool costs about 50 ms of CPU per
process, more than a small gear takes to build, and gearkit's linear algebra is too small to
gain from threads. A user's own setting always wins.

A fresh process also imports with the cycle collector paused (:func:`hold_collector`): numpy's
import makes tens of thousands of long-lived objects, and the collector would walk them all
again and again as they pile up (about 10 ms of CPU per process); once the command's modules
are in, they are frozen out of the collector's sight (``gc.freeze``) and it runs as usual. Its C
allocator keeps the memory it frees for the next arrays (:func:`keep_freed_memory`) instead of
handing it back to the system and faulting it in again. Once the command is done, such a process
ends at once (:func:`end_process`): the exit functions run and the streams are flushed, but the
interpreter does not free its modules and objects one by one.
"""
from __future__ import annotations

import atexit
import os
import sys

#: environment variables the command sets to "1" (one BLAS thread) when the user has not set them
BLAS_THREAD_VARIABLES = ("OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS")
#: the variables this process set itself, not the user (none once numpy is loaded: too late to matter);
#: a bench measuring the user's import floor drops them from its children's environment
BLAS_THREADS_SET_HERE = () if "numpy" in sys.modules else tuple(v for v in BLAS_THREAD_VARIABLES
                                                                if v not in os.environ)
os.environ.update(dict.fromkeys(BLAS_THREADS_SET_HERE, "1"))

import gc  # noqa: E402 - after the BLAS setting, which must precede any numpy import

from gearkit.cli.lean import COMMANDS, MODULE_OF, command_module  # noqa: E402, F401 - the command table


def build_parser(command: str | None = None):
    """The full argument parser (:func:`gearkit.cli.parser.build_parser`): with a known ``command``, only
    its module is imported and registered."""
    from gearkit.cli.parser import build_parser as full

    return full(command)


def parse_command_line(argv: list):
    """The parsed command line (``argv`` without ``--debug``, ``--progress`` and ``--max-points``): the
    lean reading of a plain line (:func:`gearkit.cli.lean.parse`), else the full parser's (which prints
    help or one error line and exits, as ``SystemExit``)."""
    from gearkit.cli.lean import parse

    args = parse(argv)
    if args is None:
        args = build_parser(argv[0] if argv and not argv[0].startswith("-") else None).parse_args(argv)
    return args


def hold_collector() -> bool:
    """Pause the cycle collector if this is a fresh process (numpy not loaded yet); True if paused.

    :func:`release_collector` loads numpy, freezes every object made so far out of the collector's
    sight and resumes it. A process that already loaded numpy (a test, a notebook) is left alone.
    """
    if "numpy" in sys.modules or not gc.isenabled():
        return False
    gc.disable()
    return True


#: glibc's ``mallopt`` parameters (M_MMAP_THRESHOLD, M_TRIM_THRESHOLD) and the values a fresh process sets
MALLOC_SETTINGS = ((-3, 32 << 20), (-1, 64 << 20))
#: the environment variables by which a user sets them instead (theirs win)
MALLOC_VARIABLES = ("MALLOC_MMAP_THRESHOLD_", "MALLOC_TRIM_THRESHOLD_")


def keep_freed_memory() -> bool:
    """Let the C allocator (glibc's) keep the memory the process frees, for its next arrays; True if set.

    By default a block of 128 KiB or more is mapped from the system for itself and handed back when
    freed, and so is free memory at the top of the heap: the next array of that size is mapped again
    and every page of it faulted in and zeroed once more (a few microseconds a page: about as much CPU
    as a mesh's arithmetic). Blocks up to 32 MiB now come from the heap and up to 64 MiB of free heap
    is kept: freed pages are reused as they are. Larger blocks are still mapped and handed back. A
    user's own ``MALLOC_MMAP_THRESHOLD_`` or ``MALLOC_TRIM_THRESHOLD_`` is left alone, and so is an
    allocator without ``mallopt`` (not glibc).
    """
    if any(v in os.environ for v in MALLOC_VARIABLES):
        return False
    import ctypes  # (numpy imports it too)

    try:
        mallopt = ctypes.CDLL(None).mallopt
    except (OSError, TypeError, AttributeError):  # no C library to ask, or one without mallopt: nothing to set
        return False
    return all([mallopt(parameter, value) == 1 for parameter, value in MALLOC_SETTINGS])


def release_collector() -> None:
    """Load numpy (every command uses it), freeze the objects of the imports and resume the collector."""
    import numpy  # noqa: F401 - imported here while the collector is paused

    gc.freeze()
    gc.enable()


def main(argv: list[str] | None = None) -> int:
    """Run the CLI; return the exit status (0 ok, 1 a check failed, 2 bad input, 130/143 interrupted).

    Run as the program itself (``argv`` read from ``sys.argv`` in a fresh process: the ``gearkit``
    command, ``python -m gearkit``), it ends the process once the command is done
    (:func:`end_process`) instead of returning.
    """
    held = hold_collector()
    if held:
        keep_freed_memory()
    try:
        code = _main(argv, held)
    finally:
        if held and not gc.isenabled():
            gc.enable()
    if held and argv is None:
        end_process(code)
    return code


def end_process(code: int) -> None:
    """End this process with exit status ``code`` now, skipping the interpreter's teardown.

    A finished command's objects need no freeing one by one: the teardown (a last collection, then
    every module and object freed in turn) costs about as much CPU as building a small gear. What of
    it can show is done first: the exit functions run (:mod:`atexit`) and the standard streams are
    flushed. It returns instead, leaving the usual exit to the caller, where the teardown has more to
    do: a thread (other than a daemon) still runs or is waited for at exit, a profiler or tracer is
    attached (it writes its report at exit), the interpreter stays for inspection (``-i``), or a
    stream cannot be flushed (the usual exit reports it as it always has).
    """
    threading = sys.modules.get("threading")
    if threading is not None and (getattr(threading, "_threading_atexits", None) or any(
            t.is_alive() and not t.daemon for t in threading.enumerate() if t is not threading.main_thread())):
        return
    run_exit_functions = getattr(atexit, "_run_exitfuncs", None)
    if sys.getprofile() is not None or sys.gettrace() is not None or sys.flags.inspect or run_exit_functions is None:
        return
    run_exit_functions()
    try:
        for stream in (sys.stdout, sys.stderr):
            if stream is not None:
                stream.flush()
    except (OSError, ValueError):
        return
    os._exit(code)


def _main(argv, held: bool) -> int:
    from gearkit.cli.shell import MAX_POINTS, run_guarded
    from gearkit.progress import Progress, line_break

    argv = list(sys.argv[1:] if argv is None else argv)
    debug = "--debug" in argv
    progress = "--progress" in argv
    argv = [a for a in argv if a not in ("--debug", "--progress")]
    argv, max_points = _take_max_points(argv)
    if isinstance(max_points, str):
        print(f"gearkit: error: --max-points: {max_points}", file=sys.stderr)
        return 2
    try:
        args = parse_command_line(argv)
    except SystemExit as exc:  # argparse reports bad flags itself and exits 2 (0 for --help/--version)
        return int(exc.code or 0)
    except KeyboardInterrupt:  # Ctrl-C while the command's modules load: no traceback either
        print(f"{line_break()}gearkit: interrupted", file=sys.stderr)
        return 130
    if held:
        release_collector()
    Progress.mode = "on" if progress else "auto"  # a bar on a terminal, or wherever --progress says
    MAX_POINTS[0] = max_points
    try:
        return run_guarded(args, debug=debug)
    except KeyboardInterrupt:  # an interrupt while run_guarded reports or cleans up: still one line
        name = f"gearkit {getattr(args, 'command', '')}".rstrip()
        print(f"{line_break()}{name}: interrupted", file=sys.stderr)
        return 130
    finally:
        Progress.mode = "off"
        MAX_POINTS[0] = None


def _take_max_points(argv):
    """``--max-points N`` (anywhere on the line) taken out: ``(argv, N or None)``, or an error text."""
    out, value = [], None
    i = 0
    while i < len(argv):
        a = argv[i]
        if a == "--max-points" or a.startswith("--max-points="):
            text = a.split("=", 1)[1] if "=" in a else (argv[i + 1] if i + 1 < len(argv) else "")
            i += 1 if "=" in a else 2
            try:
                value = int(float(text))
            except (ValueError, OverflowError):
                return argv, f"{text!r} must be a positive whole number"
            if value < 1:
                return argv, f"{text!r} must be a positive whole number"
            continue
        out.append(a)
        i += 1
    return out, value


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
