"""Pair geometry: working pressure angle, centre distance, tips, path of contact, ratios.

Every mesh quantity is derived in the transverse section. Positions on the line of action are
roll distances (mm) measured from ``N1``, the tangency point on the pinion's base circle,
towards the pitch point ``C`` (ISO 21771 points A, B, C, D, E).

Examples
--------
>>> g = pair_geometry(PairSpec(20, 40, module=2.0))
>>> round(g.center_distance, 6), round(g.contact_ratio, 4)
(60.0, 1.6352)
"""
from __future__ import annotations

import math
from functools import lru_cache

import numpy as np

from gearkit.curves import inv, inv_inverse
from gearkit.errors import SpecError, require
from gearkit.families.involute import GearSpec, ShaperCutter, tool_label
from gearkit.pair.spec import TIP_RULES, PairSpec
from gearkit.pair.tooling import (form_roll, graded_tip_radius, nu_radius, root_radius, section, thickness_coeff,
                                  tip_thickness)
from gearkit.values import frozen

__all__ = ["GearGeometry", "PairGeometry", "gear_specs", "gear_tip_diameter", "pair_geometry"]


@frozen
class GearGeometry:
    """Per-gear results, transverse section, lengths in mm (``None`` fields: not applicable).

    ``shift_coeff`` is the gear's shift as given, read by ``shift_convention`` (``"iso"``: by the tooth
    thickness, as if rack-cut; ``"cutter"``: the shaper's radial setting); ``cutter_setting`` is the
    shaper's radial setting that cuts the gear (None for a rack-cut gear).
    """

    teeth: int
    shift_coeff: float
    reference_diameter: float
    base_diameter: float
    working_diameter: float
    tip_diameter: float
    root_diameter: float
    form_diameter: float
    form_roll: float
    thickness_coeff: float
    tip_thickness: float
    tip_thickness_normal: float
    undercut: bool
    tool: str
    shift_convention: str = "iso"
    cutter_setting: float | None = None


@frozen
class PairGeometry:
    """Everything :func:`pair_geometry` derives (mm, radians, coefficients in m_n units).

    ``path`` holds the roll distances from N1 of the path-of-contact points A, B, C, D, E
    (ISO 21771), of N1 and N2, and of the ends of the involute flanks: ``F1`` where gear 1's
    involute begins (its form circle), ``F2`` where gear 2's ends (its form circle; for a rack,
    the end of its straight flank), and for a ring ``T2``, where its involute begins on the tip
    side (its tip circle, or O2N_u when the shaper trims it). ``path_real`` holds the ends of the
    real involute contact: the path A..E clipped by F1, F2 (and T2), e.g. shortened by undercut. ``contact_ratio`` (eps_alpha) is the real one;
    ``contact_ratio_nominal`` that of the whole tip-to-tip path.
    """

    spec: PairSpec
    kind: str
    module: float
    transverse_module: float
    pressure_angle: float
    transverse_pressure_angle: float
    helix_angle: float
    base_helix_angle: float
    reference_center_distance: float
    tight_center_distance: float
    center_distance: float
    working_pressure_angle: float
    center_distance_modification_coeff: float
    tip_shortening_coeff: float
    sum_shift_coeff: float
    gears: tuple
    line_of_action: float
    path: dict
    path_real: tuple
    base_pitch: float
    base_pitch_normal: float
    contact_ratio_nominal: float
    contact_ratio: float
    overlap_ratio: float
    specific_sliding: dict
    pressure_coeff: float
    tip_clearance: tuple
    backlash: float
    backlash_normal: float

    @property
    def total_contact_ratio(self) -> float:
        """eps_gamma = eps_alpha + eps_beta (real transverse ratio)."""
        return self.contact_ratio + self.overlap_ratio

    def sliding_at(self, roll):
        """ISO specific sliding (zeta1, zeta2) at roll distances from N1 (mm), vectorised."""
        return _sliding(self, np.asarray(roll, dtype=float))


def _sliding(g: PairGeometry, u):
    if isinstance(u, float):  # one roll distance (the ends of the path, per pair): plain floats
        try:
            return _sliding_formula(g, u)
        except ZeroDivisionError:
            u = np.asarray(u)
    with np.errstate(divide="ignore", invalid="ignore"):
        return _sliding_formula(g, u)


def _sliding_formula(g: PairGeometry, u):
    c = g.path["C"]
    if g.kind == "rack":
        return 1.0 - c / u, 1.0 - u / c
    ratio = g.gears[1].teeth / g.gears[0].teeth
    rho2 = g.line_of_action - u if g.kind == "external" else u + g.line_of_action
    return 1.0 - rho2 / (ratio * u), 1.0 - ratio * u / rho2


def _tight_alpha(kind: str, sec, z1: int, z2: int | None, d_sum: float) -> float:
    """Zero-backlash transverse working pressure angle from the thickness coefficients."""
    if kind == "rack":
        return sec.alpha_t
    if kind == "external":
        value = inv(sec.alpha_t) + d_sum / (z1 + z2)
    else:
        value = inv(sec.alpha_t) - d_sum / (z2 - z1)
    require(value > 1e-9, "shift1",
            f"the shifts are too negative for a mesh: inv(alpha_wt) = {value:.3g} <= 0")
    return inv_inverse(value)


@lru_cache(maxsize=4096)
def pair_geometry(spec: PairSpec, form_diameters: tuple | None = None) -> PairGeometry:
    """Derive the pair geometry of ``spec``.

    Parameters
    ----------
    spec : PairSpec
    form_diameters : (float, float or None) or None, mm
        Form diameters d_F of the gears as generated (where the involute flank begins), used for
        the real path of contact; None takes the tool formulas (exact when not undercut).

    Returns
    -------
    PairGeometry
    """
    kind = spec.kind
    sec = section(spec.module, spec.alpha_n_deg, spec.helix_angle_deg)
    mn, mt, at = sec.mn, sec.mt, sec.alpha_t
    tool1, tool2 = spec.tools
    z1, z2 = spec.teeth1, spec.teeth2
    x1, x2 = float(spec.shift1), (0.0 if kind == "rack" else float(spec.shift2))
    # the ring's shaper setting: its shift itself (cutter convention) or derived from the ISO shift
    x2c = spec.ring_cutter_setting if kind == "internal" else x2
    internal2 = kind == "internal"
    r1 = z1 * mt / 2
    rb1 = r1 * math.cos(at)
    d1 = thickness_coeff(sec, z1, x1, tool1, False)
    if kind == "rack":
        r2 = rb2 = math.inf
        d2 = 0.0
        a_ref = r1
        tight = r1 + mt * d1 / (2 * math.tan(at))
    else:
        r2 = z2 * mt / 2
        rb2 = r2 * math.cos(at)
        d2 = thickness_coeff(sec, z2, x2c, tool2, internal2)
        a_ref = r2 - r1 if internal2 else r1 + r2
        alpha_tight = _tight_alpha(kind, sec, z1, z2, d1 + d2)
        tight = (rb2 - rb1 if internal2 else rb1 + rb2) / math.cos(alpha_tight)
    a_w = tight if spec.center_distance is None else float(spec.center_distance)
    if kind == "rack":
        alpha_w = at
        x_sum = x1
    else:
        base = rb2 - rb1 if internal2 else rb1 + rb2
        require(a_w > base * (1 + 1e-12), "center_distance",
                f"a_w = {a_w:.6g} mm must exceed {'r_b2 - r_b1' if internal2 else 'r_b1 + r_b2'} = {base:.6g} mm")
        alpha_w = math.acos(base / a_w)
        x_sum = x2 - x1 if internal2 else x1 + x2
    y = (a_w - a_ref) / mn
    dy = y - x_sum if internal2 else x_sum - y
    # an external (or rack) pair's tips are shortened, never lengthened: a negative dy (a_w above
    # a + x_sum m) would grow them beyond the blank d + 2 m_n (h_a* + x) the gear is cut from. (An
    # internal pair keeps the textbook's signed dy, digest 3.2: its worked example lengthens by 0.147 m.)
    cut = (dy if internal2 else max(dy, 0.0)) if spec.tip_rule == "shortened" else 0.0
    ha = spec.addendum

    # tips, roots, forms
    # the allowance feeds the tool in (ISO 21771 generating shift x_E): root and form move with it.
    # Every tip is the one the check grades: the blank's, cut down to what the tool leaves.
    xe1 = x1 - spec.thinning1 / (2 * mn * math.tan(sec.alpha_n))
    ra1 = graded_tip_radius(sec, z1, xe1, tool1, False,
                            spec.tip_diameter1 / 2 if spec.tip_diameter1 else r1 + mn * (ha + x1 - cut))
    require(ra1 > rb1, "tip_diameter1", f"d_a1 = {2 * ra1:.6g} mm must exceed the base diameter {2 * rb1:.6g} mm")
    rf1 = root_radius(sec, z1, xe1, tool1, False)
    rho_l1 = form_roll(sec, z1, xe1, tool1, False)
    if kind == "rack":
        ra2 = rf2 = rho_l2 = math.inf
    else:
        if spec.tip_diameter2:
            ra2 = spec.tip_diameter2 / 2
        elif internal2:
            ra2 = r2 - mn * (ha - x2 - cut)
        else:
            ra2 = r2 + mn * (ha + x2 - cut)
        xe2 = x2c - spec.thinning2 / (2 * mn * math.tan(sec.alpha_n))
        ra2 = graded_tip_radius(sec, z2, xe2, tool2, internal2, ra2)
        rf2 = root_radius(sec, z2, xe2, tool2, internal2)
        rho_l2 = form_roll(sec, z2, xe2, tool2, internal2)
        if internal2:
            require(ra2 < rf2, "tip_diameter2", f"the ring's tip d_a2 = {2 * ra2:.6g} mm must be smaller "
                    f"than its root d_f2 = {2 * rf2:.6g} mm")
        else:
            require(ra2 > rb2, "tip_diameter2",
                    f"d_a2 = {2 * ra2:.6g} mm must exceed the base diameter {2 * rb2:.6g} mm")
    forms = _forms(form_diameters, rho_l1, rho_l2, rb1, rb2, kind)

    # path of contact (roll distances from N1)
    g_line = math.inf if kind == "rack" else a_w * math.sin(alpha_w)
    u_c = rb1 * math.tan(alpha_w)
    u_e = math.sqrt(ra1 ** 2 - rb1 ** 2)
    if kind == "external":
        u_a = g_line - math.sqrt(ra2 ** 2 - rb2 ** 2)
        u_hi = g_line - forms[1][1]
    elif internal2:
        inner2 = max(ra2, rb2, nu_radius(sec, z2, x2c, tool2))
        u_a = -g_line + math.sqrt(max(ra2, rb2) ** 2 - rb2 ** 2)
        u_lo2 = -g_line + math.sqrt(inner2 ** 2 - rb2 ** 2)
        u_hi = forms[1][1] - g_line
    else:
        u_a = u_c + (a_w - tool2.addendum * mn - r1) / math.sin(at)
        u_hi = u_c + (a_w + tool2.straight_height * mn - r1) / math.sin(at)
    p_bt = math.pi * mt * math.cos(at)
    path = {"A": u_a, "B": u_e - p_bt, "C": u_c, "D": u_a + p_bt, "E": u_e, "N1": 0.0,
            "N2": {"external": g_line, "internal": -g_line, "rack": math.inf}[kind],
            "F1": forms[0][1], "F2": u_hi}
    if internal2:
        path["T2"] = u_lo2
    lo = max(u_a, forms[0][1], u_lo2) if internal2 else max(u_a, forms[0][1])
    hi = min(u_e, u_hi)
    eps_real = max(hi - lo, 0.0) / p_bt
    eps_beta = 0.0 if spec.face_width is None else spec.face_width * math.sin(sec.beta) / (math.pi * mn)

    # pressure coefficient at the pitch point: theta = m_t (1/rho1 +- 1/rho2)
    if kind == "rack":
        theta = mt / u_c
    elif internal2:
        theta = mt * (1 / u_c - 1 / (u_c + g_line))
    else:
        theta = mt * (1 / u_c + 1 / (g_line - u_c))

    # clearances: (tip of 1 against root of 2, tip of 2 against root of 1)
    if kind == "external":
        clear = (a_w - ra1 - rf2, a_w - ra2 - rf1)
    elif internal2:
        clear = (rf2 - a_w - ra1, ra2 - a_w - rf1)
    else:
        clear = (a_w + tool2.dedendum * mn - ra1, a_w - tool2.addendum * mn - rf1)

    # backlash on the working circle (transverse), actual thicknesses
    t1 = d1 - spec.thinning1 / mn
    t2 = d2 - spec.thinning2 / mn
    if kind == "rack":
        backlash = 2 * (a_w - tight) * math.tan(at) + (spec.thinning1 + spec.thinning2) / math.cos(sec.beta)
        rw1 = r1
    else:
        rw1 = rb1 / math.cos(alpha_w)
        k = 2 * (inv(at) - inv(alpha_w))
        psi1 = (math.pi + 2 * t1) / z1 + k
        if internal2:
            eta2 = (math.pi - 2 * t2) / z2 + k
            backlash = rw1 * (z2 / z1 * eta2 - psi1)
        else:
            psi2 = (math.pi + 2 * t2) / z2 + k
            backlash = rw1 * (2 * math.pi / z1 - psi1 - z2 / z1 * psi2)
    backlash_n = backlash * math.cos(alpha_w) * math.cos(sec.beta_b)

    gears = [_gear(sec, z1, x1, r1, rb1, rw1, ra1, rf1, rho_l1, forms[0][0], t1, False, tool1)]
    if kind != "rack":
        rw2 = rb2 / math.cos(alpha_w)
        gears.append(_gear(sec, z2, x2, r2, rb2, rw2, ra2, rf2, rho_l2, forms[1][0], t2, internal2, tool2,
                           spec.shift_convention if internal2 else None, x2c))

    geo = PairGeometry(
        spec=spec, kind=kind, module=mn, transverse_module=mt, pressure_angle=sec.alpha_n,
        transverse_pressure_angle=at, helix_angle=sec.beta, base_helix_angle=sec.beta_b,
        reference_center_distance=a_ref, tight_center_distance=tight, center_distance=a_w,
        working_pressure_angle=alpha_w, center_distance_modification_coeff=y, tip_shortening_coeff=dy,
        sum_shift_coeff=x_sum, gears=tuple(gears), line_of_action=g_line, path=path, path_real=(lo, hi),
        base_pitch=p_bt, base_pitch_normal=math.pi * mn * math.cos(sec.alpha_n),
        contact_ratio_nominal=(u_e - u_a) / p_bt, contact_ratio=eps_real, overlap_ratio=eps_beta,
        specific_sliding={}, pressure_coeff=theta, tip_clearance=clear, backlash=backlash,
        backlash_normal=backlash_n)
    start, end = _sliding(geo, float(lo)), _sliding(geo, float(hi))
    geo.specific_sliding.update({"start": (float(start[0]), float(start[1])), "end": (float(end[0]), float(end[1]))})
    return geo


def _forms(form_diameters, rho_l1, rho_l2, rb1, rb2, kind):
    """((d_F1, rho_F1), (d_F2, rho_F2)): form diameters and their roll distances from N."""
    rolls = [max(rho_l1, 0.0), max(rho_l2, 0.0) if kind != "rack" else math.inf]
    if form_diameters is not None:
        for i, (d, rb) in enumerate(zip(form_diameters, (rb1, rb2))):
            if d is not None and math.isfinite(rb):
                rolls[i] = math.sqrt(max((d / 2) ** 2 - rb ** 2, 0.0))
    out = []
    for rho, rb in zip(rolls, (rb1, rb2)):
        out.append((2 * math.hypot(rb, rho) if math.isfinite(rb) else math.inf, rho))
    return tuple(out)


def _gear(sec, z, x, r, rb, rw, ra, rf, rho_l, d_form, t_actual, internal, tool, convention=None,
          setting=None) -> GearGeometry:
    s_at = tip_thickness(sec, z, t_actual, ra, internal)
    beta_a = math.atan(math.tan(sec.beta) * ra / r)
    return GearGeometry(
        teeth=z, shift_coeff=x, reference_diameter=2 * r, base_diameter=2 * rb, working_diameter=2 * rw,
        tip_diameter=2 * ra, root_diameter=2 * rf, form_diameter=d_form, form_roll=math.sqrt(max((d_form / 2) ** 2 - rb ** 2, 0.0)),
        thickness_coeff=t_actual, tip_thickness=s_at, tip_thickness_normal=s_at * math.cos(beta_a),
        undercut=bool(rho_l < 0 and not internal),
        tool=tool_label(tool),
        shift_convention=convention or ("cutter" if isinstance(tool, ShaperCutter) else "iso"),
        cutter_setting=(x if setting is None else setting) if isinstance(tool, ShaperCutter) else None)


def gear_specs(spec: PairSpec) -> tuple:
    """The kernel's :class:`~gearkit.families.involute.GearSpec` of each gear (tips from the pair).

    The wheel of an external pair has the opposite hand, a ring the same hand as the pinion.
    A rack pair yields the pinion only.
    """
    g = pair_geometry(spec)
    beta = spec.helix_angle_deg
    out = []
    gears = [(spec.teeth1, spec.shift1, beta, False, spec.tools[0], spec.thinning1)]
    if spec.kind != "rack":
        internal = spec.kind == "internal"
        gears.append((spec.teeth2, spec.shift2, beta if internal else -beta, internal, spec.tools[1], spec.thinning2))
    for i, (z, x, b, internal, tool, thin) in enumerate(gears):
        try:
            out.append(GearSpec(z, spec.module, float(x), b, internal, tool, g.gears[i].tip_diameter, thin,
                                shift_convention=spec.shift_convention))
        except SpecError as exc:  # name the gear of the pair the field belongs to
            raise SpecError(f"gear{i + 1}.{exc.field}", str(exc).split(": ", 1)[-1]) from None
    return tuple(out)


def gear_tip_diameter(gear, rule: str = "standard", mate=None, center_distance: float | None = None) -> float:
    """The tip diameter (mm) a single gear gets by a tip rule: the one tip it has in every mesh.

    Parameters
    ----------
    gear : GearSpec
    rule : {"standard", "shortened"}
        "standard": ``d + 2 m_n (h_a* + x)`` (ring ``d - 2 m_n (h_a* - x)``, ISO shift); "shortened":
        the pair's rule with ``mate`` (:class:`~gearkit.pair.PairSpec` ``tip_rule="shortened"``), which
        keeps the standard bottom clearance by ``dy m_n`` at ``center_distance`` (None: the tight mesh).
    mate : GearSpec or None
        The mating gear (required by "shortened"; a ring's mate is its pinion).

    Examples
    --------
    >>> from gearkit.families.involute import GearSpec
    >>> round(gear_tip_diameter(GearSpec(13, 2.0, 0.3), "shortened", GearSpec(40, 2.0)), 6)
    31.154268
    """
    require(rule in TIP_RULES, "tip_rule", f"{rule!r} is not one of {', '.join(TIP_RULES)}")
    h = gear.addendum_coeff
    standard = gear.reference_diameter + (-2 if gear.internal else 2) * gear.module * (h + (-1 if gear.internal else 1)
                                                                                     * gear.shift)
    if rule == "standard":
        return standard
    require(mate is not None, "mate", "the shortened tip rule needs the mating gear (its teeth and shift)")
    require(not (gear.internal and mate.internal), "mate", "two rings do not mesh")
    pinion, wheel = (mate, gear) if gear.internal else (gear, mate)
    kind = "internal" if wheel.internal else "external"
    spec = PairSpec(pinion.teeth, wheel.teeth, gear.module, pinion.shift, wheel.shift, kind,
                    helix_angle_deg=pinion.helix_angle_deg, tool1=pinion.tool, tool2=wheel.tool, addendum=h,
                    center_distance=center_distance, thinning1=pinion.thinning, thinning2=wheel.thinning,
                    shift_convention=wheel.shift_convention if wheel.internal else "iso")
    return pair_geometry(spec).gears[1 if gear is wheel else 0].tip_diameter
