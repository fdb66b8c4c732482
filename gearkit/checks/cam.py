"""Design checks of a disc cam: pressure angles (with and without friction), the smallest prime
radius, undercut and curvature, flat-face convexity and face width, and the motion law's joins.

Findings (:class:`~gearkit.checks.report.Finding`, textbook ch. VII and the friction digest §3):

``pressure_angle.rise`` / ``.return``
    the largest pressure angle read off the generated contact, against the limit (30 degrees
    translating, 45 rocker). The return counts (fail) only for a grooved cam; a spring-closed
    return above the limit is a warning.
``pressure_angle_friction.rise`` / ``.return``
    the same with friction in the roller joint: the digest's power model (``s'/eta``) or the
    textbook's friction-angle model (``alpha + atan mu``).
``prime_radius``
    r0 against the smallest prime radius that keeps the driving phases within the limit (with
    friction when it is given).
``undercut``
    a roller larger than the pitch curve's convex radius of curvature (or a non-convex flat-face
    cam): the envelope loops, the kernel cuts the loop, the cam does not give the motion there.
``roller_radius``
    the textbook's advice R_p <= min(0.7 rho_min, 0.4 r0) (warning).
``convexity``, ``face_width``
    flat face: the profile's radius of curvature must stay positive; the face must cover the
    contact's travel along it. A flat face's ``undercut`` is how far the follower, held against the
    cam the face leaves (the intersection of its half-planes), falls short of its law and where.
``motion.velocity`` / ``.acceleration`` / ``.jerk`` at each join
    a velocity jump is an infinite acceleration (hard impact), an acceleration jump a soft impact.
"""
from __future__ import annotations

import math

import numpy as np

from gearkit.checks.cycloidal import FamilyCheck
from gearkit.checks.report import CheckReport, Finding, grade

__all__ = ["CamCheck", "check_cam", "default_cam_tol", "ROLLER_ADVICE"]

#: textbook advice on the roller radius: R_p <= min(0.7 rho_min, 0.4 r0)
ROLLER_ADVICE = (0.7, 0.4)
#: cam angles per phase for the extremes read off the geometry
_PER_PHASE = 1201
#: a jump in a derivative of s (mm/rad^n) below this fraction of the stroke is no jump
_JUMP_REL = 1e-6


class CamCheck(FamilyCheck):
    """Values and findings of a cam check."""


def default_cam_tol(spec) -> float:
    """Default 2D tolerance of a cam: 1e-4 of (prime radius + stroke), mm."""
    return 1e-4 * (spec.prime_radius + spec.stroke)


def _phase_grid(p0, p1, n=_PER_PHASE):
    return np.linspace(p0, p1, n)


def _intervals(mask, phi):
    """Runs of True in ``mask`` over the grid ``phi`` as [[start_deg, end_deg]]."""
    out, start = [], None
    for k, m in enumerate(mask):
        if m and start is None:
            start = phi[k]
        if not m and start is not None:
            out.append([math.degrees(start), math.degrees(phi[k - 1])])
            start = None
    if start is not None:
        out.append([math.degrees(start), math.degrees(phi[-1])])
    return out


def _friction(spec):
    """(label, efficiency, mu) of the friction model in use, or None without friction."""
    if spec.friction > 0.0:
        return "friction angle atan(mu) added (textbook 3.15)", 1.0, spec.friction
    if spec.efficiency < 1.0:
        return "power balance eta (OP) = s' (friction digest eq. 6 / corrected 18)", spec.efficiency, 0.0
    return None


def check_cam(spec, tol: float | None = None) -> CamCheck:
    """Generate and check the cam of ``spec``; ``tol`` (mm) is the outline's chord tolerance.

    Examples
    --------
    >>> from gearkit.families.cam import CamSpec, MotionProgram
    >>> spec = CamSpec(56.7702, MotionProgram.rise_dwell_return(20.0, 60.0, 60.0, 60.0), roller_radius=10.0)
    >>> res = check_cam(spec)
    >>> round(res.values["pressure_angle_max_deg"]["rise"], 3), res.values["undercut"], res.report.status
    (30.0, False, 'ok')
    """
    from gearkit.families.cam import cam_profile, law_pressure_angle, smallest_prime_radius

    tol = default_cam_tol(spec) if tol is None else float(tol)
    prof = cam_profile(spec)
    outline = prof.outline(tol)
    f, values = [], {}
    lim = spec.limit_deg
    phases = spec.motion.phases()
    fr = _friction(spec)
    worst = {"rise": 0.0, "return": 0.0}
    worst_fr = {"rise": 0.0, "return": 0.0}
    for kind, p0, p1, _, _ in phases:
        if kind == "dwell":
            continue
        grid = _phase_grid(p0, p1)
        worst[kind] = max(worst[kind], float(np.degrees(np.abs(prof.pressure_angle(grid))).max()))
        if fr is not None:
            _, eta, mu = fr
            worst_fr[kind] = max(worst_fr[kind],
                                 float(np.degrees(np.abs(law_pressure_angle(spec, grid, eta, mu))).max()))
    values["pressure_angle_max_deg"] = worst
    values["pressure_angle_limit_deg"] = lim
    for kind in ("rise", "return"):
        driven = kind == "rise" or spec.groove
        status = grade(worst[kind], fail_above=lim) if driven else grade(worst[kind], warn_above=lim)
        f.append(Finding(f"pressure_angle.{kind}", status, worst[kind], lim,
                         f"largest pressure angle of the {kind}, degrees, read off the generated contact"
                         + ("" if driven else " (spring-closed return: a warning only)"), "max"))
    if fr is not None:
        label, eta, mu = fr
        values["pressure_angle_friction_max_deg"] = worst_fr
        values["friction_model"] = label
        for kind in ("rise", "return"):
            driven = kind == "rise" or spec.groove
            status = grade(worst_fr[kind], fail_above=lim) if driven else grade(worst_fr[kind], warn_above=lim)
            f.append(Finding(f"pressure_angle_friction.{kind}", status, worst_fr[kind], lim,
                             f"largest pressure angle of the {kind} with friction, degrees ({label})", "max"))
    r_min = smallest_prime_radius(spec, 1.0, 0.0) if spec.contact != "flat" or spec.follower == "translating" \
        else None
    values["prime_radius"] = spec.prime_radius
    values["prime_radius_min"] = r_min
    if fr is not None and spec.contact != "flat":
        _, eta, mu = fr
        r_min = smallest_prime_radius(spec, eta, mu)
        values["prime_radius_min_friction"] = r_min
    if r_min is not None:
        what = "convexity of the flat-faced cam" if spec.contact == "flat" else \
            f"pressure angle <= {lim:g} degrees over the driving phases" + (" with friction" if fr else "")
        f.append(Finding("prime_radius", "ok" if spec.prime_radius >= r_min * (1 - 1e-9) else "fail",
                         spec.prime_radius, r_min, f"prime radius r0, mm, against the smallest that keeps the {what}",
                         "min"))
    _curvature(spec, prof, f, values, tol)
    _motion(spec, f, values)
    rmin, rmax = prof.radii()
    achieved = prof.achieved(tol)
    values.update({"base_radius": rmin, "max_radius": rmax, "vertices": int(len(outline)),
                   "tolerance": {"requested": tol, "achieved": achieved}})
    return CamCheck(values, CheckReport(tuple(f)))


def _curvature(spec, prof, f, values, tol):
    """Undercut, smallest radii of curvature, roller advice, flat-face convexity and width."""
    phi = np.linspace(0.0, 2.0 * math.pi, 7201)
    values["undercut"] = prof.undercut
    values["loops_deg"] = [[math.degrees(a), math.degrees(b)] for a, b in prof.loops]
    if spec.contact == "flat":
        rho = prof.curvature_radius(phi)
        rho_min = float(np.min(rho))
        values["min_curvature_radius"] = rho_min
        f.append(Finding("convexity", "ok" if rho_min > 0 and not prof.undercut else "fail", rho_min, 0.0,
                         "smallest radius of curvature of the flat-faced cam, mm: it must stay positive (convex "
                         "cam), else the face cannot follow the motion", "min"))
        gap, actual = _departure(spec, prof, phi, tol, f, values)
        reach = np.where(gap > 0.0, actual, prof.face_contact(phi))  # where the face leaves its law: where it rests
        values["face_contact_range"] = [float(reach.min()), float(reach.max())]
        values["face_width"] = float(reach.max() - reach.min())
        f.append(Finding("face_width", "ok", values["face_width"], None,
                         f"the face must reach from {reach.min():.6g} to {reach.max():.6g} mm along it (from the "
                         "foot of the follower axis; a rocker's from the pivot): at least this width, plus a margin"))
        return
    rho_p = prof.pitch_curvature_radius(phi)
    convex = rho_p > 0
    rho_pitch = float(rho_p[convex].min()) if convex.any() else math.inf
    rr = spec.roller_radius
    values["pitch_min_curvature_radius"] = rho_pitch
    values["min_curvature_radius"] = rho_pitch - rr
    under = convex & (rho_p < rr)
    values["undercut_deg"] = _intervals(under, phi)
    f.append(Finding("undercut", "fail" if prof.undercut or rho_pitch <= rr else "ok", rr, rho_pitch,
                     f"roller radius {rr:g} mm against the pitch curve's smallest convex radius of curvature "
                     f"{rho_pitch:.6g} mm: " + ("the profile loops (cut away) and the cam undercuts"
                                               if prof.undercut else "the profile is regular"), "max"))
    if spec.contact == "roller":
        advice = min(ROLLER_ADVICE[0] * rho_pitch, ROLLER_ADVICE[1] * spec.prime_radius)
        values["roller_radius_advice"] = advice
        f.append(Finding("roller_radius", grade(rr, warn_above=advice), rr, advice,
                         "textbook advice R_p <= min(0.7 rho_min, 0.4 r0), mm", "max"))


def _departure(spec, prof, phi, tol, f, values):
    """A flat face's undercut: how far the follower held against the cam it leaves (the intersection of
    the face's half-planes) falls short of its law, and where (more than the outline's ``tol``); returns
    that shortfall and where along the face it rests on the cam, at the cam angles ``phi``."""
    from gearkit.families.cam.halfplanes import follower_departure

    gap, contact = follower_departure(spec, prof.planes, phi)
    k = int(np.argmax(gap))
    worst, at = float(gap[k]), math.degrees(phi[k])
    where = _intervals(gap > tol, phi)
    values.update({"undercut": bool(where), "departure_max": worst, "departure_at_deg": at, "departure_deg": where})
    unit = "mm of lift" if spec.follower == "translating" else "mm of arc at the arm"
    say = (f"the follower falls short of its law by up to {worst:.6g} {unit} at {at:.6g} degrees (over "
           + ", ".join(f"{a:.6g}..{b:.6g}" for a, b in where) + " degrees): the cam the face leaves, the "
           "intersection of its half-planes, cannot give the motion there") if where else \
        f"the follower keeps its law on the cam the face leaves within the outline's tol ({worst:.3g} {unit})"
    f.append(Finding("undercut", "fail" if where else "ok", worst, tol, say, "max"))
    return gap, contact


def _motion(spec, f, values):
    """Findings at every join of the motion law where a derivative jumps."""
    s, v, a, _ = spec.motion.evaluate(np.linspace(0.0, 2 * math.pi, 4001))
    h = max(spec.stroke, 1e-12)
    jumps = []
    for k, (phi, dv, da, dj) in enumerate(spec.motion.jumps()):
        deg = math.degrees(phi)
        for name, d, note, status, power in (
                ("velocity", dv, "an infinite acceleration (hard impact)", "warn", 1),
                ("acceleration", da, "a soft impact", "warn", 2),
                ("jerk", dj, "a jerk step", "ok", 3)):
            if abs(d) > _JUMP_REL * h:
                jumps.append({"phi_deg": deg, "derivative": name, "jump": d})
                f.append(Finding(f"motion.{name}.{k + 1}", status, abs(d), None,
                                 f"the {name} jumps by {d:.6g} mm/rad^{power} at {deg:.6g} degrees: {note}"))
                break
    values["jumps"] = jumps
    values["stroke"] = spec.stroke
    values["max_velocity"] = float(np.abs(v).max())
    values["max_acceleration"] = float(np.abs(a).max())
