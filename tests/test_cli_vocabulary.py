"""Issue 13, one vocabulary: each rule walks every registered command, so a new command that breaks
a rule fails here. The commands' small valid command lines are in ``tests/cli_examples.py``.
"""
import argparse
import json
import re

import pytest

from cli_examples import EXAMPLES
from gearkit.cli import build_parser, main
from gearkit.cli.common import RACKS, TIP_RULES
from gearkit.cli.parser import RenamedFlag

PARSER = build_parser()
COMMANDS = next(a for a in PARSER._actions if a.dest == "command").choices


def parsers():
    """``(name, parser)`` of every command and sub-command (``view pair``, ``view drive``)."""
    out = []
    for name, p in sorted(COMMANDS.items()):
        subs = [a for a in p._actions if isinstance(a, argparse._SubParsersAction)]
        if subs:
            out += [(f"{name} {n}", sp) for n, sp in sorted(subs[0].choices.items())]
        else:
            out.append((name, p))
    return out


def flag_actions(parser):
    """``{flag: action}`` of a parser's optional arguments (help excluded)."""
    return {s: a for a in parser._actions if a.option_strings and a.dest != "help" for s in a.option_strings}


def run(capsys, argv, tmp_path):
    code = main([a.replace("{t}", str(tmp_path)) for a in argv])
    out, err = capsys.readouterr()
    return code, out, err


def test_every_command_has_an_example():
    missing = sorted(set(COMMANDS) - set(EXAMPLES))
    assert missing == []


# ----------------------------------------------------------------------------- rack names

def test_rack_names_are_one_list():
    from gearkit.families.involute import RACK_NAMES
    from gearkit.pair.spec import TIP_RULES as SPEC_TIP_RULES

    assert RACKS == RACK_NAMES and set(TIP_RULES) == set(SPEC_TIP_RULES)


@pytest.mark.parametrize("name, parser", parsers(), ids=[n for n, _ in parsers()])
def test_standard_names_the_default_rack_wherever_a_rack_is_named(name, parser):
    """``--rack standard`` is accepted by every command with a ``--rack``, and is its default."""
    action = flag_actions(parser).get("--rack")
    if action is None:
        return
    assert action.choices is None or "standard" in action.choices, name
    assert action.default == "standard", name


@pytest.mark.parametrize("argv", [argv for argvs in EXAMPLES.values() for argv in argvs
                                  if "--rack" in flag_actions(
                                      dict(parsers()).get(" ".join(argv[:2]), COMMANDS[argv[0]]))],
                         ids=lambda a: a[0])
def test_rack_standard_runs_as_the_default(capsys, tmp_path, argv):
    """End to end: the example with ``--rack standard`` gives the same result as without it."""
    json_argv = argv + (["--json"] if "--json" in flag_actions(COMMANDS[argv[0]]) else [])
    code, out, _ = run(capsys, json_argv, tmp_path)
    code_std, out_std, _ = run(capsys, json_argv + ["--rack", "standard"], tmp_path)
    assert code_std == code and code in (0, 1)
    if "--json" in json_argv:
        a, b = json.loads(out), json.loads(out_std)
        for d in (a, b):
            d.get("pair", {}).pop("seconds", None)
            d.pop("seconds", None)
        assert a == b


def test_design_files_name_the_racks_as_the_flags_do(tmp_path):
    from gearkit.checks import load_design
    from gearkit.families.involute import BasicRack

    f = tmp_path / "d.toml"
    for name, rack in (("standard", BasicRack()), ("rack", BasicRack()), ("iso53c", BasicRack.iso53("C"))):
        f.write_text(f'module = 2.0\n[gear1]\nteeth = 18\ntool = "{name}"\n[gear2]\nteeth = 41\n')
        assert load_design(f)[0].tools[0] == rack


# ----------------------------------------------------------------------------- the tool's one spelling

TOOL = re.compile(r"^(rack \((standard basic rack|ISO 53 [ABCD]|h_aP\* .*)(, \d+(\.\d+)? deg)?\)"
                  r"|shaper cutter z0=\d+(, .*)?)$")


def _tools_in(obj):
    if isinstance(obj, dict):
        for k, v in obj.items():
            if k in ("tool", "tools"):
                yield from (v if isinstance(v, list) else [v])
            else:
                yield from _tools_in(v)
    elif isinstance(obj, list):
        for v in obj:
            yield from _tools_in(v)


def test_every_json_output_spells_the_tool_by_tool_label(capsys, tmp_path):
    """Every ``tool``/``tools`` value in any command's JSON is a :func:`tool_label` spelling."""
    seen = []
    for argvs in EXAMPLES.values():
        for argv in argvs:
            if "--json" not in flag_actions(dict(parsers()).get(" ".join(argv[:2]), COMMANDS[argv[0]])):
                continue
            code, out, _ = run(capsys, argv + ["--json"], tmp_path)
            assert code in (0, 1), argv
            seen += list(_tools_in(json.loads(out)))
    assert seen and all(isinstance(t, str) and TOOL.match(t) for t in seen), sorted(set(map(str, seen)))
    assert {"rack (standard basic rack)", "shaper cutter z0=20", "shaper cutter z0=25"} <= set(seen)


@pytest.mark.parametrize("argv, label", [
    (["gear", "-z", "20", "-m", "2"], "rack (standard basic rack)"),
    (["gear", "-z", "20", "-m", "2", "--rack", "iso53d"], "rack (ISO 53 D)"),
    (["gear", "-z", "20", "-m", "2", "--pressure-angle-deg", "25"], "rack (standard basic rack, 25 deg)"),
    (["gear", "-z", "20", "-m", "2", "--cutter-teeth", "18"], "shaper cutter z0=18"),
    (["check", "--z1", "18", "--z2", "61", "-m", "2", "--internal", "--cutter-teeth", "25", "--cutter-addendum",
      "1.3"], "shaper cutter z0=25, h_a0*=1.3"),
    (["check", "--z1", "18", "--z2", "41", "-m", "2", "--rack", "iso53b"], "rack (ISO 53 B)"),
])
def test_text_and_json_spell_the_tool_alike(capsys, tmp_path, argv, label):
    code, out, _ = run(capsys, argv, tmp_path)
    assert code in (0, 1) and label in out
    code, out, _ = run(capsys, argv + ["--json"], tmp_path)
    assert label in list(_tools_in(json.loads(out)))


# ----------------------------------------------------------------------------- one meaning per flag

#: flags whose destination differs in meaning between commands on purpose, with the reason
SAME_NAME_EXCEPTIONS = {
    "--rack": "novikov's names a circular-arc rack system (preset or file); the involute commands' a basic rack",
}
#: (command, flag) taking more values of the same quantity than elsewhere, with the reason
ARITY_EXCEPTIONS = {
    ("atlas", "--z1"): "a grid of pinion tooth numbers (START:STOP:STEP or a,b,c)",
    ("atlas", "--z2"): "a grid of wheel tooth numbers",
    ("atlas", "--criterion"): "the criteria of blocking that need no centre distance (a subset of its choices)",
    ("cycloid", "--addendum"): "one coefficient, or one per gear",
    ("contact", "-o"): "repeatable: one plot per file",
    ("contact", "--output"): "repeatable: one plot per file",
}


def _signature(action):
    kind = type(action).__name__.removeprefix("Given")  # gearkit.cli.parser.track_given's subclass
    return (kind, getattr(action.type, "__name__", action.type), tuple(sorted(action.choices or ())), action.nargs)


def test_one_flag_one_meaning():
    """A flag has one type, one set of choices and one arity in every command (``--pins`` is a count of
    pins everywhere; the pin radius is ``--pin-radius``)."""
    seen, clashes = {}, []
    for name, parser in parsers():
        for flag, action in flag_actions(parser).items():
            if isinstance(action, RenamedFlag) or flag in SAME_NAME_EXCEPTIONS or (name, flag) in ARITY_EXCEPTIONS:
                continue
            sig = _signature(action)
            first = seen.setdefault(flag, (name, sig))
            if first[1] != sig:
                clashes.append(f"{flag}: {first[0]} {first[1]} vs {name} {sig}")
    assert clashes == []


#: a pair command's per-gear flag --NAME1/--NAME2 is the single-gear flag --NAME of 'gearkit gear';
#: these stems have no single-gear flag (the pair's own quantities)
PAIR_ONLY_STEMS = {"--z": "the teeth, -z/--teeth of one gear", "--x": "the shift, -x/--shift of one gear",
                   "--allowance": "tooth thickness allowances (a pair's backlash)", "--runout": "mounting deviation"}


def test_per_gear_flags_are_the_single_gear_flags_numbered():
    """Tip diameter, thinning, bore, keyway: ``--tip-diameter`` / ``--tip-diameter1``, never ``--da1``."""
    gear = flag_actions(COMMANDS["gear"])
    odd = []
    for name, parser in parsers():
        for flag, action in flag_actions(parser).items():
            m = re.fullmatch(r"(--[a-z-]+?)([12])", flag)
            if m and not isinstance(action, RenamedFlag) and m[1] not in gear and m[1] not in PAIR_ONLY_STEMS:
                odd.append(f"{name}: {flag}")
    assert odd == []
    assert "--tip-rule" in flag_actions(COMMANDS["check"]) and "--tip-rule" in gear


@pytest.mark.parametrize("old, new", [
    (["cycloid", "-m", "1", "--pinion-teeth", "8", "--wheel-teeth", "64", "--pins", "0.4", "--json"],
     ["cycloid", "-m", "1", "--pinion-teeth", "8", "--wheel-teeth", "64", "--pin-radius", "0.4", "--json"]),
    (["check", "--z1", "18", "--z2", "41", "-m", "2", "--da1", "39.5", "--tip", "standard", "--json"],
     ["check", "--z1", "18", "--z2", "41", "-m", "2", "--tip-diameter1", "39.5", "--tip-rule", "standard", "--json"]),
    (["rack", "-m", "2", "--count", "3", "--json"], ["rack", "-m", "2", "--bar-teeth", "3", "--json"]),
    (["planetary", "--ratio", "6.1428571", "--planets", "3", "-m", "1.75", "--ratio-tol", "1e-6", "--count", "2",
      "--json"],
     ["planetary", "--ratio", "6.1428571", "--planets", "3", "-m", "1.75", "--ratio-tol", "1e-6", "--sets", "2",
      "--json"]),
])
def test_a_renamed_flag_keeps_working_with_a_deprecation_line(capsys, tmp_path, old, new):
    code_old, out_old, err_old = run(capsys, old, tmp_path)
    code_new, out_new, err_new = run(capsys, new, tmp_path)
    assert code_old == code_new and json.loads(out_old) == json.loads(out_new)
    assert "is deprecated, use -" in err_old and "deprecated" not in err_new
    # the old and the new spelling together are refused
    both = new + [old[old.index(f)] for f in old if f in ("--pins", "--da1", "--count")] + ["1"]
    assert run(capsys, both, tmp_path)[0] == 2


#: long flag names that do not say what they count or name (a flag says its quantity: --planets, --sets,
#: --bar-teeth, --steps), kept only as a renamed flag's deprecated spelling
VAGUE = ("--count", "--number", "--num", "--n", "--amount", "--size", "--value", "--file")


@pytest.mark.parametrize("name, parser", parsers(), ids=[n for n, _ in parsers()])
def test_a_flag_says_what_it_counts(name, parser):
    """``--count`` meant teeth in one command and listed sets in another: no flag is that vague."""
    vague = [f for f, a in flag_actions(parser).items() if f in VAGUE and not isinstance(a, RenamedFlag)]
    assert vague == [], name


@pytest.mark.parametrize("name, parser", parsers(), ids=[n for n, _ in parsers()])
def test_a_design_file_is_the_first_argument_everywhere(name, parser):
    """Every command that reads a design file takes it the one way (cli.design.add_design_argument: the
    first argument, flags typed overriding it); an older ``--design FILE`` is only a deprecated spelling."""
    positional = [a for a in parser._actions if a.dest == "design" and not a.option_strings]
    flagged = [a for a in parser._actions if a.dest == "design" and a.option_strings]
    assert all(isinstance(a, RenamedFlag) for a in flagged), name
    assert len(positional) == (name.split()[0] not in NO_DESIGN), name


# ----------------------------------------------------------------------------- printing

#: what a text report never shows: nan, inf, a negative zero (-0, -0.0000, -0.00e+00)
NOT_PRINTED = re.compile(r"\b(nan|inf|infinity)\b|(?<![\w.])-0(?:\.0*)?(?:e[+-]?\d+)?(?![\w.])", re.IGNORECASE)
#: designs that reach the printing edge cases: zero shifts summing to zero, spur pairs (a wheel's helix -0,
#: no axial pitch, no lead), a tight mesh (backlash round-off), a cycloid inflection
EDGE_CASES = [
    ["check", "--z1", "18", "--z2", "41", "-m", "2", "--x1", "0.3", "--x2", "-0.3"],
    ["check", "--z1", "30", "--z2", "30", "-m", "1", "--helix-angle-deg", "0", "--width", "10"],
    ["contact", "--z1", "18", "--z2", "41", "-m", "2", "--x1", "0.3", "--x2", "-0.3", "--steps", "60"],
    ["gear", "-z", "20", "-m", "2", "-x", "-0.0"],
    ["cycloidal-drive", "--pins", "12", "--lobes", "11", "--pin-circle-radius", "90", "--pin-radius", "7",
     "--eccentricity", "6", "--samples", "200"],
]


@pytest.mark.parametrize("argv", [argv for argvs in EXAMPLES.values() for argv in argvs] + EDGE_CASES,
                         ids=lambda a: " ".join(a[:3]))
def test_text_output_has_no_nan_inf_or_negative_zero(capsys, tmp_path, argv):
    code, out, err = run(capsys, argv, tmp_path)
    assert code in (0, 1), err
    bad = [ln for ln in out.splitlines() if NOT_PRINTED.search(ln)]
    assert bad == []


# ----------------------------------------------------------------------------- one range per quantity

#: every flag that sets a quantity of gearkit.cli.vocabulary.QUANTITIES
QUANTITY_FLAGS = {
    "teeth": ("-z", "--teeth", "--z1", "--z2", "--mate-teeth", "--pinion-teeth", "--wheel-teeth"),
    "module": ("-m", "--module"),
    "shift": ("-x", "--shift", "--x1", "--x2", "--mate-shift"),
    "helix_angle_deg": ("--helix-angle-deg",),
    "pressure_angle_deg": ("--pressure-angle-deg",),
    "width": ("--width",),
    "bar_teeth": ("-n", "--bar-teeth"),
}
#: numeric flags whose name looks like one of those quantities but is another, with the reason
NOT_THE_QUANTITY = {
    "--cutter-teeth": "a tool's teeth z0, [6, 1000]: checked by the cutter spec (cutter.teeth)",
    "--pinion-cutter-teeth": "a tool's teeth z0, as --cutter-teeth",
    "--span-teeth": "teeth spanned by the anvils",
    "--min-teeth": "a search limit", "--max-teeth": "a search limit",
    "--cutter-shift": "the cutter's own shift x0, [-1, 1.5]: checked by the cutter spec",
}
LOOKS_LIKE = re.compile(r"(^|_)(teeth|module|shift|helix_angle_deg|pressure_angle_deg|width)$")


def test_one_range_per_quantity_in_every_command():
    from gearkit.cli.vocabulary import QUANTITIES

    flag_quantity = {f: q for q, flags in QUANTITY_FLAGS.items() for f in flags}
    wrong = []
    for name, parser in parsers():
        for flag, action in flag_actions(parser).items():
            if isinstance(action, RenamedFlag) or (name, flag) in ARITY_EXCEPTIONS or flag in NOT_THE_QUANTITY:
                continue
            q = flag_quantity.get(flag)
            if q is None and LOOKS_LIKE.search(action.dest) and action.type in (int, float):
                wrong.append(f"{name} {flag}: a quantity flag without its QUANTITIES type")
            elif q is not None and action.type is not QUANTITIES[q]:
                wrong.append(f"{name} {flag}: {action.type!r} instead of {QUANTITIES[q]!r}")
    assert wrong == []


@pytest.mark.parametrize("flag, value, range_text", [
    ("--helix-angle-deg", "70", "(-60, 60) degrees"), ("--pressure-angle-deg", "50", "[1, 45) degrees"),
    ("-m", "0", "[0.0001, 10000] mm"), ("--width", "-5", "(0, 100000] mm"), ("--z1", "2", "[3, 100000]"),
    ("-x", "3.5", "[-3, 3]"), ("--x1", "-4", "[-3, 3]"),
])
def test_an_out_of_range_value_is_refused_alike_by_every_command(capsys, tmp_path, flag, value, range_text):
    """Every command with the flag refuses the value in one line naming the flag and the same range."""
    tried = 0
    for name, parser in parsers():
        if flag not in flag_actions(parser) or (name.split()[0], flag) in ARITY_EXCEPTIONS:
            continue
        base = next(a for a in EXAMPLES[name.split()[0]] if " ".join(a[:len(name.split())]) == name)
        code, out, err = run(capsys, base + [flag, value], tmp_path)
        lines = err.strip().splitlines()
        assert code == 2 and len(lines) == 1 and flag in lines[0] and range_text in lines[0], (name, err)
        tried += 1
    assert tried >= 1



@pytest.mark.parametrize("flag, value, needle", [
    ("--cutter-teeth", "3", ""), ("--pinion-cutter-teeth", "3", "[6, 1000]"),
    ("--cutter-shift", "0.3", "applies to a shaper cutter"), ("--cutter-addendum", "1.1", "applies to a shaper cutter"),
])
def test_a_refused_cutter_value_names_the_flag_typed(capsys, tmp_path, flag, value, needle):
    """A shaper cutter's value is refused naming the flag the user typed (not the API's ``cutter.teeth``), and a
    cutter flag where no shaper cuts the gears is refused rather than ignored (every command's first example
    is rack-cut)."""
    tried = 0
    for name, parser in parsers():
        if flag not in flag_actions(parser):
            continue
        base = next(a for a in EXAMPLES[name.split()[0]] if " ".join(a[:len(name.split())]) == name)
        assert "--cutter-teeth" not in base and "--internal" not in base, (name, base)
        code, out, err = run(capsys, base + [flag, value], tmp_path)
        lines = err.strip().splitlines()
        assert code == 2 and len(lines) == 1 and f"error: {flag}: " in lines[0] and needle in lines[0], (name, err)
        tried += 1
    assert tried >= 2


def test_the_centre_distance_split_is_refused_naming_its_flag(capsys, tmp_path):
    """A centre distance no balanced split reaches (Σx beyond both ends of the line of action) names --split."""
    code, out, err = run(capsys, ["check", "--z1", "20", "--z2", "40", "-m", "1", "--center-distance", "40"], tmp_path)
    assert code == 2 and err.count("\n") == 1 and "error: --split: " in err, err

# ----------------------------------------------------------------------------- design files

PAIR_TOML = """module = 2.0
helix_angle_deg = 15.0
face_width = 20.0
[gear1]
teeth = 18
shift = 0.3
[gear2]
teeth = 41
"""
NOVIKOV_TOML = 'z1 = 20\nz2 = 60\nmodule = 4\nhelix_angle_deg = 15\nwidth = 60\nrack = "single-arc"\nno_mesh = true\n'
DRIVE_TOML = "pins = 12\nlobes = 11\npin-circle-radius = 90\npin_radius = 7\neccentricity = 4\n"
FLAT = ["--z1", "18", "--z2", "41", "-m", "2"]
DRIVE_ARGS = ["--pins", "12", "--lobes", "11", "--pin-circle-radius", "90", "--pin-radius", "7", "--eccentricity", "3.5"]
#: command -> (design file, the command with the file and flags that override it, the same by flags alone)
DESIGN_CASES = {
    "gear": (PAIR_TOML, ["gear", "{f}", "--gear", "1", "-x", "0.5", "--json"],
             ["gear", "-z", "18", "-m", "2", "-x", "0.5", "--helix-angle-deg", "15", "--json"]),
    "check": (PAIR_TOML, ["check", "{f}", "--x1", "0.1", "--helix-angle-deg", "0", "--json"],
              ["check", *FLAT, "--x1", "0.1", "--width", "20", "--json"]),
    "pair": (PAIR_TOML, ["pair", "{f}", "--helix-angle-deg", "0", "--tol", "0.05", "--json"],
             ["pair", *FLAT, "--x1", "0.3", "--width", "20", "--tol", "0.05", "--json"]),
    "contact": (PAIR_TOML, ["contact", "{f}", "--helix-angle-deg", "0", "--steps", "60", "--json"],
                ["contact", *FLAT, "--x1", "0.3", "--width", "20", "--steps", "60", "--json"]),
    "view pair": (PAIR_TOML, ["view", "pair", "{f}", "--z2", "40", "--cycles", "1", "-o", "{t}/a.html"],
                  ["view", "pair", "--z1", "18", "--z2", "40", "-m", "2", "--x1", "0.3", "--helix-angle-deg", "15",
                   "--width", "20", "--cycles", "1", "-o", "{t}/b.html"]),
    "blocking": (PAIR_TOML, ["blocking", "{f}", "--z1", "17", "--tol", "1e-2", "--json"],
                 ["blocking", "--z1", "17", "--z2", "41", "-m", "2", "--helix-angle-deg", "15", "--tol", "1e-2",
                  "--json"]),
    "atlas": (PAIR_TOML, ["atlas", "{f}", "--z2", "40", "--tol", "1e-2", "--workers", "1", "--no-progress",
                          "-o", "{t}/a", "--json"],
              ["atlas", "--z1", "18", "--z2", "40", "-m", "2", "--helix-angle-deg", "15", "--tol", "1e-2",
               "--workers", "1", "--no-progress", "-o", "{t}/b", "--json"]),
    "novikov": (NOVIKOV_TOML, ["novikov", "{f}", "--rack", "standard", "--json"],
                ["novikov", "--z1", "20", "--z2", "60", "-m", "4", "--helix-angle-deg", "15", "--width", "60",
                 "--no-mesh", "--json"]),
    "cycloid": ("module = 1\npinion-teeth = 8\nwheel_teeth = 64\nclock = true\n",
                ["cycloid", "{f}", "--wheel-teeth", "40", "--json"],
                ["cycloid", "-m", "1", "--pinion-teeth", "8", "--wheel-teeth", "40", "--clock", "--json"]),
    "cycloidal-drive": (DRIVE_TOML, ["cycloidal-drive", "{f}", "--eccentricity", "3.5", "--samples", "100", "--json"],
                        ["cycloidal-drive", *DRIVE_ARGS, "--samples", "100", "--json"]),
    "rack": ('module = 2\nrack = "iso53b"\n', ["rack", "{f}", "-m", "3", "--json"],
             ["rack", "-m", "3", "--rack", "iso53b", "--json"]),
    "cam": ('[cam]\nprime_radius = 40\nroller_radius = 8\n[[motion]]\nkind = "rise"\nspan_deg = 90\nlift = 10\n'
            '[[motion]]\nkind = "return"\nspan_deg = 90\nlift = 10\n',
            ["cam", "{f}", "--roller-radius", "6", "--json"],
            ["cam", "--prime-radius", "40", "--roller-radius", "6", "--rise", "10", "--rise-deg", "90", "--return-deg",
             "90", "--json"]),
    "view drive": (DRIVE_TOML, ["view", "drive", "{f}", "--cycles", "1", "-o", "{t}/a.html"],
                   ["view", "drive", *DRIVE_ARGS[:-1], "4", "--cycles", "1", "-o", "{t}/b.html"]),
}
#: commands that take no design file, with the reason
NO_DESIGN = {"demo": "runs a built-in design", "bench": "measures the kernel; it describes no design",
             "scene": "its argument is a scene file (gears, shafts, carriers, meshes)",
             "planetary": "searches tooth numbers for a ratio; it describes no gear yet"}


def _comparable(out: str):
    data = json.loads(out)

    def clean(obj):
        if isinstance(obj, dict):
            return {k: clean(v) for k, v in obj.items() if k not in ("seconds", "path", "output", "dir")}
        if isinstance(obj, list):
            return [clean(v) for v in obj]
        return obj
    return clean(data)


@pytest.mark.parametrize("name", [n for n, _ in parsers()])
def test_every_gear_or_pair_command_reads_a_design_file_and_flags_override_it(capsys, tmp_path, name):
    parser = dict(parsers())[name]
    has_design = any(a.dest == "design" for a in parser._actions)
    if name.split()[0] in NO_DESIGN:
        return
    assert has_design and name in DESIGN_CASES, f"{name}: a command that describes a gear or pair reads a design file"
    text, with_file, by_flags = DESIGN_CASES[name]
    f = tmp_path / "design.toml"
    f.write_text(text)
    code_f, out_f, err_f = run(capsys, [a.replace("{f}", str(f)) for a in with_file], tmp_path)
    code_flags, out_flags, err_flags = run(capsys, by_flags, tmp_path)
    assert code_f == code_flags and code_f in (0, 1), (err_f, err_flags)
    if "--json" in with_file:
        assert _comparable(out_f) == _comparable(out_flags)
    else:
        assert (tmp_path / "a.html").read_bytes() == (tmp_path / "b.html").read_bytes()


def test_a_flag_typed_with_its_default_value_still_overrides_the_file(capsys, tmp_path):
    f = tmp_path / "d.toml"
    f.write_text(PAIR_TOML)
    spur = json.loads(run(capsys, ["check", str(f), "--helix-angle-deg", "0", "--json"], tmp_path)[1])
    assert spur["helix_angle_deg"] == 0.0 and spur["contact_ratio"]["overlap"] == 0.0


@pytest.mark.parametrize("text, needle", [
    ("pins = 12.5\n", "design: pins: 12.5 must be a whole number"),
    ("bogus = 1\n", "design: bogus: unknown key"),
    ("pins = 2\n", "pins: Z_b = 2 must be an integer in [3, 1000]"),
])
def test_a_bad_design_value_is_one_line_naming_the_key(capsys, tmp_path, text, needle):
    f = tmp_path / "d.toml"
    f.write_text(text + "lobes = 11\npin-circle-radius = 90\npin_radius = 7\neccentricity = 4\n")
    code, _, err = run(capsys, ["cycloidal-drive", str(f)], tmp_path)
    assert code == 2 and len(err.strip().splitlines()) == 1 and needle in err


# ----------------------------------------------------------------------------- --tol, --json, -o

#: commands without a --json report, with the reason
NO_JSON = {"demo": "writes a folder and prints the built-in design's report",
           "view pair": "writes a page; it prints only the line naming it", "view drive": "writes a page"}
#: commands that write no -o file, with the reason
NO_OUTPUT = {"demo": "writes several files into --out-dir (a folder)", "check": "a report only",
             "planetary": "a report only"}


@pytest.mark.parametrize("name, parser", parsers(), ids=[n for n, _ in parsers()])
def test_tol_json_and_output_mean_the_same_everywhere(name, parser):
    flags = flag_actions(parser)
    tol = flags.get("--tol")
    if tol is not None:  # a max deviation of the output: a length in mm, or (blocking, atlas) shift units, said
        assert "mm" in tol.help or "shift units" in tol.help, (name, tol.help)
    if name not in NO_JSON:
        assert "--json" in flags and flags["--json"].nargs == 0, name  # a flag, never a file
    if name not in NO_OUTPUT:
        assert {"-o", "--output"} <= set(flags), name
