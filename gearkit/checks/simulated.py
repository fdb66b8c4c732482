"""Findings from the meshing simulation, beside the formula checks: a second, independent source.

The formulas of :mod:`gearkit.checks.involute` read the pair from its path of contact; the
simulation (:mod:`gearkit.contact`) meshes the generated teeth themselves. These findings report
what the simulation sees and say where the two disagree:

============================  =============================================================  ==========
id                            checks                                                         on failure
============================  =============================================================  ==========
contact_ratio.simulated       time-averaged pairs in contact (beside the formula's eps);     warn/fail
                              fail when the two differ by more than ``EPS_AGREEMENT``
interference.simulated        overlap of the generated teeth over a cycle (depth, where)      fail
                              (warn when the formulas flag interference the teeth clear)
backlash.simulated            free play of the generated teeth (circular, normal)            fail
transmission_error.simulated  peak-to-peak transmission error on the driven base circle      (report)
============================  =============================================================  ==========
"""
from __future__ import annotations

import math

from gearkit.checks.report import Finding, grade

__all__ = ["simulated_findings", "FORMULA_INTERFERENCE", "EPS_AGREEMENT"]

#: stated accuracy of the simulated contact ratio against the formula's: both read the same exact
#: teeth (the simulation to its contact tolerance, ~1e-12 of the radii, and its root-found contact
#: instants), so on a pair the formula describes they agree to ~1e-6 (tests/test_contact.py holds
#: them to 1e-3); a larger difference means one of them describes another pair than the generated one
EPS_AGREEMENT = 1e-3

#: formula findings that predict overlap of the teeth
FORMULA_INTERFERENCE = ("interference.1", "interference.2", "tip_interference", "exit_jamming", "backlash",
                        "tip_clearance.1", "tip_clearance.2")


def simulated_findings(spec, geometry, findings, limits, analysis=None, steps: int = 2000) -> list:
    """The simulation's findings for ``spec`` (a :class:`~gearkit.pair.PairSpec`).

    Parameters
    ----------
    spec : PairSpec
    geometry : PairGeometry (the formula geometry the other findings used)
    findings : sequence of Finding (the formula findings, to compare with)
    limits : CheckLimits
    analysis : ContactAnalysis or None
        A simulation already run (default: :func:`gearkit.contact.analyse_pair` at ``steps``).
    """
    if analysis is None:
        from gearkit.contact import analyse_pair

        analysis = analyse_pair(spec, steps)
    g = geometry
    out = []
    eps, eps_f = analysis.contact_ratio, g.contact_ratio
    msg = f"simulated eps_alpha = {eps:.4f} (formula {eps_f:.4f}, difference {eps - eps_f:+.4f})"
    if analysis.slices > 1:
        msg += (f"; total eps_gamma = {analysis.total_contact_ratio:.4f} over {analysis.slices} slices "
                f"(formula {g.total_contact_ratio:.4f})")
    status = grade(eps, fail_below=1.0, warn_below=limits.min_contact_ratio)
    if not abs(eps - eps_f) <= EPS_AGREEMENT:
        status = "fail"
        msg += (f": the simulation and the formula disagree by more than their stated accuracy {EPS_AGREEMENT:g} "
                "(the formula's path of contact is not the generated teeth's)")
    out.append(Finding("contact_ratio.simulated", status, eps, limits.min_contact_ratio, msg, "min"))

    inter = analysis.interference
    flagged = [f.id for f in findings if f.id in FORMULA_INTERFERENCE and f.status == "fail"]
    if inter.found:
        worst = inter.events[0]
        msg = (f"the generated teeth overlap by {inter.max_depth:.4g} mm ({', '.join(inter.where)}; deepest: "
               f"{worst['driver_feature']} of the driver against the {worst['mate_feature']} of the mate at "
               f"{math.degrees(inter.driver_angle):.3f} deg, overlap area {inter.area:.3g} mm^2)")
        msg += (f"; the formula checks agree ({', '.join(flagged)})" if flagged else
                "; the formula checks pass: the formulas miss it")
        status = "fail"
    else:
        msg = f"no overlap deeper than {analysis.interference_tol:.3g} mm over the mesh cycle"
        status = "ok"
        if flagged:
            msg += (f"; the formula check flags {', '.join(flagged)}, but the generated teeth clear each other "
                    "(the cutter's fillet or undercut makes room for the mate's tip)")
            status = "warn"
    out.append(Finding("interference.simulated", status, inter.max_depth, analysis.interference_tol, msg, "max"))

    j, j_n = analysis.backlash, analysis.backlash_normal
    tol = analysis.interference_tol

    def mm(v):
        return f"{0.0 if abs(v) < 5e-6 else v:.5f}"  # no "-0.00000"
    msg = (f"simulated backlash {mm(j)} mm on the working circle (normal {mm(j_n)} mm); formula "
           f"{mm(g.backlash)} mm (normal {mm(g.backlash_normal)} mm)")
    out.append(Finding("backlash.simulated", "fail" if j < -tol else "ok", j, 0.0,
                       msg + ("; negative: the teeth jam" if j < -tol else ""), "min"))

    te = analysis.transmission_error_pp
    scale = 1.0 if analysis.units == "mm" else g.gears[1].base_diameter / 2
    msg = (f"peak-to-peak transmission error {te:.4g} {'mm' if analysis.units == 'mm' else 'rad'}"
           f" = {te * scale:.4g} mm on the driven base circle")
    out.append(Finding("transmission_error.simulated", "ok", te * scale if math.isfinite(te) else math.inf, None,
                       msg, None))
    return out
