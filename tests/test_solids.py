"""Gear solids: volume against the exact profile area (Cavalieri), deviation from the exact surface,
validity, bores, keyways, rings, racks and bad input."""
import math

import numpy as np
import pytest

from gearkit.distances import distances_to_polyline
from gearkit.errors import GeometryError, SpecError
from gearkit.families.involute import GearSpec, tooth_profile
from gearkit.families.involute.rack import RackSpec, rack_profile
from gearkit.solids import SolidSpec, gear_solid, rack_solid
from gearkit.solids.solid import Solid
from gearkit.families.involute import ShaperCutter

M = 1.0  # module, mm
B = 6.0  # face width, mm
TOL = 5e-3 * M  # mesh tolerance under test, mm
REF = TOL / 200  # chord tolerance of the dense reference outline, mm
TEETH = (8, 20, 97)
HELIX = (0.0, 15.0, 30.0, 45.0)


def shoelace(p):
    x, y = p[:, 0], p[:, 1]
    return 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)))


def perimeter(p):
    return float(np.linalg.norm(p - np.roll(p, -1, axis=0), axis=1).sum())


def twist_rate(prof, beta_deg):
    return math.tan(math.radians(beta_deg)) / (prof.reference_diameter / 2)


def turn(z, k, width, herringbone):
    """theta(z) of the exact surface: z tan(beta)/r, mirrored about the mid plane for a herringbone."""
    return k * (width / 2 - np.abs(z - width / 2)) if herringbone else k * z


def flank_deviation(solid, prof, k, width, herringbone=False):
    """Largest transverse distance of vertices, edge midpoints and centroids of the side facets from
    the exact transverse profile turned to their height (an upper bound of the 3D distance)."""
    v, f = solid.arrays()
    f = f[np.ptp(v[f][:, :, 2], axis=1) > 1e-9]  # side facets (the end faces are planar)
    pts = sample_points(v, f)
    th = -turn(pts[:, 2], k, width, herringbone)
    c, s = np.cos(th), np.sin(th)
    q = np.stack([c * pts[:, 0] - s * pts[:, 1], s * pts[:, 0] + c * pts[:, 1]], 1)
    return float(distances_to_polyline(to_tooth0(q, prof.teeth), three_teeth(prof)).max())


def sample_points(v, f):
    """The facets' vertices, edge midpoints and centroids, each once."""
    edges = np.unique(np.sort(np.concatenate([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]]), axis=1), axis=0)
    return np.concatenate([v[np.unique(f)], 0.5 * (v[edges[:, 0]] + v[edges[:, 1]]), v[f].mean(axis=1)])


def to_tooth0(q, z):
    """Turn each point by whole pitches onto tooth 0 (centred on +y): the exact profile's symmetry."""
    pitch = 2 * math.pi / z
    k = np.round((np.arctan2(q[:, 1], q[:, 0]) - math.pi / 2) / pitch)
    c, s = np.cos(-k * pitch), np.sin(-k * pitch)
    return np.stack([c * q[:, 0] - s * q[:, 1], s * q[:, 0] + c * q[:, 1]], 1)


def three_teeth(prof):
    """Dense exact polyline of tooth 0 and its neighbours (chords within REF)."""
    tooth = prof.tooth_points(REF)
    pitch = 2 * math.pi / prof.teeth
    parts = []
    for k in (-1, 0, 1):
        c, s = math.cos(k * pitch), math.sin(k * pitch)
        parts.append(tooth @ np.array([[c, s], [-s, c]]))
    return np.concatenate(parts)


def gears():
    for z in TEETH:
        for beta in HELIX:
            yield z, beta, False
            if beta:
                yield z, beta, True


@pytest.fixture(scope="module")
def built():
    out = {}
    for z, beta, herring in gears():
        prof = tooth_profile(GearSpec(z, M, helix_angle_deg=beta))
        out[z, beta, herring] = prof, gear_solid(prof, SolidSpec(B, herringbone=herring), TOL)
    return out


@pytest.mark.parametrize("z,beta,herring", list(gears()))
def test_volume_is_profile_area_times_width(built, z, beta, herring):
    prof, solid = built[z, beta, herring]
    exact = prof.outline(REF)
    area, per = shoelace(exact), perimeter(exact)
    r_tip = prof.tip_diameter / 2
    # every facet lies within tol of the exact surface (lateral area <= per * b * sqrt(1 + (k r_a)^2))
    bound = TOL * per * B * math.hypot(1.0, twist_rate(prof, beta) * r_tip) + REF * per * B
    assert abs(solid.volume - area * B) <= bound
    (x0, y0, z0), (x1, y1, z1) = solid.bounds
    assert (z0, z1) == (0.0, B)
    assert max(x1, y1, -x0, -y0) <= r_tip + 1e-9


@pytest.mark.parametrize("z,beta,herring", list(gears()))
def test_every_vertex_and_facet_is_within_tol_of_the_exact_surface(built, z, beta, herring):
    prof, solid = built[z, beta, herring]
    measured = flank_deviation(solid, prof, twist_rate(prof, beta), B, herring)
    assert measured <= TOL + REF
    assert solid.achieved <= TOL
    assert measured <= solid.achieved * 1.01 + REF  # the reported deviation is the measured one


def test_a_wrong_twist_is_caught_by_the_deviation_check(built):
    prof, solid = built[20, 15.0, False]
    assert flank_deviation(solid, prof, 1.01 * twist_rate(prof, 15.0), B) > 2 * TOL


def test_layers_follow_tol_not_a_constant():
    prof = tooth_profile(GearSpec(20, 2.0, helix_angle_deg=20.0))
    coarse, fine = (gear_solid(prof, SolidSpec(10.0), t) for t in (1e-2, 1e-3))
    assert fine.info["layers"] > coarse.info["layers"] >= 2
    # the helix chord alone needs r_a dtheta^2 / 8 <= tol
    twist = 10.0 * math.tan(math.radians(20.0)) / (prof.reference_diameter / 2)
    for s, t in ((coarse, 1e-2), (fine, 1e-3)):
        assert s.info["layers"] >= twist / math.sqrt(8 * t / (prof.tip_diameter / 2))
    spur = gear_solid(tooth_profile(GearSpec(20, 2.0)), SolidSpec(10.0), 1e-3)
    assert spur.info["layers"] == 1


def test_meshes_are_closed_oriented_and_free_of_degenerate_facets(built):
    for key in ((8, 45.0, True), (97, 30.0, False)):
        solid = built[key][1]
        v, f = solid.arrays()
        edges = np.sort(np.concatenate([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]]), axis=1)
        _, counts = np.unique(edges, axis=0, return_counts=True)
        assert (counts == 2).all()  # every edge shared by exactly two facets
        directed = np.concatenate([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]])
        assert len(np.unique(directed, axis=0)) == len(directed)  # consistent winding
        tri = v[f].astype(np.float32).astype(float)
        assert (np.linalg.norm(np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]), axis=1) > 0).all()
        assert solid.volume > 0


def test_bore_and_keyway_remove_exactly_their_area():
    prof = tooth_profile(GearSpec(24, 2.0))
    plain = gear_solid(prof, SolidSpec(8.0), 1e-3)
    bored = gear_solid(prof, SolidSpec(8.0, bore=10.0, keyway=(3.0, 1.4)), 1e-3)
    r, w, t = 5.0, 3.0, 1.4
    ys = math.sqrt(r * r - w * w / 4)
    cap = r * r * math.acos(ys / r) - ys * math.sqrt(r * r - ys * ys)  # circle above the keyway's chord
    removed = math.pi * r * r + w * (r + t - ys) - cap
    assert (plain.volume - bored.volume) / 8.0 == pytest.approx(removed, abs=1e-3 * 2 * math.pi * r)
    v, _ = bored.arrays()
    rho = np.hypot(v[:, 0], v[:, 1])
    inner = rho < 6.5
    on_circle = np.isclose(rho[inner], r, atol=1e-9)
    in_slot = np.isclose(np.abs(v[inner, 0]), w / 2, atol=1e-9)
    assert (on_circle | in_slot).all()


def test_herringbone_gap_is_grooved_and_symmetric():
    prof = tooth_profile(GearSpec(30, 1.5, helix_angle_deg=25.0))
    full = gear_solid(prof, SolidSpec(20.0, herringbone=True), 5e-3)
    gapped = gear_solid(prof, SolidSpec(20.0, herringbone=True, gap=4.0, bore=8.0), 5e-3)
    area = shoelace(prof.outline(1e-5))
    r_groove = prof.root_diameter / 2 - 1.5
    expected = area * 16.0 + math.pi * r_groove ** 2 * 4.0 - math.pi * 16.0 * 20.0
    assert gapped.volume == pytest.approx(expected, rel=2e-4)
    assert full.volume == pytest.approx(area * 20.0, rel=2e-4)
    v, _ = gapped.arrays()
    mid = (v[:, 2] > 8.0 + 1e-9) & (v[:, 2] < 12.0 - 1e-9)
    assert not mid.any()  # nothing between the groove's end faces but its walls' end rings


def test_ring_gear_is_an_annulus_with_the_teeth_inside():
    prof = tooth_profile(GearSpec(50, 1.0, internal=True, tool=ShaperCutter(20)))
    for kw, r_out in ((dict(outer_diameter=60.0), 30.0), (dict(rim=3.0), prof.root_diameter / 2 + 3.0)):
        ring = gear_solid(prof, SolidSpec(6.0, helix_angle_deg=None, **kw), 5e-3)
        hole = shoelace(prof.outline(1e-5))
        expected = (math.pi * r_out ** 2 - hole) * 6.0
        assert ring.volume == pytest.approx(expected, abs=5e-3 * (2 * math.pi * r_out + perimeter(prof.outline(1e-3))) * 6)
        assert ring.bounds[1][0] == pytest.approx(r_out, abs=1e-9)
    helical = tooth_profile(GearSpec(50, 1.0, helix_angle_deg=-20.0, internal=True, tool=ShaperCutter(20)))
    ring = gear_solid(helical, SolidSpec(8.0, rim=2.0), 5e-3)
    assert flank_deviation_ring(ring, helical, twist_rate(helical, -20.0), 8.0) <= 5e-3 + REF


def flank_deviation_ring(solid, prof, k, width):
    v, f = solid.arrays()
    tri = v[f]
    r_max = prof.root_diameter / 2 + 1e-6
    keep = (np.ptp(tri[:, :, 2], axis=1) > 1e-9) & (np.hypot(tri[..., 0], tri[..., 1]) < r_max).all(axis=1)
    pts = sample_points(v, f[keep])
    th = -k * pts[:, 2]
    c, s = np.cos(th), np.sin(th)
    q = np.stack([c * pts[:, 0] - s * pts[:, 1], s * pts[:, 0] + c * pts[:, 1]], 1)
    return float(distances_to_polyline(to_tooth0(q, prof.teeth), three_teeth(prof)).max())


@pytest.mark.parametrize("beta", [0.0, 20.0, -35.0])
def test_rack_bar_volume_is_whole_pitches_of_the_exact_profile(beta):
    prof = rack_profile(RackSpec(2.0, helix_angle_deg=beta))
    p, n_pitch, height, width = prof.pitch, 7, 9.0, 12.0
    bar = rack_solid(prof, n_pitch * p, height, width, 5e-3, start=-p / 2)  # cut at space centres
    tooth = prof.tooth_points(1e-5)
    back = prof.tip_height - height
    one = np.concatenate([tooth, [[tooth[-1, 0], back], [tooth[0, 0], back]]])
    area = -shoelace(one)  # the tooth row runs left to right over the bar: clockwise
    bound = 5e-3 * perimeter(one) * width
    assert bar.volume == pytest.approx(n_pitch * area * width, abs=n_pitch * bound)
    (x0, y0, z0), (x1, y1, z1) = bar.bounds
    assert (x0, x1) == pytest.approx((-p / 2, (n_pitch - 0.5) * p), abs=1e-9)
    assert (y0, y1, z0, z1) == pytest.approx((back, prof.tip_height, 0.0, width), abs=1e-9)
    assert bar.achieved <= 5e-3


def densify(poly, step):
    """The same polyline with extra vertices on long edges (the distance helper searches near vertices)."""
    out = [poly[:1]]
    for a, b in zip(poly[:-1], poly[1:]):
        n = max(1, math.ceil(np.linalg.norm(b - a) / step))
        out.append(a + (b - a) * (np.arange(1, n + 1) / n)[:, None])
    return np.concatenate(out)


def test_helical_rack_facets_lie_on_the_sheared_exact_profile():
    prof = rack_profile(RackSpec(2.0, helix_angle_deg=25.0))
    bar = rack_solid(prof, 30.0, 8.0, 10.0, 5e-3)
    v, f = bar.arrays()
    tri = v[f]
    planar = np.ptp(tri[:, :, 2], axis=1) < 1e-9  # the end faces z = 0 and z = b
    for axis, value in ((0, 0.0), (0, 30.0), (1, prof.tip_height - 8.0)):  # the bar's ends and its back
        planar |= np.isclose(tri[:, :, axis], value, atol=1e-9).all(axis=1)
    grid = np.array([(i, j, 4 - i - j) for i in range(5) for j in range(5 - i)]) / 4.0  # 15 points a facet
    pts = np.einsum("gk,fkd->fgd", grid, tri[~planar]).reshape(-1, 3)
    x = pts[:, 0] - pts[:, 2] * math.tan(math.radians(25.0))  # undo the shear
    row = densify(prof.outline(REF, teeth=12) - (4 * prof.pitch, 0.0), 0.02)
    d = distances_to_polyline(np.column_stack([x, pts[:, 1]]), row)
    assert len(pts) > 1000 and d.max() <= 5e-3 + REF


def test_an_invalid_mesh_raises_and_is_never_built():
    import manifold3d as m3

    cube = m3.Manifold.cube((1.0, 1.0, 1.0)).to_mesh64()
    v, f = np.asarray(cube.vert_properties)[:, :3], np.asarray(cube.tri_verts)
    with pytest.raises(GeometryError, match="not a valid solid"):
        Solid.from_arrays(v, f[1:], "open", {})
    with pytest.raises(GeometryError, match="inside out"):
        Solid.from_arrays(v, f[:, ::-1], "inverted", {})
    with pytest.raises(GeometryError):
        Solid.from_arrays(v, f[:0], "empty", {})


@pytest.mark.parametrize("spec,field", [
    (dict(width=0.0), "width"),
    (dict(width=5.0, gap=1.0), "gap"),
    (dict(width=5.0, herringbone=True, gap=5.0), "gap"),
    (dict(width=5.0, keyway=(2.0, 1.0)), "keyway"),
    (dict(width=5.0, bore=4.0, keyway=(5.0, 1.0)), "keyway"),
    (dict(width=5.0, outer_diameter=80.0, rim=2.0), "rim"),
    (dict(width=5.0, helix_angle_deg=85.0), "helix_angle_deg"),
])
def test_bad_solid_specs_name_the_field(spec, field):
    with pytest.raises(SpecError) as err:
        SolidSpec(**spec)
    assert err.value.field == field


def test_impossible_bodies_raise_spec_errors():
    prof = tooth_profile(GearSpec(20, 2.0, helix_angle_deg=10.0))
    with pytest.raises(SpecError, match="bore"):
        gear_solid(prof, SolidSpec(5.0, bore=40.0), 1e-2)
    with pytest.raises(SpecError, match="helix_angle_deg"):
        gear_solid(prof, SolidSpec(5.0, helix_angle_deg=20.0), 1e-2)
    with pytest.raises(SpecError, match="outer_diameter"):
        gear_solid(prof, SolidSpec(5.0, outer_diameter=80.0), 1e-2)
    ring = tooth_profile(GearSpec(40, 1.0, internal=True, tool=ShaperCutter(20)))
    with pytest.raises(SpecError, match="outer_diameter"):
        gear_solid(ring, SolidSpec(5.0, outer_diameter=30.0), 1e-2)
    with pytest.raises(SpecError, match="tol"):
        gear_solid(prof, SolidSpec(5.0), -1.0)
    with pytest.raises(SpecError, match="height"):
        rack_solid(rack_profile(RackSpec(2.0)), 20.0, 3.0, 5.0)


@pytest.mark.parametrize("beta, herring", [(0.0, False), (15.0, False), (20.0, True)])
def test_a_solid_built_from_its_plan_is_the_one_planned_and_counted_from_it(beta, herring):
    """``gear_plan`` once, then ``estimate_faces(plan=)`` and ``gear_solid(plan=)`` (the command's way: the
    tooth sampled once) build the very mesh ``gear_solid`` plans itself, and the count from the plan is
    the side facets exactly (two a quad of the polyline over every layer) plus about the caps."""
    from gearkit.solids.gear import estimate_faces, gear_plan

    prof = tooth_profile(GearSpec(20, M, helix_angle_deg=beta))
    spec = SolidSpec(B, herringbone=herring)
    plan = gear_plan(prof, spec, TOL)
    own, planned = gear_solid(prof, spec, TOL), gear_solid(prof, spec, TOL, plan=plan)
    for a, b in zip(own.arrays(), planned.arrays()):
        np.testing.assert_array_equal(a, b)
    v, f = planned.arrays()
    side = int((np.ptp(v[f][:, :, 2], axis=1) > 1e-9).sum())  # the end faces are planar
    assert side == 2 * plan.polyline.edges * prof.teeth * planned.info["layers"] * (2 if herring else 1)
    assert abs(estimate_faces(prof, spec, TOL, plan=plan) - planned.faces) / planned.faces < 0.05
