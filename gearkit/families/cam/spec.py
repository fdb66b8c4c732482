"""A disc cam and its follower, inputs only: :class:`CamSpec`.

Frames (mm, rad). The cam turns counter-clockwise by the cam angle ``phi`` about the origin of
the fixed frame; its own frame (the *cam frame*, in which the profile is given) coincides with
the fixed frame at ``phi = 0``.

* **Translating follower**: it moves along +y on the line ``x = offset`` (``e``). Its reference
  point (roller centre, knife tip) is at ``(e, H0 + s(phi))`` with ``H0 = sqrt(r0^2 - e^2)``; a
  flat face is the line ``y = r0 + s(phi)``, perpendicular to the motion.
* **Rocker** (oscillating follower): pivot ``O2`` at ``(l0, 0)`` (``pivot_distance``), arm of
  length ``l`` (``arm_length``) at the angle ``Psi = Psi0 + s(phi)/l`` from the line ``O2 -> O``,
  roller centre ``O2 + l (-cos Psi, sin Psi)``; ``Psi0`` puts it on the prime circle. A flat face
  lies along the arm (through the pivot), ``Psi0 = asin(r0/l0)``.

The **prime radius** ``r0`` is the smallest radius of the pitch curve (the path of the roller
centre or knife tip); for a flat face it is the base circle (the face's distance at ``s = 0``).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

from gearkit.errors import check_fields, is_real, require
from gearkit.families.cam.laws import MotionProgram

__all__ = ["CamSpec", "FOLLOWERS", "CONTACTS", "DEFAULT_LIMIT_DEG", "SPAN"]

FOLLOWERS = ("translating", "rocker")
CONTACTS = ("roller", "knife", "flat")
#: the lengths of a mechanism lie within this factor of its cam's size, r0 + stroke, either way
SPAN = 1e4
#: the prime radius of a cam, mm (a gear's module spans [1e-4, 1e4] mm)
PRIME_RANGE = (1e-3, 1e6)
#: recommended pressure-angle limits (textbook §38): 30 degrees translating, 45 degrees rocker
DEFAULT_LIMIT_DEG = {"translating": 30.0, "rocker": 45.0}
#: the farthest pivot and the longest arm of a rocker, in (r0 + stroke): the cam's points are computed
#: through the follower's pose, whose round-off (1e-14 of the lengths up to the pivot) stays below a
#: fifth of the cam's finest tol, 1e-9 (r0 + stroke)
REACH = 1e4


def _length(v, name, positive=True, needed_by: str = ""):
    require(v is not None, name, f"is required{needed_by} (a length in mm)")
    ok = is_real(v) and (v > 0 if positive else v >= 0)
    require(ok, name, f"{v!r} must be a {'positive' if positive else 'non-negative'} length in mm")


@dataclass(frozen=True)
class CamSpec:
    """A disc cam: its follower, its motion program and the prime radius (lengths in mm).

    Parameters
    ----------
    prime_radius : float, mm, > 0
        r0: the smallest radius of the pitch curve (base circle for a flat face).
    motion : MotionProgram
        The follower's displacement over one turn (for a rocker: the roller centre's arc).
    follower : {"translating", "rocker"}
    contact : {"roller", "knife", "flat"}
    roller_radius : float, mm
        R_p, > 0 for a roller, 0 otherwise.
    offset : float, mm
        e, translating follower: the follower line is ``x = e`` (``|e| < r0``). With the cam turning
        counter-clockwise a positive offset lowers the pressure angle of the rise.
    pivot_distance, arm_length : float or None, mm
        l0 and l of a rocker.
    efficiency : float in (0, 1]
        eta of the roller–cam couple (the power model of the friction digest: tg theta uses s'/eta).
    friction : float >= 0
        Friction coefficient for the textbook model: the friction angle atan(mu) adds to alpha.
    pressure_angle_limit_deg : float or None, degrees
        Allowed pressure angle (default 30 translating, 45 rocker).
    groove : bool
        Form-closed (grooved) cam: the return is driven too, so its pressure angle counts.

    Examples
    --------
    >>> spec = CamSpec(40.0, MotionProgram.rise_dwell_return(10.0, 90.0, 30.0, 90.0), roller_radius=8.0)
    >>> round(spec.start_height, 6), spec.limit_deg
    (40.0, 30.0)
    """

    prime_radius: float
    motion: MotionProgram
    follower: str = "translating"
    contact: str = "roller"
    roller_radius: float = 0.0
    offset: float = 0.0
    pivot_distance: float | None = None
    arm_length: float | None = None
    efficiency: float = 1.0
    friction: float = 0.0
    pressure_angle_limit_deg: float | None = None
    groove: bool = False
    name: str = field(default="cam", compare=False)

    def __post_init__(self):
        check_fields(self)
        _length(self.prime_radius, "prime_radius")
        require(isinstance(self.motion, MotionProgram), "motion", "must be a MotionProgram")
        require(self.follower in FOLLOWERS, "follower", f"{self.follower!r} is not one of {', '.join(FOLLOWERS)}")
        require(self.contact in CONTACTS, "contact", f"{self.contact!r} is not one of {', '.join(CONTACTS)}")
        _length(self.roller_radius, "roller_radius", positive=self.contact == "roller")
        if self.contact != "roller":
            require(self.roller_radius == 0.0, "roller_radius", f"a {self.contact} follower has no roller")
        require(self.roller_radius < self.prime_radius, "roller_radius", f"R_p = {self.roller_radius!r} mm must be below "
                f"the prime radius {self.prime_radius!r} mm (a roller that reaches the cam's centre leaves no cam)")
        require(is_real(self.offset), "offset", f"{self.offset!r} must be a finite length in mm")
        require(is_real(self.efficiency) and 0.0 < self.efficiency <= 1.0, "efficiency",
                f"{self.efficiency!r} must be in (0, 1]")
        require(is_real(self.friction) and 0.0 <= self.friction < 1.0, "friction",
                f"{self.friction!r} must be in [0, 1)")
        lim = self.pressure_angle_limit_deg
        require(lim is None or (is_real(lim) and 0.0 < lim < 90.0), "pressure_angle_limit_deg",
                f"{lim!r} must be in (0, 90) degrees")
        r0 = self.prime_radius
        self._spans_the_cam()
        if self.follower == "translating":
            require(self.pivot_distance is None and self.arm_length is None, "pivot_distance",
                    "a translating follower has no pivot or arm")
            if self.contact != "flat":
                require(abs(self.offset) < r0, "offset",
                        f"|e| = {abs(self.offset):g} mm must be below the prime radius {r0:g} mm (the follower "
                        "line must cut the prime circle to reach the cam)")
            return
        require(self.offset == 0.0, "offset", "a rocker has no offset (give pivot_distance and arm_length)")
        _length(self.pivot_distance, "pivot_distance", needed_by=" by a rocker follower")
        _length(self.arm_length, "arm_length", needed_by=" by a rocker follower")
        l0, arm = self.pivot_distance, self.arm_length
        reach = REACH * (r0 + self.motion.stroke)
        require(l0 <= reach, "pivot_distance", f"l0 = {l0!r} mm must be at most {reach:.6g} mm "
                f"({REACH:g} (r0 + stroke): the cam's points are computed through the pivot)")
        require(arm <= reach, "arm_length", f"l = {arm!r} mm must be at most {reach:.6g} mm "
                f"({REACH:g} (r0 + stroke): the cam's points are computed through the pivot)")
        if self.contact == "flat":
            require(r0 < l0, "prime_radius", f"r0 = {r0:g} mm must be below the pivot distance {l0:g} mm")
        else:
            require(abs(l0 - arm) < r0 < l0 + arm, "arm_length",
                    f"the rocker cannot reach the prime circle: need |l0 - l| < r0 < l0 + l (l0 = {l0:g}, "
                    f"l = {arm:g}, r0 = {r0:g} mm)")
        top = self.psi0 + self.motion.stroke / arm
        require(top < math.pi, "rise", f"the rocker would swing past the line of centres (Psi up to "
                f"{math.degrees(top):.4g} degrees; must stay below 180)")

    def _spans_the_cam(self):
        """Every length of the mechanism within ``SPAN`` of the cam's size ``r0 + stroke`` either way: the
        cam's points are computed through the follower's pose, whose round-off grows with its longest
        length (a pivot 1e300 mm away, a base circle of 1e-300 mm under a 1 mm stroke leave no digits)."""
        size = self.prime_radius + self.motion.stroke
        require(PRIME_RANGE[0] <= self.prime_radius <= PRIME_RANGE[1], "prime_radius", f"{self.prime_radius!r} must "
                f"be a length in [{PRIME_RANGE[0]:g}, {PRIME_RANGE[1]:g}] mm")
        require(self.prime_radius >= self.motion.stroke / SPAN, "prime_radius", f"{self.prime_radius!r} mm is below "
                f"1/{SPAN:g} of the stroke {self.motion.stroke:g} mm (the cam's own precision)")
        # a rocker's pivot and arm are held to REACH below, once they are known to be lengths
        require(abs(self.offset) <= SPAN * size, "offset", f"{self.offset!r} mm is beyond {SPAN:g} (r0 + stroke) = "
                f"{SPAN * size:g} mm (the cam's own precision)")

    # -- derived values --------------------------------------------------------------------
    @property
    def limit_deg(self) -> float:
        """The pressure-angle limit in use, degrees."""
        lim = self.pressure_angle_limit_deg
        return DEFAULT_LIMIT_DEG[self.follower] if lim is None else float(lim)

    @property
    def start_height(self) -> float:
        """H0 of a translating follower: height of the reference point at s = 0 (``sqrt(r0^2 - e^2)``;
        ``r0`` for a flat face)."""
        if self.contact == "flat":
            return self.prime_radius
        return math.sqrt(self.prime_radius ** 2 - self.offset ** 2)

    @property
    def psi0(self) -> float:
        """Psi0 of a rocker: arm angle at s = 0 from the line pivot -> cam centre, rad."""
        l0, arm, r0 = self.pivot_distance, self.arm_length, self.prime_radius
        if self.contact == "flat":
            return math.asin(r0 / l0)
        return math.acos((l0 * l0 + arm * arm - r0 * r0) / (2.0 * l0 * arm))

    @property
    def stroke(self) -> float:
        """Largest displacement, mm (a rocker's: the roller centre's arc)."""
        return self.motion.stroke
