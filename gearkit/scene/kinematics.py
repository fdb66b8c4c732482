"""Kinematics of a scene without geometry: the Willis relations of every mesh as one linear system.

Each mesh between gear ``a`` (on member A) and gear ``b`` (on member B) whose axes ride on frame
F (a carrier, or the ground) gives one equation, the pitch-line speeds matched in F::

    c_a (w_A - w_F) + s c_b (w_B - w_F) = 0

with ``c`` the tooth numbers and ``s = +1`` for an external mesh (the gears turn opposite ways
in F), ``s = -1`` for an internal one (same way); a rack's ``c`` is the pinion's pitch radius and
the rack's "speed" its linear speed (mm per radian). Fixed members (``w = 0``), locked members
(equal speeds) and driven members (given speeds) close the system, which is solved exactly in
rational numbers: any number of carriers, fixed-axis trains, differentials (2 DOF, two inputs)
and multi-speed boxes (one solve per brake/clutch state). The degrees of freedom are the
members less the rank of the mesh, fixed and locked equations.

Cost: a Gaussian elimination on (members + 1) columns; no tooth is built.

Examples
--------
>>> t = Train(("sun", "planet", "ring", "carrier"),
...           (Relation("sun", "planet", 21, 43, 1, "carrier"), Relation("planet", "ring", 43, 108, -1, "carrier")))
>>> s = t.solve(fixed=("ring",), inputs={"sun": 1})
>>> s.dof, s.ratio("sun", "carrier"), s.relative("planet", "carrier")
(1, Fraction(43, 7), Fraction(-756, 1849))
"""
from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction

from gearkit.errors import SpecError, require

__all__ = ["Relation", "Speeds", "Train", "scene_train", "scene_speeds"]


def _frac(v) -> Fraction:
    return v if isinstance(v, Fraction) else Fraction(v)


@dataclass(frozen=True)
class Relation:
    """One mesh equation ``c_a (w_a - w_frame) + sign c_b (w_b - w_frame) = 0`` (see the module notes).

    ``frame`` is the carrier the axes ride on (None: the ground); ``label`` names the mesh.
    """

    a: str
    b: str
    coeff_a: object
    coeff_b: object
    sign: int
    frame: str | None = None
    label: str = ""

    def __post_init__(self):
        require(self.sign in (1, -1), "sign", f"{self.sign!r} must be +1 (external) or -1 (internal)")
        object.__setattr__(self, "coeff_a", _frac(self.coeff_a))
        object.__setattr__(self, "coeff_b", _frac(self.coeff_b))
        if not self.label:
            object.__setattr__(self, "label", f"{self.a}-{self.b}")


def _rref(rows: list, ncols: int) -> tuple:
    """Reduced row echelon form in place (Fractions); returns (rows, pivot columns)."""
    pivots = []
    r = 0
    for c in range(ncols):
        p = next((i for i in range(r, len(rows)) if rows[i][c] != 0), None)
        if p is None:
            continue
        rows[r], rows[p] = rows[p], rows[r]
        inv = 1 / rows[r][c]
        rows[r] = [v * inv for v in rows[r]]
        for i in range(len(rows)):
            if i != r and rows[i][c] != 0:
                f = rows[i][c]
                rows[i] = [v - f * w for v, w in zip(rows[i], rows[r])]
        pivots.append(c)
        r += 1
        if r == len(rows):
            break
    return rows, pivots


@dataclass(frozen=True)
class Speeds:
    """Speeds of every member (exact fractions; None where the inputs leave a speed free).

    ``dof`` counts the degrees of freedom of the train with its fixed and locked members;
    ``frames`` maps each member to the carrier its axis rides on (None: the ground).
    """

    speeds: dict
    dof: int
    frames: dict
    relations: tuple

    def speed(self, member: str) -> Fraction:
        """The speed of ``member``; raises when the inputs do not determine it."""
        require(member in self.speeds, "member", f"no member {member!r}")
        w = self.speeds[member]
        if w is None:
            raise SpecError("motion", f"the speed of {member} is not determined by the inputs (the train has "
                            f"{self.dof} degree(s) of freedom): give another input, or fix or lock a member")
        return w

    def ratio(self, a: str, b: str) -> Fraction:
        """Signed ratio ``w_a / w_b``; raises when they are not connected or ``w_b`` is 0."""
        for m in (a, b):
            if self.speeds.get(m, 0) is None:
                raise SpecError("motion", f"{a} and {b} are not connected through the train: the speed of {m} is "
                                "not determined by the inputs")
        wb = self.speed(b)
        if wb == 0:
            raise SpecError("motion", f"{b} stands still: the ratio {a}/{b} is infinite")
        return self.speed(a) / wb

    def relative(self, member: str, carrier: str | None = None) -> Fraction:
        """Speed of ``member`` relative to ``carrier`` (default: the carrier its axis rides on)."""
        carrier = carrier if carrier is not None else self.frames.get(member)
        return self.speed(member) - (self.speed(carrier) if carrier is not None else 0)

    def mesh_frequencies(self) -> dict:
        """Tooth-mesh frequency of every mesh: teeth passing per unit time, ``c_a |w_a - w_frame|``,
        in cycles per revolution-unit of the speeds (input speed 1: mesh orders of the input)."""
        out = {}
        for r in self.relations:
            try:
                out[r.label] = abs(r.coeff_a * (self.speed(r.a) - (self.speed(r.frame) if r.frame else 0)))
            except SpecError:
                out[r.label] = None
        return out


@dataclass(frozen=True)
class Train:
    """Members and the mesh relations between them (a scene's kinematic skeleton)."""

    members: tuple
    relations: tuple

    def __post_init__(self):
        object.__setattr__(self, "members", tuple(self.members))
        object.__setattr__(self, "relations", tuple(self.relations))
        for r in self.relations:
            for m in (r.a, r.b) + ((r.frame,) if r.frame else ()):
                require(m in self.members, "relations", f"{r.label}: {m!r} is not a member")

    def _row(self, pairs, rhs=0) -> list:
        row = [Fraction(0)] * (len(self.members) + 1)
        for m, c in pairs:
            row[self.members.index(m)] += _frac(c)
        row[-1] = _frac(rhs)
        return row

    def _constraints(self, fixed, locked) -> list:
        rows = []
        for r in self.relations:
            pairs = [(r.a, r.coeff_a), (r.b, r.sign * r.coeff_b)]
            if r.frame:
                pairs.append((r.frame, -(r.coeff_a + r.sign * r.coeff_b)))
            rows.append(self._row(pairs))
        rows += [self._row([(m, 1)]) for m in fixed]
        for group in locked:
            rows += [self._row([(group[0], 1), (m, -1)]) for m in group[1:]]
        return rows

    def dof(self, fixed=(), locked=()) -> int:
        """Degrees of freedom with ``fixed`` members held and ``locked`` groups turning as one."""
        rows, pivots = _rref(self._constraints(fixed, locked), len(self.members))
        return len(self.members) - len(pivots)

    def solve(self, fixed=(), locked=(), inputs=None, frames=None) -> Speeds:
        """Speeds of every member for ``inputs`` {member: speed}.

        Raises SpecError when the inputs contradict the train (more inputs than degrees of
        freedom, or a driven member the train holds still).
        """
        inputs = dict(inputs or {})
        n = len(self.members)
        base = self._constraints(fixed, locked)
        dof = n - len(_rref([row[:] for row in base], n)[1])
        rows = base + [self._row([(m, 1)], w) for m, w in inputs.items()]
        rows, pivots = _rref(rows, n)
        bad = [row for row in rows if all(v == 0 for v in row[:n]) and row[n] != 0]
        if bad:
            raise SpecError("motion", f"the inputs ({', '.join(inputs)}) contradict the train: it has {dof} degree(s) "
                            "of freedom with these fixed and locked members, and the driven members cannot all move "
                            "as asked")
        speeds = {m: None for m in self.members}
        free = [c for c in range(n) if c not in pivots]
        for i, c in enumerate(pivots):
            row = rows[i]
            if all(row[f] == 0 for f in free):
                speeds[self.members[c]] = row[n]
        return Speeds(speeds, dof, dict(frames or {}), self.relations)


def scene_train(scene) -> Train:
    """The kinematic skeleton of a :class:`~gearkit.scene.Scene` (one relation per mesh)."""
    import math

    rels = []
    for mesh in scene.meshes:
        a, b = scene.gear(mesh.first), scene.gear(mesh.second)
        frame = a.carrier or b.carrier
        kind = scene.mesh_kind(mesh)
        if kind == "rack":
            pinion, rack = (a, b) if b.rack else (b, a)
            beta = math.radians(scene.helix_angles()[pinion.name])
            radius = Fraction(scene.module_of(pinion) * pinion.teeth / (2 * math.cos(beta)))
            rels.append(Relation(pinion.member, rack.member, radius, 1, -1, None, mesh.label))
        else:
            rels.append(Relation(a.member, b.member, a.teeth, b.teeth, -1 if kind == "internal" else 1, frame,
                                 mesh.label))
    return Train(scene.members, tuple(rels))


def scene_speeds(scene, state: str | None = None, inputs: dict | None = None) -> Speeds:
    """Speeds of every member of ``scene`` in ``state`` (None: its motion).

    ``inputs`` {member or gear: speed} overrides the motion's inputs. Touches no geometry.
    """
    motion = scene.state(state)
    given = inputs if inputs is not None else dict(motion.inputs)
    require(bool(given), "motion.input", "no driven member: give an input")
    fixed = tuple(scene.member_of(n) for n in motion.fixed)
    locked = tuple(tuple(scene.member_of(n) for n in group) for group in motion.locked)
    ins = {scene.member_of(k): v for k, v in given.items()}
    frames = {m: scene.carrier_of(m) for m in scene.members}
    train = scene_train(scene)
    return train.solve(fixed, locked, ins, frames)
