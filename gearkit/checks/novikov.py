"""Design check of a Novikov pair: findings with numbers, limits and reasons.

:func:`check_novikov` derives the pair geometry (:func:`~gearkit.families.novikov.novikov_pair_geometry`),
generates both gears with the envelope kernel, and (optionally) meshes them in the transverse plane
(:mod:`gearkit.families.novikov.mesh`):

==========================  ==========================================================  ==========
id                          checks                                                      on failure
==========================  ==========================================================  ==========
overlap_ratio               eps_beta = b sin(beta)/(pi m_n): < 1 fail, < 1.1 warn       fail/warn
transverse_contact_ratio    eps_alpha = 0 by design (reported, never a failure)         --
racks                       the racks' parameters are verified against a standard       warn
pointing.i                  normal tip thickness s_an of gear i                         fail/warn
working_arc.i.<arc>         the design contact point survives on gear i's generated arc fail
center_distance_window      a_w - a keeps every contact on the generated working arcs  fail/warn
tip_clearance.i             tip of gear i to the mate's root                            fail/warn
contact_axial_distance      double-arc: axial distance of a flank's two contacts        --
mesh.interference           simulated mesh: the outlines do not overlap                 fail
mesh.contact.k              simulated contact of zone k: one point, on the arcs          fail/warn
==========================  ==========================================================  ==========
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from gearkit.checks.report import CheckReport, Finding, grade
from gearkit.errors import check_fields, require
from gearkit.families.novikov import NovikovPairGeometry, NovikovPairSpec, novikov_pair_geometry, tooth_profile

__all__ = ["NovikovLimits", "NovikovCheck", "check_novikov"]


@dataclass(frozen=True)
class NovikovLimits:
    """Thresholds of :func:`check_novikov` (module units are normal-module units).

    Parameters
    ----------
    min_overlap_ratio : float
        Warn when eps_beta is below this (fail below 1).
    min_tip_thickness : float
        Warn when s_an < this * m_n (fail when the tooth is pointed).
    min_tip_clearance : float
        Warn when a tip clearance is below this * m_n (fail below 0).
    min_window : float
        Warn when a centre-distance error smaller than this * m_n (either way) runs a contact off
        its working arc.
    max_angle_error_deg : float
        Warn when the simulated contact angle differs from the rack prediction by more than this.
    """

    min_overlap_ratio: float = 1.1
    min_tip_thickness: float = 0.25
    min_tip_clearance: float = 0.05
    min_window: float = 0.01
    max_angle_error_deg: float = 0.5

    def __post_init__(self):
        check_fields(self)
        for name, lo, hi in (("min_overlap_ratio", 1.0, 5.0), ("min_tip_thickness", 0.0, 2.0),
                             ("min_tip_clearance", 0.0, 1.0), ("min_window", 0.0, 0.5),
                             ("max_angle_error_deg", 0.0, 10.0)):
            v = getattr(self, name)
            require(isinstance(v, (int, float)) and math.isfinite(v) and lo <= v <= hi, name,
                    f"{v!r} must be in [{lo}, {hi}]")


@dataclass(frozen=True)
class NovikovCheck:
    """Result of :func:`check_novikov`: geometry, generated gears, simulated contacts, findings."""

    geometry: NovikovPairGeometry
    report: CheckReport
    profiles: tuple
    contacts: tuple = ()

    @property
    def ok(self) -> bool:
        return self.report.ok

    def to_dict(self) -> dict:
        """JSON-ready dict (lengths mm, angles degrees): the geometry, the gears, the contacts, the findings."""
        out = {"ok": self.ok, "status": self.report.status}
        out.update(self.geometry.to_dict())
        out["gears"] = [p.summary() for p in self.profiles]
        out["simulated_contacts"] = [
            {"zone": c.zone, "point": [float(v) for v in c.point], "radii": list(c.radii),
             "contact_angle_deg": math.degrees(c.contact_angle),
             "contact_angle_transverse_deg": math.degrees(c.contact_angle_transverse),
             "on_arcs": c.on_arcs, "clearance": c.clearance, "touches": c.touches} for c in self.contacts]
        out["findings"] = [f.to_dict() for f in self.report.findings]
        return out


def _overlap(g, lim):
    eps, spec = g.overlap_ratio, g.spec
    m, beta = g.module, g.helix_angle
    status = grade(eps, fail_below=1.0, warn_below=lim.min_overlap_ratio)
    if beta == 0:
        msg = ("eps_beta = 0: a spur Novikov pair cannot run continuously (no transverse overlap); "
               "increase the helix angle beta (and give a face width b so that b sin(beta) > pi m_n)")
    else:
        need = lambda e: e * math.pi * m / math.sin(beta)  # noqa: E731
        msg = (f"eps_beta = b sin(beta)/(pi m_n) = {eps:.4f}; Novikov pairs have no transverse overlap, so "
               f"{'continuous drive needs eps_beta > 1' if status == 'fail' else 'the face overlap carries the drive'}")
        if status != "ok":
            msg += (f": increase the helix angle beta or the face width b (b >= {need(1.0):.2f} mm for 1, "
                    f">= {need(lim.min_overlap_ratio):.2f} mm for {lim.min_overlap_ratio:g} at beta = "
                    f"{math.degrees(beta):g} deg)")
    return Finding("overlap_ratio", status, eps, lim.min_overlap_ratio, msg, "min")


def _window_of(g, profiles):
    """Generated-arc window of a_w - a (module units) and the contact-angle range per zone."""
    lo, hi = -math.inf, math.inf
    alpha = g.contact_angle
    for zone in g.spec.racks.zones:
        cvx, ccv = profiles[zone.convex_gear - 1], profiles[2 - zone.convex_gear]
        wa, wf = cvx.working_window("convex"), ccv.working_window("concave")
        if wa is None or wf is None:
            return None
        a_lo, a_hi = max(wa[0], wf[0]), min(wa[1], wf[1])
        lo = max(lo, (math.sin(alpha) - math.sin(a_hi)) * zone.rho_diff)
        hi = min(hi, (math.sin(alpha) - math.sin(a_lo)) * zone.rho_diff)
    return lo, hi


def _gear_findings(g, profiles, lim):
    out = []
    m, beta = g.module, g.helix_angle
    for k, prof in enumerate(profiles, start=1):
        r = g.pitch_radii[k - 1]
        ra = prof.tip_diameter / 2
        beta_a = math.atan(math.tan(beta) * ra / r)
        s_an = prof.tip_thickness * math.cos(beta_a)
        status = "fail" if prof.pointed or s_an <= 0 else grade(s_an / m, warn_below=lim.min_tip_thickness)
        out.append(Finding(f"pointing.{k}", status, s_an / m, lim.min_tip_thickness,
                           f"normal tip thickness s_an = {s_an:.4f} mm"
                           + (": the tooth is pointed" if status == "fail" else "")
                           + (" (thin tip: shorten the tip or use a rack with a wider tip land)" if status == "warn"
                              else ""), "min"))
        rack = prof.spec.rack
        for which in ("convex", "concave"):
            if getattr(rack, which) is None:
                continue
            win = prof.working_window(which)
            a = rack.alpha
            margin = -math.inf if win is None else min(a - win[0], win[1] - a)
            status = "fail" if margin <= 0 else "ok"
            lo_rack = (rack.geometry.convex_window if which == "convex" else rack.geometry.concave_window)[0]
            msg = (f"the {which} arc is cut away" if win is None else
                   f"generated {which} arc spans rack angles {math.degrees(win[0]):.2f}..{math.degrees(win[1]):.2f} "
                   f"deg (rack {math.degrees(lo_rack):.2f}..); contact at {math.degrees(a):g} deg")
            if status == "fail":
                msg += ": undercut or the tip removed the contact point (fewer teeth need a smaller arc or tip)"
            out.append(Finding(f"working_arc.{k}.{which}", status, math.degrees(max(margin, -90.0)), 0.0,
                               msg + " (value: margin in degrees)", "min"))
    for k in (1, 2):
        c = g.tip_clearances[k - 1] / m
        out.append(Finding(f"tip_clearance.{k}", grade(c, fail_below=0.0, warn_below=lim.min_tip_clearance), c,
                           lim.min_tip_clearance, f"tip of gear {k} to the root of gear {3 - k}: "
                           f"{c * m:.4f} mm (value in m_n)", "min"))
    return out


def _window_finding(g, profiles, lim):
    win = _window_of(g, profiles)
    err = g.center_distance_error / g.module
    sens = math.degrees(g.sensitivity)
    if win is None:
        return Finding("center_distance_window", "fail", -1.0, lim.min_window,
                       "a working arc is cut away on a generated gear: no centre distance keeps the contact", "min")
    lo, hi = win
    half = min(err - lo, hi - err)
    status = "fail" if half <= 0 else grade(half, warn_below=lim.min_window)
    msg = (f"a_w - a = {err * g.module:+.4f} mm; the contact stays on the generated working arcs for a_w - a in "
           f"[{lo * g.module:+.4f}, {hi * g.module:+.4f}] mm ({lo:+.4f} .. {hi:+.4f} m_n); +0.01 m_n moves "
           f"alpha_k by {sens:+.2f} deg (sin a_k' = sin a_k - da/(rho_f - rho_a))")
    if status == "fail":
        msg += ": the contact runs off a working arc onto an edge; correct the centre distance"
    elif status == "warn":
        msg += ": very sensitive; a larger rho_f - rho_a widens the window"
    return Finding("center_distance_window", status, half, lim.min_window, msg + " (value in m_n)", "min")


def _mesh_findings(g, contacts, lim):
    out = []
    if not contacts:
        return out
    tol = contacts[0].tol
    clear = min(c.clearance for c in contacts)
    status = "fail" if clear < -2 * tol else "ok"
    out.append(Finding("mesh.interference", status, clear / g.module, -2 * tol / g.module,
                       f"smallest clearance between the meshing outlines away from the contact: {clear:.2e} mm "
                       f"(sampled to {tol:.1e} mm)" + (": the teeth interfere" if status == "fail" else ""), "min"))
    beta = g.helix_angle
    for c in contacts:
        zone = g.spec.racks.zones[c.zone]
        a = g.contact_angle
        s = math.sin(a) - g.center_distance_error / g.module / zone.rho_diff
        pred = math.degrees(math.asin(s)) if -1 < s < 1 else math.nan
        diff = abs(math.degrees(c.contact_angle) - pred) if math.isfinite(pred) else math.inf
        status = "ok"
        msg = (f"zone {c.zone} (convex arc on gear {zone.convex_gear}): one point at radii {c.radii[0]:.4f} / "
               f"{c.radii[1]:.4f} mm, alpha_k {math.degrees(c.contact_angle):.4f} deg (rack prediction "
               f"{pred:.4f}), alpha_t {math.degrees(c.contact_angle_transverse):.4f} deg")
        if not c.on_arcs:
            status, msg = "fail", msg + ": the contact is off the generated working arcs (edge contact)"
        elif c.touches != 1:
            status, msg = "warn", msg + f": the outlines touch in {c.touches} places"
        elif diff > lim.max_angle_error_deg:
            status, msg = "warn", msg + ": far from the rack prediction"
        if beta == 0:
            msg += " (spur: the whole arc touches at this instant only)"
        out.append(Finding(f"mesh.contact.{c.zone}", status, math.degrees(c.contact_angle),
                           pred if math.isfinite(pred) else None, msg))
    return out


def check_novikov(spec: NovikovPairSpec, limits: NovikovLimits = NovikovLimits(), simulate: bool = True,
                  tol: float | None = None) -> NovikovCheck:
    """Check a Novikov pair: overlap, pointing, working arcs, centre-distance window, clearances, mesh.

    ``simulate`` meshes the generated gears in the transverse plane (one solve per contact zone and
    an interference scan at ``tol``, default 1e-5 m_n).
    """
    from gearkit.families.novikov.mesh import NoContact, mesh_contact

    g = novikov_pair_geometry(spec)
    profiles = (tooth_profile(spec.gear(1)), tooth_profile(spec.gear(2)))
    racks = spec.racks
    findings = [_overlap(g, limits),
                Finding("transverse_contact_ratio", "ok", 0.0, None,
                        "eps_alpha = 0 by design: Novikov teeth touch at a point that travels along the face; "
                        "continuity comes from the face overlap eps_beta")]
    findings.append(Finding("racks", "ok" if racks.verified else "warn", 1.0 if racks.verified else 0.0, None,
                            f"rack system {racks.name!r} ({racks.kind})" + (
                                "" if racks.verified else ": parameters NOT verified against the standard; "
                                "verify against the standard before production")))
    findings += _gear_findings(g, profiles, limits)
    findings.append(_window_finding(g, profiles, limits))
    if g.contact_axial_distance is not None and math.isfinite(g.contact_axial_distance):
        frac = g.contact_axial_distance / g.axial_pitch
        lo, hi = math.floor(g.overlap_ratio), math.ceil(g.overlap_ratio)
        findings.append(Finding("contact_axial_distance", "ok", g.contact_axial_distance, None,
                                f"{g.contact_axial_distance:.4f} mm along the axis between the convex and the "
                                f"concave contact of one flank ({frac:.5f} p_x; their normals cross the axis "
                                f"{g.pole_axial_distance:.4f} mm apart); {2 * lo}..{2 * hi} contact points at a time "
                                f"(mean {g.mean_contacts:.3f})"))
    contacts, missing = [], []
    if simulate:
        for k in range(len(racks.zones)):
            try:
                contacts.append(mesh_contact(spec, k, tol=tol))
            except NoContact as exc:
                missing.append((k, exc))
    contacts = tuple(contacts)
    findings += _mesh_findings(g, contacts, limits)
    findings += [Finding(f"mesh.contact.{k}", "fail", g.center_distance, None,
                         f"zone {k}: the working flanks of the generated gears do not meet at a_w = "
                         f"{g.center_distance:.6g} mm ({exc}): the pair does not mesh there")
                 for k, exc in missing]
    return NovikovCheck(g, CheckReport(tuple(findings)), profiles, contacts)
