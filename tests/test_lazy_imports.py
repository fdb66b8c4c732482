"""The command line imports only what the command runs: the lazy parser loads only the module of
the command given, and the paths of ``gear`` (STL and SVG), ``check``, ``cycloidal-drive`` and
``novikov --no-mesh`` never import scipy (the kernel has its own root finder, bounded minimiser and
nearest-point search, :mod:`gearkit.roots` and :func:`gearkit.distances.nearest`).

Each command runs in a fresh interpreter (an import, once made, stays for the whole process).
"""
import ast
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


#: packages whose public names load on first use: importing one imports none of its modules
LAZY_PACKAGES = ("gearkit", "gearkit.checks", "gearkit.pair", "gearkit.solids", "gearkit.families.involute",
                 "gearkit.families.cycloidal")


@pytest.mark.parametrize("package", LAZY_PACKAGES)
def test_lazy_package_exports_every_name_of_its_all_and_imports_nothing_first(package):
    """Each name of ``__all__`` resolves (to the object of the module that defines it) and
    ``dir()`` lists it; importing the package alone loads none of its submodules."""
    probe = (f"import sys, {package} as p\n"
             f"print(sorted(m for m in sys.modules if m.startswith('{package}.')))")
    proc = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0, proc.stderr
    loaded = ast.literal_eval(proc.stdout)  # a list of module names
    assert [m for m in loaded if not m.startswith("gearkit.errors")] == []
    import importlib

    pkg = importlib.import_module(package)
    for name in pkg.__all__:
        value = getattr(pkg, name)
        assert value is not None and name in dir(pkg)
    with pytest.raises(AttributeError):
        getattr(pkg, "no_such_name")


#: modules a command must not load: the parts of the package it does not use
NOT_LOADED = {
    "gear": ("gearkit.checks", "gearkit.pair", "gearkit.solids.pair", "gearkit.solids.rack",
             "gearkit.families.involute.modification", "tempfile", "shutil", "json", "signal"),
    "check": ("gearkit.solids", "gearkit.pair.internal", "gearkit.pair.sweep", "gearkit.families.involute.modification",
              "tempfile", "shutil"),
    "cycloidal-drive": ("gearkit.families.involute", "gearkit.pair", "gearkit.checks.involute", "tempfile",
                        "shutil"),
}
UNUSED_PROBE = """
import contextlib, io, sys
from gearkit.cli import main
with contextlib.redirect_stdout(io.StringIO()):
    code = main(sys.argv[1:])
print(repr({"code": code, "modules": sorted(sys.modules)}))
"""


@pytest.mark.parametrize("argv", [c[0] for c in CASES[:2] + CASES[3:5]], ids=["gear-stl", "gear-helical", "check",
                                                                             "cycloidal-drive"])
def test_command_loads_no_module_it_does_not_use(tmp_path, argv):
    """The STL path of ``gear`` loads no pair or check code, no temporary-file, shell-utility or
    JSON module (a file written atomically needs none of them), no :mod:`signal` (its enum wrappers;
    the SIGTERM handler is set through the built-in module under it); ``check`` of an external pair none of
    the internal pair's geometry; neither a gear's micro-geometry (none is given); ``cycloidal-drive``
    no involute code."""
    argv = [a.replace("{tmp}", str(tmp_path)) for a in argv if a != "--json"]
    proc = subprocess.run([sys.executable, "-c", UNUSED_PROBE, *argv], capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stderr
    out = ast.literal_eval(proc.stdout.strip().splitlines()[-1])
    assert out["code"] in (0, 1)
    unwanted = [m for m in out["modules"] if any(m == p or m.startswith(p + ".") for p in NOT_LOADED[argv[0]])]
    assert unwanted == []


@pytest.mark.parametrize("user_value, expected", [(None, "1"), ("3", "3")])
def test_command_runs_blas_on_one_thread_unless_the_user_says_otherwise(user_value, expected):
    """``import gearkit.cli`` before numpy sets OPENBLAS_NUM_THREADS to 1; a user's value is kept
    and the bench can tell the two apart (BLAS_THREADS_SET_HERE)."""
    import os

    env = {k: v for k, v in os.environ.items() if k not in ("OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS")}
    if user_value is not None:
        env["OPENBLAS_NUM_THREADS"] = user_value
    probe = ("import os, gearkit.cli as c, numpy\n"
             "print(os.environ['OPENBLAS_NUM_THREADS'], 'OPENBLAS_NUM_THREADS' in c.BLAS_THREADS_SET_HERE)")
    proc = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True, env=env, timeout=120)
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout.split() == [expected, str(user_value is None)]


COLLECTOR_PROBE = """
import gc, sys
if sys.argv[1] == "numpy-first":
    import numpy
from gearkit.cli import main
collections = []  # one entry per collection once main runs: has the command begun building its gear?
gc.callbacks.append(lambda phase, info: phase == "start" and collections.append(
    "gearkit.families.involute.gear" in sys.modules))
code = main(sys.argv[2:])
print(repr({"code": code, "enabled": gc.isenabled(), "frozen": gc.get_freeze_count(),
            "before_run": collections.count(False)}))
"""


@pytest.mark.parametrize("first, argv", [("fresh", ["gear", "-z", "12", "-m", "2"]), ("fresh", ["--help"]),
                                         ("numpy-first", ["gear", "-z", "12", "-m", "2"])],
                         ids=["fresh", "help", "numpy-loaded"])
def test_fresh_command_imports_without_the_collector_and_leaves_it_on(first, argv):
    """A fresh ``gearkit`` process imports numpy and its modules with the cycle collector paused (no
    collection before the command runs), then freezes those objects and resumes the collector; a
    process that loaded numpy first is left alone, and every way out (``--help`` too) leaves it on."""
    proc = subprocess.run([sys.executable, "-c", COLLECTOR_PROBE, first, *argv], capture_output=True, text=True,
                          timeout=120)
    assert proc.returncode == 0, proc.stderr
    out = ast.literal_eval(proc.stdout.strip().splitlines()[-1])
    assert out["code"] == 0 and out["enabled"]
    if first == "numpy-first":
        assert out["frozen"] == 0
    elif argv[0] == "gear":
        assert out["before_run"] == 0  # none while numpy, the parser and the command's modules load
        assert out["frozen"] > 10_000  # numpy's and the command's objects, out of the collector's sight


CLASSES_PROBE = """
import contextlib, dataclasses, io, sys
from gearkit.cli import main
with contextlib.redirect_stdout(io.StringIO()):
    code = main(sys.argv[1:])
made = {}
for name, module in list(sys.modules.items()):
    if name.split(".")[0] == "gearkit":
        for value in vars(module).values():
            if isinstance(value, type) and dataclasses.is_dataclass(value) and value.__module__ == name:
                made[name + "." + value.__qualname__] = value.__init__.__module__
print(repr({"code": code, "made": made}))
"""


#: ``cycloidal-drive`` with its output mechanism too (its pins and holes are one more value class)
CYCLOID_ALL = CASES[4][0] + ["--output-pins", "6", "-o", "{tmp}/disc.stl"]


@pytest.mark.parametrize("argv", [c[0] for c in CASES[:1] + CASES[3:4]] + [CYCLOID_ALL],
                         ids=["gear-stl", "check", "cycloidal-drive"])
def test_command_paths_make_their_value_classes_without_compiling(tmp_path, argv):
    """Every dataclass the ``gear``, ``check`` and ``cycloidal-drive`` paths load is made by
    ``gearkit.values.frozen`` (its ``__init__`` is the closure of that module), none by
    ``dataclass(frozen=True)``, which compiles six methods per class as the command starts."""
    argv = [a.replace("{tmp}", str(tmp_path)) for a in argv if a != "--json"]
    proc = subprocess.run([sys.executable, "-c", CLASSES_PROBE, *argv], capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stderr
    out = ast.literal_eval(proc.stdout.strip().splitlines()[-1])
    assert out["code"] in (0, 1) and len(out["made"]) >= 10  # the specs and records of the path are seen
    compiled = sorted(name for name, maker in out["made"].items() if maker != "gearkit.values")
    assert compiled == []
