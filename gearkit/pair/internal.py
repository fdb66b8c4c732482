"""Internal pairs (pinion in ring): exit jamming, trimming of the ring by its shaper, tip sweep.

All in the transverse section, from a :class:`~gearkit.pair.PairGeometry`.

* **Exit jamming** (textbook 3.10(a); the closed form of GOST 19274 / DIN 3993 "tip
  interference"): where the two tip circles cross, the pinion's tip corner must already be
  in the ring's tooth space: ``z1 (inv a_a1 + d1) + (z2 - z1) inv a_wt - z2 (inv a_a2 + d2) >= 0``.
* **Trimming during the plunge** (textbook 3.108): while the shaper is fed radially to depth,
  the ring tooth's tip corner must stay outside the shaper tooth's tip corner,
  ``min (X2 - X0) > 0``.
* **Trimming beyond N_u** (textbook 3.109/3.110): the ring's tip circle must not reach inside
  ``O2 N_u`` (N_u: the machine line of action's tangency point on the shaper's base circle),
  or the shaper trims the ring's involute near its tip.
* **Tip sweep**: a rigid-body sweep of the tip corners of each gear along their relative
  (trochoidal) paths through the mate's teeth, in and out of mesh; it catches the exit jamming
  of the closed form and any tip interference the closed form does not see.
"""
from __future__ import annotations

import math

import numpy as np

from gearkit.curves import inv
from gearkit.pair.geometry import PairGeometry
from gearkit.pair.tooling import cutter_machine, half_angle, section
from gearkit.pair.tooling import nu_radius as tooling_nu_radius

__all__ = ["exit_jamming_margin", "plunge_trimming", "nu_radius", "tip_sweep", "tip_sweep_depth", "sweep_depth"]


def _sec(g: PairGeometry):
    s = g.spec
    return section(s.module, s.alpha_n_deg, s.helix_angle_deg)


def _ring_tip(g: PairGeometry) -> float:
    """The ring's tip radius where its involute can begin (not inside its base circle)."""
    ring = g.gears[1]
    return max(ring.tip_diameter, ring.base_diameter) / 2


def exit_jamming_margin(g: PairGeometry) -> float:
    """Exit-jamming expression (rad, >= 0 passes) of an internal pair.

    ``+inf`` when the pinion's tip circle lies wholly inside the ring's (the teeth never overlap).

    Examples
    --------
    >>> from gearkit.pair import PairSpec, pair_geometry
    >>> from gearkit.families.involute import ShaperCutter
    >>> g = pair_geometry(PairSpec(41, 49, 1.0, kind="internal", tool2=ShaperCutter(20)))
    >>> exit_jamming_margin(g) < 0    # zero shifts, z2 = 49: the difference must be at least 9
    True
    """
    z1, z2 = g.gears[0].teeth, g.gears[1].teeth
    a = g.center_distance
    ra1 = g.gears[0].tip_diameter / 2
    ra2 = _ring_tip(g)
    rb1, rb2 = g.gears[0].base_diameter / 2, g.gears[1].base_diameter / 2
    if ra2 >= ra1 + a:
        return math.inf
    c1 = (ra2 ** 2 - ra1 ** 2 - a ** 2) / (2 * a * ra1)
    c2 = (ra2 ** 2 - ra1 ** 2 + a ** 2) / (2 * a * ra2)
    d1 = math.acos(min(max(c1, -1.0), 1.0))
    d2 = math.acos(min(max(c2, -1.0), 1.0))
    aa1 = math.acos(rb1 / ra1)
    aa2 = math.acos(rb2 / ra2)
    return z1 * (inv(aa1) + d1) + (z2 - z1) * inv(g.working_pressure_angle) - z2 * (inv(aa2) + d2)


def nu_radius(g: PairGeometry) -> float:
    """O2 N_u (mm) of the ring of ``g``: inside it the shaper trims the ring's involute (3.109/3.110)."""
    ring = g.gears[1]
    return tooling_nu_radius(_sec(g), ring.teeth, ring.cutter_setting, g.spec.tools[1])


def plunge_trimming(g: PairGeometry, samples: int = 801) -> tuple[float, float]:
    """Textbook 3.108: ``(min (X2 - X0), phi2)`` in (mm, rad) over ``phi2 in [0, pi z0/(2 z2)]``.

    ``X2 = R2 sin(phi2 + d2)`` is the ring tooth's tip corner, ``X0 = R0 sin(z2 phi2 / z0 + d0)`` the
    shaper tooth's (sharp) tip corner; ``d2`` is half the ring's angular space width at its tip,
    ``d0`` half the shaper's angular tooth thickness at its tip. The minimum must be positive.
    """
    from gearkit.roots import fminbound
    sec = _sec(g)
    ring = g.gears[1]
    cutter = g.spec.tools[1]
    z2, z0 = ring.teeth, cutter.teeth
    r2 = _ring_tip(g)
    # half space width of the ring = pi/z2 - half tooth of the ring
    d2 = math.pi / z2 - float(half_angle(sec, z2, ring.thickness_coeff, r2, True))
    _, _, ra0, _, _ = cutter_machine(sec, z2, ring.cutter_setting, cutter, True)
    d0 = float(half_angle(sec, z0, 2 * cutter.shift * math.tan(sec.alpha_n), ra0, False))
    k = z2 / z0

    def gap(phi):
        return r2 * np.sin(phi + d2) - ra0 * np.sin(k * phi + d0)

    hi = math.pi / (2 * k)
    phi = np.linspace(0.0, hi, samples)
    values = gap(phi)
    i = int(np.argmin(values))
    lo_b, hi_b = phi[max(i - 1, 0)], phi[min(i + 1, samples - 1)]
    if hi_b > lo_b:
        x, fun = fminbound(gap, lo_b, hi_b, xatol=1e-13)
        if fun < values[i]:
            return fun, x
    return float(values[i]), float(phi[i])


def _wrap(angle, period):
    return (angle + period / 2) % period - period / 2


SWEEP_START = 64  #: intervals over a pinion turn the sweep's branch and bound starts from
SWEEP_BAND = 0.5  #: maxima above this fraction of the resolution are refined (the margin is exact near 0)
SWEEP_GOLDEN = 60  #: golden-section steps refining the deepest sample (to round-off)
SWEEP_GRADIENT = 2.0  #: bound on the gradient of a tooth's depth function (at most ~1.5, see _tooth_depth)
_GOLD = (math.sqrt(5.0) - 1.0) / 2.0


def _farthest(r, r_w, angle, w):
    """Largest distance from the pitch point P = (0, r_w) (from the gear's centre) of a corner at radius
    ``r`` whose angle from the line of centres runs over ``[angle - w, angle + w]``, arrays."""
    far = np.abs(_wrap(angle, 2 * math.pi)) + w
    c = np.where(far >= math.pi, -1.0, np.cos(np.minimum(far, math.pi)))
    return np.sqrt(np.maximum(r * r + r_w * r_w - 2 * r * r_w * c, 0.0))


def _tooth_depth(rho, theta, teeth, centre, half, r_in, r_out, rb):
    """Signed depth (mm) of points at polar (``rho``, ``theta``) inside the teeth of a gear (tooth 0
    at ``centre``; ``theta`` measured counter-clockwise from +y).

    A tooth is the region between radii ``r_in`` and ``r_out`` and its two involute flanks; the
    depth is the smallest of the distances to those boundaries (the flank distance measured
    along the base-circle tangent, ``r_b (half(r) - |angle|)``), negative outside. The function
    is continuous with a gradient of at most ~1.5 (used by the sweep's bound).
    """
    delta = np.abs(_wrap(theta - centre, 2 * math.pi / teeth))
    flank = (half(np.maximum(rho, rb)) - delta) * rb
    return np.minimum(np.minimum(rho - r_in, r_out - rho), flank)


def sweep_depth(sec, z1: int, z2: int, a, ra1, ra2, rl1, rf2, t1, t2, rw2, resolution: float):
    """The tip sweep of many internal pairs at once: the largest depth (mm) of a tip corner in a
    mate's tooth over a pinion turn, and the pinion angle, arrays (n,) -> ((n,), (n,)).

    One function for the check (:func:`tip_sweep`, n = 1) and the blocking arrays
    (:mod:`gearkit.blocking.arrays`): per pair, the pinion's centre distance ``a``, tip ``ra1``, the
    ring's tip ``ra2`` (not inside its base circle), the radius ``rl1`` above which a pinion tooth
    counts (its form circle, not inside its base circle), the ring's root ``rf2``, the thickness
    coefficients ``t1``, ``t2`` and the ring's working radius ``rw2``; ``sec``, ``z1``, ``z2`` are
    shared. NaN parameters give depth -inf.

    Geometry (as :func:`tip_sweep`): the ring at O2 = 0, the pinion at O1 = (0, a), both turning
    counter-clockwise, the ring by ``phi z1/z2``. A pinion tip corner is swept in the ring's frame
    through the ring's teeth, a ring tip corner in the pinion's frame through the pinion's teeth.
    One corner of each suffices: the mirror image of the mesh (x -> -x) is the mesh at ``-phi`` with
    the other corner, and a whole pinion turn (the sweep's range) is symmetric.

    The maximum is found by a branch and bound on ``phi``, vectorised over (pair, interval): in the
    mate's frame a corner turns about the pitch point P at ``1 - k`` per radian, so over an interval
    of half width ``w`` its depth changes at most ``S = SWEEP_GRADIENT (1 - k) D w`` (``D`` its largest
    distance from P there: small in mesh, where it matters). An interval whose mid-point depth is
    below ``max(best, SWEEP_BAND resolution) - S`` cannot hold the maximum (nor an interference) and
    is dropped; the rest are halved until ``S`` is below ``resolution / 100``; then golden-section
    steps refine the deepest sample to round-off. A maximum above ``SWEEP_BAND resolution`` is found to ``resolution / 100`` or
    better (to round-off where it is the only one that close); below it, a lower bound is returned
    (contact along the path of contact, depth 0, is not refined: no interference is near).
    """
    a, ra1, ra2, rl1, rf2, t1, t2, rw2 = (np.atleast_1d(np.asarray(v, dtype=float))
                                          for v in (a, ra1, ra2, rl1, rf2, t1, t2, rw2))
    n = a.size
    rb1 = z1 * sec.mt * math.cos(sec.alpha_t) / 2
    rb2 = z2 * sec.mt * math.cos(sec.alpha_t) / 2
    k = z1 / z2
    c2 = math.pi / z2
    rw1 = rw2 - a
    with np.errstate(invalid="ignore", divide="ignore"):
        s1 = np.maximum(half_angle(sec, z1, t1, ra1, False), 0.0)
        s2 = np.maximum(half_angle(sec, z2, t2, ra2, True), 0.0)

    def depth(i, phi, w=None):
        """max of the two corners' depths at ``phi`` (pairs ``i``); with a half width ``w``, also the
        bound on the depth over ``[phi - w, phi + w]`` and the bound's slack."""
        aa, r1, r2 = a[i], ra1[i], ra2[i]
        u = phi + s1[i]  # the pinion's corner in the ring's frame
        vx, vy = r1 * np.sin(u), aa + r1 * np.cos(u)
        d = _tooth_depth(np.hypot(vx, vy), np.arctan2(vx, vy) - k * phi, z2, c2,
                         lambda r: half_angle(sec, z2, t2[i], r, True), r2, rf2[i], rb2)
        psi = c2 + s2[i] + k * phi  # the ring's corner in the pinion's frame
        vx, vy = r2 * np.sin(psi), r2 * np.cos(psi) - aa
        e = _tooth_depth(np.hypot(vx, vy), np.arctan2(vx, vy) - phi, z1, 0.0,
                         lambda r: half_angle(sec, z1, t1[i], r, False), rl1[i], r1, rb1)
        if w is None:
            return np.maximum(d, e)
        # the mate's frame turns about the pitch point P at (1 - k) per radian of phi: a corner at
        # distance D from P moves (1 - k) D, its depth at most SWEEP_GRADIENT times that
        sd = SWEEP_GRADIENT * (1.0 - k) * w * _farthest(r1, rw1[i], u, w)
        se = SWEEP_GRADIENT * (1.0 - k) * w * _farthest(r2, rw2[i], psi, k * w)
        return np.maximum(d, e), np.maximum(d + sd, e + se), np.maximum(sd, se)

    floor = SWEEP_BAND * resolution
    stop = resolution / 100
    best, at, width = np.full(n, -np.inf), np.zeros(n), np.full(n, math.pi / SWEEP_START)
    w = math.pi / SWEEP_START
    owner = np.repeat(np.arange(n), SWEEP_START)
    mid = np.tile(-math.pi + w * (2 * np.arange(SWEEP_START) + 1), n)
    with np.errstate(invalid="ignore", divide="ignore"):
        while owner.size:
            d, bound, slack = depth(owner, mid, w)
            d = np.where(np.isnan(d), -np.inf, d)
            starts = np.flatnonzero(np.r_[True, owner[1:] != owner[:-1]])
            top = np.maximum.reduceat(d, starts)
            o = owner[starts]
            hit = np.flatnonzero(d == np.repeat(top, np.diff(np.r_[starts, owner.size])))
            first = hit[np.unique(owner[hit], return_index=True)[1]]
            up = top > best[o]
            best[o[up]], at[o[up]], width[o[up]] = top[up], mid[first[up]], w
            keep = (bound > np.maximum(best, floor)[owner]) & (slack >= stop)
            owner, m = owner[keep], mid[keep]
            owner = np.repeat(owner, 2)
            mid = np.column_stack([m - w / 2, m + w / 2]).ravel()
            w /= 2
        # golden section on the deepest sample's neighbourhood
        live = np.flatnonzero(np.isfinite(best))
        lo, hi = at[live] - 2 * width[live], at[live] + 2 * width[live]
        p, q = hi - _GOLD * (hi - lo), lo + _GOLD * (hi - lo)
        fp, fq = depth(live, p), depth(live, q)
        for _ in range(SWEEP_GOLDEN):
            left = fp >= fq  # the maximum lies in [lo, q]: q moves to p; else in [p, hi]: p moves to q
            lo, hi = np.where(left, lo, p), np.where(left, q, hi)
            p, q = np.where(left, hi - _GOLD * (hi - lo), q), np.where(left, p, lo + _GOLD * (hi - lo))
            new = depth(live, np.where(left, p, q))
            fp, fq = np.where(left, new, fq), np.where(left, fp, new)
        x = np.where(fp >= fq, p, q)
        fx = np.maximum(fp, fq)
        up = fx > best[live]
        best[live[up]], at[live[up]] = fx[up], x[up]
    return best, at


def tip_sweep_depth(g: PairGeometry, resolution: float | None = None) -> tuple[float, float]:
    """:func:`sweep_depth` of the pair ``g``: (the largest tip-corner depth, mm, and its pinion angle),
    negative when no corner reaches a mate's tooth. :func:`tip_sweep` grades it."""
    sec = _sec(g)
    res = 1e-4 * sec.mn if resolution is None else float(resolution)
    p, ring = g.gears
    rb1 = p.base_diameter / 2
    depth, phi = sweep_depth(sec, p.teeth, ring.teeth, g.center_distance, p.tip_diameter / 2, _ring_tip(g),
                             max(rb1, p.form_diameter / 2), ring.root_diameter / 2, p.thickness_coeff,
                             ring.thickness_coeff, ring.working_diameter / 2, res)
    return float(depth[0]), float(phi[0])


def tip_sweep(g: PairGeometry, resolution: float | None = None) -> tuple[float, float]:
    """Largest penetration (mm) of a tip corner into a mate's tooth over a pass, and the pinion angle.

    Gear 2 (ring) at O2 = 0, pinion at O1 = (0, a_w); both turn counter-clockwise, the ring by
    ``phi z1/z2``; pinion tooth 0 and ring space 0 are centred on +y at ``phi = 0``. Teeth are the
    exact involute teeth with their actual thicknesses; a pinion tooth counts above
    ``max(d_b1, d_F1)``. The tip corners of each gear are swept along their relative (trochoidal)
    paths through all of the mate's teeth over a whole turn of the pinion (:func:`sweep_depth`, a
    branch and bound on ``phi`` with a Lipschitz bound, then golden-section steps).

    Contact along the path of contact has depth 0, so penetrations up to ``resolution`` (default
    ``1e-4 m_n``) count as contact; beyond it the returned depth is accurate to ``resolution / 100``
    or better.

    Returns
    -------
    depth : float, mm (0 when nothing penetrates deeper than ``resolution``)
    phi : float, rad (pinion angle of the deepest penetration; 0 when none)
    """
    res = 1e-4 * _sec(g).mn if resolution is None else float(resolution)
    best, at = tip_sweep_depth(g, res)
    if not best > res:
        return 0.0, 0.0
    return best, at
