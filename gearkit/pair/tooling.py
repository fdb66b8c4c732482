"""Per-gear formulas of the machine mesh: what a rack or a shaper cutter leaves on one gear.

Closed forms (textbook 3.83, 3.95-3.102; ISO 21771) in the transverse section of a gear with
``z`` teeth and normal shift ``x`` (module units). For a shaper-cut gear ``x`` is the radial
setting of the cutter: machine centre distance ``a_0 = m_t (z +- z_0)/2 + x m_n``. Radial sizes
of a helical shaper (addendum, shift) are in normal-module units, as on the tool.

The thickness coefficient ``Delta`` (transverse, m_t units) gives the arc tooth thickness on
the reference circle, ``s_t = m_t (pi/2 + Delta)``; for a ring it is the ring tooth's.
"""
from __future__ import annotations

import math
from functools import lru_cache

from gearkit.curves import inv
from gearkit.errors import SpecError
from gearkit.families.involute import BasicRack, ShaperCutter
from gearkit.values import frozen

__all__ = ["Section", "section", "thickness_coeff", "cutter_machine", "cutter_radii", "root_radius", "form_roll",
           "tip_thickness", "half_angle", "nu_radius", "cut_tip_radius", "graded_tip_radius"]


@frozen
class Section:
    """Normal and transverse constants of a pair: m_n, m_t (mm), alpha_n, alpha_t, beta, beta_b (rad)."""

    mn: float
    mt: float
    alpha_n: float
    alpha_t: float
    beta: float
    beta_b: float


@lru_cache(maxsize=256)
def section(module: float, alpha_n_deg: float, helix_deg: float) -> Section:
    """Transverse section of the normal system (ISO 21771): m_t = m_n/cos b, tan a_t = tan a_n/cos b.

    Examples
    --------
    >>> s = section(6.0, 20.0, 20.5)
    >>> round(s.mt, 5), round(math.tan(s.alpha_t), 6)
    (6.40566, 0.388578)
    """
    beta = math.radians(abs(helix_deg))
    an = math.radians(alpha_n_deg)
    at = math.atan(math.tan(an) / math.cos(beta))
    beta_b = math.atan(math.tan(beta) * math.cos(at))
    return Section(module, module / math.cos(beta), an, at, beta, beta_b)


def cutter_machine(sec: Section, z: int, x: float, cutter: ShaperCutter, internal: bool):
    """Machine mesh of a shaper cutter with a gear.

    Returns
    -------
    a0 : float, mm
        Machine centre distance ``m_t (z +- z0)/2 + x m_n`` (textbook 3.101).
    alpha_c : float, rad
        Machine (cutting) pressure angle, ``cos a_c = (r_b +- r_b0)/a_0``.
    ra0, rb0 : float, mm
        Cutter tip and base radii.
    rc0 : float, mm
        Radius where the cutter's involute flank ends under its tip rounding (= ra0 if sharp).
    """
    mt, mn = sec.mt, sec.mn
    sign = -1 if internal else 1
    a0 = mt * (z + sign * cutter.teeth) / 2 + x * mn
    rb = z * mt * math.cos(sec.alpha_t) / 2
    rb0, ra0, rc0 = cutter_radii(sec, cutter)
    if a0 <= abs(rb + sign * rb0):
        raise SpecError("shift2" if internal else "shift1",
                        f"x = {x:g}: the cutter setting a_0 = {a0:.6g} mm leaves no involute machine mesh "
                        f"(needs a_0 > {abs(rb + sign * rb0):.6g} mm)")
    alpha_c = math.acos((rb + sign * rb0) / a0)
    return a0, alpha_c, ra0, rb0, rc0


def cutter_radii(sec: Section, cutter: ShaperCutter):
    """A shaper cutter's base radius ``rb0``, tip radius ``ra0`` and the radius ``rc0`` where its
    involute flank ends under the tip rounding (= ``ra0`` if sharp), all in mm.

    The rounding of radius rho touches the tip circle and the involute: its centre lies on the
    involute's normal, at roll length ``t rb0 - rho`` from the base tangency point.

    Examples
    --------
    >>> rb0, ra0, rc0 = cutter_radii(section(1.0, 20.0, 0.0), ShaperCutter(20, tip_radius=0.0))
    >>> round(rb0, 6), round(ra0, 6), rc0 == ra0
    (9.396926, 11.25, True)
    """
    mt, mn = sec.mt, sec.mn
    rb0 = cutter.teeth * mt * math.cos(sec.alpha_t) / 2
    ra0 = cutter.teeth * mt / 2 + (cutter.shift + cutter.addendum) * mn
    rho = cutter.tip_radius * mn
    roll_c = rho + math.sqrt(max((ra0 - rho) ** 2 - rb0 ** 2, 0.0))
    return rb0, ra0, math.hypot(rb0, roll_c)


def cut_tip_radius(sec: Section, z: int, x, tool, internal: bool):
    """The tip radius (mm) the tool can leave on the gear at generating shift ``x`` (float or array).

    The tool's body beyond its root line (rack) or inside its root circle (shaper) removes all the
    blank it sweeps, so a tip circle beyond it is cut down to it: rack ``r + (x_E + h_fP*) m_n``
    (its root line); shaper, external gear ``a_0 - r_f0``, ring ``a_0 + r_f0`` (the inner edge of
    the annulus its root circle sweeps: a ring's tip cannot lie inside it), with
    ``r_f0 = m_t z0/2 + (x0 - h_f0*) m_n``. ``x`` is the rack's generating shift x_E or the shaper's
    radial setting.

    Examples
    --------
    >>> s = section(1.0, 20.0, 0.0)
    >>> round(cut_tip_radius(s, 20, 0.3, BasicRack(), False), 6)       # 10 + 0.3 + 1.25
    11.55
    >>> round(cut_tip_radius(s, 60, 0.0, ShaperCutter(20), True), 6)   # 20 + (10 - 1.25)
    28.75
    """
    if isinstance(tool, BasicRack):
        return z * sec.mt / 2 + (x + tool.dedendum) * sec.mn
    sign = -1 if internal else 1
    a0 = sec.mt * (z + sign * tool.teeth) / 2 + x * sec.mn
    rf0 = tool.teeth * sec.mt / 2 + (tool.shift - tool.dedendum) * sec.mn
    return a0 + rf0 if internal else a0 - rf0


def graded_tip_radius(sec: Section, z: int, x, tool, internal: bool, blank):
    """The tip radius (mm) a pair check grades: the blank's tip ``blank`` (by the pair's tip rule, or
    given), cut down to what the tool can leave (:func:`cut_tip_radius` at ``x``, the generating shift
    or shaper setting): ``min(blank, cut)``, for a ring ``max(blank, cut)``. Floats or arrays (the
    blocking arrays grade the same tip at many shift pairs at once).

    Examples
    --------
    >>> s = section(1.0, 20.0, 0.0)
    >>> graded_tip_radius(s, 20, 0.3, BasicRack(), False, 11.4), round(graded_tip_radius(s, 20, 0.3, BasicRack(), False, 11.6), 6)
    (11.4, 11.55)
    """
    cut = cut_tip_radius(sec, z, x, tool, internal)
    if isinstance(blank, float) and isinstance(cut, float):
        return max(blank, cut) if internal else min(blank, cut)
    import numpy as np

    return (np.maximum if internal else np.minimum)(blank, cut)


def thickness_coeff(sec: Section, z: int, x: float, tool, internal: bool) -> float:
    """Nominal thickness coefficient Delta of the generated tooth (transverse, m_t units).

    Rack: ``2 x_n tan a_n``. Shaper (textbook 3.100, general cutter): external
    ``(z + z0)(inv a_c - inv a_t) - Delta_0``, ring ``(z - z0)(inv a_t - inv a_c) - Delta_0``, with the
    cutter's own ``Delta_0 = 2 x_0 tan a_n``.

    Examples
    --------
    >>> s = section(8.0, 20.0, 0.0)
    >>> round(thickness_coeff(s, 49, 0.52, ShaperCutter(20, addendum=1.3), True), 6)
    -0.424382
    """
    if isinstance(tool, BasicRack):
        if internal:
            raise SpecError("tool2", "a ring cannot be cut by a rack: give a ShaperCutter")
        return 2 * x * math.tan(sec.alpha_n)
    _, alpha_c, _, _, _ = cutter_machine(sec, z, x, tool, internal)
    d0 = 2 * tool.shift * math.tan(sec.alpha_n)
    if internal:
        return (z - tool.teeth) * (inv(sec.alpha_t) - inv(alpha_c)) - d0
    return (z + tool.teeth) * (inv(alpha_c) - inv(sec.alpha_t)) - d0


def root_radius(sec: Section, z: int, x: float, tool, internal: bool) -> float:
    """Root radius r_f cut by the tool, mm: rack ``r + (x - h_fP*) m_n``; shaper ``a_0 -+ r_a0``."""
    if isinstance(tool, BasicRack):
        return z * sec.mt / 2 + (x - tool.dedendum) * sec.mn
    a0, _, ra0, _, _ = cutter_machine(sec, z, x, tool, internal)
    return a0 + ra0 if internal else a0 - ra0


def form_roll(sec: Section, z: int, x: float, tool, internal: bool) -> float:
    """Roll length rho_l (mm) from the base tangency point N to where the involute begins.

    Rack: ``r sin a_t - (h_s - x) m_n / sin a_t`` with ``h_s`` the straight-flank height of the
    rack (textbook, digest 1.4). Shaper, external: ``a_0 sin a_c - sqrt(r_c0^2 - r_b0^2)``; ring:
    ``a_0 sin a_c + sqrt(r_c0^2 - r_b0^2)`` (textbook 3.127/3.128). A negative value on an external
    gear means undercut: the real involute start lies further out and needs the generated tooth.
    """
    if isinstance(tool, BasicRack):
        r = z * sec.mt / 2
        s = math.sin(sec.alpha_t)
        return r * s - (tool.straight_height - x) * sec.mn / s
    a0, alpha_c, _, rb0, rc0 = cutter_machine(sec, z, x, tool, internal)
    cutter_roll = math.sqrt(max(rc0 ** 2 - rb0 ** 2, 0.0))
    along = a0 * math.sin(alpha_c)
    return along + cutter_roll if internal else along - cutter_roll


def half_angle(sec: Section, z: int, delta: float, radius, internal: bool):
    """Half the angular tooth thickness at ``radius`` (rad), vectorised (textbook 3.83).

    External: ``(pi/2 + Delta)/z + inv a_t - inv a_y``; ring tooth: ``(pi/2 + Delta)/z - inv a_t + inv a_y``,
    with ``cos a_y = r_b / radius`` (radius >= r_b).
    """
    import numpy as np

    rb = z * sec.mt * math.cos(sec.alpha_t) / 2
    if isinstance(radius, (float, int)):  # one radius: plain floats (called per point by the pair formulas)
        ay = math.acos(min(max(rb / radius, -1.0), 1.0))
    else:
        ay = np.arccos(np.minimum(np.maximum(rb / np.asarray(radius, dtype=float), -1.0), 1.0))  # (np.clip: slower)
    sign = -1.0 if internal else 1.0
    return (math.pi / 2 + delta) / z + sign * (inv(sec.alpha_t) - inv(ay))


def tip_thickness(sec: Section, z: int, delta: float, ra: float, internal: bool) -> float:
    """Transverse arc tooth thickness on the tip circle, mm (negative: the flanks cross below it).

    A ring whose tip circle lies inside its base circle is measured on the base circle, where its
    involute begins.
    """
    rb = z * sec.mt * math.cos(sec.alpha_t) / 2
    r = max(ra, rb)
    return float(2 * r * half_angle(sec, z, delta, r, internal))


def nu_radius(sec: Section, z2: int, x2: float, cutter: ShaperCutter) -> float:
    """O2 N_u (mm): inside this radius the shaper trims a ring's involute (textbook 3.109/3.110).

    N_u is where the machine line of action touches the shaper's base circle:
    ``O2N_u^2 = a_0^2 + 2 r_b2 r_b0 - r_b0^2``.
    """
    a0, _, _, rb0, _ = cutter_machine(sec, z2, x2, cutter, True)
    rb2 = z2 * sec.mt * math.cos(sec.alpha_t) / 2
    return math.sqrt(a0 ** 2 + 2 * rb2 * rb0 - rb0 ** 2)
