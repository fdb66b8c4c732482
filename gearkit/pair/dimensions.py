"""Inspection dimensions of involute gears by the standard formulas (ISO 21771 / DIN 3960 style).

Everything here is closed form, in the transverse section of a gear with ``z`` teeth, from its
:class:`~gearkit.pair.tooling.Section` and its *actual* thickness coefficient ``delta`` (transverse,
``s_t = m_t (pi/2 + delta)`` on the reference circle, allowances included; for a ring the ring
tooth's). :mod:`gearkit.pair.gauging` measures the same dimensions on the generated tooth.

* **Span** (base tangent length) over ``k`` teeth, external gears:
  ``W_t = (k - 1) p_bt + s_bt`` with the base thickness ``s_bt = d_b (s_t/d + inv a_t)``, and in the
  normal section (what the anvils read) ``W = W_t cos b_b``. The anvils touch the flanks on the
  measuring circle ``d_M = 2 sqrt(r_b^2 + (W_t/2)^2)``. The span number is chosen so that
  ``d_M`` comes nearest the circle ``d + 2 x m_n`` (the basic rack's datum line), as the standards do.
  A helical gear needs a face width ``b > W sin b_b`` for the anvils to touch both flanks.
* **Dimension over pins or balls** ``M``: the pin centre lies on the circle ``d_M = d_b / cos a_M``,
  external ``inv a_M = s_t/d + inv a_t + d_p/(d_b cos b_b) - pi/z``, ring
  ``inv a_M = pi/z - s_t/d + inv a_t - d_p/(d_b cos b_b)``; ``M = d_M (cos(pi/(2z)) for odd z) +- d_p``
  (helical gears: balls, measured in one transverse plane).
* **Chordal thickness and height** at a circle ``d_y`` (default the reference circle): spur gears
  exactly, ``s = d_y sin psi_y``, ``h = r_a - r_y cos psi_y``; helical gears through the virtual gear
  ``z_n = z / (cos^2 b_b cos b)`` in the normal section.

Examples
--------
>>> from gearkit.pair.tooling import section
>>> s = span(section(2.0, 20.0, 0.0), 20, 0.0)
>>> s.k, round(s.W, 3)
(3, 15.321)
"""
from __future__ import annotations

import math

from gearkit.curves import inv, inv_inverse
from gearkit.errors import require
from gearkit.pair.tooling import Section
from gearkit.values import frozen

__all__ = ["Span", "OverPins", "Chordal", "span", "span_number", "over_pins", "suggested_pin", "chordal"]


@frozen
class Span:
    """Span over ``k`` teeth: ``W`` (normal section, mm), ``W_t`` (transverse), ``d_M`` the measuring circle
    (where the anvils touch the flanks), ``b_min = W sin b_b`` the face width the anvils need (helical)."""

    k: int
    W: float
    W_t: float
    d_M: float
    b_min: float


@frozen
class OverPins:
    """Dimension over pins/balls (external) or between them (internal): ``M`` (mm) with pins of
    diameter ``d_p``; ``d_M`` the circle of the pin centres, ``d_contact`` where the pins touch the flanks."""

    d_p: float
    M: float
    d_M: float
    d_contact: float
    internal: bool


@frozen
class Chordal:
    """Chordal tooth thickness ``s`` and chordal height ``h`` (from the tip) at the circle ``d_y`` (mm)."""

    s: float
    h: float
    d_y: float


def _radii(sec: Section, z: int):
    r = z * sec.mt / 2
    return r, r * math.cos(sec.alpha_t)


def _base_half_angle(sec: Section, z: int, delta: float) -> float:
    """Half the angular thickness of an external tooth on its base circle, ``s_t/d + inv a_t`` (rad)."""
    return (math.pi / 2 + delta) / z + inv(sec.alpha_t)


def span_number(sec: Section, z: int, delta: float, d_m: float) -> int:
    """The span number ``k`` whose anvils touch the flanks nearest the circle ``d_m`` (mm).

    ``k = round((d_b tan a_M - s_bt) / p_bt) + 1`` with ``cos a_M = d_b / d_m``, kept in ``[1, (z + 1) // 2]``.
    """
    r, rb = _radii(sec, z)
    tan_m = math.sqrt(max((d_m / 2) ** 2 - rb ** 2, 0.0)) / rb
    s_bt = 2 * rb * _base_half_angle(sec, z, delta)
    p_bt = 2 * math.pi * rb / z
    k = round((2 * rb * tan_m - s_bt) / p_bt) + 1
    return int(min(max(k, 1), (z + 1) // 2))


def span(sec: Section, z: int, delta: float, k: int | None = None, x: float | None = None) -> Span:
    """Span over ``k`` teeth of an external gear (None: the standard span number).

    Parameters
    ----------
    sec : Section
    z : int
    delta : float
        Actual thickness coefficient (transverse, m_t units; allowances included).
    k : int or None
        Teeth spanned, in ``[1, (z + 1) // 2]``.
    x : float or None
        Shift placing the measuring circle of the standard span number, ``d + 2 x m_n``; None takes
        the shift of ``delta`` (``delta / (2 tan a_n)``).

    Examples
    --------
    >>> from gearkit.pair.tooling import section
    >>> round(span(section(1.0, 20.0, 0.0), 30, 0.0, k=4).W, 6)
    10.752626
    """
    r, rb = _radii(sec, z)
    if k is None:
        x = delta / (2 * math.tan(sec.alpha_n)) if x is None else x
        k = span_number(sec, z, delta, 2 * r + 2 * x * sec.mn)
    require(isinstance(k, int) and 1 <= k <= (z + 1) // 2, "span_teeth",
            f"k = {k!r} must be an integer in [1, {(z + 1) // 2}] for z = {z}")
    w_t = (k - 1) * 2 * math.pi * rb / z + 2 * rb * _base_half_angle(sec, z, delta)
    w = w_t * math.cos(sec.beta_b)
    return Span(k, w, w_t, 2 * math.hypot(rb, w_t / 2), w * math.sin(sec.beta_b))


def _pin_centre_angle(sec: Section, z: int, delta: float, rho_t: float, internal: bool) -> float:
    r, rb = _radii(sec, z)
    s_over_d = (math.pi / 2 + delta) / z
    if internal:
        value = math.pi / z - s_over_d + inv(sec.alpha_t) - rho_t / rb
    else:
        value = s_over_d + inv(sec.alpha_t) + rho_t / rb - math.pi / z
    require(value > 0, "pin_diameter", "the pin centre falls inside the base circle: give a "
            + ("smaller" if internal else "larger") + " pin")
    return inv_inverse(value)


def suggested_pin(sec: Section, z: int, delta: float, internal: bool = False,
                  d_contact: float | None = None) -> float:
    """Pin/ball diameter ``d_p`` (mm) that touches the flanks on the circle ``d_contact`` (default: d).

    The contact normal is tangent to the base circle, so the pin centre lies ``rho_t`` further along
    it: external ``a_M = tan a_c - s_t/d - inv a_t + pi/z``, ``rho_t = r_b (tan a_M - tan a_c)``; ring
    ``a_M = tan a_c - pi/z + s_t/d - inv a_t``, ``rho_t = r_b (tan a_c - tan a_M)``; ``d_p = 2 rho_t cos b_b``.
    """
    r, rb = _radii(sec, z)
    d_c = 2 * r if d_contact is None else float(d_contact)
    require(math.isfinite(d_c) and d_c > 2 * rb, "pin_contact_diameter",
            f"{d_c!r} mm must exceed the base diameter {2 * rb:.6g} mm")
    tan_c = math.sqrt((d_c / 2) ** 2 - rb ** 2) / rb
    s_over_d = (math.pi / 2 + delta) / z
    if internal:
        a_m = tan_c - math.pi / z + s_over_d - inv(sec.alpha_t)
        rho_t = rb * (tan_c - math.tan(a_m))
    else:
        a_m = tan_c - s_over_d - inv(sec.alpha_t) + math.pi / z
        rho_t = rb * (math.tan(a_m) - tan_c)
    require(rho_t > 0 and a_m > 0, "pin_contact_diameter", f"no pin touches the flanks at d = {d_c:.6g} mm")
    return 2 * rho_t * math.cos(sec.beta_b)


def over_pins(sec: Section, z: int, delta: float, d_p: float | None = None, internal: bool = False) -> OverPins:
    """Dimension over two pins/balls (external) or between them (ring), mm.

    Examples
    --------
    >>> from gearkit.pair.tooling import section
    >>> m = over_pins(section(1.0, 20.0, 0.0), 20, 0.0, d_p=1.75)
    >>> round(m.M, 6)
    22.464645
    """
    d_p = suggested_pin(sec, z, delta, internal) if d_p is None else float(d_p)
    require(math.isfinite(d_p) and d_p > 0, "pin_diameter", f"{d_p!r} must be a positive length in mm")
    r, rb = _radii(sec, z)
    rho_t = d_p / (2 * math.cos(sec.beta_b))
    a_m = _pin_centre_angle(sec, z, delta, rho_t, internal)
    r_m = rb / math.cos(a_m)
    centres = 2 * r_m * (math.cos(math.pi / (2 * z)) if z % 2 else 1.0)
    m = centres - d_p if internal else centres + d_p
    roll = rb * math.tan(a_m) + (rho_t if internal else -rho_t)
    return OverPins(d_p, m, 2 * r_m, 2 * math.hypot(rb, roll), internal)


def chordal(sec: Section, z: int, delta: float, d_a: float, internal: bool = False,
            d_y: float | None = None) -> Chordal:
    """Chordal tooth thickness and height at the circle ``d_y`` (default the reference circle), mm.

    Spur: ``s = d_y sin psi_y``, ``h = r_a - r_y cos psi_y`` (ring: ``r_y cos psi_y - r_a``) with
    ``psi_y`` half the angular tooth thickness on ``d_y``. Helical: the virtual spur gear of the normal
    section, ``d_yn = d_n + d_y - d``, ``s_yn = s_yt cos b_y`` (``tan b_y = tan b d_y/d``),
    ``s = d_yn sin(s_yn/d_yn)``, ``h = r_a - r_y + (d_yn/2)(1 - cos(s_yn/d_yn))`` (ring: ``r_y - r_a - ...``).

    Examples
    --------
    >>> from gearkit.pair.tooling import section
    >>> c = chordal(section(2.0, 20.0, 0.0), 20, 0.0, 44.0)
    >>> round(c.s, 6), round(c.h, 6)
    (3.138364, 2.061653)
    """
    r, rb = _radii(sec, z)
    d_y = 2 * r if d_y is None else float(d_y)
    require(math.isfinite(d_y) and d_y >= 2 * rb, "chordal_diameter",
            f"{d_y!r} mm must be at least the base diameter {2 * rb:.6g} mm")
    a_y = math.acos(min(2 * rb / d_y, 1.0))
    sign = -1.0 if internal else 1.0
    psi = (math.pi / 2 + delta) / z + sign * (inv(sec.alpha_t) - inv(a_y))
    require(psi > 0, "chordal_diameter", f"the tooth is pointed below d_y = {d_y:.6g} mm")
    if sec.beta == 0.0:
        s, top = d_y * math.sin(psi), d_y / 2 * math.cos(psi)
        return Chordal(s, top - d_a / 2 if internal else d_a / 2 - top, d_y)
    z_n = z / (math.cos(sec.beta_b) ** 2 * math.cos(sec.beta))
    d_yn = sec.mn * z_n + d_y - 2 * r
    beta_y = math.atan(math.tan(sec.beta) * d_y / (2 * r))
    s_yn = d_y * psi * math.cos(beta_y)
    half = s_yn / d_yn
    sag = d_yn / 2 * (1 - math.cos(half))
    return Chordal(d_yn * math.sin(half), (d_y - d_a) / 2 - sag if internal else (d_a - d_y) / 2 + sag, d_y)
