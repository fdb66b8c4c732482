"""The command table, and the lean reading of a clean command line.

A command's flags are declared once, by its module's ``register(subparsers)``. The full parser
(:mod:`gearkit.cli.parser`, argparse) builds every option's help text and formatter and looks up
argparse's translations: about as much work as a small gear. Most command lines are plain (each
flag spelled in full, each value valid), so :func:`parse` first runs the same ``register`` against
a recorder (:class:`Commands`) that only notes each flag's name, destination, type, choices and
default, and reads the line with those: exact flag names (``--flag value``, ``--flag=value``,
``-f value``), switches, one optional leading positional, a value that is a word or a negative
number. Anything else (``--help``, an abbreviated or unknown flag, a bad value, a missing required
flag, two flags of an exclusive group, a repeated-value or renamed flag, a nested command) returns
None, and the full parser reads the line, with its own help and error messages: the lean reading
never reports an error itself, so every message is the full parser's.

What it returns equals what the full parser returns for the same line (a test holds the two side
by side), as a :class:`Namespace` of the same attributes; ``flag_actions`` maps each destination to
the recorded :class:`Flag` (with the ``nargs``, ``type`` and ``choices`` a design file's values are
checked by).

Examples
--------
>>> args = parse(["gear", "-z", "12", "-m", "2", "--helix-angle-deg=-20", "--json"])
>>> args.command, args.teeth, args.module, args.helix_angle_deg, args.json, args.output
('gear', 12, 2.0, -20.0, True, None)
>>> sorted(args.given_flags)
['helix_angle_deg', 'json', 'module', 'teeth']
>>> parse(["gear", "-z", "2", "-m", "2"]) is None  # out of range: the full parser says so
True
"""
from __future__ import annotations

import importlib

__all__ = ["COMMANDS", "MODULE_OF", "SUPPRESS", "Commands", "Flag", "Namespace", "command_module", "negative_number",
           "parse"]

#: command modules, in the order ``gearkit --help`` lists them
COMMANDS = ("demo", "gear", "rack", "check", "pair", "bench", "novikov", "blocking", "atlas", "cycloid", "contact",
            "view", "cam", "scene", "planetary")
#: command name -> module, where they differ (a module may register several commands)
MODULE_OF = {"cycloidal-drive": "cycloid"}
#: the default of a flag that sets nothing unless typed (argparse's marker, spelled the same)
SUPPRESS = "==SUPPRESS=="
#: the top-level parser's own destinations and defaults (``--debug``, ``--max-points`` and
#: ``--progress`` are taken off the line before it is read, so they keep their defaults)
TOP_DEFAULTS = {"debug": False, "max_points": None, "progress": False}
_NOT_GIVEN = object()
#: ``add_argument`` settings that only word the help (or name a renamed flag's successor)
_TEXT_ONLY = frozenset({"help", "metavar", "new_flag", "version"})
#: the action kinds the lean reading knows: a flag that takes one value, and a switch
_SWITCHES = {"store_true": True, "store_false": False}


def negative_number(text: str) -> bool:
    """True for ``-5``, ``-0.5`` or ``-.5``: a value, not a flag, as argparse reads it (its pattern
    ``^-\\d+$|^-\\d*\\.\\d+$``, without compiling a regular expression; a trailing newline,
    which that pattern lets through, is left to argparse).

    >>> [negative_number(t) for t in ("-5", "-0.5", "-.5", "-5.", "-1e-3", "--5", "-x", "5")]
    [True, True, True, False, False, False, False, False]
    """
    if not text.startswith("-"):
        return False
    whole, dot, fraction = text[1:].partition(".")
    if not dot:
        return whole.isdecimal()
    return fraction.isdecimal() and (whole == "" or whole.isdecimal())


def command_module(command: str | None) -> str | None:
    """The module (in :data:`COMMANDS`) that registers ``command``; None when unknown."""
    if command is None:
        return None
    module = MODULE_OF.get(command, command)
    return module if module in COMMANDS else None


class Unsupported(Exception):
    """A command line (or a ``register``) the lean reading leaves to the full parser."""


class _Recorder:
    """Any call a ``register`` makes that the recorders below do not know leaves the line to the full parser."""

    def __getattr__(self, name):
        raise Unsupported(name)


class Namespace:
    """The parsed command line: one attribute per destination (as ``argparse.Namespace``)."""

    def __init__(self, **kwargs):
        self.__dict__.update(kwargs)

    def __eq__(self, other):
        if not isinstance(other, Namespace):
            return NotImplemented
        return vars(self) == vars(other)

    def __contains__(self, key):
        return key in self.__dict__

    def __repr__(self):
        return f"Namespace({', '.join(f'{k}={v!r}' for k, v in self.__dict__.items())})"


class Flag:
    """One recorded ``add_argument``: its names, destination and how it reads a value.

    ``kind`` is ``"store"``, ``"store_true"``, ``"store_false"``, or anything else the lean reading
    leaves to the full parser when the flag is typed (an action class or another action's name).
    """

    def __init__(self, names, dest, kind, nargs, default, type, choices, required, const=None):
        self.option_strings, self.dest, self.kind, self.nargs = list(names), dest, kind, nargs
        self.default, self.type, self.choices, self.required, self.const = default, type, choices, required, const

    def __repr__(self):
        return f"Flag({self.option_strings or self.dest!r}, {self.kind})"

    def value(self, text: str):
        """``text`` read as the full parser reads it; Unsupported where that would be an error."""
        try:
            value = text if self.type is None else self.type(text)
        except Exception:  # the full parser reports it (or lets it through): its message, not ours
            raise Unsupported(self.dest) from None
        if self.choices is not None and value not in self.choices:
            raise Unsupported(self.dest)
        return value


class Parser(_Recorder):
    """Records one command's ``add_argument`` calls, groups and defaults (argument groups share it)."""

    def __init__(self, name: str):
        self.name, self.actions, self.defaults, self.exclusive = name, [], {}, []
        self.add_argument("-h", "--help", action="help", default=SUPPRESS)

    @property
    def flags(self) -> list:
        return [a for a in self.actions if a.option_strings]

    @property
    def positionals(self) -> list:
        return [a for a in self.actions if not a.option_strings]

    def add_argument(self, *names, action="store", group=None, **kw):
        if names and names[0].startswith("-"):
            long = [n for n in names if n.startswith("--")]
            dest = kw.pop("dest", None) or (long or names)[0].lstrip("-").replace("-", "_")
        else:
            if kw.pop("dest", None) is not None or len(names) != 1:
                raise Unsupported("positional")
            dest, names = names[0], ()
        nargs, const = kw.pop("nargs", None), kw.pop("const", None)
        if action in _SWITCHES:
            nargs, const = 0, _SWITCHES[action]
        given_default = kw.pop("default", _NOT_GIVEN)
        if action in ("renamed", "help"):  # a renamed flag sets its destination only when typed
            default = SUPPRESS
        elif given_default is not _NOT_GIVEN:
            default = given_default
        elif dest in self.defaults:
            default = self.defaults[dest]
        else:
            default = (not const) if action in _SWITCHES else None
        required = kw.pop("required", not names and nargs not in ("?", "*"))
        flag = Flag(names, dest, action, nargs, default, kw.pop("type", None), kw.pop("choices", None), required,
                    const)
        if set(kw) - _TEXT_ONLY:  # a setting that could change what the line means: not read here
            raise Unsupported(f"{dest}: {sorted(set(kw) - _TEXT_ONLY)}")
        self.actions.append(flag)
        if group is not None:
            group.append(flag)
        return flag

    def add_argument_group(self, *args, **kwargs):
        return _Group(self, None)

    def add_mutually_exclusive_group(self, required: bool = False):
        members: list = []
        self.exclusive.append((members, required))
        return _Group(self, members)

    def set_defaults(self, **kwargs):
        self.defaults.update(kwargs)
        for flag in self.actions:
            if flag.dest in kwargs:
                flag.default = kwargs[flag.dest]

    def add_subparsers(self, *args, **kwargs):
        raise Unsupported("nested commands")


class _Group(_Recorder):
    """An argument group (or an exclusive one, ``members``) of a :class:`Parser`."""

    def __init__(self, parser: Parser, members):
        self.parser, self.members = parser, members

    def add_argument(self, *names, **kw):
        return self.parser.add_argument(*names, group=self.members, **kw)

    def add_mutually_exclusive_group(self, required: bool = False):
        return self.parser.add_mutually_exclusive_group(required)


class Commands(_Recorder):
    """Stands for argparse's sub-command action in a ``register(subparsers)`` call: records each command."""

    def __init__(self):
        self.parsers: dict = {}

    def add_parser(self, name: str, **kwargs):
        if set(kwargs) - {"help", "description", "epilog", "formatter_class"}:  # aliases, parents, prefixes...
            raise Unsupported(name)
        self.parsers[name] = Parser(name)
        return self.parsers[name]


def parse(argv: list) -> Namespace | None:
    """``argv`` (the command first) read as the full parser reads it, or None when it is not plain."""
    module = command_module(argv[0]) if argv else None
    if module is None:
        return None
    commands = Commands()
    try:
        importlib.import_module(f"gearkit.cli.{module}").register(commands)
        parser = commands.parsers.get(argv[0])
        if parser is None:
            return None
        return Namespace(**{**TOP_DEFAULTS, "command": argv[0], **read(parser, argv[1:])})
    except Unsupported:
        return None


def read(parser: Parser, argv: list) -> dict:
    """The destinations and values of one command's line (``argv`` after the command)."""
    by_name = {name: flag for flag in parser.flags for name in flag.option_strings}
    values, typed = {}, []
    i = 0
    if len(parser.positionals) > 1 or any(p.nargs not in (None, "?") for p in parser.positionals):
        raise Unsupported("positionals")
    for positional in parser.positionals:
        if argv and not argv[0].startswith("-"):
            values[positional.dest] = positional.value(argv[0])
            i = 1
        elif positional.nargs is None:
            raise Unsupported(positional.dest)  # a required positional missing
        elif isinstance(positional.default, str):
            values[positional.dest] = positional.value(positional.default)
    while i < len(argv):
        text, explicit = argv[i], None
        flag = by_name.get(text)
        if flag is None and text.startswith("--") and "=" in text:
            text, explicit = text.split("=", 1)
            flag = by_name.get(text) if explicit != "--" else None  # argparse drops a "--" value
        if flag is None:
            raise Unsupported(text)  # a positional out of place, an abbreviation, "--", an unknown flag
        if flag.kind in _SWITCHES and explicit is None:
            values[flag.dest] = flag.const
        elif flag.kind == "store" and flag.nargs is None:
            if explicit is None:
                if i + 1 >= len(argv) or (argv[i + 1].startswith("-") and not negative_number(argv[i + 1])):
                    raise Unsupported(text)
                explicit = argv[i + 1]
                i += 1
            values[flag.dest] = flag.value(explicit)
        else:
            raise Unsupported(text)
        typed.append(flag)
        i += 1
    _check(parser, typed, by_name)
    return _namespace(parser, values, typed)


def _check(parser: Parser, typed: list, by_name: dict) -> None:
    """Required flags typed, at most one flag of an exclusive group, and no flag that looks like a
    negative number (which would make such values flags)."""
    if any(negative_number(name) for name in by_name):
        raise Unsupported("negative-number flags")
    seen = {id(f) for f in typed}
    if any(f.required and id(f) not in seen for f in parser.flags):
        raise Unsupported("a required flag")
    for members, required in parser.exclusive:
        count = sum(id(f) in seen for f in members)
        if count > 1 or (required and count == 0):
            raise Unsupported("an exclusive group")


def _namespace(parser: Parser, values: dict, typed: list) -> dict:
    """Every destination in the full parser's order: the flags' defaults (a text default read by the
    flag's type), the command's own defaults, the typed values, and which flags were typed."""
    out = {}
    for flag in parser.actions:
        if flag.dest not in out and not (isinstance(flag.default, str) and flag.default == SUPPRESS):
            default = flag.default
            if isinstance(default, str) and flag.type is not None and flag.dest not in values:
                default = flag.value(default)
            out[flag.dest] = default
    for dest, value in parser.defaults.items():
        out.setdefault(dest, value)
    out.update(values)
    actions = {}
    for flag in parser.flags:
        if flag.dest in ("help", "version"):
            continue
        if flag.dest not in actions or actions[flag.dest].kind == "renamed":
            actions[flag.dest] = flag
    given = frozenset(f.dest for f in typed)
    for dest in ("given_flags", "flag_actions"):  # set last, as the full parser sets them
        out.pop(dest, None)
    out.update(given_flags=given, flag_actions=actions)
    return out
