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
from gearkit.export import json_number

__all__ = ["CamCheck", "check_cam", "default_cam_tol", "ROLLER_ADVICE"]

#: textbook advice on the roller radius: R_p <= min(0.7 rho_min, 0.4 r0)
ROLLER_ADVICE = (0.7, 0.4)
#: cam angles per phase for the extremes read off the geometry
_PER_PHASE = 1201
#: a jump in a derivative of s (mm/rad^n) below this fraction of the stroke is no jump
_JUMP_REL = 1e-6
#: step of the central differences of a flat-faced cam's radius of curvature over the cam angle, rad
_FD_STEP = 2e-4


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
    behind = {"rise": [], "return": []}
    for kind, p0, p1, _, _ in phases:
        if kind == "dwell":
            continue
        grid = _phase_grid(p0, p1)
        alpha = np.degrees(np.abs(prof.pressure_angle(grid)))
        if _pivoted_face(spec):  # behind the pivot the face's force turns the arm against its lift
            back = prof.face_contact(grid) <= 0.0
            behind[kind] += _intervals(back, grid)
            alpha = alpha[~back]
        worst[kind] = max(worst[kind], float(alpha.max()) if alpha.size else 0.0)
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
                         + ("" if driven else " (spring-closed return: a warning only)") + _behind_note(behind[kind]),
                         "max"))
    if _pivoted_face(spec):
        values["contact_behind_pivot_deg"] = behind["rise"] + behind["return"]
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


def _pivoted_face(spec) -> bool:
    """A flat face along a rocker's arm: its pressure angle is defined only where the contact lies ahead of
    the pivot."""
    return spec.contact == "flat" and spec.follower == "rocker"


def _behind_note(where) -> str:
    """The pressure-angle finding's words for the cam angles where a flat rocker's contact lies behind its
    pivot: the angle between the face's force and the contact's velocity is 180 degrees there, which says
    the cam would turn the arm against its lift, not how well it drives it; the undercut finding says how far
    the follower falls short there."""
    if not where:
        return ""
    return ("; not read over " + ", ".join(f"{a:.6g}..{b:.6g}" for a, b in where) + " degrees, where the "
            "prescribed contact lies behind the pivot: the face's force there would turn the arm against its lift "
            "(180 degrees), the cam cannot drive it, and the follower leaves its law (see undercut)")


def _curvature(spec, prof, f, values, tol):
    """Undercut, smallest radii of curvature, roller advice, flat-face convexity and width."""
    phi = np.linspace(0.0, 2.0 * math.pi, 7201)
    values["undercut"] = prof.undercut
    values["loops_deg"] = [[math.degrees(a), math.degrees(b)] for a, b in prof.loops]
    if spec.contact == "flat":
        back = _turning_back(spec, phi)
        at = ", ".join(f"{math.degrees(x):.6g}" for x in back)
        rho_min = -math.inf if back else float(np.min(prof.curvature_radius(*_one_sided(spec, phi))))
        values["min_curvature_radius"] = json_number(rho_min)  # None: unbounded below (where: the list)
        values["curvature_unbounded_deg"] = [math.degrees(x) for x in back]
        f.append(Finding("convexity", "ok" if rho_min > 0 and not prof.undercut else "fail", rho_min, 0.0,
                         (f"the radius of curvature of the flat-faced cam is unbounded below: the face stops turning "
                          f"against the cam and turns back (1 + psi' = 0) at {at} degrees, where its contact runs "
                          "off along the face (the cam is not convex there)") if back else
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
    values["pitch_min_curvature_radius"] = json_number(rho_pitch)  # None: the pitch curve is nowhere convex
    values["min_curvature_radius"] = json_number(rho_pitch - rr)
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


def _joins(spec, velocity_only: bool = False) -> np.ndarray:
    """Cam angles of the motion law's joins (only those where the velocity jumps, with ``velocity_only``), rad,
    each also a turn on and back (the grids run over 0..2 pi)."""
    h = max(spec.stroke, 1e-12)
    at = np.array([p for p, dv, _, _ in spec.motion.jumps() if not velocity_only or abs(dv) > _JUMP_REL * h])
    return np.concatenate([at, at + 2.0 * math.pi, at - 2.0 * math.pi])


def _one_sided(spec, phi, h: float = _FD_STEP):
    """The cam angles ``phi`` with every node whose difference stencil ``phi -+ h`` would straddle a join of
    the motion law replaced by two nodes one and a half steps either side of it: the radius of curvature
    follows ``s''``, which may jump there, so a difference across the join reads neither side; returns
    ``(angles, h)``."""
    joins = _joins(spec)
    if not len(joins):
        return phi, h
    near = (np.abs(phi[:, None] - joins[None, :]) <= h).any(axis=1)
    hit = joins[(joins >= phi[0]) & (joins <= phi[-1])]
    return np.concatenate([phi[~near], hit - 1.5 * h, hit + 1.5 * h]), h


def _turning_back(spec, phi) -> list:
    """Cam angles (rad) where a flat rocker's face stops turning against the cam and turns back smoothly.

    The face turns against the cam at ``theta' = -(1 + psi')``, ``psi' = s'/l``. The cam is the envelope of
    the face's lines, whose support distance ``p`` gives the radius of curvature ``rho = p + d2p/dtheta2 =
    p + (p'' theta' - p' theta'') / theta'^3``: where ``theta'`` passes through zero (not at a velocity
    jump) ``rho`` runs to infinity with both signs, and its smallest value is unbounded below. Each root
    is bracketed on the grid ``phi`` and closed by bisection on the law's ``s'``. A translating face turns
    with the cam (``theta' = -1``): never.

    Examples
    --------
    >>> from gearkit.families.cam import CamSpec, MotionProgram
    >>> spec = CamSpec(20.0, MotionProgram.rise_dwell_return(35.0, 20.0, 1.75, 20.0, "polynomial_345"),
    ...                "rocker", "flat", pivot_distance=24.0, arm_length=27.13)
    >>> back = _turning_back(spec, np.linspace(0.0, 2 * math.pi, 7201))
    >>> len(back), bool(np.all(np.abs(1.0 + spec.motion.evaluate(np.array(back))[1] / 27.13) < 1e-9))
    (2, True)
    """
    if spec.follower != "rocker":
        return []

    def turn(x):
        return 1.0 + spec.motion.evaluate(x)[1] / spec.arm_length

    t = turn(phi)
    jumps = _joins(spec, velocity_only=True)
    k = np.nonzero((np.sign(t[:-1]) != np.sign(t[1:])) & (t[:-1] != 0.0))[0]
    k = k[~((jumps[None, :] > phi[k, None]) & (jumps[None, :] <= phi[k + 1, None])).any(axis=1)]
    lo, hi = phi[k], phi[k + 1]
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        same = np.sign(turn(mid)) == np.sign(t[k])
        lo, hi = np.where(same, mid, lo), np.where(same, hi, mid)
    return [float(x) for x in 0.5 * (lo + hi)]


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
