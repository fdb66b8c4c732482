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
from gearkit.pair.sweep import sweep_depth
from gearkit.pair.tooling import cutter_machine, half_angle, section
from gearkit.pair.tooling import nu_radius as tooling_nu_radius

__all__ = ["exit_jamming_margin", "plunge_trimming", "nu_radius", "tip_sweep", "tip_sweep_depth", "SWEEP_RESOLUTION"]


SWEEP_RESOLUTION = 1e-4  #: (m_n) penetrations of the tip sweep up to this count as contact (depth 0 along the
#: path of contact, to round-off); deeper ones are tip interference


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


def tip_sweep_depth(g: PairGeometry, resolution: float | None = None,
                    enough: float = math.inf) -> tuple[float, float]:
    """:func:`~gearkit.pair.sweep.sweep_depth` of the pair ``g``: (the largest tip-corner depth, mm, and
    its pinion angle), negative when no corner reaches a mate's tooth; beyond ``enough`` (mm) a lower
    bound. :func:`tip_sweep` grades it."""
    sec = _sec(g)
    res = SWEEP_RESOLUTION * sec.mn if resolution is None else float(resolution)
    p, ring = g.gears
    rb1 = p.base_diameter / 2
    depth, phi = sweep_depth(sec, p.teeth, ring.teeth, g.center_distance, p.tip_diameter / 2, _ring_tip(g),
                             max(rb1, p.form_diameter / 2), ring.root_diameter / 2, p.thickness_coeff,
                             ring.thickness_coeff, ring.working_diameter / 2, res, enough)
    return float(depth[0]), float(phi[0])


def tip_sweep(g: PairGeometry, resolution: float | None = None) -> tuple[float, float]:
    """Largest penetration (mm) of a tip corner into a mate's tooth over a pass, and the pinion angle.

    Gear 2 (ring) at O2 = 0, pinion at O1 = (0, a_w); both turn counter-clockwise, the ring by
    ``phi z1/z2``; pinion tooth 0 and ring space 0 are centred on +y at ``phi = 0``. Teeth are the
    exact involute teeth with their actual thicknesses; a pinion tooth counts above
    ``max(d_b1, d_F1)``. The tip corners of each gear are swept along their relative (trochoidal)
    paths through all of the mate's teeth over a whole turn of the pinion
    (:func:`~gearkit.pair.sweep.sweep_depth`: a branch and bound on ``phi`` with first- and
    second-order bounds of each corner's depth, then zooming samples).

    Contact along the path of contact has depth 0, so penetrations up to ``resolution`` (default
    ``1e-4 m_n``) count as contact; beyond it the returned depth is the deepest maximum to
    round-off (of two maxima closer than ``resolution / 100`` too).

    Returns
    -------
    depth : float, mm (0 when nothing penetrates deeper than ``resolution``)
    phi : float, rad (pinion angle of the deepest penetration; 0 when none)
    """
    res = SWEEP_RESOLUTION * _sec(g).mn if resolution is None else float(resolution)
    best, at = tip_sweep_depth(g, res)
    if not best > res:
        return 0.0, 0.0
    return best, at
