"""The swept-tool oracle's convergence, next to the envelope path's cost for the same accuracy.

The oracle (:mod:`gearkit.oracles.involute`) cuts the blank with the rack at discrete roll steps; its
error against the exact envelope shrinks with the step (second order for a rounded rack
tip). For each step the bench reports the oracle's time and error, and the time the envelope
path needs to produce the same gear at a tolerance equal to that error.
"""
from __future__ import annotations

import numpy as np

from gearkit.bench.timing import median_time
from gearkit.distances import distances_to_polyline

#: roll steps of the oracle, in modules
STEPS_QUICK = (0.16, 0.08, 0.04)
STEPS_FULL = (0.16, 0.08, 0.04, 0.02, 0.01)


def oracle_convergence(quick: bool, repeats: int):
    """Rows {step, oracle_error, oracle_seconds, envelope_tol, envelope_seconds, envelope_vertices, speedup}
    for the rack-cut spur gear z = 20, m = 1 (errors and tolerances in mm)."""
    from gearkit.families.involute import GearSpec, tooth_profile
    from gearkit.oracles.involute import swept_rack_gear, tooth_zone_points

    spec = GearSpec(20, 1.0)
    m = spec.module
    ra = spec.blank_tip_diameter / 2.0
    exact = tooth_profile(spec).outline(1e-8 * m)
    rows = []
    for step_m in (STEPS_QUICK if quick else STEPS_FULL):
        t_or, contours = median_time(
            lambda: swept_rack_gear(spec.teeth, m, spec.shift, spec.tool, ra, step_m * m), 1 if quick else 3)
        pts = tooth_zone_points(contours, spec.teeth, ra)
        err = float(distances_to_polyline(pts, exact, closed=True).max())
        tol = max(err, 1e-7 * m)

        def envelope():
            prof = tooth_profile.__wrapped__(spec)
            return prof.outline(tol)

        t_env, outline = median_time(envelope, repeats)
        rows.append({"family": "involute", "case": "spur z=20", "step": step_m * m, "oracle_error": err,
                     "oracle_seconds": t_or, "oracle_points": int(len(pts)), "envelope_tol": tol,
                     "envelope_seconds": t_env, "envelope_vertices": int(len(outline)),
                     "speedup": t_or / t_env})
    errs = np.array([r["oracle_error"] for r in rows])
    steps = np.array([r["step"] for r in rows])
    order = float(np.polyfit(np.log(steps), np.log(errs), 1)[0]) if len(rows) > 1 else float("nan")
    return rows, order
