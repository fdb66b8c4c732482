"""Formula-level layout of a scene: one spec per gear, centre distances, axes, planet positions.

Built from pair formulas only (no tooth is generated):

1. **Centre distances.** A fixed-axis mesh runs at its tight (zero-backlash) centre distance, or
   the one it gives. A planet shaft sits at one radius from its carrier's axis for all its
   meshes with central gears: their tight (zero-backlash) distances must agree to ``CLOSE_TOL``
   modules, or the loop does not close and the error names the meshes. An external mesh needs
   ``a_w >=`` its tight distance, an internal one ``a_w <=`` its own (beyond either the teeth
   jam): the radius is the middle of that interval (or its one end).
2. **Tips, per gear.** Each mesh at its ``a_w`` says how much the standard tip of each of its
   gears must shrink (a ring's tip circle grow) to keep the bottom clearance ``c* m`` and to end
   its path of contact on the mate's involute (not in its fillet); a gear takes the largest cut
   any of its meshes asks, so it has one tip wherever it meshes.
3. **Axes.** Carriers are coaxial with the central gears their planets mesh (and with the
   ``coaxial`` groups); fixed-axis meshes place one axis from another at ``a_w`` in the mesh's
   direction. A loop that places an axis twice must agree, and the error names the gears.
4. **Planets.** Copies sit at their angles on the carrier; their angles must assemble
   (:mod:`gearkit.scene.phasing`) and their tips must clear each other.

Examples
--------
>>> from gearkit.scene.model import Gear, Mesh, Scene
>>> s = Scene((Gear("a", 15), Gear("idler", 30, 0.5), Gear("b", 40)), (Mesh("a", "idler"), Mesh("idler", "b")),
...           module=2.0)
>>> lay = scene_layout(s)
>>> round(lay.tips["idler"], 3), [round(m.spec.tip_diameter1 or m.spec.tip_diameter2, 3) for m in lay.meshes]
(65.864, [33.864, 65.864])
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace
from functools import lru_cache

from gearkit.errors import SpecError
from gearkit.pair import PairSpec, pair_geometry
from gearkit.scene.phasing import PlanetMesh, assembly_positions
from gearkit.families.involute import ShaperCutter

__all__ = ["MeshLayout", "Layout", "scene_layout", "cutter_teeth", "CLOSE_TOL"]

#: a planet's meshes close when their tight centre distances agree to this (module units; rounded shifts)
CLOSE_TOL = 1e-3
_PLACE_TOL = 1e-6  # axes placed twice must agree to this (module units)
_FILLET_MARGIN = 1e-6  # a tip stops this far (module units) short of the mate's form circle


def cutter_teeth(gear) -> int:
    """Teeth of the shaper that cuts a ring: given, else 20 (at most z - 4)."""
    return gear.cutter_teeth if gear.cutter_teeth is not None else min(20, gear.teeth - 4)


@dataclass(frozen=True)
class MeshLayout:
    """One mesh as a :class:`~gearkit.pair.PairSpec`: ``names`` are the scene gears that are the
    spec's gear 1 (pinion; the non-ring of an internal mesh) and gear 2 (wheel, ring or rack)."""

    mesh: object
    kind: str
    names: tuple
    spec: PairSpec

    @property
    def center_distance(self) -> float:
        return float(self.spec.center_distance)


@dataclass(frozen=True)
class Layout:
    """Everything the formula layout decides (mm, radians).

    ``positions``: axis of every member (planet shafts: of copy 0 at carrier angle 0);
    ``radii``: planet shaft -> distance from its carrier's axis; ``tips``: gear -> d_a;
    ``meshes``: one :class:`MeshLayout` per scene mesh; ``neighbour_clearance``: carrier ->
    smallest gap between the tip circles of neighbouring planets (mm).
    """

    scene: object
    helix: dict
    positions: dict
    radii: dict
    tips: dict
    meshes: tuple
    neighbour_clearance: dict

    def mesh(self, label: str) -> MeshLayout:
        for m in self.meshes:
            if m.mesh.label == label:
                return m
        raise SpecError("mesh", f"no mesh {label!r}")

    def gear_spec(self, name: str):
        """The kernel :class:`~gearkit.families.involute.GearSpec` of gear ``name`` (its one shape)."""
        from gearkit.pair import gear_specs

        for m in self.meshes:
            if name in m.names:
                i = m.names.index(name)
                return gear_specs(m.spec)[i]
        raise SpecError("gears", f"{name} meshes nothing: it has no tip to size")

    def axis(self, member: str, copy: int = 0, carrier_angle: float = 0.0) -> tuple:
        """Axis (x, y) of a member's copy with its carrier turned by ``carrier_angle`` (rad)."""
        scene = self.scene
        carrier = scene.carrier_of(member)
        if carrier is None:
            return self.positions[member]
        cx, cy = self.positions[carrier]
        gear = scene.member_gears(member)[0]
        ang = gear.angles()[copy] + carrier_angle
        r = self.radii[member]
        return (cx + r * math.cos(ang), cy + r * math.sin(ang))


def _oriented(scene, mesh, helix):
    a, b = scene.gear(mesh.first), scene.gear(mesh.second)
    kind = scene.mesh_kind(mesh)
    if kind == "internal" and a.internal or kind == "rack" and a.rack:
        a, b = b, a
    return a, b, kind


def _pair(scene, mesh, helix, center_distance=None, tips=(None, None)) -> tuple:
    p, w, kind = _oriented(scene, mesh, helix)
    tool2 = None
    if kind == "internal":
        tool2 = ShaperCutter(cutter_teeth(w), scene.pressure_angle_deg)
    try:
        spec = PairSpec(p.teeth, None if kind == "rack" else w.teeth, scene.module_of(p), p.shift,
                        0.0 if kind == "rack" else w.shift, kind, scene.pressure_angle_deg, helix[p.name],
                        scene.face_width, None, tool2, scene.addendum, "standard", tips[0], tips[1],
                        center_distance, p.thinning, w.thinning)
    except SpecError as exc:
        field = {"1": p.name, "2": w.name}.get(exc.field[-1:], mesh.label)
        raise SpecError(f"{mesh.label} ({field})", str(exc).split(": ", 1)[-1]) from None
    return (p.name, w.name), kind, spec


@lru_cache(maxsize=4096)
def _tight(spec: PairSpec) -> float:
    return pair_geometry(spec).center_distance


def _radii(scene, helix) -> dict:
    """Planet shaft -> carrier radius (the closing rule of the module notes)."""
    out = {}
    for member in scene.members:
        carrier = scene.carrier_of(member)
        if carrier is None:
            continue
        gears = {g.name for g in scene.member_gears(member)}
        lo, hi, given, names = [], [], [], []
        for mesh in scene.meshes:
            if not {mesh.first, mesh.second} & gears:
                continue
            other = mesh.second if mesh.first in gears else mesh.first
            if scene.gear(other).carrier is not None:
                raise SpecError("meshes", f"{mesh.label}: planets meshing planets are not placed by scenes yet")
            tight = _tight(_pair(scene, mesh, helix)[2])
            (hi if scene.mesh_kind(mesh) == "internal" else lo).append((tight, mesh.label))
            if mesh.center_distance is not None:
                given.append((mesh.center_distance, mesh.label))
        if not lo and not hi:
            raise SpecError(f"{member}", f"planet shaft {member} meshes no central gear: its radius is unknown")
        m = scene.module_of(scene.member_gears(member)[0])
        if given:
            r = given[0][0]
            bad = [lbl for a, lbl in given if abs(a - r) > _PLACE_TOL * m]
            if bad:
                raise SpecError("meshes", f"{given[0][1]} and {', '.join(bad)} give different centre distances for "
                                f"planet shaft {member}")
            out[member] = r
            continue
        a_lo = max(lo) if lo else None
        a_hi = min(hi) if hi else None
        ends = sorted(lo + hi)
        if ends[-1][0] - ends[0][0] > CLOSE_TOL * m:
            (a, first), (b, second) = ends[0], ends[-1]
            raise SpecError("meshes", f"the loop through {first} and {second} does not close: their tight centre "
                            f"distances are {a:.6g} mm and {b:.6g} mm ({b - a:.4g} mm apart, more than "
                            f"{CLOSE_TOL:g} m); shift the gears so both reach one centre distance")
        if a_lo and a_hi:
            out[member] = (a_lo[0] + a_hi[0]) / 2
        else:
            out[member] = (a_lo or a_hi)[0]
    return out


def _mesh_distance(scene, mesh, helix, radii) -> float:
    for name in (mesh.first, mesh.second):
        g = scene.gear(name)
        if g.carrier is not None:
            return radii[g.member]
    if mesh.center_distance is not None:
        return float(mesh.center_distance)
    return _tight(_pair(scene, mesh, helix)[2])


def _fillet_cut(g, i: int) -> float:
    """How far (mm, radially) gear ``i``'s tip must draw back so it ends on the mate's involute,
    not in its fillet: the path of contact may reach the mate's form circle and no further."""
    if g.kind == "rack":
        return 0.0
    gear = g.gears[i]
    ra, rb = gear.tip_diameter / 2, gear.base_diameter / 2
    margin = _FILLET_MARGIN * g.module
    if i == 0:
        roll = g.path["F2"]
        if not math.isfinite(roll) or roll <= 0:
            return 0.0
        return ra - math.hypot(rb, roll - margin)
    if g.kind == "external":
        return ra - math.hypot(rb, g.line_of_action - g.path["F1"] - margin)
    return math.hypot(rb, g.path["F1"] + g.line_of_action + margin) - ra


def _tips(scene, helix, distances) -> dict:
    """Gear -> tip diameter: the standard tip cut by the largest clearance any mesh asks."""
    cut = {}
    standard = {}
    for mesh in scene.meshes:
        names, kind, spec = _pair(scene, mesh, helix, distances[mesh.label])
        g = pair_geometry(spec)
        for i, name in enumerate(names[: len(g.gears)]):
            need = max(scene.clearance * spec.module - g.tip_clearance[i], _fillet_cut(g, i), 0.0)
            standard[name] = g.gears[i].tip_diameter
            cut[name] = max(cut.get(name, 0.0), need)
    return {n: standard[n] + (2 * cut[n] if scene.gear(n).internal else -2 * cut[n]) for n in standard}


def _union(groups: dict, a: str, b: str) -> None:
    ra, rb = groups[a], groups[b]
    if ra != rb:
        for k, v in groups.items():
            if v == rb:
                groups[k] = ra


def _positions(scene, distances) -> dict:
    groups = {m: m for m in scene.members}
    for mesh in scene.meshes:  # a carrier shares the axis of the central gears its planets mesh
        a, b = scene.gear(mesh.first), scene.gear(mesh.second)
        for p, c in ((a, b), (b, a)):
            if p.carrier is not None and c.carrier is None:
                _union(groups, p.carrier, c.member)
    for group in scene.coaxial:
        for name in group[1:]:
            _union(groups, scene.member_of(group[0]), scene.member_of(name))
    at = {}
    fixed_axis = [m for m in scene.meshes if scene.gear(m.first).carrier is None
                  and scene.gear(m.second).carrier is None]
    for root in [groups[m] for m in scene.members if scene.carrier_of(m) is None]:
        if root in at:
            continue
        at[root] = (0.0, 0.0) if not at else None
        if at[root] is None:  # a second unconnected piece
            raise SpecError("meshes", f"{root} is connected to nothing placed: give it a mesh or a coaxial group")
        stack = [root]
        while stack:
            g = stack.pop()
            for mesh in fixed_axis:
                ga, gb = groups[scene.gear(mesh.first).member], groups[scene.gear(mesh.second).member]
                if ga == gb:
                    raise SpecError("meshes", f"{mesh.first} and {mesh.second} share one axis and cannot mesh")
                if g not in (ga, gb):
                    continue
                a = distances[mesh.label]
                ang = math.radians(mesh.angle_deg)
                sign = 1.0 if g == ga else -1.0
                other = gb if g == ga else ga
                pos = (at[g][0] + sign * a * math.cos(ang), at[g][1] + sign * a * math.sin(ang))
                if other in at:
                    d = math.dist(pos, at[other])
                    m = scene.module_of(scene.gear(mesh.first))
                    if d > _PLACE_TOL * m:
                        raise SpecError("meshes", f"the loop through {mesh.label} does not close: it puts the axis "
                                        f"of {other} {d:.6g} mm away from where the other meshes put it")
                else:
                    at[other] = pos
                    stack.append(other)
    return {m: at[groups[m]] for m in scene.members if groups[m] in at}


def _check_planets(scene, radii, tips, positions) -> dict:
    """Assembly of every planet shaft's angles, and the tip clearance between neighbours."""
    out = {}
    for carrier in scene.carriers:
        shafts = [m for m in scene.members if scene.carrier_of(m) == carrier]
        circles = []
        for member in shafts:
            gears = scene.member_gears(member)
            meshes = []
            for mesh in scene.meshes:
                for g in gears:
                    if g.name in (mesh.first, mesh.second):
                        other = scene.gear(mesh.second if g.name == mesh.first else mesh.first)
                        meshes.append(PlanetMesh(other.teeth, g.teeth, other.internal))
            positions_per_turn = assembly_positions(meshes)
            angles = gears[0].angles()
            if positions_per_turn:
                for k, ang in enumerate(angles[1:], start=1):
                    steps = (ang - angles[0]) / (2 * math.pi) * positions_per_turn
                    if abs(steps - round(steps)) > 1e-7:
                        step = 360.0 / positions_per_turn
                        raise SpecError(f"{member}.angles_deg", f"planet {k + 1} of {member} at "
                                        f"{math.degrees(ang):.6g} deg cannot be assembled: identical planets fit "
                                        f"only every {step:.6g} deg from the first ({len(angles)} equally spaced "
                                        f"planets need (z_sun + z_ring)/K integer, or unequal angles)")
            r_tip = max(tips[g.name] for g in gears) / 2
            for k in range(len(angles)):
                circles.append((member, k, r_tip))
        worst = math.inf
        lay = Layout(scene, {}, positions, radii, tips, (), {})
        for i in range(len(circles)):
            for j in range(i + 1, len(circles)):
                (ma, ka, ra), (mb, kb, rb) = circles[i], circles[j]
                gap = math.dist(lay.axis(ma, ka), lay.axis(mb, kb)) - ra - rb
                if gap < 0:
                    raise SpecError("planets", f"the tips of planet {ma}#{ka + 1} and {mb}#{kb + 1} overlap by "
                                    f"{-gap:.4g} mm: fewer planets, other angles or smaller planets")
                worst = min(worst, gap)
        out[carrier] = worst
    return out


@lru_cache(maxsize=256)
def scene_layout(scene) -> "Layout":
    """The formula layout of ``scene`` (see the module notes; cached per scene); raises SpecError
    for scenes that cannot exist, naming the gears."""
    helix = scene.helix_angles()
    radii = _radii(scene, helix)
    distances = {m.label: _mesh_distance(scene, m, helix, radii) for m in scene.meshes}
    tips = _tips(scene, helix, distances)
    meshes = []
    for mesh in scene.meshes:
        names, kind, spec = _pair(scene, mesh, helix, distances[mesh.label])
        spec = replace(spec, tip_diameter1=tips[names[0]], tip_diameter2=None if kind == "rack" else tips[names[1]])
        meshes.append(MeshLayout(mesh, kind, names, spec))
    positions = _positions(scene, distances)
    clearance = _check_planets(scene, radii, tips, positions)
    return Layout(scene, helix, positions, radii, tips, tuple(meshes), clearance)

