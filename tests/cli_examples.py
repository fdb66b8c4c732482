"""A small valid command line of every registered command, for the tests that walk them all.

``EXAMPLES[name]`` lists argument vectors of command ``name`` (``{t}`` is a scratch folder), each
cheap (about a second) and chosen to reach the printing paths a rule is about (a spur Novikov pair
has no axial pitch; a pair's wheel has the opposite helix, -0 for a spur pair). A command missing
here fails ``test_every_command_has_an_example``, so a new command joins every walk.
"""
from gearkit.cli import MODULE_OF, COMMANDS

PAIR = ["--z1", "18", "--z2", "41", "-m", "2"]
DRIVE = ["--pins", "12", "--lobes", "11", "--pin-circle-radius", "90", "--pin-radius", "7", "--eccentricity", "4"]
NOVIKOV = ["--z1", "20", "--z2", "60", "-m", "4", "--width", "60", "--no-mesh"]
CAM = ["--prime-radius", "40", "--roller-radius", "8", "--rise", "10", "--rise-deg", "90", "--return-deg", "90"]

EXAMPLES = {
    "demo": [["demo", "--out-dir", "{t}/demo"]],
    "gear": [["gear", "-z", "20", "-m", "2"], ["gear", "-z", "40", "-m", "2", "--internal", "--cutter-teeth", "20"]],
    "rack": [["rack", "-m", "2"]],
    "check": [["check", *PAIR], ["check", "--z1", "18", "--z2", "61", "-m", "2", "--internal", "--cutter-teeth", "25"]],
    "pair": [["pair", *PAIR, "--width", "5"]],
    "bench": [],  # minutes of measurement: its printing is covered by tests/test_bench.py
    "novikov": [["novikov", *NOVIKOV, "--helix-angle-deg", "15"], ["novikov", *NOVIKOV, "--helix-angle-deg", "0"]],
    "blocking": [["blocking", "--z1", "13", "--z2", "16", "--tol", "1e-2"]],
    "atlas": [["atlas", "--z1", "13", "--z2", "16", "--tol", "1e-2", "--workers", "1", "--no-progress",
               "-o", "{t}/atlas"]],
    "cycloidal-drive": [["cycloidal-drive", *DRIVE, "--samples", "200"]],
    "cycloid": [["cycloid", "-m", "1", "--pinion-teeth", "8", "--wheel-teeth", "64", "--clock"],
                ["cycloid", "-m", "1", "--pinion-teeth", "8", "--wheel-teeth", "64", "--pin-radius", "0.4"]],
    "contact": [["contact", "--z1", "20", "--z2", "40", "-m", "2", "--steps", "100"]],
    "view": [["view", "pair", *PAIR, "-o", "{t}/p.html", "--cycles", "1"],
             ["view", "drive", *DRIVE, "-o", "{t}/d.html", "--cycles", "1"]],
    "cam": [["cam", *CAM]],
    "scene": [["scene", "examples/planetary.toml"]],
    "planetary": [["planetary", "--ratio", "6.1428571", "--planets", "3", "-m", "1.75", "--ratio-tol", "1e-6"]],
}


def command_names(subparsers_action) -> list:
    """Every registered command name (a module may register several)."""
    return sorted(subparsers_action.choices)


def examples_of(name: str) -> list:
    return EXAMPLES.get(name, [])


def all_examples(tmp) -> list:
    """Every example with ``{t}`` filled in."""
    return [[a.replace("{t}", str(tmp)) for a in argv] for argvs in EXAMPLES.values() for argv in argvs]


assert set(COMMANDS) | set(MODULE_OF) >= {n for n in EXAMPLES if n in COMMANDS or n in MODULE_OF}
