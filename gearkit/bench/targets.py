"""Speed targets beside their measurements: one generic row shape for every product.

A target row is ``{name, measured, target, unit, pass}`` (plus optional ``note``): ``pass`` is
``measured <= target`` (None without a target or a measurement). Every producer of targets
(whole-process times here, contact analysis, blocking contours, ...) returns such rows and
:func:`format_target_rows` / :func:`markdown_target_rows` print them all in one table.

The whole-process targets are ratios to the **import floor** measured in the same run: the CPU
time of ``python -c "import numpy, manifold3d"`` (the least any command that writes a mesh must
pay), in the user's environment. The ``gearkit`` command runs numpy's BLAS on one thread (see
:mod:`gearkit.cli`), which saves the thread pool's start-up; the floor with one BLAS thread is
measured too and each row's note gives the ratio to it: gearkit's own cost over the least any
process importing numpy and manifold3d pays. The command also imports with the cycle collector
paused (:func:`gearkit.cli.hold_collector`), which the floor's plain ``python -c`` does not. CPU time of the child process (user + system) is
what passes or fails: it holds on a shared machine where wall time is inflated by other work;
wall time is reported beside it.

Examples
--------
>>> row = target_row("rigid cycle", 0.05, 0.1, "s CPU")
>>> row["pass"], target_row("unmeasured", None, 1.0, "s")["pass"]
(True, None)
"""
from __future__ import annotations

import os
import resource
import subprocess
import sys
import tempfile
import time

import numpy as np

from gearkit.bench.process import user_environment

__all__ = ["target_row", "user_environment", "one_blas_thread", "process_target_rows", "mesh_target_rows",
           "contact_targets", "blocking_targets", "format_target_rows", "markdown_target_rows"]

FLOOR_COMMAND = ("import numpy, manifold3d",)

#: (name, gearkit arguments, target ratio to the floor); ``{out}`` is a file in a temporary folder
PROCESS_TARGETS = (
    ("gear z=12 m=2 b=5 -> STL", ["gear", "-z", "12", "-m", "2", "--width", "5", "-o", "{out}.stl"], 1.15),
    ("gear z=40 m=2 b=5 -> STL", ["gear", "-z", "40", "-m", "2", "--width", "5", "-o", "{out}.stl"], 1.15),
    ("gear helical z=20 m=2 b=10 beta=20 -> STL",
     ["gear", "-z", "20", "-m", "2", "--helix-angle-deg", "20", "--width", "10", "-o", "{out}.stl"], 1.15),
    ("gear z=200 m=1 b=5 -> STL", ["gear", "-z", "200", "-m", "1", "--width", "5", "-o", "{out}.stl"], 1.15),
    ("check 20/40 m=2", ["check", "--z1", "20", "--z2", "40", "-m", "2"], 1.3),
    ("cycloidal-drive 12 pins", ["cycloidal-drive", "--pins", "12", "--lobes", "11", "--pin-circle-radius", "40",
                                 "--pin-radius", "3", "--eccentricity", "1.5"], 1.3),
)
TOL_MM = 0.001


def target_row(name: str, measured, target, unit: str, note: str | None = None) -> dict:
    """One target row; ``pass`` is ``measured <= target`` (None when either is missing)."""
    ok = None if measured is None or target is None else bool(measured <= target)
    row = {"name": name, "measured": measured, "target": target, "unit": unit, "pass": ok}
    if note:
        row["note"] = note
    return row


def _child_times(cmd, env) -> tuple[float, float, int]:
    """(CPU s, wall s, exit code) of one child process."""
    r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    proc = subprocess.run(cmd, capture_output=True, text=True, env=env)
    wall = time.perf_counter() - t0
    r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (r1.ru_utime - r0.ru_utime) + (r1.ru_stime - r0.ru_stime), wall, proc.returncode


def one_blas_thread(env: dict) -> dict:
    """``env`` with numpy's BLAS on one thread, as the ``gearkit`` command sets it (user settings kept)."""
    from gearkit.cli import BLAS_THREAD_VARIABLES

    return {**dict.fromkeys(BLAS_THREAD_VARIABLES, "1"), **env}


def process_target_rows(runs: int = 5) -> tuple[dict, list]:
    """The import floor and the whole-process target rows over ``runs`` runs each.

    Each run of a command is paired with a run of the floor just before it (and one of the floor
    with one BLAS thread): the row's ratio is the median of the paired ratios, so a load that
    drifts during the bench (another process starting or ending) hits both sides of each ratio.

    Returns
    -------
    floor : dict ``{cpu_seconds, wall_seconds, runs, command, one_blas_thread_cpu_seconds}`` (medians)
    rows : list of target rows (measured = median of CPU time / floor CPU time; the note adds the
        median CPU and wall times and the ratio to the one-BLAS-thread floor)
    """
    from gearkit.bench.process import gearkit_command

    env = user_environment()
    floor_cmd = [sys.executable, "-c", *FLOOR_COMMAND]
    samples = {"cpu": [], "wall": [], "cpu1": []}
    _child_times(floor_cmd, env)
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        measured = []
        for name, args, target in PROCESS_TARGETS:
            cmd = gearkit_command() + [a.replace("{out}", os.path.join(tmp, "out")) for a in args]
            if args[0] == "gear":
                cmd += ["--tol", str(TOL_MM)]
            code = _child_times(cmd, env)[2]  # warm-up: bytecode cached, files in the page cache
            cpu, wall, ratio, ratio1 = [], [], [], []
            for _ in range(runs):
                f_cpu, f_wall, _ = _child_times(floor_cmd, env)
                f1_cpu = _child_times(floor_cmd, one_blas_thread(env))[0]
                c, w, code = _child_times(cmd, env)
                samples["cpu"].append(f_cpu)
                samples["wall"].append(f_wall)
                samples["cpu1"].append(f1_cpu)
                cpu.append(c)
                wall.append(w)
                ratio.append(c / f_cpu)
                ratio1.append(c / f1_cpu)
            measured.append((name, target, *(float(np.median(v)) for v in (cpu, wall, ratio, ratio1)), code))
    floor = {"cpu_seconds": float(np.median(samples["cpu"])), "wall_seconds": float(np.median(samples["wall"])),
             "runs": len(samples["cpu"]), "command": f"python -c \"{FLOOR_COMMAND[0]}\"",
             "one_blas_thread_cpu_seconds": float(np.median(samples["cpu1"]))}
    for name, target, cpu, wall, ratio, ratio1, code in measured:
        note = f"{cpu * 1e3:.0f} ms CPU, {wall * 1e3:.0f} ms wall; {ratio1:.2f}x the one-BLAS-thread floor"
        if code not in (0, 1):
            rows.append(target_row(name, None, target, "x floor", f"exit {code}"))
        else:
            rows.append(target_row(name, ratio, target, "x floor", note))
    return floor, rows


#: the large-mesh case: spur z = 1000, m = 1, b = 5 mm, STL at tol 1e-3 mm
BIG_GEAR = (1000, 1.0, 5.0, 1e-3)
BIG_GEAR_CPU_TARGET = 0.3  # s
RSS_PER_FACE_TARGET = 0.4  # KB
PER_FACE_TARGET = 0.65  # us CPU a face, spec to file: half the 1.3 us of a solid checked by manifold3d

_BIG_GEAR_SCRIPT = """
import resource, sys, time
import numpy, manifold3d
from gearkit.families.involute import GearSpec, tooth_profile
from gearkit.solids import SolidSpec, gear_solid
from gearkit.solids.export import write_mesh
z, m, b, tol = (float(a) for a in sys.argv[1:5])


def peak_kb():  # this image's high-water mark (ru_maxrss would carry over the forking parent's)
    try:
        with open("/proc/self/status") as fh:
            return float(next(line.split()[1] for line in fh if line.startswith("VmHWM:")))
    except (OSError, StopIteration):
        return float(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss)


base = peak_kb()
t0 = time.process_time()
solid = gear_solid(tooth_profile(GearSpec(int(z), m)), SolidSpec(b), tol)
write_mesh(sys.argv[5], [solid])
cpu = time.process_time() - t0
print(cpu, solid.faces, peak_kb() - base)
"""


def mesh_target_rows(runs: int = 3) -> list:
    """z = 1000 spur to STL at tol 1e-3 mm, each run in a fresh process: CPU time from spec to file
    (median), the same per face, and the peak resident memory it adds over the imports, per face
    (KB; Linux counts KB)."""
    z, m, b, tol = BIG_GEAR
    env = user_environment()
    samples = []
    with tempfile.TemporaryDirectory() as tmp:
        for _ in range(max(1, runs)):
            proc = subprocess.run([sys.executable, "-c", _BIG_GEAR_SCRIPT, str(z), str(m), str(b), str(tol),
                                   os.path.join(tmp, "big.stl")], capture_output=True, text=True, env=env)
            if proc.returncode != 0:
                err = (proc.stderr.strip().splitlines() or [""])[-1]
                return [target_row(f"z={z} m={m:g} b={b:g} tol {tol:g} -> STL, CPU", None, BIG_GEAR_CPU_TARGET,
                                   "s CPU", err)]
            cpu, faces, rss = proc.stdout.split()
            samples.append((float(cpu), int(faces), float(rss)))
    cpu = float(np.median([c for c, _, _ in samples]))
    faces = samples[0][1]
    rss = float(np.median([r for _, _, r in samples])) / faces
    return [target_row(f"z={z} m={m:g} b={b:g} tol {tol:g} -> STL, CPU", cpu, BIG_GEAR_CPU_TARGET, "s CPU",
                       f"{faces} faces, spec to file"),
            target_row(f"z={z} -> STL, CPU per face", cpu / faces * 1e6, PER_FACE_TARGET, "us CPU",
                       "the CPU time above over the faces"),
            target_row(f"z={z} -> STL, peak RSS per face", rss, RSS_PER_FACE_TARGET, "KB",
                       "peak resident memory added over the imports, divided by the faces")]


def contact_targets(rows) -> list:
    """The contact bench's rows (:func:`gearkit.bench.contact.contact_target_rows`) as target rows."""
    return [target_row(f"{r['case']}, {r['steps']} steps" + (f", {r['slices']} slices" if r["slices"] > 1 else ""),
                       r["cpu_seconds"], r["target"], "s CPU", f"{r['seconds']:.3f} s wall")
            for r in rows if r["target"] is not None]


def blocking_targets(rows) -> list:
    """The blocking bench's rows (``{target, measured, limit, unit, pass}``) as target rows (their
    verdicts kept: some compare more than a number, e.g. that time grows as tol falls)."""
    return [{"name": r["target"], "measured": r["measured"], "target": r["limit"], "unit": r["unit"] or "",
             "pass": r["pass"]} for r in rows]


def _num(x):
    return "" if x is None else (f"{x:.3g}" if abs(x) >= 1e-3 else f"{x:.2e}")


def _verdict(row):
    return "" if row["pass"] is None else ("pass" if row["pass"] else "FAIL")


def _header(res):
    floor = res.get("floor")
    meta = res["meta"]
    one = floor.get("one_blas_thread_cpu_seconds") if floor else None
    fl = "" if not floor else (f"import floor `{floor['command']}` {floor['cpu_seconds'] * 1e3:.0f} ms CPU "
                               f"({floor['wall_seconds'] * 1e3:.0f} ms wall"
                               + (f"; {one * 1e3:.0f} ms CPU with one BLAS thread, as gearkit runs" if one else "")
                               + "), measured in this run; ")
    blas = meta.get("blas_threads")
    inproc = "" if blas is None else ("; in-process rows with one BLAS thread" if blas == "1" else
                                      f"; in-process rows with BLAS threads: {blas}")
    return (f"{fl}load average {meta.get('load_before')} before, {meta.get('load_after')} after, on "
            f"{meta.get('cpus')} CPUs; pass/fail reads CPU time{inproc}")


def format_target_rows(res: dict) -> list:
    """Plain-text lines: every target beside its measurement."""
    rows = res.get("targets") or []
    lines = ["targets (" + _header(res) + ")",
             f"  {'name':52} {'measured':>10} {'target':>8} {'unit':12} {'':4}  note"]
    for r in rows:
        lines.append(f"  {r['name']:52} {_num(r['measured']):>10} {_num(r['target']):>8} {r['unit']:12} "
                     f"{_verdict(r):4}  {r.get('note', '')}")
    return lines


def markdown_target_rows(res: dict) -> list:
    """Markdown lines of the target table."""
    out = ["**Targets** (" + _header(res) + ")", "", "| target | measured | target | unit | pass | note |",
           "|---|---:|---:|---|---|---|"]
    for r in res.get("targets") or []:
        out.append(f"| {r['name']} | {_num(r['measured'])} | {_num(r['target'])} | {r['unit']} | {_verdict(r)} "
                   f"| {r.get('note', '')} |")
    return out
