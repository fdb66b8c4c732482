"""The command line under random and hostile argument vectors (issue 13).

For every command registered in ``gearkit.cli.COMMANDS`` (new commands are covered by
construction), argument vectors are drawn from the command's own argparse actions: its flags
with values of the declared type biased towards the legal range, hostile numbers (0, negative,
huge, nan, inf), unknown choices, paths that are folders, missing folders, binary files, and
stray tokens; half the vectors use only plausible values (listed choices, small numbers inside a
flag's declared range, fresh file names) so that the working paths run too. Each vector runs in-process through ``gearkit.cli.main`` in a scratch folder, with
a timer that interrupts a long run as Ctrl-C would. Asserted for every run:

- the exit status is 0, 1, 2 or 130 (never 70, an internal error, nor anything else);
- no traceback on stdout or stderr, and an exit 2 says why on stderr;
- on 0 or 1 with ``--json``, stdout is one strict JSON value (no NaN/Infinity);
- no partial file (``*.part``) is left in the scratch folder.

About 2000 examples in all (tens of seconds). ``GEARKIT_FUZZ_EXAMPLES=N`` runs N per command
(e.g. 5000 for a long run) and ``GEARKIT_FUZZ_SECONDS`` sets the per-run timer (default 0.4 s).
``GEARKIT_FUZZ_REPORT=FILE`` appends one JSON line per command -- ``{"command", "tried", "exit_0",
"exit_1", "exit_2", "exit_130", "defects": [...]}`` -- and lets a command's run go on past a defect
(each is listed; the test still fails at the end of that command), with fresh random examples::

    GEARKIT_FUZZ_EXAMPLES=1250 GEARKIT_FUZZ_REPORT=cli-fuzz.jsonl nice python -m pytest tests/test_cli_fuzz.py
"""
import contextlib
import io
import json
import os
import signal
import tempfile
from collections import Counter
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from gearkit.cli import COMMANDS, build_parser, main

EXAMPLES = int(os.environ.get("GEARKIT_FUZZ_EXAMPLES", "125"))
SECONDS = float(os.environ.get("GEARKIT_FUZZ_SECONDS", "0.4"))
ALLOWED = {0, 1, 2, 130}
REPORT = os.environ.get("GEARKIT_FUZZ_REPORT")

def _import_everything() -> None:
    """Import gearkit's modules and the libraries they load lazily, once, before any timer runs.

    In a real process an interrupt ends the process; here the next example runs in the same
    interpreter, and a library whose first import was cut short is left half-registered.
    """
    import importlib
    import pkgutil

    import gearkit

    for mod in pkgutil.walk_packages(gearkit.__path__, "gearkit."):
        if mod.name.endswith("__main__"):  # running it would run the command line
            continue
        try:
            importlib.import_module(mod.name)
        except ImportError:  # an optional extra that is not installed (e.g. the STEP writer)
            pass
    for lib in ("ezdxf", "trimesh", "manifold3d", "matplotlib.backends.backend_agg",
                "matplotlib.backends.backend_svg", "scipy.optimize", "scipy.spatial"):
        try:
            importlib.import_module(lib)
        except ImportError:
            pass


_import_everything()
PARSER = build_parser()
SUBPARSERS = next(a for a in PARSER._actions if a.dest == "command").choices

HOSTILE_NUMBERS = ["0", "-1", "-0", "nan", "inf", "-inf", "1e308", "-1e308", "1e-300", "2e9", "99999999999999999999",
                   "0x10", "1_000", " 3", "3.", ".5", "1e", "--1"]
SUFFIXES = ["svg", "dxf", "csv", "json", "png", "stl", "obj", "glb", "3mf", "step", "html", "toml", "txt", ""]
WORDS = ["", "-", "--", "standard", "x", "1,2", "0.5,0.3", "3x1.4", "a,b,c,d", "1,2,3,4", "dca24", "é", "--json"]


def _text():
    return st.text(alphabet=st.characters(blacklist_categories=("Cs", "Cc")), max_size=8)


def _path(scratch: Path):
    """Paths a user might give: fresh names of every suffix, a folder, a missing folder, a binary file."""
    return st.one_of(
        st.sampled_from(SUFFIXES).map(lambda s: str(scratch / f"out.{s}")),
        st.sampled_from([str(scratch / "folder.svg"), str(scratch / "missing" / "x.png"), str(scratch / "bin.toml"),
                         str(scratch / "afile"), str(scratch), "", "."]),
    )


#: plausible values (half the command lines use only these: the legal paths get exercised too)
PLAUSIBLE_FLOATS = ["0", "0.1", "0.25", "0.5", "1", "2", "5", "10", "20", "40"]
PLAUSIBLE_WORDS = ["standard", "0.5,0.3", "3x1.4", "1,2,3,4", "20,40", "12:20:4"]
PLAUSIBLE_SUFFIXES = ["svg", "dxf", "csv", "json", "png", "stl", "html"]
#: flags a plausible line always gives (a pair command takes them or a design file)
CORE = {"z1", "z2", "module", "teeth"}


def _plausible(action, scratch: Path):
    """A value a user would give: a listed choice, a small number in the flag's range, a fresh file name."""
    if action.choices is not None:
        return st.sampled_from(sorted(map(str, action.choices)))
    kind = getattr(action.type, "kind", action.type)  # a vocabulary Quantity says its kind and range
    lo, hi = getattr(action.type, "lo", None), getattr(action.type, "hi", None)
    if kind is int:
        low = 3 if lo is None else max(int(lo), 3)
        return st.integers(low, max(low, min(60, int(hi) if hi is not None else 60))).map(str)
    if kind is float:
        values = [v for v in PLAUSIBLE_FLOATS if (lo is None or float(v) > lo) and (hi is None or float(v) < hi)]
        return st.sampled_from(values or PLAUSIBLE_FLOATS)
    return st.one_of(st.sampled_from(PLAUSIBLE_SUFFIXES).map(lambda x: str(scratch / f"out.{x}")),
                     st.sampled_from(PLAUSIBLE_WORDS))


def _plain(action) -> bool:
    """A switch, a choice, a number or the output file: what a plausible line may add."""
    kind = getattr(action.type, "kind", action.type)
    return action.nargs == 0 or action.choices is not None or kind in (int, float) or action.dest == "output"


def _value(action, scratch: Path):
    if action.choices is not None:
        return st.one_of(st.sampled_from(sorted(map(str, action.choices))), _text())
    kind = getattr(action.type, "kind", action.type)
    if kind is int:
        return st.one_of(st.integers(-3, 60).map(str), st.sampled_from(HOSTILE_NUMBERS), st.integers().map(str))
    if kind is float:
        return st.one_of(st.floats(-5, 60).map(repr), st.sampled_from(HOSTILE_NUMBERS),
                         st.floats(allow_nan=True, allow_infinity=True).map(repr))
    return st.one_of(_path(scratch), st.sampled_from(WORDS), _text(), st.sampled_from(HOSTILE_NUMBERS))


def _takes_value(action) -> bool:
    return action.nargs != 0


def _tokens(action, scratch: Path, plausible: bool = False):
    """The tokens of one use of ``action`` (its flag and value(s))."""
    flag = st.sampled_from(action.option_strings) if action.option_strings else st.just(None)
    n = action.nargs
    count = 0 if n == 0 else (n if isinstance(n, int) else 1)
    if n in ("*", "+"):
        count = 2
    value = _plausible(action, scratch) if plausible else _value(action, scratch)
    values = st.lists(value, min_size=count, max_size=count)
    return st.tuples(flag, values).map(lambda fv: ([fv[0]] if fv[0] else []) + fv[1])


@st.composite
def argv_for(draw, name: str, scratch: Path):
    parser = SUBPARSERS[name]
    actions = [a for a in parser._actions if a.dest != "help"]
    out = [name]
    plausible = draw(st.booleans())  # only plausible values, fewer optional flags, no stray token
    taken = set()  # plausible lines use one flag of a mutually exclusive group
    exclusive = {id(a): g for g in parser._mutually_exclusive_groups for a in g._group_actions}
    for action in actions:
        if not action.option_strings:  # positional
            if action.nargs in ("?", "*") and (plausible or draw(st.booleans())):
                continue
            out += draw(_tokens(action, scratch, plausible))
        elif plausible and action.dest in CORE and not action.required:  # the pair a design file would give
            out += draw(_tokens(action, scratch, True))
        elif plausible and not action.required and not _plain(action):
            continue  # free text (keyways, windows, files) stays for the hostile half
        elif action.required or draw(st.integers(0, 7 if plausible else 3)) == 0:
            group = exclusive.get(id(action))
            if plausible and group is not None:
                if id(group) in taken:
                    continue
                taken.add(id(group))
            out += draw(_tokens(action, scratch, plausible))
    if not plausible and draw(st.integers(0, 5)) == 0:
        out.insert(draw(st.integers(1, len(out))), draw(st.sampled_from(WORDS + HOSTILE_NUMBERS)))
    return out


def _scratch() -> Path:
    root = Path(tempfile.mkdtemp(prefix="gearkit-fuzz-"))
    (root / "folder.svg").mkdir()
    (root / "bin.toml").write_bytes(b"\xff\xfe\x00\x01")
    (root / "afile").write_text("not a folder")
    return root


class _Timer:
    """Interrupt a run after ``SECONDS`` as Ctrl-C would (exit 130 is a legal answer)."""

    returned = False  # set as soon as main returns: a late alarm is the harness's, not the command's

    def __enter__(self):
        def fire(signum, frame):
            if not self.returned:
                raise KeyboardInterrupt

        self.previous = signal.signal(signal.SIGALRM, fire)
        signal.setitimer(signal.ITIMER_REAL, SECONDS)
        return self

    def __exit__(self, *exc):
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, self.previous)
        return False


def _strict_json(text: str):
    def bad(name):
        raise ValueError(f"non-strict JSON constant {name}")

    return json.loads(text, parse_constant=bad)


def run_one(argv, scratch: Path):
    out, err = io.StringIO(), io.StringIO()
    cwd = os.getcwd()
    os.chdir(scratch)
    try:
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err), _Timer() as timer:
            try:
                code = main(list(argv))
            except KeyboardInterrupt:  # a real process would print a traceback
                raise AssertionError(f"gearkit {' '.join(map(repr, argv))}: Ctrl-C escaped main") from None
            timer.returned = True
    finally:
        os.chdir(cwd)
    return code, out.getvalue(), err.getvalue()


@pytest.mark.parametrize("name", sorted(SUBPARSERS))
def test_cli_fuzz(name):
    scratch = _scratch()

    counts, defects = Counter(), []

    @settings(max_examples=EXAMPLES, deadline=None, derandomize=not REPORT, database=None,
              suppress_health_check=list(HealthCheck))
    @given(argv=argv_for(name, scratch))
    def check(argv):
        code, out, err = run_one(argv, scratch)
        counts["tried"] += 1
        counts[f"exit_{code}"] += 1
        try:
            _judge(argv, code, out, err, scratch)
        except AssertionError as exc:
            if not REPORT:
                raise
            defects.append(str(exc)[:2000])
            for part in scratch.rglob("*.part"):  # the next example starts clean
                part.unlink()

    check()
    if REPORT:
        with open(REPORT, "a") as fh:
            fh.write(json.dumps({"command": name, **{k: counts[k] for k in sorted(counts)},
                                 "defects": defects}) + "\n")
    assert defects == [], defects[0] if defects else ""


def _judge(argv, code, out, err, scratch):
    """The promises every run keeps (AssertionError naming the command line otherwise)."""
    where = f"gearkit {' '.join(map(repr, argv))}\nstderr: {err[-800:]}"
    assert code in ALLOWED, where
    assert "Traceback" not in err and "Traceback" not in out, where
    if code == 2:
        assert err.strip(), where
    if code in (0, 1) and "--json" in argv and out.strip():
        try:
            _strict_json(out)
        except ValueError as exc:
            raise AssertionError(f"{where}\nstdout is not strict JSON: {exc}") from None
    parts = [p.name for p in scratch.rglob("*") if p.name.endswith(".part")]
    assert parts == [], where


def test_every_registered_command_is_fuzzed():
    """The fuzz covers what the parser registers: a new command is fuzzed without touching this file."""
    assert set(SUBPARSERS) >= set(COMMANDS)
    assert len(COMMANDS) >= 14
