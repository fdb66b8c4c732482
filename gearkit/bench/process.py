"""Whole-process time of the ``gearkit`` command, as a user runs it (interpreter start included).

The three reference gears (tol 0.001 mm) are the ones a script-based CAD gear library was
timed on: spur z = 12 m = 2 b = 5, helical z = 20 m = 2 b = 10 beta = 20 deg, spur z = 200 m = 1
b = 5. With a mesh export the command writes STL; without one it writes the 2D profile
(SVG), and the row says so.
"""
from __future__ import annotations

import os
import subprocess
import sys
import tempfile
import time

import numpy as np

#: (name, gear flags, face width b in mm)
REFERENCE_GEARS = (
    ("spur z=12 m=2 b=5", ["-z", "12", "-m", "2"], 5.0),
    ("helical z=20 m=2 b=10 beta=20", ["-z", "20", "-m", "2", "--helix-angle-deg", "20"], 10.0),
    ("spur z=200 m=1 b=5", ["-z", "200", "-m", "1"], 5.0),
)
TOL_MM = 0.001


def gearkit_command():
    """The command line that runs the installed ``gearkit`` (its script beside this interpreter)."""
    exe = os.path.join(os.path.dirname(sys.executable), "gearkit")
    return [exe] if os.path.exists(exe) else [sys.executable, "-m", "gearkit"]


def user_environment() -> dict:
    """This process's environment without the BLAS settings the ``gearkit`` command made itself
    (the environment a user's ``python`` starts in), bytecode writing allowed."""
    env = dict(os.environ)
    cli = sys.modules.get("gearkit.cli")
    for variable in getattr(cli, "BLAS_THREADS_SET_HERE", ()):
        env.pop(variable, None)
    env.pop("PYTHONDONTWRITEBYTECODE", None)  # a user's install runs from cached bytecode
    return env


def blas_threads() -> str:
    """numpy's BLAS threads in this process as its environment set them: ``"1"`` where the ``gearkit``
    command (or the user) held them to one, ``"default"`` (a thread per core) where nothing did."""
    return os.environ.get("OPENBLAS_NUM_THREADS") or "default"


def mesh_export_available() -> bool:
    """True when ``gearkit gear`` can write an STL (the solids module exists)."""
    try:
        from gearkit.cli import gear as gear_cli
        import inspect

        return "stl" in inspect.getsource(gear_cli).lower()
    except Exception:  # noqa: BLE001 - any failure means: not available
        return False


def _face_width_flag():
    from gearkit.cli import gear as gear_cli
    import inspect

    src = inspect.getsource(gear_cli)
    for flag in ("--face-width", "--width", "-b"):
        if f'"{flag}"' in src:
            return flag
    return None


def process_times(runs: int = 5):
    """Median whole-process wall time (s) over ``runs`` runs for each reference gear."""
    env = user_environment()  # as a user runs it: cached bytecode, BLAS threads as the command sets them
    stl = mesh_export_available()
    width_flag = _face_width_flag() if stl else None
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for name, flags, b in REFERENCE_GEARS:
            out = os.path.join(tmp, "gear.stl" if stl else "gear.svg")
            cmd = gearkit_command() + ["gear"] + flags + ["--tol", str(TOL_MM), "-o", out]
            if stl and width_flag:
                cmd += [width_flag, str(b)]
            times, ok, err = [], True, ""
            for _ in range(runs):
                t0 = time.perf_counter()
                proc = subprocess.run(cmd, capture_output=True, text=True, env=env)
                times.append(time.perf_counter() - t0)
                if proc.returncode != 0:
                    ok, err = False, proc.stderr.strip().splitlines()[-1:] or [""]
                    break
            rows.append({"gear": name, "output": "stl" if stl else "svg (2D; no mesh export yet)",
                         "tol": TOL_MM, "seconds": float(np.median(times)), "runs": len(times), "ok": ok,
                         "achieved": _achieved(flags, b, stl), **({"error": err[0]} if not ok else {})})
    return rows


def _achieved(flags, width, stl: bool):
    """The deviation (mm) of the same gear built in-process, measured independently on mesh sections
    (2D: on the outline); None if it cannot be built here."""
    from gearkit.bench.meshes import mesh_deviation
    from gearkit.bench.profiles import measured_deviation
    from gearkit.families.involute import GearSpec, tooth_profile

    opts = dict(zip(flags[::2], flags[1::2]))
    spec = GearSpec(int(opts["-z"]), float(opts["-m"]), helix_angle_deg=float(opts.get("--helix-angle-deg", 0.0)))
    prof = tooth_profile(spec)
    if not stl:
        outline = prof.outline(TOL_MM)
        return measured_deviation(prof, outline, len(prof.half_points(TOL_MM)[0]))
    from gearkit.solids import SolidSpec, gear_solid

    solid = gear_solid(prof, SolidSpec(width), tol=TOL_MM)
    return mesh_deviation(prof, solid, width, spec.helix_angle_deg)
