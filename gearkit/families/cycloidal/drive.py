"""The cycloid–pin-wheel planetary drive: inputs, derived parameters and the closed forms.

A ring of ``Z_b`` pins (radius ``r_Z``, centres on the pin circle ``R_Z``) meshes a disc of
``Z_g`` lobes whose centre runs on a crank of eccentricity ``e``. ``dz = Z_b - Z_g`` is the
tooth difference: positive for a disc inside the pins (an equidistant of a curtate
epicycloid), negative for a cycloid *ring* outside the pins (an equidistant of a curtate
hypocycloid). The derived values are signed so one set of formulas serves both signs
(reference digest on cycloid–pin-wheel meshing, §1.1 and §1.11):

``Z_e = Z_b/dz``, ``Z_d = Z_g/dz``, ``K1 = e Z_e / R_Z`` (curtate coefficient),
``r_b' = e Z_b/dz`` (pin-wheel pitch radius), ``r_g' = e Z_g/dz`` (disc pitch radius).

Frames. The disc's own frame has its centre at the origin and lobe 0 centred on +y (the
gearkit tooth convention); angles are measured from +y towards +x. The closed forms here
are the reference the generated disc (:mod:`gearkit.families.cycloidal.disc`) is held
against; they are not used to build it.

Modifications (grinding corrections): ``shift_mod`` ΔR grinds with the pin circle
``R_Z + ΔR``, ``equidistant_mod`` Δr with the pin radius ``r_Z + Δr``; the drive runs on the
nominal pins, so a positive ``Δr - ΔR`` opens a clearance (backlash).
"""
from __future__ import annotations

import math
from functools import lru_cache

import numpy as np

from gearkit.errors import check_fields, is_int, is_real, require
from gearkit.values import frozen

__all__ = ["DriveSpec", "disc_curve", "theoretical_curve", "curve_normal", "curvature_radius",
           "min_curvature_radius", "psi_max", "contact_ratio", "line_of_action_point", "frame_phase", "turn_polar"]




@frozen
class DriveSpec:
    """A cycloid–pin-wheel drive, inputs only (lengths in mm).

    Parameters
    ----------
    pins : int, >= 3
        Z_b, number of pins in the pin ring.
    lobes : int, >= 2
        Z_g, teeth (lobes) of the cycloid disc; ``pins - lobes`` is the tooth difference dz
        (positive: disc inside the pins; negative: cycloid ring outside them).
    pin_circle_radius : float, mm, > 0
        R_Z, radius of the circle through the pin centres.
    pin_radius : float, mm, > 0
        r_Z.
    eccentricity : float, mm, > 0
        e, the crank's eccentricity (centre distance of disc and pin ring when running).
    equidistant_mod : float, mm
        Δr: the disc is ground with pins of radius ``r_Z + Δr`` (default 0).
    shift_mod : float, mm
        ΔR: the disc is ground on the pin circle ``R_Z + ΔR`` (default 0).
    disc_eccentricity : float or None, mm
        e', the eccentricity the disc was generated with (default: ``eccentricity``). The
        correct-meshing condition is e' = e.
    tip_radius : float or None, mm
        Truncate the disc's teeth with this addendum circle (for a ring, ``dz < 0``: its inner
        tip circle). Default: none (a multi-tooth disc then has pointed teeth).
    """

    pins: int
    lobes: int
    pin_circle_radius: float
    pin_radius: float
    eccentricity: float
    equidistant_mod: float = 0.0
    shift_mod: float = 0.0
    disc_eccentricity: float | None = None
    tip_radius: float | None = None

    def __post_init__(self):
        check_fields(self)
        require(is_int(self.pins) and 3 <= self.pins <= 1000, "pins", f"Z_b = {self.pins!r} must be an integer "
                "in [3, 1000]")
        require(is_int(self.lobes) and 2 <= self.lobes <= 1000, "lobes", f"Z_g = {self.lobes!r} must be an "
                "integer in [2, 1000]")
        require(self.pins != self.lobes, "lobes", f"Z_g = {self.lobes} must differ from Z_b = {self.pins} "
                "(the tooth difference dz = Z_b - Z_g cannot be 0)")
        big_r = self.pin_circle_radius
        require(is_real(big_r) and 1e-3 <= big_r <= 1e5, "pin_circle_radius", f"R_Z = {big_r!r} must be a length in "
                "[0.001, 100000] mm")
        for name, rel in (("pin_radius", 1e-12), ("eccentricity", 1e-4)):  # lengths on the scale of R_Z
            v = getattr(self, name)
            require(is_real(v) and v >= rel * big_r, name, f"{v!r} must be a length of at least {rel:g} R_Z = "
                    f"{rel * big_r:.6g} mm")
        r, e = self.pin_radius, self.eccentricity
        require(e < big_r, "eccentricity", f"e = {e!r} must be smaller than the pin-circle radius R_Z = {big_r!r}")
        require(r < big_r, "pin_radius", f"r_Z = {r!r} must be smaller than the pin-circle radius R_Z = {big_r!r}")
        for name in ("equidistant_mod", "shift_mod"):
            v = getattr(self, name)
            require(is_real(v) and abs(v) <= 0.25 * min(r, e) + 0.0, name,
                    f"{v!r} must be a small correction, |.| <= {0.25 * min(r, e):.6g} mm (a quarter of the "
                    "smaller of pin radius and eccentricity)")
        require(r + self.equidistant_mod > 0, "equidistant_mod", "the grinding pin radius r_Z + dr must be > 0")
        if self.disc_eccentricity is not None:
            v = self.disc_eccentricity
            require(is_real(v) and 0 < v < big_r, "disc_eccentricity", f"e' = {v!r} must be in (0, R_Z) mm")
        if self.tip_radius is not None:
            v = self.tip_radius
            if self.tooth_difference < 0:
                lo, hi = self.grind_circle - e + self.grind_pin, self.grind_circle + e + self.grind_pin
            else:
                lo, hi = self.grind_circle - e - self.grind_pin, self.grind_circle + e - self.grind_pin
            require(is_real(v) and lo < v < hi, "tip_radius", f"{v!r} mm must lie between the disc's root and "
                    f"crest radii ({lo:.6g}, {hi:.6g}) mm")

    # -- derived (signed) ---------------------------------------------------------------------
    @property
    def tooth_difference(self) -> int:
        """dz = Z_b - Z_g (signed)."""
        return int(self.pins) - int(self.lobes)

    @property
    def sign(self) -> int:
        """sgn(dz): +1 disc inside the pins, -1 cycloid ring outside them."""
        return 1 if self.tooth_difference > 0 else -1

    @property
    def generating_eccentricity(self) -> float:
        """e', the eccentricity the disc is generated with."""
        return self.eccentricity if self.disc_eccentricity is None else float(self.disc_eccentricity)

    @property
    def grind_circle(self) -> float:
        """R_Z + ΔR, mm."""
        return self.pin_circle_radius + self.shift_mod

    @property
    def grind_pin(self) -> float:
        """r_Z + Δr, mm."""
        return self.pin_radius + self.equidistant_mod

    @property
    def equivalent_pins(self) -> float:
        """Z_e = Z_b/dz (signed)."""
        return self.pins / self.tooth_difference

    @property
    def equivalent_lobes(self) -> float:
        """Z_d = Z_g/dz (signed)."""
        return self.lobes / self.tooth_difference

    @property
    def k1(self) -> float:
        """K1 = e Z_e / R_Z, the curtate coefficient (signed; |K1| < 1 for a curtate cycloid)."""
        return self.eccentricity * self.equivalent_pins / self.pin_circle_radius

    @property
    def pin_pitch_radius(self) -> float:
        """r_b' = e Z_b / dz (signed), mm."""
        return self.eccentricity * self.pins / self.tooth_difference

    @property
    def disc_pitch_radius(self) -> float:
        """r_g' = e Z_g / dz (signed), mm."""
        return self.eccentricity * self.lobes / self.tooth_difference

    @property
    def rolling_radius(self) -> float:
        """a = e / K1 = R_Z dz / Z_b (signed): the classical generating (rolling) circle, mm."""
        return self.pin_circle_radius * self.tooth_difference / self.pins

    @property
    def closed(self) -> bool:
        """Z_g/dz is an integer: the generated profile closes on itself."""
        return self.lobes % abs(self.tooth_difference) == 0

    @property
    def active_pin_arc(self) -> float:
        """Largest deviation of the contact from the pin's innermost (outermost for dz < 0) point,
        arcsin |K1|, rad; NaN-free: 90 degrees when |K1| >= 1."""
        return math.asin(min(1.0, abs(self.k1)))

    @property
    def pin_overlap_limit(self) -> float:
        """R_Z sin(pi/Z_b): pins of this radius or larger touch each other, mm."""
        return self.pin_circle_radius * math.sin(math.pi / self.pins)

    def grinding(self) -> "DriveSpec":
        """The drive whose nominal pins are the grinding pins (R_Z + ΔR, r_Z + Δr, e'); made once per
        drive (the closed forms ask for it at every evaluation)."""
        return _grinding(self)


@lru_cache(maxsize=64)
def _grinding(spec: DriveSpec) -> DriveSpec:
    from dataclasses import replace

    return replace(spec, pin_circle_radius=spec.grind_circle, pin_radius=spec.grind_pin,
                   eccentricity=spec.generating_eccentricity, equidistant_mod=0.0, shift_mod=0.0,
                   disc_eccentricity=None)


# ----------------------------------------------------------------------------- closed forms
def frame_phase(spec: DriveSpec) -> float:
    """Polar angle turning the reference digest's frame into the gearkit frame (lobe 0 on +y).

    In the digest's frame family 0's root (the pin nearest the disc centre for dz > 0, farthest
    for dz < 0) is at psi = 0 (dz > 0) or psi = pi/|Z_d| (dz < 0, where T's polar angle equals psi);
    gearkit puts that tooth space at polar angle pi/Z_g.
    """
    if spec.sign > 0:
        return math.pi / spec.lobes
    return math.pi / spec.lobes * (1 - abs(spec.tooth_difference))


def turn_polar(points, angle):
    """Add ``angle`` (scalar, or one per point) to the polar angle (from +y towards +x) of ``points``.

    Examples
    --------
    >>> turn_polar(np.array([0.0, 1.0]), math.pi / 2).round(12).tolist()
    [1.0, 0.0]
    """
    c, s = np.cos(angle), np.sin(angle)
    x, y = points[..., 0], points[..., 1]
    return np.stack([x * c + y * s, -x * s + y * c], -1)


def theoretical_curve(spec: DriveSpec, psi, family: int = 0):
    """Pin-centre locus T(psi) in the disc frame (the curtate cycloid), mm, for the grinding pins.

    ``psi`` is the relative angle (rad); ``family`` j shifts the e-term by 2 pi j/dz (pin k belongs
    to family k mod |dz|). Shape ``(n, 2)``.
    """
    g = spec.grinding()
    psi = np.asarray(psi, dtype=float)
    ph = g.equivalent_pins * psi + 2.0 * math.pi * family / g.tooth_difference
    big_r, e = g.pin_circle_radius, g.eccentricity
    t = np.stack([big_r * np.sin(psi) - e * np.sin(ph), big_r * np.cos(psi) - e * np.cos(ph)], -1)
    return turn_polar(t, frame_phase(spec))


def curve_normal(spec: DriveSpec, psi, family: int = 0):
    """Unit normal N(psi) of the theoretical curve (pointing away from the disc for both signs)."""
    g = spec.grinding()
    psi = np.asarray(psi, dtype=float)
    ph = g.equivalent_pins * psi + 2.0 * math.pi * family / g.tooth_difference
    k1 = g.k1
    n = np.stack([np.sin(psi) - k1 * np.sin(ph), np.cos(psi) - k1 * np.cos(ph)], -1)
    n = n / np.linalg.norm(n, axis=-1, keepdims=True)
    return turn_polar(n, frame_phase(spec))


def disc_curve(spec: DriveSpec, psi, family: int = 0):
    """Actual (ground) profile P(psi) = T - sgn(dz) (r_Z + Δr) N, disc frame, mm, ``(n, 2)``.

    Examples
    --------
    >>> s = DriveSpec(12, 11, 90.0, 7.0, 4.0)
    >>> [round(float(v), 9) for v in np.hypot(*disc_curve(s, [0.0, -math.pi / 11]).T)]
    [79.0, 87.0]
    """
    return theoretical_curve(spec, psi, family) - spec.sign * spec.grind_pin * curve_normal(spec, psi, family)


def curvature_radius(spec: DriveSpec, phi):
    """Signed curvature radius rho_0 of the theoretical curve at phi = Z_d psi (grinding pins), mm.

    ``rho_0 > 0`` where the curve is concave (centre of curvature outside), ``< 0`` where convex.
    """
    g = spec.grinding()
    k1, z = g.k1, g.equivalent_pins
    phi = np.asarray(phi, dtype=float)
    s = 1.0 + k1 * k1 - 2.0 * k1 * np.cos(phi)
    with np.errstate(divide="ignore", invalid="ignore"):  # an inflection (denominator 0) has an infinite radius
        rho = g.pin_circle_radius * s ** 1.5 / (k1 * (1.0 + z) * np.cos(phi) - (1.0 + z * k1 * k1))
    # |K1| = 1 exactly (an ordinary cycloid): at its cusp both vanish and the radius tends to 0
    return np.where(s == 0.0, 0.0, rho)


def min_curvature_radius(spec: DriveSpec):
    """|rho_0|min on the part of the theoretical curve where the pin's offset can loop, and where.

    For dz > 0 that is the convex part (rho_0 < 0); for dz < 0 the ring lies on the other side of
    the pins, so the critical part is the concave one (rho_0 > 0). Returns ``(value_mm, phi_rad)``
    with phi in [0, pi]; ``(inf, None)`` when the curve never bends that way (no radius limits
    the pins: the offset cannot loop). ``inf`` is the exact value for the Python API; JSON reports
    carry it as ``null`` with a message.
    """
    from gearkit.roots import fminbound

    phi = np.linspace(0.0, math.pi, 2049)
    rho = curvature_radius(spec, phi) * -spec.sign
    crit = np.where(rho > 0, rho, np.inf)
    i = int(np.argmin(crit))
    if not np.isfinite(crit[i]):
        return math.inf, None
    lo, hi = phi[max(i - 1, 0)], phi[min(i + 1, len(phi) - 1)]
    x, fun = fminbound(lambda p: float(-spec.sign * curvature_radius(spec, p)), lo, hi, xatol=1e-13)
    best = min((float(crit[i]), float(phi[i])), (fun, x))
    return best


def _root_psi(spec: DriveSpec) -> float:
    """Relative angle of family 0's root in the digest's parametrisation (polar pi/Z_g in gearkit's)."""
    return 0.0 if spec.sign > 0 else math.pi / abs(spec.equivalent_lobes)


def psi_max(spec: DriveSpec) -> float:
    """psi_max (rad): relative angle over which family 0's flank runs from its root to where it meets
    the tooth's symmetry axis (reference digest eq. 16); pi/|Z_g| for |dz| = 1."""
    from gearkit.roots import brentq

    if abs(spec.tooth_difference) == 1:
        return math.pi / spec.lobes
    root = _root_psi(spec)

    def polar(x):  # gearkit frame: the root at polar pi/Z_g, the tooth axis at 0; psi decreases towards it
        p = disc_curve(spec, [root - x])[0]
        return math.atan2(p[0], p[1])
    return brentq(polar, 1e-12, math.pi / abs(spec.equivalent_lobes), xtol=1e-15, rtol=1e-15)


def contact_ratio(spec: DriveSpec) -> float:
    """epsilon = Z_b Z_g psi_max / (2 pi |dz|) (reference digest eq. 27)."""
    return spec.pins * spec.lobes * psi_max(spec) / (2.0 * math.pi * abs(spec.tooth_difference))


def line_of_action_point(spec: DriveSpec, phi):
    """Contact point in the fixed frame OXY of the reference digest (pin-wheel centre at the
    origin, pin centre at R_Z(-sin phi, cos phi), pitch point (0, K1 R_Z)), mm, ``(n, 2)``."""
    phi = np.asarray(phi, dtype=float)
    big_r, k1 = spec.pin_circle_radius, spec.k1
    c = big_r * np.stack([-np.sin(phi), np.cos(phi)], -1)
    p = np.array([0.0, k1 * big_r])
    d = c - p
    return c - spec.sign * spec.pin_radius * d / np.linalg.norm(d, axis=-1, keepdims=True)
