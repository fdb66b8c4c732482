"""The lean reading of a plain command line (``gearkit.cli.lean``) against the full parser, the oracle.

For every command, command lines are drawn from the full parser's own flags (valid and invalid values,
every spelling of a flag, abbreviations, repeats, exclusive pairs, positionals in and out of place,
``--help``, ``--``): wherever the lean reading returns a namespace, the full parser must accept the same
line silently and return the same attributes (and ``flag_actions`` the same flags); wherever the full
parser refuses a line or prints anything, the lean reading must leave the line to it (None). The plain
lines a user types most (the bench's gears) must take the lean path, or nothing is being compared.
"""
import argparse
import contextlib
import io
import random

import pytest

from gearkit.cli import COMMANDS, MODULE_OF, build_parser, main, parse_command_line
from gearkit.cli.lean import SUPPRESS, parse

FULL = build_parser()
SUB = next(a for a in FULL._actions if a.dest == "command").choices
NAMES = sorted(SUB)
#: lines drawn per command
LINES = 120


def full_parse(argv):
    """``(namespace or None, exit code or None, what argparse printed)`` of the full parser."""
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        try:
            return FULL.parse_args(argv), None, out.getvalue() + err.getvalue()
        except SystemExit as exc:
            return None, exc.code, out.getvalue() + err.getvalue()


def assert_same(argv):
    """The lean reading of ``argv`` is None or equals the full parser's; returns whether it was taken."""
    lean = parse(list(argv))
    if lean is None:
        return False
    full, code, printed = full_parse(argv)
    assert full is not None and printed == "", (argv, code, printed)
    mine, theirs = dict(vars(lean)), dict(vars(full))
    lean_actions, full_actions = mine.pop("flag_actions"), theirs.pop("flag_actions")
    assert _nan_named(mine) == _nan_named(theirs), argv
    assert lean_actions.keys() == full_actions.keys(), argv
    for dest, action in full_actions.items():
        flag = lean_actions[dest]
        assert (flag.option_strings, flag.nargs, flag.type, flag.choices, flag.default) == \
               (action.option_strings, action.nargs, action.type, action.choices, action.default), (argv, dest)
    return True


def _nan_named(values: dict) -> dict:
    """``values`` with a NaN (never equal to itself) spelled out, so two NaNs compare equal."""
    return {k: "NaN" if isinstance(v, float) and v != v else v for k, v in values.items()}


def _values(action, rng):
    """Texts for a flag's value: valid, out of range, not numbers, negative, empty, flag-like."""
    pool = ["3", "20", "0", "-2", "-0.5", "2.5", "1e-3", "-1e-3", "nan", "inf", "abc", "", "-", "--", "x.stl",
            "a b", "99999999", "7x2", "0.25", "-.5", "1,2"]
    if action.choices is not None:
        pool += [str(c) for c in action.choices] * 3
    kind = getattr(action.type, "kind", action.type)
    if kind in (int, float) and hasattr(action.type, "lo"):
        q = action.type
        pool += [f"{q.lo:g}", f"{q.hi:g}", f"{(q.lo + q.hi) / 2:g}", f"{q.lo - 1:g}", f"{q.hi * 2:g}"] * 2
    return rng.choice(pool)


def _line(name, parser, rng):
    """One command line for command ``name``, drawn from its parser's actions."""
    actions = [a for a in parser._actions if a.option_strings]
    positional = [a for a in parser._actions if not a.option_strings and not isinstance(a, argparse._SubParsersAction)]
    argv = [name]
    if positional and rng.random() < 0.3:
        argv.append(rng.choice(["d.toml", "", "examples/planetary.toml"]))
    for a in [a for a in actions if a.required]:  # most lines give the required flags
        if rng.random() < 0.9:
            argv += [rng.choice(a.option_strings), _values(a, rng)]
    for _ in range(rng.randint(0, 6)):
        a = rng.choice(actions)
        flag = rng.choice(a.option_strings)
        form = rng.random()
        if form < 0.05 and flag.startswith("--") and len(flag) > 4:
            flag = flag[:-2]  # an abbreviation (or an unknown flag)
        if a.nargs == 0:
            argv.append(flag if form < 0.9 else flag + "=1")
        elif form < 0.25 and flag.startswith("--"):
            argv.append(f"{flag}={_values(a, rng)}")
        elif a.nargs in ("+", "*"):
            argv += [flag] + [_values(a, rng) for _ in range(rng.randint(1, 2))]
        else:
            argv += [flag, _values(a, rng)]
    extra = rng.random()
    if extra < 0.03:
        argv.insert(rng.randint(1, len(argv)), rng.choice(["-h", "--help", "--", "--nope", "-q"]))
    elif extra < 0.06:
        argv.append("late.toml")  # a positional after the flags
    elif extra < 0.08 and len(argv) > 2:
        argv.pop()  # a flag missing its value (or a value cut)
    return argv


@pytest.mark.parametrize("name", NAMES)
def test_lean_reading_matches_the_full_parser_on_drawn_lines(name):
    rng = random.Random(f"lean {name}")
    parser = SUB[name]
    taken = sum(assert_same(_line(name, parser, rng)) for _ in range(LINES))
    nested = any(isinstance(a, argparse._SubParsersAction) for a in parser._actions)
    if not nested:  # a command of plain flags: a good share of the drawn lines is read lean
        assert taken > 0, name


#: plain lines: the bench's gears and the spellings the lean reading takes (each checked against the oracle)
PLAIN = [
    ["gear", "-z", "12", "-m", "2", "--width", "5", "-o", "x.stl"],
    ["gear", "-z", "40", "-m", "2", "--width", "5", "-o", "x.stl"],
    ["gear", "-z", "20", "-m", "2", "--helix-angle-deg", "20", "--width", "10", "-o", "x.stl", "--tol", "0.001"],
    ["gear", "-z", "200", "-m", "1", "--width", "5", "-o", "x.stl"],
    ["gear", "-z", "20", "-m", "2", "-x", "-0.5", "--helix-angle-deg=-20", "--json", "--rack", "iso53b"],
    ["gear", "design.toml", "--gear", "2", "--thinning", "0.05"],
    ["gear", "--teeth=30", "--module=1.5", "--internal", "--cutter-teeth", "20", "--ring-shift", "cutter"],
    ["gear", "-z", "12", "-z", "13", "-m", "2"],
    ["check", "--z1", "18", "--z2", "41", "-m", "2", "--json"],
    ["check", "d.toml", "--x1", "0.3", "--tip-rule", "standard", "--tip-diameter1", "40"],
    ["cycloidal-drive", "--pins", "12", "--lobes", "11", "--pin-circle-radius", "90", "--pin-radius", "7",
     "--eccentricity", "4"],
    ["rack", "-m", "2"], ["demo"], ["planetary", "--ratio", "6", "--planets", "3", "-m", "1.75"],
]
#: lines the full parser must read (help, errors, a quirk of a positional after the flags, renamed flags)
NOT_PLAIN = [
    ["gear", "--help"], ["gear", "-z", "2", "-m", "2"], ["gear", "-z12", "-m", "2"], ["gear", "--wid", "5"],
    ["gear", "-z", "12", "-m", "2", "d.toml"], ["gear", "-z", "12", "-m", "2", "--", "x"],
    ["gear", "-z", "12", "-m", "2", "--outer-diameter", "50", "--rim", "3"], ["gear", "-z", "12", "-m"],
    ["gear", "--json=1"], ["gear", "-x", "-1e-3"], ["gear", "-x", "-5\n"], ["gear", "-o=x.stl"], ["gear", "--output=--"],
    ["check", "--z1", "18", "--z2", "41", "-m", "2", "--tip", "standard"],
    ["check", "--z1", "18", "--da1", "40"], ["view", "pair", "--z1", "18", "--z2", "41", "-m", "2"],
    ["gear", "-z", "12", "-m", "2", "--tip-rule", "pointy"], ["nope"], [], ["--version"],
]


@pytest.mark.parametrize("argv", PLAIN, ids=[" ".join(a[:3]) for a in PLAIN])
def test_plain_lines_take_the_lean_reading_and_match(argv):
    assert assert_same(argv)


@pytest.mark.parametrize("argv", NOT_PLAIN, ids=[" ".join(a[:4]) or "empty" for a in NOT_PLAIN])
def test_other_lines_are_left_to_the_full_parser(argv):
    assert parse(list(argv)) is None


def test_errors_and_help_are_the_full_parsers(capsys):
    """Through the command line: a refused value is the full parser's one line and exit 2, help its text."""
    assert main(["gear", "-z", "2", "-m", "2"]) == 2
    err = capsys.readouterr().err
    assert err == ("gearkit gear: error: argument -z/--teeth: 2 is outside [3, 100000] (tooth number) "
                   "(see 'gearkit gear --help')\n")
    with pytest.raises(SystemExit) as exc:
        parse_command_line(["gear", "--help"])
    out = capsys.readouterr().out
    assert exc.value.code == 0
    full, code, printed = full_parse(["gear", "--help"])
    assert code == 0 and printed == out


def test_every_command_is_found_by_the_lean_reading():
    """Each command the full parser lists is registered by the module the command table names."""
    from gearkit.cli.lean import Commands, Unsupported, command_module

    for name in NAMES:
        commands = Commands()
        try:
            __import__(f"gearkit.cli.{command_module(name)}", fromlist=["register"]).register(commands)
        except Unsupported:  # a command of sub-commands (view): left to the full parser whole
            assert name == "view"
            continue
        assert name in commands.parsers
    assert SUPPRESS == argparse.SUPPRESS


def test_a_setting_the_recorder_does_not_know_leaves_the_line_to_the_full_parser():
    """A ``register`` using more of argparse than the recorder models (parents, aliases, nested commands,
    a setting that changes how a flag reads) is not read lean, rather than read wrongly."""
    from gearkit.cli.lean import Commands, Unsupported

    for attempt in (lambda: Commands().add_parser("x", parents=[]), lambda: Commands().add_parser("x", aliases=["y"]),
                    lambda: Commands().add_parser("x").add_subparsers(dest="what"),
                    lambda: Commands().add_parser("x").add_argument("--y", type=int, dest_hint="z"),
                    lambda: Commands().add_parser("x").parse_known_args):
        with pytest.raises(Unsupported):
            attempt()
