"""The command line under random and hostile argument vectors (issue 13).

For every command registered in ``gearkit.cli.COMMANDS`` (new commands are covered by
construction), argument vectors are drawn in three kinds, a third each:

- *hostile*: the command's own argparse actions with values of the declared type, hostile numbers
  (0, negative, huge, nan, inf), unknown choices, paths that are folders, missing folders, binary
  files, and stray tokens;
- *plausible*: only listed choices, small numbers inside a flag's declared range and fresh file names;
- *realistic*: a small valid line of the command (``tests/cli_examples.py``) with flags added or
  changed from :data:`REALISTIC`, a table of values a user would type per flag (the vocabulary's
  quantities at cheap sizes: few teeth, coarse tolerances, few steps, tiny atlas grids), so that the
  vectors reach the command's real work. At least :data:`REACH` of them must end in 0 or 1 (a run
  that stops at argument checking does not count), per command.

Each vector runs in-process through ``gearkit.cli.main`` in a scratch folder, with a CPU-time timer
(so a loaded machine does not cut runs short) that interrupts a long run as Ctrl-C would: 0.25 s, and a
second for a realistic line (two for a page of ``view``); and a wall-clock one at ``WALL`` times that, for the
time a run waits on a child process, whose CPU the first does not count (the bench measures in child
processes; a run waiting on them was never interrupted: once, 838 s of one worker's time in the suite). Asserted
for every run:

- the exit status is 0, 1, 2 or 130 (never 70, an internal error, nor anything else);
- no traceback on stdout or stderr, and an exit 2 says why on stderr;
- on 0 or 1 with ``--json``, stdout is one strict JSON value (no NaN/Infinity);
- no partial file (``*.part``) is left in the scratch folder.

About 1600 examples in all (a few minutes of CPU). ``GEARKIT_FUZZ_EXAMPLES=N`` runs N per command (a
third of that for the bench; e.g. 5000 for a long run) and ``GEARKIT_FUZZ_SECONDS`` sets the CPU
budget of a hostile or plausible run (default 0.25 s; a realistic run gets four times as much, a page
of ``view`` eight). ``GEARKIT_FUZZ_REPORT=FILE`` appends one JSON line per command
-- ``{"command", "tried", "exit_0", "exit_1", "exit_2", "exit_130", "realistic", "realistic_ran",
"defects": [...]}`` -- and lets a command's run go on past a defect (each is listed; the test still
fails at the end of that command), with fresh random examples::

    GEARKIT_FUZZ_EXAMPLES=1250 GEARKIT_FUZZ_REPORT=cli-fuzz.jsonl nice python -m pytest tests/test_cli_fuzz.py
"""
import contextlib
import io
import itertools
import json
import os
import signal
import tempfile
from collections import Counter
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from cli_examples import EXAMPLES as CLI_EXAMPLES
from gearkit.cli import COMMANDS, build_parser, main
from gearkit.cli.vocabulary import QUANTITIES

EXAMPLES = int(os.environ.get("GEARKIT_FUZZ_EXAMPLES", "100"))
#: the bench has no cheap line (its quick run takes minutes): every line it runs meets the timer, so
#: fewer of them tell as much
BENCH_EXAMPLES = max(1, EXAMPLES // 3)
SECONDS = float(os.environ.get("GEARKIT_FUZZ_SECONDS", "0.25"))
WALL = 40.0  #: the wall-clock timer's budget over the CPU one's
ALLOWED = {0, 1, 2, 130}
#: the shipped examples (design and scene files)
EXAMPLES_DIR = Path(__file__).resolve().parent.parent / "examples"
#: the least share of a command's realistic vectors that must end in 0 or 1 (real work done)
REACH = 0.4
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


#: values a user would type, per quantity of the vocabulary (cheap sizes)
QUANTITY_VALUES = {"teeth": ["12", "17", "20", "25", "31"], "module": ["0.5", "1", "2", "3.5"],
                   "shift": ["-0.3", "0", "0.25", "0.5"], "helix_angle_deg": ["0", "10", "-15", "20"],
                   "pressure_angle_deg": ["14.5", "20", "25"], "width": ["5", "10", "20"], "bar_teeth": ["1", "3", "8"]}
#: values a user would type, per argparse destination (a command's own options); a destination of a
#: quantity takes QUANTITY_VALUES, a choice its choices, a switch nothing; any other is left out
REALISTIC = {
    "tol": {"blocking": ["1e-2", "5e-3"], "atlas": ["1e-2"], None: ["0.05", "0.02", "0.01"]},
    "steps": ["32", "64", "100"], "samples": ["100", "200"], "sweep": ["2", "3"],
    "cycles": ["1"], "slices": ["1", "3"], "cutter_teeth": ["12", "20", "25"], "pinion_cutter_teeth": ["12", "20"],
    "cutter_shift": ["0", "0.1"], "cutter_addendum": ["1.25"], "addendum": ["1", "0.8"], "thinning": ["0", "0.05"],
    "thinning1": ["0", "0.05"], "thinning2": ["0", "0.05"], "bore": ["6", "8"], "bore1": ["6"], "bore2": ["8"],
    "keyway": ["2x1"], "keyway1": ["2x1"], "keyway2": ["2x1"], "rim": ["4", "6"], "gap": ["2"], "angle_deg": ["0", "7"],
    "prime_radius": ["30", "40", "50"], "roller_radius": ["5", "8"], "rise": ["5", "10"], "rise_deg": ["60", "90"],
    "return_deg": ["60", "90"], "dwell_deg": ["0", "30"], "offset": ["0", "5"], "friction": ["0.05", "0.1"],
    "limit_deg": ["30", "35"], "pivot_distance": ["60"], "arm_length": ["40"], "pin_radius": ["0.2", "0.4"],
    "dedendum": ["1.2"], "lobes": ["11"], "pins": ["12"], "pin_circle_radius": ["60", "90"], "eccentricity": ["3", "4"],
    "equidistant_mod": ["0", "0.02"], "shift_mod": ["0", "0.02"], "output_pins": ["4", "6"], "points": ["40"],
    "workers": ["1"], "torque": ["10", "50"], "crowning": ["0", "0.005"], "misalignment": ["0", "1e-4"],
    "runout1": ["0", "0.005"], "runout2": ["0", "0.005"], "min_overlap_ratio": ["1.1"], "min_contact_ratio": ["1.1"],
    "min_tip_thickness": ["0.2"], "min_tip_clearance": ["0.1"], "ratio": ["4.5", "5", "6.1428571"], "planets": ["3", "4"],
    "ratio_tol": ["1e-3", "1e-2"], "max_teeth": ["60", "80"], "min_teeth": ["12", "17"], "sets": ["1", "3"],
    "angle": ["0", "10"], "rack": ["standard", "iso53a", "dca24", "single-arc"],
    "fidelity": ["formula", "generated", "solid"],  # not simulated: seconds of contact per mesh
    "z1": {"atlas": ["13", "15", "12:14:2"]}, "z2": {"atlas": ["16", "20", "17,19"]},
}
#: per command, the outputs a user would name (a fresh file in the scratch folder)
OUTPUTS = {"gear": ["svg", "dxf", "csv", "json", "stl", "obj", "glb", "3mf"], "rack": ["svg", "dxf", "stl"],
           "pair": ["stl", "obj", "glb"], "novikov": ["svg", "stl"], "cycloid": ["svg", "dxf"],
           "cycloidal-drive": ["svg", "stl"], "cam": ["svg", "stl", "html"], "scene": ["svg", "glb", "stl"],
           "blocking": ["png", "svg", "json"], "contact": ["png"], "view": ["html"]}
#: what a flag needs beside it to mean something (a user adds it too): destination -> tokens, per command
#: (None: any); "{o}" is a fresh solid file
SOLID = ["-o", "{o}", "--width", "5"]
COMPANIONS = {
    "cutter_teeth": {"gear": ["--internal"], "rack": [], None: ["--internal"]},
    "width": {k: ["-o", "{o}"] for k in ("gear", "rack", "cycloid", "cycloidal-drive", "cam")},
    "herringbone": {"gear": SOLID + ["--helix-angle-deg", "20"], None: ["-o", "{o}", "--helix-angle-deg", "20"]},
    "gap": {"gear": SOLID + ["--herringbone", "--helix-angle-deg", "20"],
            None: ["-o", "{o}", "--herringbone", "--helix-angle-deg", "20"]},
    "bore": {"gear": SOLID, "cam": SOLID, None: ["-o", "{o}"]},
    "keyway": {"gear": SOLID + ["--bore", "8"], "cam": SOLID + ["--bore", "10"], None: ["-o", "{o}", "--bore", "10"]},
    "bore1": {None: ["-o", "{o}"]}, "bore2": {None: ["-o", "{o}"]}, "keyway1": {None: ["-o", "{o}", "--bore1", "6"]},
    "keyway2": {None: ["-o", "{o}", "--bore2", "8"]}, "rim": {None: SOLID + ["--internal", "--cutter-teeth", "20"]},
    "ascii": {"gear": SOLID, "cam": SOLID, None: ["-o", "{o}"]}, "tip_rule": {"gear": ["--mate-teeth", "30"]},
    "torque": {"contact": ["--width", "10"]}, "split": {None: ["--center-distance", "60"]},
    **{k: {"contact": ["--torque", "20", "--width", "10"]} for k in ("crowning", "misalignment", "runout1", "runout2")},
    "groove": {"cam": ["--contact", "roller"]}, "pivot_distance": {"cam": ["--rocker", "--arm-length", "40", "--offset", "0"]},
    "arm_length": {"cam": ["--rocker", "--pivot-distance", "60", "--offset", "0"]},
}


def _realistic_values(command: str, action, scratch: Path):
    """The table's values of ``action`` in ``command`` (a list of strings), or None when it has none."""
    if action.nargs == 0:
        return None
    if action.dest == "output" and command in OUTPUTS:
        return [str(scratch / f"real.{suffix}") for suffix in OUTPUTS[command]]
    table = REALISTIC.get(action.dest)
    if isinstance(table, dict):
        table = table.get(command, table.get(None))
    quantity = next((k for k, q in QUANTITIES.items() if action.type is q), None)
    values = table if table is not None else QUANTITY_VALUES.get(quantity)
    if values is None and action.choices is not None:
        values = sorted(map(str, action.choices))
    if values is not None and action.choices is not None:
        values = [v for v in values if v in map(str, action.choices)] or sorted(map(str, action.choices))
    return values or None


def _parser_of(argv):
    parser = SUBPARSERS[argv[0]]
    subs = [a for a in parser._actions if a.dest == "what"]
    return subs[0].choices[argv[1]] if subs else parser


@st.composite
def realistic_argv(draw, name: str, scratch: Path):
    """A small valid line of the command with up to three flags added or changed from the table."""
    examples = [[a.replace("{t}", str(scratch)).replace("examples/", f"{EXAMPLES_DIR}/") for a in argv]
                for argv in CLI_EXAMPLES.get(name, []) if argv and argv[0] == name]
    if not examples:  # the bench: no cheap line exists
        return [name, "--quick"]
    out = list(draw(st.sampled_from(examples)))
    parser = _parser_of(out)
    exclusive = {id(a): g for g in parser._mutually_exclusive_groups for a in g._group_actions}
    options = []
    for action in parser._actions:
        if not action.option_strings or action.dest == "help" or isinstance(action.default, str) and \
                action.default == "==SUPPRESS==":
            continue
        group = exclusive.get(id(action))
        if group is not None and any(s in out for a in group._group_actions if a is not action
                                     for s in a.option_strings):
            continue
        if action.nargs == 0 and action.dest not in ("json",):
            options.append((action, None))
            continue
        values = _realistic_values(name, action, scratch)
        if values is not None and action.nargs in (None, "?"):
            options.append((action, values))
    for action, values in draw(st.lists(st.sampled_from(options), max_size=3, unique_by=lambda o: id(o[0]))) \
            if options else []:
        out.append(action.option_strings[-1])
        if values is not None:
            out.append(draw(st.sampled_from(values)))
        needs = COMPANIONS.get(action.dest, {})
        needs = needs.get(name, needs.get(None, []))
        for k, token in enumerate(needs):
            if not token.startswith("-"):
                continue
            value = needs[k + 1: k + 2] if k + 1 < len(needs) and not needs[k + 1].startswith("-") else []
            if token not in out:  # what the line already says stays
                out += [token, *value]
    if name == "atlas":  # a fresh dataset: an atlas resumes only with the same template and options
        out += ["-o", str(scratch / f"atlas-{next(FRESH)}")]
    fresh = str(scratch / "real.stl")
    out = [fresh if t == "{o}" else t for t in out]
    if "--json" in {s for a in parser._actions for s in a.option_strings} and draw(st.booleans()):
        out.append("--json")
    return out


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
def argv_for(draw, name: str, scratch: Path, plausible: bool):
    """A hostile line, or a plausible one: only plausible values, fewer optional flags, no stray token."""
    parser = SUBPARSERS[name]
    actions = [a for a in parser._actions if a.dest != "help"]
    out = [name]
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


KINDS = ("hostile", "plausible", "realistic")
#: a realistic line's CPU budget in SECONDS (4 by default): a drive's page simulates its whole mesh cycle
REALISTIC_BUDGET = {"view": 8}
FRESH = itertools.count()  # names of fresh folders


def vectors(name: str, scratch: Path):
    """``{kind: argv}``: a hostile, a plausible and a realistic line of command ``name`` (the test runs
    one of them in turn, so each kind gets a third of the examples)."""
    return st.fixed_dictionaries({"hostile": argv_for(name, scratch, False), "plausible": argv_for(name, scratch, True),
                                  "realistic": realistic_argv(name, scratch)})


class _Timer:
    """Interrupt a run after ``seconds`` of CPU time, or ``WALL`` times that of wall-clock time, as Ctrl-C would
    (exit 130 is a legal answer)."""

    returned = False  # set as soon as main returns: a late alarm is the harness's, not the command's

    def __init__(self, seconds: float):
        self.seconds = seconds

    def __enter__(self):
        def fire(signum, frame):
            if not self.returned:
                raise KeyboardInterrupt

        self.previous = signal.signal(signal.SIGPROF, fire), signal.signal(signal.SIGALRM, fire)
        signal.setitimer(signal.ITIMER_PROF, self.seconds)
        signal.setitimer(signal.ITIMER_REAL, WALL * self.seconds)
        return self

    def __exit__(self, *exc):
        signal.setitimer(signal.ITIMER_PROF, 0)
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGPROF, self.previous[0])
        signal.signal(signal.SIGALRM, self.previous[1])
        return False


def _strict_json(text: str):
    def bad(name):
        raise ValueError(f"non-strict JSON constant {name}")

    return json.loads(text, parse_constant=bad)


def run_one(argv, scratch: Path, seconds: float = SECONDS):
    out, err = io.StringIO(), io.StringIO()
    cwd = os.getcwd()
    os.chdir(scratch)
    try:
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err), _Timer(seconds) as timer:
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

    @settings(max_examples=BENCH_EXAMPLES if name == "bench" else EXAMPLES, deadline=None, derandomize=not REPORT, database=None,
              suppress_health_check=list(HealthCheck))
    @given(vector=vectors(name, scratch))
    def check(vector):
        kind = KINDS[counts["tried"] % 3] if name != "bench" else KINDS[counts["tried"] % 2]  # the bench has no
        argv = vector[kind]  # cheap line: its quick run takes minutes
        code, out, err = run_one(argv, scratch, REALISTIC_BUDGET.get(name, 4) * SECONDS if kind == "realistic"
                                 else SECONDS)
        counts["tried"] += 1
        counts[f"exit_{code}"] += 1
        if kind == "realistic":
            counts["realistic"] += 1
            counts["realistic_ran"] += code in (0, 1)
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
    if name != "bench":
        assert counts["realistic_ran"] >= REACH * counts["realistic"], (
            f"{name}: only {counts['realistic_ran']} of {counts['realistic']} realistic lines reached the work")


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
