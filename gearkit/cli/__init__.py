"""The ``gearkit`` command line: a thin shell over the public API.

Every command lives in its own module ``gearkit.cli.<name>`` exposing
``register(subparsers)``; registration must stay cheap (heavy imports happen
inside the command's run function), so ``gearkit <cmd>`` pays only for what it uses.
"""
from __future__ import annotations

import argparse
import importlib
import sys

from gearkit.errors import GearkitError

#: command modules, in the order ``gearkit --help`` lists them
COMMANDS = ("demo", "gear", "rack", "check", "pair", "bench", "novikov", "blocking", "atlas", "cycloid", "contact",
            "view", "cam", "scene", "planetary")


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="gearkit",
        description="Gear geometry and tooth-contact kernel: generate, check and export gears (lengths in mm).",
    )
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", required=True)
    for name in COMMANDS:
        importlib.import_module(f"gearkit.cli.{name}").register(sub)
    return parser


def main(argv: list[str] | None = None) -> int:
    """Run the CLI; return the exit status (0 ok, 1 a check failed, 2 bad input)."""
    parser = build_parser()
    try:
        args = parser.parse_args(argv)
    except SystemExit as exc:  # argparse reports bad flags itself and exits 2
        return int(exc.code or 0)
    try:
        return int(args.run(args) or 0)
    except GearkitError as exc:
        print(f"gearkit {args.command}: error: {exc}", file=sys.stderr)
        return 2
    except BrokenPipeError:  # output piped into a reader that stopped early (e.g. `| head`)
        import os
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
