"""The full argument parser (argparse): every command's options, help text and error messages.

:func:`build_parser` registers the commands of :data:`~gearkit.cli.lean.COMMANDS` (only the named
command's module when one is given) on an :class:`ArgumentParser`, whose errors are one line naming
the flag, the value and the range, with help text as wide as the terminal (:class:`HelpFormatter`).
Every flag records, when typed, its destination in ``args.given_flags`` (:func:`track_given`), so a
flag typed with its default value still overrides a design file. A flag's earlier spelling stays
accepted with one deprecation line (:class:`RenamedFlag`, the action ``"renamed"``).

The command line reaches this parser only when the lean reading (:mod:`gearkit.cli.lean`) leaves a
line to it: ``--help``, an error, or anything but plain flags and values.

Examples
--------
>>> args = build_parser("gear").parse_args(["gear", "-z", "12", "-m", "2", "--json"])
>>> args.command, args.teeth, sorted(args.given_flags)
('gear', 12, ['json', 'module', 'teeth'])
"""
from __future__ import annotations

import argparse
import importlib
import os
import sys

from gearkit.cli.lean import COMMANDS, command_module

__all__ = ["ArgumentParser", "HelpFormatter", "RenamedFlag", "build_parser", "terminal_columns", "track_given",
           "version"]


def version() -> str:
    """The installed version of gearkit (the source tree's when not installed)."""
    try:
        from importlib.metadata import version as _v

        return _v("gearkit")
    except Exception:  # running from a source tree that is not installed
        return "0+unknown"


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


class RenamedFlag(argparse.Action):
    """The earlier spelling of a flag, kept working: it stores into the new flag's destination and
    prints one deprecation line on stderr (:func:`gearkit.cli.vocabulary.add_renamed_flag`); it sets
    nothing unless typed."""

    def __init__(self, option_strings, dest, new_flag: str = "", **kwargs):
        self.new_flag = new_flag
        kwargs["default"] = argparse.SUPPRESS
        super().__init__(option_strings, dest, **kwargs)

    def __call__(self, parser, namespace, values, option_string=None):
        print(f"{parser.prog}: {option_string} is deprecated, use {self.new_flag} (the same value)", file=sys.stderr)
        setattr(namespace, self.dest, values)


class ArgumentParser(argparse.ArgumentParser):
    """argparse's parser with :class:`HelpFormatter` by default (every command's parser is one too), whose
    errors are one line naming the flag, the value and the range, as every other error of the command line
    (``--help`` still prints the usage); it knows the action ``"renamed"`` (:class:`RenamedFlag`)."""

    def __init__(self, *args, **kwargs):
        kwargs.setdefault("formatter_class", HelpFormatter)
        super().__init__(*args, **kwargs)
        self.register("action", "renamed", RenamedFlag)

    def error(self, message):
        head, _, tail = message.partition(": ")
        if head.startswith("argument ") and tail == "expected one argument":
            # the value may be there, read as a flag: a list or range starting with '-' (``--mark -0.2,0.3``)
            flag = head[len("argument "):].split("/")[-1]
            message += f" (none given, or one starting with '-': write {flag}=VALUE)"
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

    def track(p):  # every command (and sub-command) knows which flags were typed: they override a design file
        for action in p._actions:
            if isinstance(action, argparse._SubParsersAction):
                for child in action.choices.values():
                    track(child)
        track_given(p)
    for child in sub.choices.values():
        track(child)
    return parser


def track_given(p) -> None:
    """Record in ``args.given_flags`` the destination of every flag of ``p`` typed on the command line
    (:func:`build_parser` calls it on every command's parser once registered); ``args.flag_actions``
    maps each destination to its action."""
    flags = [a for a in p._actions if a.option_strings and a.dest not in ("help", "version")]
    for action in flags:
        if not isinstance(action, _Given):
            action.__class__ = _given_class(type(action))
    actions = {}
    for action in flags:  # a renamed flag's old spelling shares the destination: the new one checks a value
        if action.dest not in actions or isinstance(actions[action.dest], RenamedFlag):
            actions[action.dest] = action
    p.set_defaults(given_flags=frozenset(), flag_actions=actions)


class _Given:
    """Mixin of a tracked action: records its destination in ``given_flags`` when it is called."""

    def __call__(self, parser, namespace, values, option_string=None):
        namespace.given_flags = frozenset(getattr(namespace, "given_flags", frozenset()) | {self.dest})
        super().__call__(parser, namespace, values, option_string)


_CLASSES: dict = {}


def _given_class(cls):
    if cls not in _CLASSES:
        _CLASSES[cls] = type(f"Given{cls.__name__}", (_Given, cls), {})
    return _CLASSES[cls]
