"""The command line imports only what the command runs: the lazy parser loads only the module of
the command given, and the paths of ``gear`` (STL and SVG), ``check``, ``cycloidal-drive`` and
``novikov --no-mesh`` never import scipy (the kernel has its own root finder, bounded minimiser and
nearest-point search, :mod:`gearkit.roots` and :func:`gearkit.accuracy.nearest`).

Each command runs in a fresh interpreter (an import, once made, stays for the whole process).
"""
import json
import subprocess
import sys

import pytest

from gearkit import cli

PROBE = """
import contextlib, io, json, sys
from gearkit.cli import main
with contextlib.redirect_stdout(io.StringIO()):
    code = main(json.loads(sys.argv[1]))
print(json.dumps({"code": code, "modules": sorted(m for m in sys.modules
                  if m.split(".")[0] == "scipy" or m.startswith("gearkit.cli."))}))
"""

CASES = [
    (["gear", "-z", "12", "-m", "2", "--width", "5", "--tol", "0.001", "-o", "{tmp}/z12.stl"], "gear"),
    (["gear", "-z", "20", "-m", "2", "--helix-angle-deg", "20", "--width", "10", "-o", "{tmp}/h20.stl"], "gear"),
    (["gear", "-z", "40", "-m", "2", "-o", "{tmp}/z40.svg"], "gear"),
    (["check", "--z1", "20", "--z2", "40", "-m", "2", "--json"], "check"),
    (["cycloidal-drive", "--pins", "12", "--lobes", "11", "--pin-circle-radius", "40", "--pin-radius", "3",
      "--eccentricity", "1.5"], "cycloid"),
    (["novikov", "--z1", "20", "--z2", "40", "-m", "2", "--helix-angle-deg", "20", "--width", "20",
      "--no-mesh"], "novikov"),
]


@pytest.mark.parametrize("argv, module", CASES, ids=[" ".join(c[0][:3]) for c in CASES])
def test_command_imports_only_its_module_and_no_scipy(tmp_path, argv, module):
    argv = [a.replace("{tmp}", str(tmp_path)) for a in argv]
    proc = subprocess.run([sys.executable, "-c", PROBE, json.dumps(argv)], capture_output=True, text=True,
                          timeout=300)
    assert proc.returncode == 0, proc.stderr
    out = json.loads(proc.stdout.strip().splitlines()[-1])
    assert out["code"] in (0, 1), proc.stderr  # 1: a check reports a failing finding, still a run
    mods = out["modules"]
    assert not [m for m in mods if m.split(".")[0] == "scipy"], f"scipy imported by {argv[0]}: {mods}"
    commands = [m for m in mods if m.startswith("gearkit.cli.") and m.split(".")[2] in cli.COMMANDS]
    assert commands == [f"gearkit.cli.{module}"]  # of the command modules only its own (shell helpers aside)


def test_every_command_maps_to_a_registered_module():
    """The name -> module table covers every command the full parser knows (so each runs lazily)."""
    parser = cli.build_parser()
    sub = next(a for a in parser._actions if a.dest == "command")
    for name in sub.choices:
        module = cli.command_module(name)
        assert module is not None, name
        lazy = cli.build_parser(name)
        assert name in next(a for a in lazy._actions if a.dest == "command").choices
