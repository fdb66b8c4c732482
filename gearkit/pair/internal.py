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

__all__ = ["exit_jamming_margin", "plunge_trimming", "nu_radius", "tip_sweep"]


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


def _rotate(points, angles):
    """Rotate ``points`` ((2,) or (n, 2)) by ``angles`` (n,), counter-clockwise."""
    c, s = np.cos(angles), np.sin(angles)
    x, y = points[..., 0], points[..., 1]
    return np.stack([c * x - s * y, s * x + c * y], -1)


def _depth(q, teeth, centre, half, r_in, r_out, rb):
    """Signed depth (mm) of points ``q`` (n, 2) inside the teeth of a gear (tooth 0 at ``centre``).

    A tooth is the region between radii ``r_in`` and ``r_out`` and its two involute flanks; the
    depth is the smallest of the distances to those boundaries (the flank distance measured
    along the base-circle tangent, ``r_b (half(r) - |angle|)``), negative outside. The function
    is continuous with a gradient of at most ~1.5 (used by the sweep's bound).
    """
    rho = np.hypot(q[:, 0], q[:, 1])
    theta = np.arctan2(-q[:, 0], q[:, 1])
    delta = np.abs(_wrap(theta - centre, 2 * math.pi / teeth))
    flank = (half(np.clip(rho, rb, None)) - delta) * rb
    return np.minimum(np.minimum(rho - r_in, r_out - rho), flank)


def tip_sweep(g: PairGeometry, resolution: float | None = None) -> tuple[float, float]:
    """Largest penetration (mm) of a tip corner into a mate's tooth over a pass, and the pinion angle.

    Gear 2 (ring) at O2 = 0, pinion at O1 = (0, a_w); both turn counter-clockwise, the ring by
    ``phi z1/z2``; pinion tooth 0 and ring space 0 are centred on +y at ``phi = 0``. Teeth are the
    exact involute teeth with their actual thicknesses; a pinion tooth counts above
    ``max(d_b1, d_F1)``. Every tip corner of each gear is swept along its relative (trochoidal)
    path through all of the mate's teeth over a whole turn of the pinion.

    The search is a branch and bound on ``phi``: the depth changes at most ``L`` per radian
    (twice the largest relative speed of a corner), so an interval whose mid-point depth is
    below ``resolution - L w`` (``w`` its half width) cannot hold interference and is dropped;
    the rest are halved until ``L w`` is below ``resolution / 100``. Contact along the path of
    contact has depth 0, so penetrations up to ``resolution`` (default ``1e-4 m_n``) count as
    contact; beyond it the returned depth is accurate to ``resolution / 100``.

    Returns
    -------
    depth : float, mm (0 when nothing penetrates deeper than ``resolution``)
    phi : float, rad (pinion angle of the deepest penetration; 0 when none)
    """
    sec = _sec(g)
    res = 1e-4 * sec.mn if resolution is None else float(resolution)
    p, ring = g.gears
    z1, z2 = p.teeth, ring.teeth
    a = g.center_distance
    ra1, ra2 = p.tip_diameter / 2, _ring_tip(g)
    rb1, rb2 = p.base_diameter / 2, ring.base_diameter / 2
    rl1 = max(rb1, p.form_diameter / 2)
    rf2 = ring.root_diameter / 2

    def h1(r):
        return half_angle(sec, z1, p.thickness_coeff, r, False)

    def h2(r):
        return half_angle(sec, z2, ring.thickness_coeff, r, True)

    ha1 = max(float(h1(ra1)), 0.0)
    ha2 = max(float(h2(ra2)), 0.0)
    c2 = math.pi / z2
    pin_corners = [ra1 * np.array([-math.sin(s), math.cos(s)]) for s in (ha1, -ha1)]
    ring_corners = [ra2 * np.array([-math.sin(c2 + s), math.cos(c2 + s)]) for s in (ha2, -ha2)]
    o1 = np.array([0.0, a])
    k = z1 / z2

    def depth(phi):
        best = np.full(phi.shape, -np.inf)
        for c in pin_corners:  # pinion corner in the ring's frame
            q = _rotate(o1 + _rotate(c, phi), -k * phi)
            best = np.maximum(best, _depth(q, z2, c2, h2, ra2, rf2, rb2))
        for c in ring_corners:  # ring corner in the pinion's frame
            q = _rotate(_rotate(c, k * phi) - o1, -phi)
            best = np.maximum(best, _depth(q, z1, 0.0, h1, rl1, ra1, rb1))
        return best

    # relative motion is a rotation at rate (1 - z1/z2) about the pitch point
    r_w2 = ring.working_diameter / 2
    lip = 2.0 * (1.0 - k) * (a + max(ra1, rf2) + r_w2)
    n0 = 4096
    w = math.pi / n0
    mid = -math.pi + w * (2 * np.arange(n0) + 1)
    best, at = -math.inf, 0.0
    while mid.size:
        d = depth(mid)
        i = int(np.argmax(d))
        if d[i] > best:
            best, at = float(d[i]), float(mid[i])
        if lip * w < res / 100:
            break
        keep = d + lip * w > max(best, res)
        mid = np.concatenate([mid[keep] - w / 2, mid[keep] + w / 2])
        w /= 2
    if best <= res:
        return 0.0, 0.0
    return best, at
