"""Poses of every gear copy: axes from the layout, rotations phased so every mesh has its teeth
interleaved, and the motion at an input angle (planets turn with the carrier).

A gear at rotation ``rho`` has tooth ``k`` centred at ``pi/2 + rho + 2 pi k / z`` (the kernel's
profiles put tooth 0 on +y). Its phase towards direction ``psi`` is
``u(psi) = frac(z (psi - pi/2 - rho) / 2 pi)`` (0: a tooth centred on ``psi``). An external mesh,
B in direction ``gamma`` from A, needs ``u_A(gamma) + u_B(gamma + pi) = 1/2``; a pinion inside a
ring, in direction ``delta`` from the ring's axis, needs ``u_P(delta) - u_R(delta) = 1/2`` (a tooth
faces a space, with the backlash shared by both flanks). Rotations are solved over the meshes of
the first planet copies; every further copy of a planet block turns so all its meshes fit (the
assembly condition), else the scene cannot be assembled and the error says which planet.

Examples
--------
>>> from gearkit.scene.model import Gear, Mesh, Motion, Scene
>>> from gearkit.scene.layout import scene_layout
>>> s = Scene((Gear("a", 20), Gear("b", 30)), (Mesh("a", "b"),), motion=Motion(inputs={"a": 1}))
>>> [(p.gear, round(p.x, 6), round(math.degrees(p.rotation), 6)) for p in poses(s, scene_layout(s))]
[('a', 0.0, 0.0), ('b', 25.0, 84.0)]
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from gearkit.errors import SpecError

__all__ = ["Pose", "base_rotations", "poses"]

_PHASE_TOL = 1e-7  # mesh cycles


@dataclass(frozen=True)
class Pose:
    """One placed gear copy: axis (x, y) mm, rotation rad, and its part name (``gear`` or ``gear#k``)."""

    gear: str
    copy: int
    x: float
    y: float
    rotation: float

    @property
    def name(self) -> str:
        return self.gear if self.copy == 0 and "#" not in self.gear else f"{self.gear}#{self.copy + 1}"


def _phase(z: int, psi: float, rho: float) -> float:
    return (z * (psi - math.pi / 2 - rho) / (2 * math.pi)) % 1.0


def _solve(z: int, psi: float, u: float) -> float:
    """The rotation giving phase ``u`` towards ``psi``."""
    return psi - math.pi / 2 - 2 * math.pi * u / z


def _edges(scene, layout, carrier_angles) -> list:
    """(gear a, copy, gear b, copy, kind, psi_a, psi_b) for every mesh of every copy."""
    out = []
    for mesh in scene.meshes:
        a, b = scene.gear(mesh.first), scene.gear(mesh.second)
        kind = scene.mesh_kind(mesh)
        if kind == "rack":
            raise SpecError("meshes", f"{mesh.label}: racks are kinematic and formula-checked only; they are not "
                            "placed in scene geometry yet")
        copies = max(a.count, b.count)
        for k in range(copies):
            ka, kb = (k if a.count > 1 else 0), (k if b.count > 1 else 0)
            pa = layout.axis(a.member, ka, carrier_angles.get(a.carrier, 0.0))
            pb = layout.axis(b.member, kb, carrier_angles.get(b.carrier, 0.0))
            if kind == "internal":
                pin, ring = (a, b) if b.internal else (b, a)
                pp, pr = (pa, pb) if b.internal else (pb, pa)
                delta = math.atan2(pp[1] - pr[1], pp[0] - pr[0])
                ends = {pin.name: delta, ring.name: delta}
            else:
                gamma = math.atan2(pb[1] - pa[1], pb[0] - pa[0])
                ends = {a.name: gamma, b.name: gamma + math.pi}
            out.append((a.name, ka, b.name, kb, kind, ends[a.name], ends[b.name]))
    return out


def _residual(scene, edge, rot) -> float:
    a, ka, b, kb, kind, psi_a, psi_b = edge
    ga, gb = scene.gear(a), scene.gear(b)
    ua, ub = _phase(ga.teeth, psi_a, rot[(a, ka)]), _phase(gb.teeth, psi_b, rot[(b, kb)])
    if kind == "external":
        value = ua + ub - 0.5
    elif gb.internal:
        value = ua - ub - 0.5
    else:
        value = ub - ua - 0.5
    value %= 1.0
    return min(value, 1.0 - value)


def _mate(scene, edge, rot, known: str) -> tuple:
    """The rotation of the unknown end of ``edge`` given the ``known`` end ('a' or 'b')."""
    a, ka, b, kb, kind, psi_a, psi_b = edge
    ga, gb = scene.gear(a), scene.gear(b)
    if known == "a":
        ua = _phase(ga.teeth, psi_a, rot[(a, ka)])
        ub = (0.5 - ua) if kind == "external" else (ua - 0.5 if gb.internal else ua + 0.5)
        return (b, kb), _solve(gb.teeth, psi_b, ub)
    ub = _phase(gb.teeth, psi_b, rot[(b, kb)])
    ua = (0.5 - ub) if kind == "external" else (ub + 0.5 if gb.internal else ub - 0.5)
    return (a, ka), _solve(ga.teeth, psi_a, ua)


def base_rotations(scene, layout) -> dict:
    """{(gear, copy): rotation (rad)} at the base pose, every mesh phased; raises SpecError when a
    planet copy or a loop of meshes cannot be assembled."""
    edges = _edges(scene, layout, {})
    rot = {}
    first = [e for e in edges if e[1] == 0 and e[3] == 0]
    for g in scene.gears:  # the first copies: spread rotations through the meshes
        if (g.name, 0) in rot:
            continue
        mates = [rot[(h.name, 0)] for h in scene.member_gears(g.member) if (h.name, 0) in rot]
        rot[(g.name, 0)] = mates[0] if mates else 0.0
        stack = [g.name]
        while stack:
            name = stack.pop()
            for e in first:
                for end, other in (("a", e[2]), ("b", e[0])):
                    if (e[0] if end == "a" else e[2]) == name and (other, 0) not in rot:
                        key, value = _mate(scene, e, rot, end)
                        rot[key] = value
                        stack.append(other)
    for member in scene.members:  # further planet copies: one block rotation fitting every mesh
        gears = scene.member_gears(member)
        if not gears or gears[0].count == 1:
            continue
        for k in range(1, gears[0].count):
            _place_copy(scene, edges, rot, gears, k)
    for e in edges:
        if _residual(scene, e, rot) > _PHASE_TOL:
            raise SpecError("meshes", f"{e[0]}{_tag(e[1], scene.gear(e[0]))} and {e[2]}{_tag(e[3], scene.gear(e[2]))} "
                            "cannot mesh: the loop of meshes through them puts a tooth against a tooth")
    return rot


def _tag(copy: int, gear) -> str:
    return f"#{copy + 1}" if gear.count > 1 else ""


def _place_copy(scene, edges, rot, gears, k) -> None:
    names = {g.name for g in gears}
    mine = [e for e in edges if (e[0] in names and e[1] == k) or (e[2] in names and e[3] == k)]
    g0 = gears[0]
    if not mine:
        for g in gears:
            rot[(g.name, k)] = rot[(g.name, 0)]
        return
    e0 = mine[0]
    end = "b" if e0[0] in names else "a"  # the known end is the central gear
    (name, _), value = _mate(scene, e0, rot, end)
    z = scene.gear(name).teeth
    base = value - rot[(name, 0)]
    for j in range(z):  # the block turns by base + j pitches of that gear: find one fitting all meshes
        turn = base + 2 * math.pi * j / z
        trial = dict(rot)
        for g in gears:
            trial[(g.name, k)] = rot[(g.name, 0)] + turn
        if all(_residual(scene, e, trial) <= _PHASE_TOL for e in mine):
            rot.update({(g.name, k): trial[(g.name, k)] for g in gears})
            return
    where = math.degrees(g0.angles()[k])
    raise SpecError(f"{g0.member}.angles_deg", f"planet {g0.member}#{k + 1} at {where:.6g} deg cannot be "
                    "assembled: no rotation of the planet meshes all its central gears")


def poses(scene, layout, speeds=None, angle: float = 0.0) -> list:
    """Every gear copy placed with the input turned by ``angle`` (rad): each member turns by its
    speed times ``angle`` (``speeds`` from :func:`~gearkit.scene.scene_speeds`, per unit input),
    planets ride their carrier."""
    rot0 = base_rotations(scene, layout)

    def turn(member):
        if speeds is None or not angle:
            return 0.0
        return float(speeds.speed(member)) * angle

    out = []
    for g in scene.gears:
        for k in range(g.count):
            cx, cy = layout.axis(g.member, k, turn(g.carrier) if g.carrier else 0.0)
            out.append(Pose(g.name, k, cx, cy, rot0[(g.name, k)] + turn(g.member)))
    return out

