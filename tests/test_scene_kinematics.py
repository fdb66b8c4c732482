"""Scene kinematics: the Willis relations as one linear system, against the textbook digest's worked
examples (seed_textbook_other_gears_trains.md §4, §6, §7) and closed-form ratios."""
from fractions import Fraction
from pathlib import Path

import pytest

from gearkit.errors import SpecError
from gearkit.scene import Gear, Mesh, Motion, Relation, Scene, Train, scene_speeds
from gearkit.scene.files import load_scene, scene_from_text

ISSUE_SCENE = (Path(__file__).resolve().parent.parent / "examples" / "planetary.toml").read_text(encoding="utf-8")


def simple_set(z_sun, z_planet, z_ring, fixed="ring", inputs=None, **kw):
    return Scene((Gear("sun", z_sun), Gear("planet", z_planet, count=3, carrier="carrier"),
                  Gear("ring", z_ring, internal=True)), (Mesh("sun", "planet"), Mesh("planet", "ring")),
                 motion=Motion(fixed=(fixed,) if fixed else (), inputs=inputs or {"sun": 1}, output="carrier"), **kw)


def test_issue_scene_loads_as_written_and_gives_its_ratio(tmp_path):
    path = tmp_path / "planetary.toml"
    path.write_text(ISSUE_SCENE)
    scene = load_scene(path)
    s = scene_speeds(scene)
    assert s.dof == 1
    assert s.ratio("sun", "carrier") == 1 + Fraction(108, 21)
    # Willis: the planet relative to the carrier, w_p - w_c = -(z_s/z_p)(w_s - w_c)
    assert s.relative("planet") == -Fraction(21, 43) * (1 - s.speed("carrier"))
    # a fixed ring meets every tooth of the carrier's planets: f = z_ring w_c = z_sun (w_s - w_c)
    f = s.mesh_frequencies()
    assert f["sun-planet"] == f["planet-ring"] == 108 * s.speed("carrier")


def test_example_1_sun_planet_ring():
    """Ex.1 (L16019): z1 = 20, fixed ring z3 = 100: i_1B = 1 + z3/z1 = 6."""
    assert scene_speeds(simple_set(20, 40, 100)).ratio("sun", "carrier") == 6


def test_example_2_fixed_axis_stage_into_a_planetary():
    """Ex.2 (L16481): i12 = -4, fixed ring 140, planet block 32/27, output ring 135:
    i_63^(B) = 7/8, i_6B = 1/8, i16 = -32, w6 = -1 rad/s at w1 = 32 rad/s."""
    gears = (Gear("g1", 20), Gear("g2", 80, shaft="carrier"), Gear("ring3", 140, internal=True),
             Gear("p4", 32, shaft="block", carrier="carrier", count=3),
             Gear("p5", 27, shaft="block", carrier="carrier", count=3), Gear("ring6", 135, internal=True))
    meshes = (Mesh("g1", "g2"), Mesh("p4", "ring3"), Mesh("p5", "ring6"))
    scene = Scene(gears, meshes, motion=Motion(fixed=("ring3",), inputs={"g1": 32}, output="ring6"))
    s = scene_speeds(scene)
    assert s.speed("ring6") == -1
    assert s.ratio("g1", "ring6") == -32
    assert s.ratio("ring6", "carrier") == Fraction(1, 8)
    assert s.dof == 1


def bevel_helicopter() -> Train:
    """Ex.3 (L17052) rebuilt as in the digest: bevel 1 and 3 on either side of planet 2, whose
    second gear 2' meshes the fixed bevel 4; carrier B. i14^(B) = -2, i34^(B) = +2."""
    return Train(("b1", "b3", "planet", "b4", "B"), (
        Relation("b1", "planet", 25, 25, 1, "B"), Relation("b3", "planet", 25, 25, -1, "B"),
        Relation("planet", "b4", 25, 50, -1, "B")))


def test_example_3_bevel_planetary_reduced_ratios_and_outputs():
    t = bevel_helicopter()
    held_b = t.solve(fixed=("B",), inputs={"b1": 1})
    assert held_b.ratio("b1", "b4") == -2 and held_b.ratio("b3", "b4") == 2
    s = t.solve(fixed=("b4",), inputs={"b1": 1})
    assert s.ratio("b1", "B") == 3  # i_1B^(4) = 1 + 25*50/(25*25)
    assert s.ratio("b1", "b3") == -3  # 3 and B counter-rotate at a third of the input
    assert s.ratio("b3", "B") == -1


def test_differential_two_inputs():
    """(3.221): w_B = (z1 w1 + z3 w3)/(z1 + z3); two degrees of freedom."""
    scene = simple_set(30, 24, 78, fixed=None, inputs={"sun": 7, "ring": -2})
    s = scene_speeds(scene)
    assert s.dof == 2
    assert s.speed("carrier") == Fraction(30 * 7 + 78 * -2, 30 + 78)
    one_input = scene_speeds(scene, inputs={"sun": 1})
    with pytest.raises(SpecError, match="not determined"):
        one_input.speed("carrier")


def test_bevel_car_differential_averages():
    """(3.227-3.228) z1 = z3: w_B = (w1 + w3)/2; braking B gives w1 = -w3."""
    t = Train(("left", "right", "spider", "B"), (Relation("left", "spider", 16, 10, 1, "B"),
                                               Relation("right", "spider", 16, 10, -1, "B")))
    s = t.solve(inputs={"left": 5, "right": 1})
    assert t.dof() == 2 and s.speed("B") == 3
    assert t.solve(fixed=("B",), inputs={"left": 1}).speed("right") == -1


def test_cardan_and_parallel_motion():
    """Cardan (L16436): z_ring = 2 z_planet gives a planet turning at -w_B. Parallel motion
    (L16461): fixed wheel 1 and planet 3 with z3 = z1 through an idler: planet 3 only translates."""
    cardan = Scene((Gear("planet", 20, carrier="arm"), Gear("ring", 40, internal=True)),
                   (Mesh("planet", "ring"),), motion=Motion(fixed=("ring",), inputs={"arm": 1}))
    assert scene_speeds(cardan).speed("planet") == -1
    parallel = Scene((Gear("w1", 30), Gear("idler", 17, carrier="arm"), Gear("w3", 30, carrier="arm")),
                     (Mesh("w1", "idler"), Mesh("idler", "w3")), motion=Motion(fixed=("w1",), inputs={"arm": 1}))
    s = scene_speeds(parallel)
    assert s.speed("w3") == 0 and s.relative("w3") == -1


def four_speed_box(k: int) -> Scene:
    """Seed 003's box (digest §6.2): suns 1, 3, 5, ring 4, carrier H, planet block 2 | 2' | 2''."""
    z = {"s1": 15 * k, "p2": 5 * k, "p2b": 2 * k, "p2c": 10 * k, "s3": 18 * k, "ring4": 30 * k, "s5": 10 * k}
    blk = {"shaft": "block", "carrier": "H", "count": 4}
    gears = (Gear("s1", z["s1"]), Gear("s3", z["s3"]), Gear("s5", z["s5"]), Gear("ring4", z["ring4"], internal=True),
             Gear("p2", z["p2"], **blk), Gear("p2b", z["p2b"], **blk), Gear("p2c", z["p2c"], **blk))
    meshes = (Mesh("s1", "p2"), Mesh("s3", "p2b"), Mesh("s5", "p2c"), Mesh("p2c", "ring4"))
    states = (("first", Motion(fixed=("s3",))), ("second", Motion(fixed=("H",))), ("third", Motion(fixed=("ring4",))),
              ("fourth", Motion(locked=(("s1", "H"),))))
    return Scene(gears, meshes, module=2.0, motion=Motion(inputs={"s1": 1}, output="s5"), states=states)


@pytest.mark.parametrize("k", [4, 8])
def test_seed_003_four_speed_box(k):
    """S3 L11-57: w5/w1 = 4, 3, 2, 1 braking 3, H, 4 and locking 1 to H, for the handbook's
    z1 = 60 set (k = 4) and the doubled one (k = 8)."""
    box = four_speed_box(k)
    assert scene_speeds(box, inputs={"s1": 1}).dof == 2  # a differential until a brake holds a member
    for state, expected in (("first", 4), ("second", 3), ("third", 2), ("fourth", 1)):
        s = scene_speeds(box, state)
        assert s.dof == 1
        assert s.ratio("s5", "s1") == expected
    # the Kutzbach form w5/w1 = z1 (z5 - z_X) / (z5 (z1 - z_X)), z_X = z3, z1 + z2, z4
    z1, z5 = 15 * k, 10 * k
    for state, z_x in (("first", 18 * k), ("second", 20 * k), ("third", 30 * k)):
        assert scene_speeds(box, state).ratio("s5", "s1") == Fraction(z1 * (z5 - z_x), z5 * (z1 - z_x))


def test_compound_scheme_a_large_ratio_remark():
    """L16240: z1 = z3 = 100, z2 = 99, z4 = 101 (scheme a): i_B1 = 10000."""
    gears = (Gear("g1", 100), Gear("g2", 99, shaft="blk", carrier="B"), Gear("g3", 100, shaft="blk", carrier="B"),
             Gear("g4", 101))
    scene = Scene(gears, (Mesh("g1", "g2"), Mesh("g3", "g4")), motion=Motion(fixed=("g4",), inputs={"B": 1}))
    assert scene_speeds(scene).ratio("B", "g1") == 10000


def test_fixed_axis_trains_sign_and_idler():
    """(3.205): an idler changes only the sign; (3.209) compound trains multiply stage ratios."""
    idler = Scene((Gear("a", 15), Gear("idler", 30, 0.5), Gear("b", 40)), (Mesh("a", "idler"), Mesh("idler", "b")),
                  module=2.0, motion=Motion(inputs={"a": 1}, output="b"))
    assert scene_speeds(idler).ratio("a", "b") == Fraction(40, 15)
    ex5 = Scene((Gear("z1", 18, module=3.5), Gear("z2", 72, module=3.5, shaft="mid"), Gear("z3", 35, module=4.5,
                 shaft="mid"), Gear("z4", 105, module=4.5, internal=True)), (Mesh("z1", "z2"), Mesh("z3", "z4")),
                motion=Motion(inputs={"z1": 1}, output="z4"))
    assert scene_speeds(ex5).ratio("z1", "z4") == -12  # ext + int: one external mesh


def test_scene_file_states_and_two_inputs():
    text = ISSUE_SCENE.replace('input  = "sun"', 'input  = { sun = 3.0 }') + (
        '[states.free]\nfixed = []\n[states.direct]\nlocked = ["sun", "carrier"]\n')
    scene = scene_from_text(text)
    assert scene_speeds(scene).speed("carrier") == 3 * Fraction(7, 43)
    assert scene_speeds(scene, "direct").speed("ring") == 3
    assert scene_speeds(scene, "free").dof == 2


@pytest.mark.parametrize("text, match", [
    (ISSUE_SCENE.replace("count = 3", "count = 3, colour = 1"), "colour"),
    (ISSUE_SCENE.replace('["planet", "ring"]', '["planet", "moon"]'), "moon"),
    (ISSUE_SCENE.replace('fixed  = ["ring"]', 'fixed  = ["sun"]'), "both fixed and driven"),
    (ISSUE_SCENE.replace("teeth = 108", "teeth = 40"), "needs more teeth"),
    (ISSUE_SCENE.replace("shift = 0.438 }", "shift = 0.438, module = 2 }"), "sun .* and planet .* modules differ"),
    (ISSUE_SCENE.replace("shift = 0.438 }", "shift = 0.438, helix_angle_deg = 12 }").replace(
        "count = 3,", "count = 3, helix_angle_deg = 12,"), "sun .* planet .* helix rule"),
    ("[gears\n", "not valid TOML"),
])
def test_impossible_scenes_name_the_gears(text, match):
    with pytest.raises(SpecError, match=match):
        scene_from_text(text)


def test_ratio_between_unconnected_members_names_them():
    scene = Scene((Gear("a", 20), Gear("b", 30), Gear("c", 20), Gear("d", 40)), (Mesh("a", "b"), Mesh("c", "d")),
                  motion=Motion(inputs={"a": 1}))
    s = scene_speeds(scene)
    assert s.ratio("a", "b") == Fraction(-3, 2)
    with pytest.raises(SpecError, match="a and d are not connected"):
        s.ratio("a", "d")


def test_contradicting_inputs_raise():
    with pytest.raises(SpecError, match="contradict"):
        scene_speeds(simple_set(20, 40, 100), inputs={"sun": 1, "carrier": 1})
