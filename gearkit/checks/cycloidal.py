"""Design checks of the cycloidal family: pin-wheel drives, cycloid pairs, pin gearing.

Each check is a :class:`~gearkit.checks.report.Finding` with its number, its limit and a reason
(reference digest on cycloid–pin-wheel meshing §4 item 15; textbook §53):

drive
    ``meshing.condition`` e' = e (the disc generated with the crank's eccentricity);
    ``curtate`` |K1| < 1; ``profile.closed`` Z_g/|dz| an integer; ``pins.overlap``
    r_Z < R_Z sin(pi/Z_b); ``looping`` grinding pin radius below |rho_0|min (and the kernel cut
    no loop); ``tip.pointed`` for |dz| > 1 without an addendum circle; ``contact_ratio``;
    ``clearance`` Δr - ΔR >= 0 (tip and root); then the simulated mesh: ``pins_in_contact``,
    ``load_carrying_pins``, ``active_pin_arc``, ``backlash``.
pair
    ``pointed.1``/``.2``, ``undercut.1``/``.2``, ``contact_ratio``.
pin gearing
    ``flank.loop`` (the equidistant's loop is trimmed; fail when no working flank is left),
    ``pointed``, ``contact_ratio``.
"""
from __future__ import annotations

import math

from gearkit.checks.report import CheckReport, Finding, grade
from gearkit.errors import GearkitError
from gearkit.values import frozen

__all__ = ["DriveCheck", "check_drive", "PairCheck", "check_cycloid_pair", "PinGearCheck", "check_pin_gearing",
           "MIN_CONTACT_RATIO"]

#: warn below this contact ratio (fail below 1)
MIN_CONTACT_RATIO = 1.2


@frozen
class FamilyCheck:
    """The values of a check (JSON-ready through :meth:`to_dict`) and its findings."""

    values: dict
    report: CheckReport

    def to_dict(self) -> dict:
        out = dict(self.values)
        out.update(self.report.to_dict())
        return out


class DriveCheck(FamilyCheck):
    """Values and findings of a cycloid-pin-wheel drive check."""


class PairCheck(FamilyCheck):
    """Values and findings of a cycloid pair (or clock gearing) check."""


class PinGearCheck(FamilyCheck):
    """Values and findings of a pin-gearing check."""


def _deg(x):
    return math.degrees(x)


def check_drive(spec, samples: int = 2000) -> DriveCheck:
    """Check a cycloid–pin-wheel drive (:class:`~gearkit.families.cycloidal.DriveSpec`).

    The simulated mesh runs ``samples`` instants over one mesh period on the generated disc.
    """
    from gearkit.families.cycloidal import (backlash, contact_ratio, disc_profile, min_curvature_radius,
                                            psi_max, simulate_mesh)

    f = []
    e, e_gen = spec.eccentricity, spec.generating_eccentricity
    f.append(Finding("meshing.condition", "ok" if abs(e_gen - e) <= 1e-9 * e else "fail", abs(e_gen - e), 0.0,
                     f"disc generated with e' = {e_gen:g} mm, crank e = {e:g} mm: the correct-meshing condition is "
                     "e' = e (the disc's pitch 2 pi e' must equal the pin wheel's)", "max"))
    k1 = abs(spec.k1)
    f.append(Finding("curtate", "ok" if k1 < 1.0 else "fail", k1, 1.0,
                     f"|K1| = e Z_b/(R_Z |dz|) = {k1:.6g}: must be below 1 for a curtate cycloid (practical "
                     "designs 0.5-0.8)", "max"))
    zd = spec.lobes / abs(spec.tooth_difference)
    f.append(Finding("profile.closed", "ok" if spec.closed else "fail", zd, float(round(zd)),
                     f"Z_g/|dz| = {zd:.6g} must be an integer, else the profile does not close on itself"))
    lim = spec.pin_overlap_limit
    f.append(Finding("pins.overlap", "ok" if spec.pin_radius < lim else "fail", spec.pin_radius, lim,
                     f"pin radius {spec.pin_radius:g} mm against R_Z sin(pi/Z_b) = {lim:.6g} mm: larger pins "
                     "overlap their neighbours", "max"))
    gap = spec.equidistant_mod - spec.shift_mod
    f.append(Finding("clearance", grade(gap, fail_below=0.0), gap, 0.0,
                     f"radial clearance at tip and root dr - dR = {gap:.6g} mm (negative: the disc interferes "
                     "with the pins)", "min"))
    values = {"tooth_difference": spec.tooth_difference, "k1": spec.k1, "equivalent_pins": spec.equivalent_pins,
              "pin_pitch_radius": spec.pin_pitch_radius, "disc_pitch_radius": spec.disc_pitch_radius,
              "rolling_radius": spec.rolling_radius, "active_pin_arc_deg": _deg(spec.active_pin_arc)}
    rho_min, phi_at = min_curvature_radius(spec)
    values["min_curvature_radius"] = rho_min if math.isfinite(rho_min) else None  # None: never bends that way
    broken = [x for x in f if x.status == "fail" and x.id in ("curtate", "profile.closed", "pins.overlap",
                                                            "meshing.condition")]
    disc = None
    if not broken or all(x.id == "meshing.condition" for x in broken):
        try:
            disc = disc_profile(spec)
        except GearkitError as exc:
            f.append(Finding("generation", "fail", 0.0, None, f"the disc could not be generated: {exc}"))
    r_grind = spec.grind_pin
    looped = bool(disc is not None and disc.looped)
    status = "fail" if (r_grind >= rho_min or looped) else "ok"
    f.append(Finding("looping", status, r_grind, rho_min,
                     (f"grinding pin radius {r_grind:.6g} mm against the theoretical curve's smallest curvature "
                      f"radius |rho_0|min = {rho_min:.6g} mm (at phi = {_deg(phi_at):.2f} deg): "
                      if phi_at is not None else "the theoretical curve never bends towards the pins (no curvature "
                      "radius limits the pin radius): ") + ("the offset loops and the pins undercut the disc (the kernel cut a loop away)"
                                 if status == "fail" else "regular"), "max"))
    side = "innermost" if spec.sign > 0 else "outermost"
    f.append(Finding("active_pin_arc", "ok", _deg(spec.active_pin_arc), 90.0,
                     f"contact stays within +-{_deg(spec.active_pin_arc):.4f} deg (arcsin |K1|) of the pin's "
                     f"{side} point", "max"))
    if disc is None:
        return DriveCheck(values, CheckReport(tuple(f)))
    values.update({"tip_radius": disc.tip_diameter / 2.0, "root_radius": disc.root_diameter / 2.0,
                   "pointed": disc.pointed})
    if abs(spec.tooth_difference) > 1:
        f.append(Finding("tip.pointed", "warn" if disc.pointed else "ok", disc.tip_thickness, 0.0,
                         "the teeth of a multi-tooth-difference disc meet in a point at the symmetry axis; truncate "
                         "them with an addendum circle (tip_radius)" if disc.pointed else
                         f"teeth truncated at r = {disc.tip_diameter / 2:.6g} mm", "min"))
    try:
        eps = contact_ratio(spec)
        values["psi_max_deg"] = _deg(psi_max(spec))
    except (GearkitError, ValueError) as exc:
        eps = 0.0
        values["psi_max_deg"] = None
        f.append(Finding("contact_ratio.formula", "warn", 0.0, None, f"psi_max not found: {exc}"))
    values["contact_ratio"] = eps
    f.append(Finding("contact_ratio", grade(eps, fail_below=1.0, warn_below=MIN_CONTACT_RATIO), eps,
                     MIN_CONTACT_RATIO, f"eps = Z_b Z_g psi_max/(2 pi |dz|) = {eps:.6g} pins on the loaded flank "
                     "on average", "min"))
    if spec.generating_eccentricity != spec.eccentricity or gap < 0:
        return DriveCheck(values, CheckReport(tuple(f)))
    beta, state = backlash(spec)
    values["backlash_rad"] = beta
    if beta > 0.0:  # a modified disc: at zero load only the pins met after taking up the backlash touch
        touching = state.touching
        values["pins_in_contact"] = float(touching.sum())
        values["load_carrying_pins"] = float(state.load_carrying(-1).sum())
        values["mesh_state"] = "zero load, backlash taken up (crank at psi0 = 0)"
        f.append(Finding("pins_in_contact", "ok", float(touching.sum()), None,
                         f"at zero load, after the disc turns {beta * 1e3:.5f} mrad, {int(touching.sum())} pin(s) "
                         "touch; more share the load only as the parts deform (not modelled)"))
        f.append(Finding("load_carrying_pins", grade(float(state.load_carrying(-1).sum()), fail_below=1.0),
                         float(state.load_carrying(-1).sum()), 1.0,
                         f"pins carrying load at zero load: {int(state.load_carrying(-1).sum())} (the unmodified "
                         f"drive: {eps:.4f})", "min"))
    else:
        stats = simulate_mesh(spec, samples=samples)
        values["pins_in_contact"] = stats.touching[0]
        values["load_carrying_pins"] = stats.loaded[0]
        values["mesh_state"] = f"unmodified, averaged over one mesh period ({stats.samples} instants)"
        values["pins_in_contact_range"] = [stats.touching[1], stats.touching[2]]
        values["load_carrying_range"] = [stats.loaded[1], stats.loaded[2]]
        f.append(Finding("pins_in_contact", "ok", stats.touching[0], None,
                         f"pins touching the generated disc: {stats.touching[0]:.4f} on average "
                         f"({stats.touching[1]}..{stats.touching[2]}) over one mesh period"))
        f.append(Finding("load_carrying_pins", grade(stats.loaded[0], fail_below=1.0), stats.loaded[0], 1.0,
                         f"pins carrying load in one direction: {stats.loaded[0]:.4f} on average "
                         f"({stats.loaded[1]}..{stats.loaded[2]}); the contact ratio predicts {eps:.4f}", "min"))
    f.append(Finding("backlash", "ok", beta, None,
                     f"the disc turns {beta * 1e3:.5f} mrad (crank held) before a pin touches"
                     + (f"; then {int(state.touching.sum())} pin(s) touch" if beta > 0 else " (no backlash)")))
    return DriveCheck(values, CheckReport(tuple(f)))


def check_cycloid_pair(spec) -> PairCheck:
    """Check a cycloid pair (:class:`~gearkit.families.cycloidal.CycloidPairSpec`) on the generated gears."""
    from gearkit.families.cycloidal import (clock_factors, cycloid_gear, generated_contact_ratio,
                                            pair_contact_ratio)

    f = []
    values = {"module": spec.module, "pinion_teeth": spec.pinion_teeth, "wheel_teeth": spec.wheel_teeth,
              "center_distance": spec.center_distance, "rolling_radius1": spec.rolling(1),
              "rolling_radius2": spec.rolling(2), "clock": spec.clock}
    for k in (1, 2):
        g = cycloid_gear(spec, k)
        values[f"tip_diameter{k}"] = g.tip_diameter
        values[f"root_diameter{k}"] = g.root_diameter
        values[f"form_diameter{k}"] = g.form_diameter
        f.append(Finding(f"pointed.{k}", "fail" if g.pointed else "ok", g.tip_thickness, 0.0,
                         f"gear {k}: tip thickness {g.tip_thickness:.6g} mm" + (" (pointed below its tip circle: a "
                         "larger generating circle or a smaller addendum)" if g.pointed else ""), "min"))
        f.append(Finding(f"undercut.{k}", "warn" if g.undercut else "ok", float(g.undercut), 0.0,
                         f"gear {k}: " + ("the cutter's tip corner cuts into the hypocycloidal flank"
                                          if g.undercut else "no undercut"), "max"))
    eps = pair_contact_ratio(spec)
    values["contact_ratio"] = eps
    values["contact_ratio_generated"] = generated_contact_ratio(spec)
    f.append(Finding("contact_ratio", grade(eps, fail_below=1.0, warn_below=MIN_CONTACT_RATIO), eps,
                     MIN_CONTACT_RATIO, f"eps = (arc of approach + arc of recess)/(pi m) = {eps:.6g} (from the "
                     f"generated flanks: {values['contact_ratio_generated']:.6g})", "min"))
    if spec.clock:
        big_a, add, rad = clock_factors(spec.module, spec.pinion_teeth, spec.wheel_teeth)
        values.update({"theoretical_addendum": big_a, "wheel_addendum_factor": add,
                       "wheel_addendum_radius_factor": rad})
    return PairCheck(values, CheckReport(tuple(f)))


def check_pin_gearing(spec) -> PinGearCheck:
    """Check pin (lantern) gearing (:class:`~gearkit.families.cycloidal.PinGearSpec`) on the generated wheel."""
    from gearkit.families.cycloidal import first_usable_roll, pin_gear_wheel

    w = pin_gear_wheel(spec)
    f = []
    values = {"module": spec.module, "pins": spec.pins, "wheel_teeth": spec.wheel_teeth,
              "pin_radius": spec.pin_radius, "center_distance": spec.center_distance,
              "tip_diameter": w.tip_diameter, "root_diameter": w.root_diameter,
              "first_usable_roll_deg": math.degrees(first_usable_roll(spec))}
    try:
        r_use = w.usable_flank_radius()
        s0, s1 = w.contact_rolls()
        eps = (s1 - s0) / (math.pi * spec.module)
    except GearkitError:
        r_use, eps = w.tip_diameter / 2.0, 0.0
    values["usable_flank_radius"] = r_use
    top = w.tip_diameter / 2.0
    status = "fail" if r_use >= top - 1e-9 * top else "ok"
    f.append(Finding("flank.loop", status, r_use, top,
                     f"the flank's equidistant loops next to the pitch circle and is trimmed: pins touch the wheel "
                     f"from r = {r_use:.6g} mm" + (" - no working flank is left below the tip" if status == "fail"
                                                 else f" to the tip r = {top:.6g} mm"), "max"))
    f.append(Finding("pointed", "warn" if w.pointed else "ok", w.tip_thickness, 0.0,
                     f"wheel tip thickness {w.tip_thickness:.6g} mm" + (" (pointed below the tip circle)"
                                                                        if w.pointed else ""), "min"))
    values["contact_ratio"] = eps
    f.append(Finding("contact_ratio", grade(eps, fail_below=1.0, warn_below=MIN_CONTACT_RATIO), eps,
                     MIN_CONTACT_RATIO, f"contact on one side of the line of centres only: eps = {eps:.6g} (the "
                     "pin wheel's turn while a pin runs from the trim point to the tip, over the pitch)", "min"))
    return PinGearCheck(values, CheckReport(tuple(f)))
