"""``gearkit bench``: the speed-accuracy trade, measured.

For every family and product that exists, the bench measures

* the **accuracy ladder**: requested tol from 1e-1 m down to 1e-7 m -> the achieved maximum
  deviation, measured independently by dense re-evaluation of the exact curve (see
  :mod:`gearkit.bench.profiles`), the vertex count and the wall time (median of repeats);
* **scaling** in the tooth count z = 10 ... 10000 (and the rack, when the kernel has one);
* the **swept-tool oracle's convergence** (error vs roll step) next to the envelope path's time
  for the same accuracy;
* the **kernel overhead**: time of the z = 40 involute outline at tol 1e-6 m over the time numpy
  needs to evaluate as many points of the closed-form involute (a ratio that holds on any machine);
* the **whole-process time** of ``gearkit gear`` for three reference gears;
* **targets**: every speed target beside its measurement (generic rows
  ``{name, measured, target, unit, pass}``, see :mod:`gearkit.bench.targets`): whole-process
  CPU time over the import floor measured in the same run, kernel overhead, contact cycles;
* **scenes**: the cold cost of each query of a 3-planet set and the four-speed box at each
  fidelity (ratio, checks, solids) with what it built, and the planetary synthesis time.

:func:`run_bench` returns one JSON-ready dict; :func:`format_table` renders it.
"""
from __future__ import annotations

import os
import platform
import time

import numpy as np

from gearkit.progress import Progress

__all__ = ["run_bench", "format_table", "markdown_table"]


#: the bench's parts, for its progress bar
SECTIONS = 11


def run_bench(quick: bool = False, process: bool = True, progress=None) -> dict:
    """Run the bench; ``quick`` keeps it under a minute on two cores. ``progress``, if given, is
    called with the name of each part as it starts; the command line draws a progress bar
    (:class:`gearkit.progress.Progress`) instead.

    Returns
    -------
    dict with keys ``ladder`` (list of {family, product, tol, achieved, vertices, seconds, ...}),
    ``scaling``, ``oracle``, ``oracle_order``, ``products``, ``unmeasured``, ``process``,
    ``overhead``, ``overhead_ratio``, ``targets`` (list of {name, measured, target, unit, pass}),
    ``floor`` (the import floor, when ``process``) and ``meta`` (lengths in mm, times in s).
    """
    from gearkit.bench import blocking, meshes, oracle, process as proc, products, profiles, targets, vertices

    with Progress("bench", SECTIONS, unit="parts") as bar:
        started = [0]

        def say(msg):  # a part starts: the bar counts those finished and names this one
            if progress is not None:
                progress(msg)
            bar.note = msg
            bar.update(started[0])
            started[0] += 1

        repeats = 3 if quick else 7
        t0 = time.perf_counter()
        out = {"meta": {"quick": quick, "repeats": repeats, "python": platform.python_version(),
                        "numpy": np.__version__, "machine": platform.machine(), "cpus": os.cpu_count(),
                        "load_before": _load(), "blas_threads": proc.blas_threads()}}
        say("overhead against the closed-form involute")
        out["overhead"] = profiles.overhead(11 if quick else 31)
        out["overhead_ratio"] = out["overhead"]["overhead_ratio"]
        out["targets"] = [targets.target_row("kernel overhead: z=40 outline, tol 1e-6 m",
                                             out["overhead_ratio"], profiles.OVERHEAD_TARGET, "x closed form",
                                             f"CPU time; sampling alone {out['overhead']['overhead_ratio_sampling']:.1f}x")]
        say("accuracy ladder: 2D profiles")
        out["ladder"] = (profiles.involute_ladder(quick, repeats) + profiles.novikov_ladder(quick, repeats)
                         + profiles.cycloidal_ladder(quick, repeats) + profiles.cam_ladder(quick, repeats))
        if products.available("gearkit.solids"):
            say("accuracy ladder: meshes")
            out["ladder"] += meshes.mesh_ladder(quick, repeats)
        out["targets"] += vertices.vertex_target_rows() + [vertices.bound_target_row(out["ladder"])]
        if products.available("gearkit.solids"):
            say("large mesh: z = 1000 to STL, CPU and memory per face")
            out["targets"] += targets.mesh_target_rows(1 if quick else 3)
        if products.available("gearkit.blocking.contour"):
            say("blocking contour: ladder, targets, atlas throughput")
            out["ladder"] += blocking.ladder_rows(quick)
            out["contract"] = blocking.contract_rows(quick)
            out["blocking_targets"] = blocking.target_rows(out["ladder"]) + [blocking.contract_target(out["contract"])]
            out["targets"] += targets.blocking_targets(out["blocking_targets"])
            out["atlas"] = blocking.atlas_rows(quick)
        say("scaling in z")
        out["scaling"] = profiles.involute_scaling(quick, repeats)
        say("swept-tool oracle convergence")
        out["oracle"], out["oracle_order"] = oracle.oracle_convergence(quick, repeats)
        say("pair check, simulated meshes")
        out["products"] = (products.pair_check_rows(quick, repeats) + products.involute_contact_rows(quick, repeats)
                           + products.cycloidal_mesh_rows(quick, repeats) + products.novikov_contact_rows(quick, repeats))
        if products.available("gearkit.contact.loaded"):
            from gearkit.bench.contact import contact_target_rows

            say("contact analysis against its targets")
            out["contact_targets"] = contact_target_rows(quick)
            out["targets"] += targets.contact_targets(out["contact_targets"])
        if products.available("gearkit.scene"):
            from gearkit.bench import scenes

            say("scenes: queries at each fidelity, planetary synthesis")
            out["scenes"] = scenes.scene_rows(quick, repeats)
            out["synthesis"] = scenes.synthesis_rows(quick, repeats)
        measured = {(r["family"], r["product"]) for r in out["ladder"] + out["products"]}
        out["unmeasured"] = products.unmeasured_products(measured)
        if process:
            say("whole-process times against the import floor")
            out["floor"], rows = targets.process_target_rows(3 if quick else 5)
            out["targets"] = rows + out["targets"]
            out["process"] = proc.process_times(5)
        else:
            out["process"] = []
        bar.note = ""
        bar.update(SECTIONS)
    out["meta"]["seconds"] = time.perf_counter() - t0
    out["meta"]["load_after"] = _load()
    return out


def _load():
    """1-minute load average (None where the platform has none): other work inflates every time."""
    try:
        return round(os.getloadavg()[0], 2)
    except (AttributeError, OSError):
        return None


def _fmt_s(s):
    return f"{s * 1e3:8.2f} ms" if s < 1.0 else f"{s:8.3f} s "


def format_table(res: dict) -> str:
    """The bench result as a plain-text report."""
    from gearkit.bench.targets import format_target_rows

    lines = []
    ov = res["overhead"]
    lines.append("gearkit bench" + (" (quick)" if res["meta"]["quick"] else "")
                 + f"  -- lengths in mm, times median of {res['meta']['repeats']} repeats")
    lines.append("")
    lines.append("accuracy ladder (achieved = max distance of the exact curve/surface from the output, measured by "
                 "dense re-evaluation; mesh: on sections; blocking: tol and achieved in shift units)")
    lines.append(f"  {'product':16} {'family':9} {'case':26} {'tol':>9} {'achieved':>10} {'ach/tol':>7} "
                 f"{'count':>9} {'time':>11}")
    for r in res["ladder"]:
        ach = "" if r["achieved"] is None else f"{r['achieved']:10.3e}"
        ratio = "" if r["achieved"] is None else f"{r['achieved'] / r['tol']:7.3f}"
        lines.append(f"  {r['product']:16} {r['family']:9} {r['case']:26} {r['tol']:9.1e} {ach:>10} {ratio:>7} "
                     f"{r['vertices']:9d} {_fmt_s(r['seconds']):>11}")
    lines.append("")
    lines.append("scaling in z (involute spur, m = 1)")
    lines.append(f"  {'z':>6} {'tol':>9} {'achieved':>10} {'vertices':>9} {'time':>11}")
    for r in res["scaling"]:
        if r.get("available", True):
            lines.append(f"  {r['teeth']:>6} {r['tol']:9.1e} {r['achieved']:10.3e} {r['vertices']:9d} "
                         f"{_fmt_s(r['seconds']):>11}")
        else:
            lines.append(f"  {r['teeth']:>6}  -- {r['note']}")
    lines.append("")
    lines.append(f"swept-tool oracle vs envelope (spur z = 20, m = 1; oracle error order in the step: "
                 f"{res['oracle_order']:.2f})")
    lines.append(f"  {'step':>6} {'oracle err':>10} {'oracle time':>11} {'envelope time':>13} {'speed-up':>8}")
    for r in res["oracle"]:
        lines.append(f"  {r['step']:6.2f} {r['oracle_error']:10.2e} {_fmt_s(r['oracle_seconds']):>11} "
                     f"{_fmt_s(r['envelope_seconds']):>13} {r['speedup']:7.0f}x")
    lines.append("")
    lines.append(f"kernel overhead: z = 40 involute outline at tol 1e-6 m, {ov['points']} points: "
                 f"{ov['kernel_seconds'] * 1e3:.2f} ms CPU from spec ({ov['sampling_seconds'] * 1e3:.2f} ms sampling "
                 f"a generated tooth) vs {ov['baseline_seconds'] * 1e3:.2f} ms for numpy's closed form -> "
                 f"overhead ratio {ov['overhead_ratio']:.1f}x (sampling only {ov['overhead_ratio_sampling']:.1f}x; "
                 f"target <= {ov['target']:.0f}x)")
    lines.append("")
    lines.append("other products")
    for r in res["products"]:
        extra = (f"  contact ratio {r['contact_ratio']:.6f} (closed form +- {r['contact_ratio_error']:.1e}), "
                 f"max |TE| {r['transmission_error_max_rad']:.1e} rad" if "contact_ratio" in r else "")
        lines.append(f"  {r['family']:9} {r['product']:18} {r['case']:38} {_fmt_s(r['seconds']):>11}{extra}")
    for r in res["unmeasured"]:
        lines.append(f"  {r['family']:9} {r['product']:18} -- {r['note']} ({r['module']})")
    if res.get("scenes"):
        from gearkit.bench.scenes import format_rows

        lines += [""] + format_rows(res)
    if res.get("contact_targets"):
        from gearkit.bench.contact import format_contact_rows

        lines += [""] + format_contact_rows(res["contact_targets"])
    if "blocking_targets" in res:
        from gearkit.bench.blocking import format_section
        lines += format_section(res)
    if res["process"]:
        lines.append("")
        lines.append("whole process (gearkit gear ... -o FILE, tol 0.001 mm, median of 5 runs)")
        for r in res["process"]:
            status = "" if r["ok"] else f"  FAILED: {r.get('error', '')}"
            ach = "" if r.get("achieved") is None else f"  achieved {r['achieved'] * 1e3:.2f} um"
            lines.append(f"  {r['gear']:32} {r['output']:30} {_fmt_s(r['seconds']):>11}{ach}{status}")
    lines += [""] + format_target_rows(res)
    lines.append("")
    lines.append(f"bench time {res['meta']['seconds']:.1f} s; load average {res['meta'].get('load_before')} before, "
                 f"{res['meta'].get('load_after')} after, on {res['meta'].get('cpus')} CPUs (load from other work "
                 "inflates every time above)")
    return "\n".join(lines)


def markdown_table(res: dict) -> str:
    """The bench result as the README's Markdown section body."""
    from gearkit.bench.markdown import render

    return render(res)
