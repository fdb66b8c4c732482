"""The inputs of an involute gear pair: :class:`PairSpec` (frozen, validated).

Conventions
-----------
* Normal system of ISO 21771: shifts are normal coefficients ``x_n``, the module is ``m_n``, the
  pressure angle ``alpha_n``; the textbook's transverse xi is ``x_n cos(beta)``.
* The pinion is gear 1; gear 2 is the wheel, the ring of an internal pair, or the rack.
* A ring's shift ``x2`` is read by ``shift_convention``: ``"iso"`` (default; ISO 21771, by the
  tooth thickness as if the ring were rack-cut, ``s_n2 = m_n (pi/2 - 2 x2 tan alpha_n)``, the
  shaper setting that cuts it derived by :func:`~gearkit.families.involute.ring_cutter_setting`),
  or ``"cutter"`` (the shaper's radial setting, ``a_0 = m_t (z2 - z_0)/2 + x2 m_n``, the thickness
  following from it, textbook 3.100-3.102). Positive ``x2`` makes the ring's teeth thinner and its
  tip (inner) diameter larger either way.
* An external gear cut by a shaper cutter has ``x`` = radial setting of the cutter:
  ``a_0 = m_t (z + z_0)/2 + x m_n``.
"""
from __future__ import annotations

import math
from dataclasses import replace

from gearkit.errors import SpecError, check_fields, is_int, is_real, require
from gearkit.families.involute.tools import MIN_PRESSURE_ANGLE_DEG, BasicRack, ShaperCutter
from gearkit.families.involute.gear import SHIFT_CONVENTIONS, ring_cutter_setting
from gearkit.values import frozen

__all__ = ["KINDS", "TIP_RULES", "PairSpec"]

KINDS = ("external", "internal", "rack")
TIP_RULES = ("shortened", "standard")




@frozen
class PairSpec:
    """Inputs of an involute gear pair (frozen; derived values come from :func:`pair_geometry`).

    Parameters
    ----------
    teeth1 : int
        z1, pinion teeth.
    teeth2 : int or None
        z2, wheel teeth (the ring's teeth for an internal pair); None for a rack.
    module : float, mm
        Normal module m_n.
    shift1, shift2 : float
        Normal profile-shift coefficients x_n1, x_n2 (ring: textbook sign, see the module notes).
        For a rack pair ``shift2`` is ignored: the rack's position is the centre distance.
    kind : {"external", "internal", "rack"}
    pressure_angle_deg : float or None, degrees
        Normal pressure angle alpha_n; None takes the tools' (20 without tools).
    helix_angle_deg : float, degrees
        beta of the pinion (sign = hand); the wheel has the opposite hand (external) or the same
        (internal). Only abs(beta) enters the geometry.
    face_width : float or None, mm
        b, for the overlap ratio eps_beta (taken as 0 when not given).
    tool1, tool2 : BasicRack or ShaperCutter or None
        Generating tools. Default: the basic rack at ``pressure_angle_deg`` for external gears.
        A ring needs a :class:`ShaperCutter`. For a rack pair, ``tool2`` is the mating rack's
        own profile (default: the basic rack).
    addendum : float
        h_a*, addendum coefficient of both gears (module units).
    tip_rule : {"shortened", "standard"}
        "shortened" keeps the standard bottom clearance, d_a = d + 2 m_n (h_a* + x - dy)
        (ring: d_a2 = d2 - 2 m_n (h_a* - x2 - dy)); an external or rack pair only shortens (a
        negative dy, from a centre distance above a + (x1 + x2) m_n, leaves its tips at the
        standard d + 2 m_n (h_a* + x)); "standard" uses dy = 0.
    tip_diameter1, tip_diameter2 : float or None, mm
        Given tip diameters, overriding ``tip_rule``.
    center_distance : float or None, mm
        Operating centre distance a_w (rack pair: distance from the pinion axis to the rack's
        datum line). None is the tight (zero-backlash) mesh of the nominal teeth.
    thinning1, thinning2 : float, mm
        Reduction of the normal tooth thickness at the reference circle (for backlash); the cutter is
        fed in to cut it (ISO 21771 generating shift x_E), so the root moves with it.
    shift_convention : {"iso", "cutter"}
        How a ring's ``shift2`` is read (module doc); "iso" by default.
    """

    teeth1: int
    teeth2: int | None
    module: float
    shift1: float = 0.0
    shift2: float = 0.0
    kind: str = "external"
    pressure_angle_deg: float | None = None
    helix_angle_deg: float = 0.0
    face_width: float | None = None
    tool1: BasicRack | ShaperCutter | None = None
    tool2: BasicRack | ShaperCutter | None = None
    addendum: float = 1.0
    tip_rule: str = "shortened"
    tip_diameter1: float | None = None
    tip_diameter2: float | None = None
    center_distance: float | None = None
    thinning1: float = 0.0
    thinning2: float = 0.0
    shift_convention: str = "iso"

    def __post_init__(self):
        check_fields(self)
        require(self.kind in KINDS, "kind", f"{self.kind!r} is not one of {', '.join(KINDS)}")
        require(is_int(self.teeth1) and 3 <= self.teeth1 <= 100000, "teeth1",
                f"z1 = {self.teeth1!r} must be an integer in [3, 100000]")
        if self.kind == "rack":
            require(self.teeth2 is None, "teeth2", "a rack pair has no z2 (give None)")
        else:
            require(is_int(self.teeth2) and 3 <= self.teeth2 <= 100000, "teeth2",
                    f"z2 = {self.teeth2!r} must be an integer in [3, 100000]")
        if self.kind == "internal":
            require(self.teeth2 > self.teeth1, "teeth2",
                    f"the ring needs more teeth than the pinion (z2 = {self.teeth2} <= z1 = {self.teeth1})")
        require(is_real(self.module) and 1e-4 <= self.module <= 1e4, "module",
                f"m_n = {self.module!r} must be a length in [0.0001, 10000] mm")
        for name in ("shift1", "shift2"):
            v = getattr(self, name)
            require(is_real(v) and -3.0 <= v <= 3.0, name, f"x = {v!r} must be in [-3, 3]")
        b = self.helix_angle_deg
        require(is_real(b) and abs(b) < 60.0, "helix_angle_deg", f"{b!r} must be in (-60, 60) degrees")
        if self.face_width is not None:
            require(is_real(self.face_width) and 0 < self.face_width <= 1e5, "face_width",
                    f"b = {self.face_width!r} must be a length in (0, 100000] mm")
        require(is_real(self.addendum) and 0.0 < self.addendum <= 3.0, "addendum",
                f"h_a* = {self.addendum!r} must be in (0, 3]")
        require(self.shift_convention in SHIFT_CONVENTIONS, "shift_convention",
                f"{self.shift_convention!r} is not one of {', '.join(SHIFT_CONVENTIONS)}")
        require(self.tip_rule in TIP_RULES, "tip_rule", f"{self.tip_rule!r} is not one of {', '.join(TIP_RULES)}")
        for name in ("tip_diameter1", "tip_diameter2", "center_distance"):
            v = getattr(self, name)
            if v is not None:
                require(is_real(v) and v > 0, name, f"{v!r} must be a positive length in mm")
        if self.center_distance is not None:  # within 10 modules of the reference (shifts are within +-3)
            a_ref = self.module / math.cos(math.radians(b)) * (
                self.teeth1 / 2 if self.kind == "rack" else abs(self.teeth2 + (-1 if self.kind == "internal" else 1)
                                                                * self.teeth1) / 2)
            hi = a_ref + 10 * self.module
            require(self.center_distance <= hi, "center_distance", f"a_w = {self.center_distance!r} mm must be at "
                    f"most a + 10 m_n = {hi:.6g} mm (a = {a_ref:.6g} mm, the reference centre distance)")
        if self.kind == "rack":
            require(self.tip_diameter2 is None, "tip_diameter2", "a rack has no tip diameter")
        for name in ("thinning1", "thinning2"):
            v = getattr(self, name)
            require(is_real(v) and 0.0 <= v <= 0.5 * self.module, name,
                    f"{v!r} must be in [0, {0.5 * self.module:g}] mm (half a module)")
        self._check_tools()

    def _check_tools(self):
        if self.pressure_angle_deg is not None:
            a = self.pressure_angle_deg
            require(is_real(a) and MIN_PRESSURE_ANGLE_DEG <= a < 45.0, "pressure_angle_deg",
                    f"{a!r} must be in [{MIN_PRESSURE_ANGLE_DEG:g}, 45) degrees")
        for name in ("tool1", "tool2"):
            tool = getattr(self, name)
            require(tool is None or isinstance(tool, (BasicRack, ShaperCutter)), name,
                    f"{type(tool).__name__} is not a BasicRack or ShaperCutter")
        if self.kind == "internal":
            require(isinstance(self.tool2, ShaperCutter), "tool2",
                    "a ring (internal gear) is cut by a shaper cutter: give ShaperCutter(teeth=...)")
            require(self.teeth2 - self.tool2.teeth >= 4, "tool2",
                    f"a shaper with {self.tool2.teeth} teeth cannot cut a ring of {self.teeth2} teeth "
                    f"(needs at most z2 - 4 = {self.teeth2 - 4})")
        if self.kind == "rack":
            require(self.tool2 is None or isinstance(self.tool2, BasicRack), "tool2",
                    "the mate of a rack pair is a rack: give a BasicRack profile")
        for n, thin in ((1, self.thinning1), (2, self.thinning2)):
            if thin and isinstance(getattr(self, f"tool{n}"), ShaperCutter):
                raise SpecError(f"thinning{n}", "applies to rack-cut gears; thin a shaper-cut gear by its "
                                "cutter setting (its shift) instead")
        angles = {t.pressure_angle_deg for t in (self.tool1, self.tool2) if t is not None}
        if self.pressure_angle_deg is not None:
            angles.add(self.pressure_angle_deg)
        require(len(angles) <= 1, "pressure_angle_deg",
                f"the tools and the pair disagree on the pressure angle ({sorted(angles)} degrees)")

    # -- resolved inputs (still inputs, not geometry) -------------------------------------
    @property
    def alpha_n_deg(self) -> float:
        """The pair's normal pressure angle, degrees (explicit, else the tools', else 20)."""
        if self.pressure_angle_deg is not None:
            return float(self.pressure_angle_deg)
        for t in (self.tool1, self.tool2):
            if t is not None:
                return float(t.pressure_angle_deg)
        return 20.0

    @property
    def tools(self) -> tuple:
        """(tool1, tool2) with defaults filled in; tool2 of a rack pair is the mating rack."""
        if self.tool1 is not None and self.tool2 is not None:  # called per evaluation: no default to build
            return (self.tool1, self.tool2)
        rack = BasicRack(pressure_angle_deg=self.alpha_n_deg)
        return (self.tool1 or rack, self.tool2 or rack)

    @property
    def ring_cutter_setting(self) -> float | None:
        """The ring shaper's radial setting (normal module units) that cuts ``shift2``; None unless internal."""
        if self.kind != "internal":
            return None
        if self.shift_convention == "cutter":
            return float(self.shift2)
        return ring_cutter_setting(self.teeth2, self.shift2, self.tool2, self.helix_angle_deg)

    def with_shifts(self, shift1: float, shift2: float, center_distance: float | None = None) -> "PairSpec":
        """A copy with other shifts (and operating centre distance)."""
        return replace(self, shift1=float(shift1), shift2=float(shift2), center_distance=center_distance)


