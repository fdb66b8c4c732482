"""The ``gearkit`` command line: a thin shell over the public API.

Every command lives in its own module ``gearkit.cli.<name>`` exposing
``register(subparsers)``; heavy imports happen inside the command's run function.
The parser is lazy: ``gearkit <cmd> ...`` imports and registers only the module of
``<cmd>`` (:data:`COMMANDS` lists the modules, :data:`MODULE_OF` names the module of a
command whose name differs from it), so a command pays only for what it uses; the
full parser (every module) is built only for ``gearkit --help`` and unknown commands.

The command runs numpy's BLAS on one thread (:data:`BLAS_THREAD_VARIABLES`, set before numpy
loads unless the user set them): starting the BLAS thread pool costs about 50 ms of CPU per
process, more than a small gear takes to build, and gearkit's linear algebra is too small to
gain from threads. A user's own setting always wins.

A fresh process also imports with the cycle collector paused (:func:`hold_collector`): numpy's
import makes tens of thousands of long-lived objects, and the collector would walk them all
again and again as they pile up (about 10 ms of CPU per process); once the command's modules
are in, they are frozen out of the collector's sight (``gc.freeze``) and it runs as usual.
"""
from __future__ import annotations

import os
import sys

#: environment variables the command sets to "1" (one BLAS thread) when the user has not set them
BLAS_THREAD_VARIABLES = ("OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS")
#: the variables this process set itself, not the user (none once numpy is loaded: too late to matter);
#: a bench measuring the user's import floor drops them from its children's environment
BLAS_THREADS_SET_HERE = () if "numpy" in sys.modules else tuple(v for v in BLAS_THREAD_VARIABLES
                                                                if v not in os.environ)
os.environ.update(dict.fromkeys(BLAS_THREADS_SET_HERE, "1"))

import argparse  # noqa: E402 - after the BLAS setting, which must precede any numpy import
import gc  # noqa: E402
import importlib  # noqa: E402


#: command modules, in the order ``gearkit --help`` lists them
COMMANDS = ("demo", "gear", "rack", "check", "pair", "bench", "novikov", "blocking", "atlas", "cycloid", "contact",
            "view", "cam", "scene", "planetary")
#: command name -> module, where they differ (a module may register several commands)
MODULE_OF = {"cycloidal-drive": "cycloid"}


def version() -> str:
    """The installed version of gearkit (the source tree's when not installed)."""
    try:
        from importlib.metadata import version as _v

        return _v("gearkit")
    except Exception:  # running from a source tree that is not installed
        return "0+unknown"


def command_module(command: str | None) -> str | None:
    """The module (in :data:`COMMANDS`) that registers ``command``; None when unknown."""
    if command is None:
        return None
    module = MODULE_OF.get(command, command)
    return module if module in COMMANDS else None


def terminal_columns() -> int:
    """Columns of the terminal (``COLUMNS`` first, 80 when not a terminal), as the standard library
    reckons them for help text, without importing ``shutil`` (and its compression modules)."""
    try:
        columns = int(os.environ.get("COLUMNS", "0"))
    except ValueError:
        columns = 0
    if columns <= 0:
        try:
            columns = os.get_terminal_size(sys.__stdout__.fileno()).columns
        except (AttributeError, ValueError, OSError):
            columns = 0
    return columns if columns > 0 else 80


class HelpFormatter(argparse.HelpFormatter):
    """argparse's help formatter, told the terminal width up front (:func:`terminal_columns`)."""

    def __init__(self, prog, *args, **kwargs):
        if len(args) < 3 and kwargs.get("width") is None:
            kwargs["width"] = terminal_columns() - 2  # as argparse trims its own look-up
        super().__init__(prog, *args, **kwargs)


class ArgumentParser(argparse.ArgumentParser):
    """argparse's parser with :class:`HelpFormatter` by default (every command's parser is one too), whose
    errors are one line naming the flag, the value and the range, as every other error of the command line
    (``--help`` still prints the usage)."""

    def __init__(self, *args, **kwargs):
        kwargs.setdefault("formatter_class", HelpFormatter)
        super().__init__(*args, **kwargs)

    def error(self, message):
        self.exit(2, f"{self.prog}: error: {message} (see '{self.prog} --help')\n")


def build_parser(command: str | None = None) -> argparse.ArgumentParser:
    """The argument parser: with a known ``command``, only its module is imported and registered."""
    from gearkit.cli.common import add_progress_flag

    parser = ArgumentParser(
        prog="gearkit",
        description="Gear geometry and tooth-contact kernel: generate, check and export gears (lengths in mm). "
                    "Exit status: 0 ok, 1 a design check fails, 2 bad input or a file problem, 130/143 "
                    "interrupted, 70 an internal error (a bug).",
    )
    # the version is looked up (importlib.metadata: slow) only for the full parser: a command's
    # parser never sees a top-level --version
    parser.add_argument("--version", action="version",
                        version=f"gearkit {version()}" if command_module(command) is None else "gearkit")
    parser.add_argument("--debug", action="store_true",
                        help="show the traceback of an internal error (also accepted after the command)")
    parser.add_argument("--max-points", type=int, default=None, metavar="N",
                        help="raise the size limit a refused output names (points, faces, steps; also after the "
                             "command)")
    add_progress_flag(parser)
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", required=True)
    module = command_module(command)
    for name in (module,) if module else COMMANDS:
        importlib.import_module(f"gearkit.cli.{name}").register(sub)
    from gearkit.cli.design import track_given

    def track(p):  # every command (and sub-command) knows which flags were typed: they override a design file
        for action in p._actions:
            if isinstance(action, argparse._SubParsersAction):
                for child in action.choices.values():
                    track(child)
        track_given(p)
    for child in sub.choices.values():
        track(child)
    return parser


def hold_collector() -> bool:
    """Pause the cycle collector if this is a fresh process (numpy not loaded yet); True if paused.

    :func:`release_collector` loads numpy, freezes every object made so far out of the collector's
    sight and resumes it. A process that already loaded numpy (a test, a notebook) is left alone.
    """
    if "numpy" in sys.modules or not gc.isenabled():
        return False
    gc.disable()
    return True


def release_collector() -> None:
    """Load numpy (every command uses it), freeze the objects of the imports and resume the collector."""
    import numpy  # noqa: F401 - imported here while the collector is paused

    gc.freeze()
    gc.enable()


def main(argv: list[str] | None = None) -> int:
    """Run the CLI; return the exit status (0 ok, 1 a check failed, 2 bad input, 130/143 interrupted)."""
    held = hold_collector()
    try:
        return _main(argv, held)
    finally:
        if held and not gc.isenabled():
            gc.enable()


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
        parser = build_parser(argv[0] if argv and not argv[0].startswith("-") else None)  # lazy: its module only
        args = parser.parse_args(argv)
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
