"""The scene: several placed gears as one frozen value (gears, shafts, carriers, meshes, motion).

A **gear** has identity: it is one spec wherever it meshes. Gears that share a ``shaft`` name
turn together (compound planets, stepped gears); a gear without one is its own shaft. A gear
with a ``carrier`` is a planet: ``count`` copies ride on that carrier (equally spaced, or at the
given ``angles_deg``). **Members** are what turns: the shafts and the carriers; a carrier may
also carry gears (``shaft = "carrier"``), which is how stages are chained. A **mesh** joins two
gears; its kind follows from them (``internal`` when one is a ring, ``rack`` when one is a
rack, else ``external``). The **motion** says which members are fixed, which are locked
together, which are driven and at what speed, and which one is the output; **states** are
alternative sets of fixed and locked members (the brakes and clutches of a multi-speed box).

Examples
--------
>>> s = Scene(module=1.75, gears=(Gear("sun", 21), Gear("planet", 43, count=3, carrier="carrier"),
...           Gear("ring", 108, internal=True)), meshes=(Mesh("sun", "planet"), Mesh("planet", "ring")),
...           motion=Motion(fixed=("ring",), inputs=(("sun", 1.0),), output="carrier"))
>>> s.members
('sun', 'planet', 'ring', 'carrier')
>>> s.mesh_kind(s.meshes[1])
'internal'
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

from gearkit.errors import SpecError, check_fields, is_int, is_real, require
from gearkit.scene.hands import helix_angles

__all__ = ["Gear", "Mesh", "Motion", "Scene", "MESH_KINDS"]

MESH_KINDS = ("external", "internal", "rack")


def _name(value, field_name: str) -> str:
    require(isinstance(value, str) and value.strip() != "" and value == value.strip(), field_name,
            f"{value!r} must be a non-empty name without surrounding spaces")
    return value


def _names(values, field_name: str, depth: int = 1) -> None:
    require(isinstance(values, (tuple, list)), field_name, f"{values!r} must be a list of names")
    for v in values:  # depth 2: a list of lists of names
        _names(v, field_name) if depth == 2 else _name(v, field_name)


@dataclass(frozen=True)
class Gear:
    """One gear of a scene (inputs only).

    Parameters
    ----------
    name : str
    teeth : int, >= 3
    shift : float
        Normal profile-shift coefficient x_n (a ring's follows the pair layer's convention, the
        ``shift2`` of an internal :class:`~gearkit.pair.PairSpec`).
    module : float or None, mm
        Normal module m_n; None takes the scene's.
    internal : bool
        A ring (internal gear), cut by a shaper of ``cutter_teeth`` teeth.
    rack : bool
        A rack (straight gear); ``teeth`` is then the number of teeth on the bar.
    shaft : str or None
        The member the gear turns with (default: its own name).
    carrier : str or None
        The carrier of a planet; ``count`` copies ride on it.
    count : int, >= 1
        Number of planets.
    angles_deg : tuple of float or None, degrees
        Planet angles on the carrier (default: equally spaced, the first at 0).
    helix_angle_deg : float or None, degrees
        Signed helix angle (right hand positive); None takes the hand its meshes imply from the
        scene's ``helix_angle_deg``.
    thinning : float, mm
        Tooth-thickness allowance for backlash (normal, on the reference circle), the same at
        every mesh of the gear.
    cutter_teeth : int or None
        Teeth of the shaper that cuts a ring (default: the largest standard shaper that fits, at
        most 25 teeth).
    """

    name: str
    teeth: int
    shift: float = 0.0
    module: float | None = None
    internal: bool = False
    rack: bool = False
    shaft: str | None = None
    carrier: str | None = None
    count: int = 1
    angles_deg: tuple | None = None
    helix_angle_deg: float | None = None
    thinning: float = 0.0
    cutter_teeth: int | None = None

    def __post_init__(self):
        n = _name(self.name, "gears")
        check_fields(self, f"{n}.")
        require(is_int(self.teeth) and 3 <= self.teeth <= 100000, f"{n}.teeth",
                f"z = {self.teeth!r} must be an integer in [3, 100000]")
        require(is_real(self.shift) and -3.0 <= self.shift <= 3.0, f"{n}.shift", f"x = {self.shift!r} must be in [-3, 3]")
        require(self.module is None or is_real(self.module) and 1e-4 <= self.module <= 1e4, f"{n}.module",
                f"m = {self.module!r} must be a length in [0.0001, 10000] mm")
        require(not (self.internal and self.rack), f"{n}.internal", "a gear cannot be both a ring and a rack")
        for key in ("shaft", "carrier"):
            if getattr(self, key) is not None:
                _name(getattr(self, key), f"{n}.{key}")
        require(is_int(self.count) and 1 <= self.count <= 64, f"{n}.count", f"{self.count!r} must be in [1, 64]")
        require(self.count == 1 or self.carrier is not None, f"{n}.count", "only planets (gears with a carrier) "
                "come in several copies")
        if self.angles_deg is not None:
            require(self.carrier is not None, f"{n}.angles_deg", "only planets have angles on a carrier")
            a = self.angles_deg
            require(isinstance(a, (tuple, list)) and len(a) == self.count and all(is_real(v) for v in a),
                    f"{n}.angles_deg", f"give {self.count} angles in degrees, one per planet")
            object.__setattr__(self, "angles_deg", tuple(float(v) for v in a))
        require(self.carrier is None or not (self.internal or self.rack), f"{n}.carrier",
                "a planet is an external gear")
        require(self.helix_angle_deg is None or abs(self.helix_angle_deg) < 60, f"{n}.helix_angle_deg",
                f"{self.helix_angle_deg!r} must be in (-60, 60) degrees")
        require(is_real(self.thinning) and self.thinning >= 0, f"{n}.thinning", f"{self.thinning!r} must be >= 0 mm")
        if self.cutter_teeth is not None:
            require(self.internal, f"{n}.cutter_teeth", "only a ring is cut by a shaper here")
            require(is_int(self.cutter_teeth) and 6 <= self.cutter_teeth <= self.teeth - 4, f"{n}.cutter_teeth",
                    f"{self.cutter_teeth!r} must be an integer in [6, {self.teeth - 4}]")

    @property
    def member(self) -> str:
        """The member this gear turns with."""
        return self.shaft or self.name

    def angles(self) -> tuple:
        """Planet angles on the carrier, radians (one angle, 0, for a gear that is not a planet)."""
        if self.angles_deg is not None:
            return tuple(math.radians(a) for a in self.angles_deg)
        return tuple(2 * math.pi * k / self.count for k in range(self.count))


@dataclass(frozen=True)
class Mesh:
    """Two gears in mesh (by name).

    ``angle_deg`` places a fixed-axis mesh: the direction from the first gear's axis to the
    second's (degrees, default 0); planets are placed by their carrier instead.
    ``center_distance`` (mm) overrides the tight working centre distance of a fixed-axis mesh.
    """

    first: str
    second: str
    angle_deg: float = 0.0
    center_distance: float | None = None

    def __post_init__(self):
        _name(self.first, "meshes")
        _name(self.second, "meshes")
        check_fields(self, f"{self.label}.")
        require(self.first != self.second, "meshes", f"{self.first} cannot mesh with itself")
        require(is_real(self.angle_deg), f"{self.label}.angle_deg", f"{self.angle_deg!r} must be a number of degrees")
        if self.center_distance is not None:
            require(is_real(self.center_distance) and self.center_distance > 0, f"{self.label}.center_distance",
                    f"{self.center_distance!r} must be a positive length in mm")

    @property
    def label(self) -> str:
        return f"{self.first}-{self.second}"


@dataclass(frozen=True)
class Motion:
    """Which members are fixed, locked together, driven (with speeds) and which is the output.

    Names may be members or gears (a gear stands for its member).
    """

    fixed: tuple = ()
    locked: tuple = ()
    inputs: tuple = ()
    output: str | None = None

    def __post_init__(self):
        check_fields(self)
        _names(self.fixed, "fixed")
        _names(self.locked, "locked", 2)
        object.__setattr__(self, "fixed", tuple(self.fixed))
        object.__setattr__(self, "locked", tuple(tuple(p) for p in self.locked))
        inputs = tuple(self.inputs.items()) if isinstance(self.inputs, dict) else self.inputs
        for kv in inputs if isinstance(inputs, (tuple, list)) else (inputs,):
            require(isinstance(kv, (tuple, list)) and len(kv) == 2 and isinstance(kv[0], str), "inputs",
                    f"{kv!r} must be a (member, speed) pair")
            require(is_real(kv[1]), f"input.{kv[0]}", f"{kv[1]!r} must be a finite speed")
        object.__setattr__(self, "inputs", tuple((k, float(v)) for k, v in inputs))
        for pair in self.locked:
            require(len(pair) >= 2, "locked", f"{list(pair)!r}: a lock joins two or more members")


@dataclass(frozen=True)
class Scene:
    """Placed gears: the value every scene query works on (see the module notes).

    Parameters
    ----------
    gears : tuple of Gear
    meshes : tuple of Mesh
    module : float, mm
        Normal module of the gears that do not give their own.
    motion : Motion
    states : tuple of (str, Motion)
        Alternative fixed/locked sets (brakes, clutches); their inputs and output default to
        ``motion``'s.
    pressure_angle_deg, helix_angle_deg : float, degrees
        Normal pressure angle; helix angle of the gears that do not give their own (its hand is
        that of the first gear; meshes decide the others').
    addendum, clearance : float
        h_a* and the bottom clearance c* (module units) every tip is sized for.
    face_width : float or None, mm
    coaxial : tuple of tuple of str
        Groups of members that must share an axis (e.g. the input and output of a reverted train).
    """

    gears: tuple
    meshes: tuple
    module: float = 1.0
    motion: Motion = field(default_factory=Motion)
    states: tuple = ()
    pressure_angle_deg: float = 20.0
    helix_angle_deg: float = 0.0
    addendum: float = 1.0
    clearance: float = 0.25
    face_width: float | None = None
    coaxial: tuple = ()

    def __post_init__(self):
        check_fields(self)
        for key in ("gears", "meshes", "states"):
            require(isinstance(getattr(self, key), (tuple, list)), key, f"{getattr(self, key)!r} must be a list")
        require(isinstance(self.motion, Motion), "motion", f"{self.motion!r} must be a Motion")
        require(all(isinstance(s, (tuple, list)) and len(s) == 2 and isinstance(s[1], Motion) for s in self.states),
                "states", f"{self.states!r} must be (name, Motion) pairs")
        _names(self.coaxial, "coaxial", 2)
        object.__setattr__(self, "gears", tuple(self.gears))
        object.__setattr__(self, "meshes", tuple(self.meshes))
        object.__setattr__(self, "states", tuple((str(k), v) for k, v in self.states))
        object.__setattr__(self, "coaxial", tuple(tuple(g) for g in self.coaxial))
        require(len(self.gears) >= 1 and all(isinstance(g, Gear) for g in self.gears), "gears", "give at least one Gear")
        require(all(isinstance(m, Mesh) for m in self.meshes), "meshes", "give Mesh values")
        require(is_real(self.module) and 1e-4 <= self.module <= 1e4, "module",
                f"m = {self.module!r} must be a length in [0.0001, 10000] mm")
        require(is_real(self.pressure_angle_deg) and 1 <= self.pressure_angle_deg < 45, "pressure_angle_deg",
                f"{self.pressure_angle_deg!r} must be in [1, 45) degrees")
        require(is_real(self.helix_angle_deg) and abs(self.helix_angle_deg) < 60, "helix_angle_deg",
                f"{self.helix_angle_deg!r} must be in (-60, 60) degrees")
        require(is_real(self.addendum) and 0 < self.addendum <= 3, "addendum", f"{self.addendum!r} must be in (0, 3]")
        require(is_real(self.clearance) and 0 <= self.clearance <= 1, "clearance",
                f"c* = {self.clearance!r} must be in [0, 1]")
        require(self.face_width is None or is_real(self.face_width) and 0 < self.face_width <= 1e5, "face_width",
                f"{self.face_width!r} must be a length in (0, 100000] mm")
        names = [g.name for g in self.gears]
        dup = {n for n in names if names.count(n) > 1}
        require(not dup, "gears", f"gear names must be unique ({', '.join(sorted(dup))} repeated)")
        self._check_members()
        self._check_meshes()
        for group in self.coaxial:
            require(len(group) >= 2, "coaxial", f"{list(group)!r}: a coaxial group names two or more members")
            for name in group:
                self.member_of(name)
        for state, motion in (("motion", self.motion), *self.states):
            self._check_motion(state, motion)

    # -- structure ------------------------------------------------------------------------
    def gear(self, name: str) -> Gear:
        """The gear called ``name``."""
        for g in self.gears:
            if g.name == name:
                return g
        raise SpecError("gears", f"no gear called {name!r} (gears: {', '.join(g.name for g in self.gears)})")

    @property
    def carriers(self) -> tuple:
        """Carrier names, in order of first use."""
        out = []
        for g in self.gears:
            if g.carrier is not None and g.carrier not in out:
                out.append(g.carrier)
        return tuple(out)

    @property
    def members(self) -> tuple:
        """Everything that turns: shafts (in gear order), then carriers that are not shafts."""
        out = []
        for g in self.gears:
            if g.member not in out:
                out.append(g.member)
        return tuple(out) + tuple(c for c in self.carriers if c not in out)

    def member_gears(self, member: str) -> tuple:
        """The gears on ``member``."""
        return tuple(g for g in self.gears if g.member == member)

    def member_of(self, name: str) -> str:
        """The member a name stands for (a member, or a gear's member)."""
        if name in self.members:
            return name
        if name in {g.name for g in self.gears}:
            return self.gear(name).member
        raise SpecError("motion", f"{name!r} is neither a member nor a gear (members: {', '.join(self.members)})")

    def carrier_of(self, member: str) -> str | None:
        """The carrier a member's axis rides on (None: a fixed axis)."""
        gears = self.member_gears(member)
        return gears[0].carrier if gears else None

    def module_of(self, gear: Gear) -> float:
        return float(gear.module if gear.module is not None else self.module)

    def mesh_kind(self, mesh: Mesh) -> str:
        """"external", "internal" or "rack"."""
        a, b = self.gear(mesh.first), self.gear(mesh.second)
        if a.internal or b.internal:
            return "internal"
        if a.rack or b.rack:
            return "rack"
        return "external"

    # -- validation -----------------------------------------------------------------------
    def _check_members(self):
        for member in self.members:
            gears = self.member_gears(member)
            if not gears:
                continue
            carriers = {g.carrier for g in gears}
            names = ", ".join(g.name for g in gears)
            require(len(carriers) == 1, f"{member}.carrier", f"gears on one shaft ({names}) must ride on one carrier")
            require(len({g.count for g in gears}) == 1 and len({g.angles_deg for g in gears}) == 1,
                    f"{member}.count", f"gears on one shaft ({names}) must come in the same count and angles")
            require(member not in carriers, f"{member}.carrier", "a shaft cannot ride on itself")
            if gears[0].carrier is not None:
                require(gears[0].carrier not in {g.member for g in self.gears if g.carrier is not None},
                        f"{member}.carrier", f"carrier {gears[0].carrier} is itself a planet shaft")
            require(not any(g.rack for g in gears) or len(gears) == 1, f"{member}.shaft",
                    f"a rack moves alone ({names})")

    def _check_meshes(self):
        seen = set()
        for m in self.meshes:
            a, b = self.gear(m.first), self.gear(m.second)
            key = frozenset((a.name, b.name))
            require(key not in seen, "meshes", f"{m.label} is given twice")
            seen.add(key)
            require(a.member != b.member, "meshes", f"{a.name} and {b.name} turn together (one shaft) and cannot mesh")
            require(not (a.internal and b.internal), "meshes", f"{a.name} and {b.name} are both rings")
            require(not (a.rack and b.rack), "meshes", f"{a.name} and {b.name} are both racks")
            require(not ((a.internal and b.rack) or (a.rack and b.internal)), "meshes",
                    f"a ring ({a.name if a.internal else b.name}) cannot mesh a rack")
            ma, mb = self.module_of(a), self.module_of(b)
            require(math.isclose(ma, mb, rel_tol=1e-12), "meshes",
                    f"{a.name} (m_n = {ma:g} mm) and {b.name} (m_n = {mb:g} mm) mesh but their normal modules differ")
            ca, cb = a.carrier, b.carrier
            require(ca is None or cb is None or ca == cb, "meshes",
                    f"{a.name} and {b.name} are planets of different carriers ({ca}, {cb})")
            if a.internal or b.internal:
                ring, pin = (a, b) if a.internal else (b, a)
                require(ring.teeth > pin.teeth, "meshes",
                        f"ring {ring.name} (z = {ring.teeth}) needs more teeth than {pin.name} (z = {pin.teeth})")
            if (a.rack or b.rack):
                require(a.carrier is None and b.carrier is None, "meshes",
                        f"{a.name}-{b.name}: a rack meshes fixed-axis gears only")
        self.helix_angles()  # raises when two meshing gears break the helix rule

    def helix_angles(self) -> dict:
        """Signed helix angle of every gear, degrees (see :func:`gearkit.scene.hands.helix_angles`)."""
        return helix_angles(self)

    def _check_motion(self, state: str, motion: Motion):
        require(isinstance(motion, Motion), state, "give a Motion")
        for name in motion.fixed:
            self.member_of(name)
        for pair in motion.locked:
            members = {self.member_of(n) for n in pair}
            require(len(members) == len(pair), f"{state}.locked", f"{list(pair)!r} names one member twice")
        for name, _ in motion.inputs:
            self.member_of(name)
        if motion.output is not None:
            self.member_of(motion.output)
        fixed = {self.member_of(n) for n in motion.fixed}
        driven = [n for n, _ in motion.inputs if self.member_of(n) in fixed]
        require(not driven, f"{state}.input", f"{', '.join(driven)} cannot be both fixed and driven")

    def state(self, name: str | None) -> Motion:
        """The motion of state ``name`` (None: the scene's motion); a state inherits the inputs and
        output of the scene's motion."""
        if name is None:
            return self.motion
        for key, motion in self.states:
            if key == name:
                return Motion(motion.fixed, motion.locked, motion.inputs or self.motion.inputs,
                              motion.output or self.motion.output)
        raise SpecError("--state", f"no state {name!r} (states: {', '.join(k for k, _ in self.states) or 'none'})")
