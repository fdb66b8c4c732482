"""Design check of an involute pair: "will this pair work?", answered with numbers and reasons.

:func:`check_pair` derives the pair geometry, generates both gears with the kernel (so the
form circles, undercut and tip thickness are those the cutters really leave), and returns a
:class:`PairCheck` whose :class:`~gearkit.checks.CheckReport` holds one finding per check:

=========================  ======================================================  ==========
id                         checks                                                  on failure
=========================  ======================================================  ==========
undercut.i                 the generated gear i is undercut (value x, limit x_min)  warn
pointing.i                 normal tip thickness s_an (<= 0 fail)                    warn/fail
inspection.*.i             span, over pins, chordal: formula vs generated tooth     warn
                           (:mod:`gearkit.checks.inspection`; generated geometry)
contact_ratio              real eps_alpha (undercut/interference-shortened)         warn/fail
interference.1             active profile start of gear 1 vs its form circle        fail
interference.2             active profile end on gear 2 vs its form circle          fail
tip_clearance.i            tip of gear i to the mate's root                         warn/fail
min_teeth.i                z_i vs the undercut-free tooth number at its shift       warn
backlash                   circumferential backlash on the working circle           fail
internal pairs only:
exit_jamming               closed-form tip interference on leaving mesh            fail
tip_interference           sweep of the tip corners' trochoidal paths               fail
trimming.plunge            ring trimmed by the shaper while plunging (3.108)        fail
trimming.nu                ring's tip inside O2N_u: involute trimmed (3.110)        warn
ring_tip.base              ring's tip circle inside its base circle                 warn
min_teeth.difference       z2 - z1 vs (z_p)min (exit jamming)                       fail
min_teeth.cutter           z2 - z0 vs (z_pc)min (plunge trimming)                   fail
=========================  ======================================================  ==========

Interference values are roll distances (mm) from N1 along the line of action: the active
profile must lie inside the involute parts of both flanks, ``F1 <= A`` and ``E <= F2``.
"""
from __future__ import annotations

import math
from dataclasses import replace


from gearkit.checks.limits import CheckLimits, min_cutter_difference, min_teeth_undercut, min_tooth_difference
from gearkit.checks.report import ROUND_OFF, CheckReport, Finding, grade
from gearkit.curves import bracketed_root
from gearkit.errors import SpecError, require
from gearkit.export import json_number
from gearkit.pair.geometry import PairGeometry, gear_specs, pair_geometry
from gearkit.pair.spec import PairSpec
from gearkit.pair.tooling import form_roll, section
from gearkit.families.involute import BasicRack
from gearkit.values import frozen

__all__ = ["PairCheck", "check_pair", "fail_margins", "internal_findings", "min_shift_undercut"]

GEOMETRY_MODES = ("generated", "formula")


@frozen
class PairCheck:
    """Result of :func:`check_pair`: the geometry checked, the generated gears, the findings."""

    geometry: PairGeometry
    report: CheckReport
    profiles: tuple = ()
    inspections: tuple = ()

    @property
    def ok(self) -> bool:
        """True when no finding fails."""
        return self.report.ok

    def to_dict(self) -> dict:
        """The JSON object of ``gearkit check --json`` (lengths in mm, angles in degrees)."""
        g = self.geometry
        gears = []
        for i, gear in enumerate(g.gears):
            prof = self.profiles[i] if self.profiles else None
            gears.append({
                "teeth": gear.teeth, "shift_coeff": gear.shift_coeff, "shift_convention": gear.shift_convention,
                "cutter_setting": gear.cutter_setting, "internal": g.kind == "internal" and i == 1,
                "reference_diameter": gear.reference_diameter, "base_diameter": gear.base_diameter,
                "working_diameter": gear.working_diameter, "tip_diameter": gear.tip_diameter,
                "root_diameter": prof.root_diameter if prof else gear.root_diameter,
                "form_diameter": gear.form_diameter,
                "tip_thickness": prof.tip_thickness if prof else max(gear.tip_thickness, 0.0),
                "tip_thickness_normal": gear.tip_thickness_normal,
                "undercut": bool(prof.undercut) if prof else gear.undercut, "tool": gear.tool})
            if self.inspections:
                gears[-1]["inspection"] = self.inspections[i].to_dict()
        return {
            "ok": self.report.ok, "status": self.report.status, "kind": g.kind,
            "module": g.module, "transverse_module": g.transverse_module,
            "pressure_angle_deg": math.degrees(g.pressure_angle), "helix_angle_deg": math.degrees(g.helix_angle),
            "center_distance": g.center_distance, "reference_center_distance": g.reference_center_distance,
            "working_pressure_angle_deg": math.degrees(g.working_pressure_angle),
            "center_distance_modification_coeff": g.center_distance_modification_coeff,
            "tip_shortening_coeff": g.tip_shortening_coeff, "sum_shift_coeff": g.sum_shift_coeff,
            "contact_ratio": {"transverse": g.contact_ratio, "overlap": g.overlap_ratio,
                              "total": g.total_contact_ratio, "transverse_nominal": g.contact_ratio_nominal},
            "path_of_contact": {k: json_number(v) for k, v in g.path.items()},
            "specific_sliding": {k: [json_number(v) for v in pair] for k, pair in g.specific_sliding.items()},
            "pressure_coeff": g.pressure_coeff, "base_pitch": g.base_pitch,
            "tip_clearance": list(g.tip_clearance),
            "backlash": {"transverse": g.backlash, "normal": g.backlash_normal},
            "gears": gears,
            "findings": [f.to_dict() for f in self.report.findings],
            "geometry": "generated" if self.profiles else "formula",
        }


def min_shift_undercut(spec: PairSpec, which: int) -> float:
    """x_min of gear ``which`` (1 or 2): the smallest normal shift its tool cuts without undercut.

    Rack: ``h_s - z sin^2(a_t) / (2 cos b)`` (textbook 3.106/3.107); shaper: root of ``rho_l(x) = 0``.
    """
    sec = section(spec.module, spec.alpha_n_deg, spec.helix_angle_deg)
    tool = spec.tools[which - 1]
    z = spec.teeth1 if which == 1 else spec.teeth2
    if isinstance(tool, BasicRack):
        return tool.straight_height - z * math.sin(sec.alpha_t) ** 2 / (2 * math.cos(sec.beta))
    lo = -(z + tool.teeth) * (sec.mt / sec.mn) * (1 - math.cos(sec.alpha_t)) / 2 + 1e-9

    def rho(x):
        return form_roll(sec, z, x, tool, False)
    if rho(lo) >= 0:
        return lo
    return bracketed_root(rho, lo, 5.0, xtol=1e-13)


def fail_margins(g: PairGeometry) -> dict:
    """Signed margins of the findings that can fail, read off the pair geometry: each of them
    fails exactly when its margin is negative.

    Keys and units (mm unless said): ``pointing.i`` (normal tip thickness s_an; a zero thickness
    counts as pointed), ``contact_ratio`` (eps_alpha - 1, real ratio), ``interference.1``
    (A - F1 + tol), ``interference.2`` (F2 - E + tol), ``tip_clearance.i``, ``backlash``
    (j_wt + tol), with ``tol = 1e-9 m_n``. The blocking contours trace these same margins.
    """
    tol = 1e-9 * g.module
    out = {}
    for i, gear in enumerate(g.gears):
        s = gear.tip_thickness_normal
        out[f"pointing.{i + 1}"] = s if s != 0 else -5e-324
    out["contact_ratio"] = g.contact_ratio - 1.0
    out["interference.1"] = g.path["A"] - g.path["F1"] + tol
    out["interference.2"] = g.path["F2"] - g.path["E"] + tol
    for i, c in enumerate(g.tip_clearance):
        out[f"tip_clearance.{i + 1}"] = c
    out["backlash"] = g.backlash + tol
    return out


def check_pair(spec: PairSpec, limits: CheckLimits = CheckLimits(), geometry: str = "generated",
               simulate: bool = False, *, profiles: tuple | None = None, analysis=None) -> PairCheck:
    """Check a pair: every finding of the module table, from the generated or the formula geometry.

    Parameters
    ----------
    spec : PairSpec
    limits : CheckLimits
    geometry : {"generated", "formula"}
        "generated" (default) generates both gears and reads their form circles, undercut and tip
        thickness off them; "formula" uses the tool formulas only (fast, exact without undercut;
        an undercut gear's form circle is then taken at its base circle).
    simulate : bool
        Also mesh the generated gears over a cycle (:mod:`gearkit.contact`, about a second) and add
        the findings of :mod:`gearkit.checks.simulated`: the simulated contact ratio beside the
        formula's, and interference the formulas miss (or flag where the teeth clear).
    profiles : tuple of ToothProfile or None
        The generated gears of ``spec`` (those of :func:`gear_specs`) when the caller has them
        already (a scene builds each gear once); None generates them.
    analysis : ContactAnalysis or None
        The simulation of ``spec`` when the caller has run it already.

    Returns
    -------
    PairCheck
    """
    require(geometry in GEOMETRY_MODES, "geometry", f"{geometry!r} is not one of {', '.join(GEOMETRY_MODES)}")
    if geometry == "generated" and profiles is not None:
        require(len(profiles) == len(gear_specs(spec)), "profiles", "give one generated profile per gear of the pair")
        profiles = tuple(profiles)
    elif geometry == "generated":
        from gearkit.families.involute import tooth_profile

        profiles = []
        for i, gspec in enumerate(gear_specs(spec)):
            try:
                profiles.append(tooth_profile(gspec))
            except SpecError as exc:  # name the gear of the pair the field belongs to
                raise SpecError(f"gear{i + 1}.{exc.field}", str(exc).split(": ", 1)[-1]) from None
        profiles = tuple(profiles)
    else:
        profiles = ()
    if profiles:
        forms = tuple(p.form_diameter for p in profiles) + ((None,) if spec.kind == "rack" else ())
        g = pair_geometry(spec, forms)
        # the checked tip is the cut tip: a tooth that points below its blank's tip circle ends at its point
        cut = {f"tip_diameter{i + 1}": p.tip_diameter for i, p in enumerate(profiles)
               if p.pointed and not p.internal and p.tip_diameter < g.gears[i].tip_diameter}
        if cut:
            g = pair_geometry(replace(spec, **cut), forms)
    else:
        g = pair_geometry(spec)
    findings = _gear_findings(spec, g, profiles, limits)
    inspections = ()
    if profiles:
        from gearkit.checks.inspection import inspection_findings
        from gearkit.pair.inspection import inspect_gear

        inspections = []
        for i, (gspec, prof) in enumerate(zip(gear_specs(spec), profiles)):
            try:
                inspections.append(inspect_gear(gspec, profile=prof))
            except SpecError as exc:  # a tooth no instrument can measure is a finding, not an error
                findings.append(Finding(f"inspection.{i + 1}", "warn", 0.0, None,
                                        f"gear {i + 1}: no inspection dimensions ({exc})"))
                inspections = ()
                break
            findings += inspection_findings(inspections[-1], 1e-3 * spec.module, spec.face_width, f".{i + 1}")
        inspections = tuple(inspections)
    findings += _mesh_findings(spec, g, limits)
    if spec.kind == "internal":
        findings += internal_findings(spec, g)
    if simulate:
        from gearkit.checks.simulated import simulated_findings
        findings += simulated_findings(spec, g, findings, limits, analysis)
    return PairCheck(g, CheckReport(tuple(findings)), profiles, inspections)


def _gear_findings(spec, g, profiles, lim) -> list:
    margins = fail_margins(g)
    out = []
    mn = g.module
    names = ("pinion", "ring" if g.kind == "internal" else "wheel")
    for i, gear in enumerate(g.gears):
        n = i + 1
        who = f"gear {n} ({names[i]}, z = {gear.teeth})"
        ring = g.kind == "internal" and i == 1
        prof = profiles[i] if profiles else None
        if not ring:
            x_min = min_shift_undercut(spec, n)
            under = prof.undercut if prof else gear.undercut
            if under:
                depth = prof.undercut_depth if prof else 0.0
                depth = f"the fillet cuts {depth:.4g} mm into the flank; " if depth > 0 else ""
                msg = (f"{who} is undercut: {depth}the involute starts at d_F = "
                       f"{gear.form_diameter:.4f} mm; no undercut needs x >= {x_min:.4f}")
            else:
                msg = f"{who}: no undercut (x = {gear.shift_coeff:.4f}, x_min = {x_min:.4f})"
            out.append(Finding(f"undercut.{n}", "warn" if under else "ok", gear.shift_coeff, x_min, msg, "min"))
        s = gear.tip_thickness_normal
        pointed = margins[f"pointing.{n}"] < 0 or (prof is not None and prof.pointed)
        need = lim.min_tip_thickness * mn
        status = "fail" if pointed else grade(s, warn_below=need)
        msg = (f"{who}: the flanks meet below the tip circle (pointed tooth, s_an = {s:.4f} mm)" if pointed else
               f"{who}: normal tip thickness s_an = {s:.4f} mm = {s / mn:.3f} m_n (limit {lim.min_tip_thickness:g} m_n)")
        out.append(Finding(f"pointing.{n}", status, s, need, msg, "min"))
    return out


def _mesh_findings(spec, g, lim) -> list:
    mn = g.module
    margins = fail_margins(g)
    out = []
    eps, nominal = g.contact_ratio, g.contact_ratio_nominal
    short = "" if abs(eps - nominal) < 1e-9 else f", shortened from the tip-to-tip {nominal:.4f}"
    beta = f"; eps_beta = {g.overlap_ratio:.4f}, eps_gamma = {g.total_contact_ratio:.4f}" if g.helix_angle else ""
    if g.helix_angle and spec.face_width is None:
        beta += " (no face width given: eps_beta taken as 0)"
    status = "fail" if margins["contact_ratio"] < 0 else grade(eps, warn_below=lim.min_contact_ratio)
    out.append(Finding("contact_ratio", status, eps,
                       lim.min_contact_ratio, f"transverse contact ratio eps_alpha = {eps:.4f}{short}{beta}", "min"))
    tol = 1e-9 * mn
    f1, f2 = g.path["F1"], g.path["F2"]
    a, e = g.path["A"], g.path["E"]
    mate = "the rack" if g.kind == "rack" else "gear 2"
    msg = (f"the tip of {mate} meets gear 1 at roll {a:.4f} mm from N1, "
           + (f"inside its form circle (involute from {f1:.4f} mm, d_F1 = {g.gears[0].form_diameter:.4f} mm): "
              "it digs into the fillet" if a < f1 - tol else f"on the involute (it begins at {f1:.4f} mm)"))
    out.append(Finding("interference.1", "fail" if margins["interference.1"] < 0 else "ok", a, f1, msg, "min"))
    where = "the rack's straight flank ends" if g.kind == "rack" else "the involute of gear 2 ends"
    msg = (f"the tip of gear 1 meets {mate} at roll {e:.4f} mm from N1; {where} at {f2:.4f} mm"
           + (": it digs into the fillet" if e > f2 + tol else ""))
    out.append(Finding("interference.2", "fail" if margins["interference.2"] < 0 else "ok", e, f2, msg, "max"))
    need = lim.min_tip_clearance * mn
    for i, c in enumerate(g.tip_clearance):
        n = i + 1
        if g.kind == "rack" and n == 2:
            who = "the rack's tip to the pinion's root"
        else:
            who = f"the tip of gear {n} to the root of {'the rack' if g.kind == 'rack' else f'gear {3 - n}'}"
        status = "fail" if margins[f"tip_clearance.{n}"] < 0 else grade(c, warn_below=need)
        out.append(Finding(f"tip_clearance.{n}", status, c, need,
                           f"clearance from {who}: c = {c:.4f} mm = {c / mn:.3f} m_n (limit {lim.min_tip_clearance:g} m_n)"
                           + ("; the tip hits the root" if c < 0 else ""), "min"))
    for i, gear in enumerate(g.gears):
        if g.kind == "internal" and i == 1:
            continue
        z_min = min_teeth_undercut(spec.tools[i], gear.shift_coeff, mn, spec.alpha_n_deg, spec.helix_angle_deg)
        status = "warn" if gear.teeth < z_min else "ok"
        out.append(Finding(f"min_teeth.{i + 1}", status, gear.teeth, z_min,
                           f"gear {i + 1}: z = {gear.teeth}; its tool cuts without undercut from z = {z_min:.4f} "
                           f"at x = {gear.shift_coeff:.4f}", "min"))
    j = 0.0 if abs(g.backlash) < ROUND_OFF * mn else g.backlash  # a tight mesh's round-off is no backlash
    j_n = 0.0 if abs(g.backlash_normal) < ROUND_OFF * mn else g.backlash_normal
    status = "fail" if margins["backlash"] < 0 else "ok"
    msg = (f"backlash j_wt = {j:.5f} mm on the working circle (normal j_bn = {j_n:.5f} mm)"
           + ("; negative: the centre distance is below the tight mesh of these teeth" if status == "fail" else ""))
    out.append(Finding("backlash", status, j, 0.0, msg, "min"))
    return out


def internal_findings(spec: PairSpec, g: PairGeometry) -> list:
    """The internal-pair findings of :func:`check_pair` (see the module's table), from the internal
    pair geometry of :mod:`gearkit.pair.internal` (loaded here: an external pair's check never needs it)."""
    from gearkit.pair.internal import SWEEP_RESOLUTION, exit_jamming_margin, nu_radius, plunge_trimming, tip_sweep

    mn = g.module
    p, ring = g.gears
    z1, z2, z0 = p.teeth, ring.teeth, spec.tools[1].teeth
    out = []
    margin = exit_jamming_margin(g)
    out.append(Finding("exit_jamming", "fail" if margin < 0 else "ok", margin, 0.0,
                       "tip circles never overlap: no exit jamming" if math.isinf(margin) else
                       f"tip interference on leaving mesh: margin {margin:.5f} rad "
                       + ("< 0: the pinion's tip corner hits the ring's tooth tip (raise x2 or z2 - z1)"
                          if margin < 0 else ">= 0"), "min"))
    depth, phi = tip_sweep(g)
    res = SWEEP_RESOLUTION * mn
    out.append(Finding("tip_interference", "fail" if depth > 0 else "ok", depth, res,
                       f"tip corners swept along their trochoidal paths through the mate's teeth: "
                       + (f"penetrate {depth:.4g} mm at pinion angle {math.degrees(phi):.2f} deg" if depth > 0
                          else f"no penetration deeper than {res:.3g} mm"), "max"))
    gap, at = plunge_trimming(g)
    out.append(Finding("trimming.plunge", "fail" if gap <= 0 else "ok", gap, 0.0,
                       f"shaper plunge: closest approach of the ring's and the shaper's tip corners "
                       f"{gap:.4f} mm at {math.degrees(at):.2f} deg"
                       + (" <= 0: the shaper trims the ring's teeth while feeding in" if gap <= 0 else ""), "min"))
    r_nu = nu_radius(g)
    d_nu = 2 * r_nu
    da2 = ring.tip_diameter
    trimmed = da2 < d_nu - 1e-9 * mn
    out.append(Finding("trimming.nu", "warn" if trimmed else "ok", da2, d_nu,
                       (f"the ring's tip circle d_a2 = {da2:.4f} mm lies inside 2 O2N_u = {d_nu:.4f} mm: the shaper "
                        f"trims its involute there ({(d_nu - da2) / 2:.4f} mm of height)") if trimmed else
                       f"the ring's tip circle d_a2 = {da2:.4f} mm is outside 2 O2N_u = {d_nu:.4f} mm: no trimming",
                       "min"))
    below = ring.tip_diameter < ring.base_diameter
    out.append(Finding("ring_tip.base", "warn" if below else "ok", ring.tip_diameter, ring.base_diameter,
                       (f"the ring's tip circle d_a2 = {ring.tip_diameter:.4f} mm lies inside its base circle "
                        f"d_b2 = {ring.base_diameter:.4f} mm: its teeth are not involute there") if below else
                       "the ring's tip circle lies outside its base circle", "min"))
    k_min = min_tooth_difference(spec)
    limit = math.inf if k_min is None else float(k_min)
    jams = margin < 0  # the pair as checked: its own difference never contradicts exit_jamming
    out.append(Finding("min_teeth.difference", "fail" if z2 - z1 < limit or jams else "ok", float(z2 - z1), limit,
                       f"tooth difference z2 - z1 = {z2 - z1}; exit jamming needs at least "
                       + ("(none found)" if k_min is None else f"{k_min}") + " at these shifts"
                       + ("; this pair's own tips jam (exit_jamming)" if jams and z2 - z1 >= limit else ""), "min"))
    c_min = min_cutter_difference(spec)
    limit = math.inf if c_min is None else float(c_min)
    out.append(Finding("min_teeth.cutter", "fail" if z2 - z0 < limit else "ok", float(z2 - z0), limit,
                       f"ring minus shaper teeth z2 - z0 = {z2 - z0}; plunging without trimming needs at least "
                       + ("(none found)" if c_min is None else f"{c_min}"), "min"))
    return out
