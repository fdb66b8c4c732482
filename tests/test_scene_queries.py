"""Scenes as geometry: one spec per gear, the issue's planetary set, lazy queries at each fidelity
(what was built), placement and export, and the two commands."""
import json
import math
from fractions import Fraction
from pathlib import Path

import pytest

from gearkit.cli import main
from gearkit.errors import SpecError
from gearkit.pair import PairSpec, pair_geometry
from gearkit.scene import Gear, Mesh, Motion, Scene, load_scene, scene_layout
from gearkit.scene.query import SceneModel

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
PLANETARY = EXAMPLES / "planetary.toml"
#: the issue's a_w = 56.8 mm holds to 1e-4 mm (the shifts are rounded to three figures)
A_W_TOL = 1e-4


def idler_scene():
    return Scene((Gear("a", 15), Gear("idler", 30, 0.5), Gear("b", 40)), (Mesh("a", "idler"), Mesh("idler", "b")),
                 module=2.0, motion=Motion(inputs={"a": 1}, output="b"))


def test_idler_has_one_tip_wherever_it_meshes():
    """The issue's idler: per pair, the shortened tips are 65.864 mm (with z = 15) and 65.906 mm (with
    z = 40); as one gear it takes the smaller in both meshes, keeping >= 0.25 m clearance at both."""
    per_pair = [pair_geometry(PairSpec(15, 30, 2.0, 0.0, 0.5)).gears[1].tip_diameter,
                pair_geometry(PairSpec(30, 40, 2.0, 0.5, 0.0)).gears[0].tip_diameter]
    assert per_pair == pytest.approx([65.864, 65.906], abs=5e-4)
    lay = scene_layout(idler_scene())
    assert lay.tips["idler"] == pytest.approx(min(per_pair), abs=1e-12)
    tips = [m.spec.tip_diameter2 if m.names[1] == "idler" else m.spec.tip_diameter1 for m in lay.meshes]
    assert tips == [lay.tips["idler"]] * 2
    for m in lay.meshes:
        assert min(pair_geometry(m.spec).tip_clearance) >= 0.25 * 2.0 - 1e-12


def test_issue_planetary_set_meshes_tips_and_clearances():
    scene = load_scene(PLANETARY)
    lay = scene_layout(scene)
    assert [m.center_distance for m in lay.meshes] == pytest.approx([56.8, 56.8], abs=A_W_TOL)
    geos = [pair_geometry(m.spec) for m in lay.meshes]
    # the sun and the planet have one tip diameter in every mesh they are in
    sun_planet, planet_ring = geos
    assert sun_planet.gears[1].tip_diameter == planet_ring.gears[0].tip_diameter == lay.tips["planet"]
    assert sun_planet.gears[0].tip_diameter == lay.tips["sun"]
    c = 0.25 * 1.75
    # 0.25 m bottom clearance: met exactly where it binds (the sun-planet mesh), kept at the ring
    assert sun_planet.tip_clearance == pytest.approx((c, c), abs=1e-9)
    assert min(planet_ring.tip_clearance) >= c - 1e-12
    # the ring's tip keeps the path of contact on the planet's involute (no tip-fillet interference)
    assert planet_ring.path["A"] >= planet_ring.path["F1"]
    # planets at r = a_w, 120 degrees apart
    for k in range(3):
        x, y = lay.axis("planet", k)
        assert (x, y) == pytest.approx((56.8 * math.cos(2 * math.pi * k / 3), 56.8 * math.sin(2 * math.pi * k / 3)),
                                       abs=A_W_TOL)


def test_fidelity_builds_only_what_it_needs():
    model = SceneModel(load_scene(PLANETARY))
    assert model.ratio() == 1 + Fraction(108, 21)
    formula = model.check("formula")
    assert [c.status for c in formula] == ["ok", "ok"]
    assert model.built == {"profiles": 0, "simulations": 0, "solids": 0, "interference": 0}
    generated = model.check("generated")
    assert model.built["profiles"] == 3  # sun, planet, ring: each distinct gear once, not once per mesh
    assert [c.status for c in generated] == ["ok", "ok"]
    model.check("generated")
    assert model.built["profiles"] == 3  # cached by (gear, fidelity, tol)


def test_solids_once_per_gear_and_interference_only_where_asked(tmp_path):
    model = SceneModel(load_scene(PLANETARY), tol=0.02, width=6.0)
    (sun_planet,) = model.check("solid", meshes=["sun-planet"])
    assert model.built["solids"] == 2 and model.built["interference"] == 1
    assert sun_planet.interference <= sun_planet.interference_bound
    path = model.export(tmp_path / "scene.obj", angle_deg=4.0)
    assert model.built["solids"] == 3  # the ring is built for the export; planets are copies
    names = [ln.split()[1] for ln in path.read_text().splitlines() if ln.startswith("o ")]
    assert sorted(names) == ["planet", "planet#2", "planet#3", "ring", "sun"]


def test_simulated_fidelity_runs_one_simulation_per_mesh():
    model = SceneModel(load_scene(PLANETARY), steps=300)
    checks = model.check("simulated", meshes=["sun-planet"])
    assert model.built["simulations"] == 1 and model.built["profiles"] == 2
    ids = {f.id for f in checks[0].check.report.findings}
    assert "contact_ratio.simulated" in ids


def test_poses_turn_with_the_carrier():
    """At input angle t the carrier turns t/i and each planet about its axis by w_p t (Willis)."""
    model = SceneModel(load_scene(PLANETARY))
    base = {p.name: p for p in model.poses(0.0)}
    moved = {p.name: p for p in model.poses(30.0)}
    t = math.radians(30.0)
    wc = 7 / 43
    wp = wc - 21 / 43 * (1 - wc)
    for name in ("planet", "planet#2", "planet#3"):
        a0 = math.atan2(base[name].y, base[name].x)
        a1 = math.atan2(moved[name].y, moved[name].x)
        assert (a1 - a0) % (2 * math.pi) == pytest.approx(wc * t, abs=1e-12)
        assert moved[name].rotation - base[name].rotation == pytest.approx(wp * t, abs=1e-12)
    assert moved["sun"].rotation - base["sun"].rotation == pytest.approx(t, abs=1e-12)


def test_cli_scene_json_keys_and_laziness(capsys):
    assert main(["scene", str(PLANETARY), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["dof"] == 1
    assert out["ratio"] == pytest.approx(1 + 108 / 21, rel=1e-15)
    assert out["speeds"]["sun"] == 1.0 and out["speeds"]["carrier"] == pytest.approx(7 / 43, rel=1e-15)
    assert [m["gears"] for m in out["meshes"]] == [["sun", "planet"], ["planet", "ring"]]
    assert [m["center_distance"] for m in out["meshes"]] == pytest.approx([56.8, 56.8], abs=A_W_TOL)
    assert all(m["status"] == "ok" for m in out["meshes"])
    assert out["built"]["profiles"] == 0
    assert main(["scene", str(PLANETARY), "--json", "--fidelity", "generated"]) == 0
    assert json.loads(capsys.readouterr().out)["built"]["profiles"] == 3


def test_cli_scene_four_speed_box_states(capsys):
    assert main(["scene", str(EXAMPLES / "four_speed_box.toml"), "--json", "--state", "first"]) == 0
    out = json.loads(capsys.readouterr().out)
    # input s1, output s5: w1/w5 = 1/4, 1/3, 1/2, 1 (the handbook's w5/w1 = 4, 3, 2, 1)
    assert [out["states"][s]["ratio"] for s in ("first", "second", "third", "direct")] == pytest.approx(
        [1 / 4, 1 / 3, 1 / 2, 1], rel=1e-15)
    assert out["dof"] == 1


def test_cli_scene_bad_input_is_one_line(tmp_path, capsys):
    bad = tmp_path / "bad.toml"
    bad.write_text(PLANETARY.read_text().replace("teeth = 108", "teeth = 110"))
    assert main(["scene", str(bad)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "sun-planet" in err[0] and "planet-ring" in err[0] and "does not close" in err[0]
    assert main(["scene", str(tmp_path / "missing.toml")]) == 2
    assert main(["scene", str(PLANETARY), "-o", str(tmp_path / "scene.xyz")]) == 2
    assert not (tmp_path / "scene.xyz").exists()


def test_cli_planetary_json_keys(capsys):
    assert main(["planetary", "--ratio", str(1 + 108 / 21), "--planets", "3", "-m", "1.75", "--sets", "2",
                 "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    best = out["candidates"][0]
    keys = {"sun", "planet", "ring", "planets", "ratio", "planet_angles_deg", "ring_phase_deg", "phasing",
            "neighbour_clearance"}
    assert keys <= set(best)
    assert (best["sun"], best["planet"], best["ring"], best["planets"]) == (21, 43, 108, 3)
    assert best["planet_angles_deg"] == pytest.approx([0, 120, 240]) and best["phasing"] == "in_phase"
    assert main(["planetary", "--ratio", "1.5", "--planets", "3", "-m", "1"]) == 2


@pytest.mark.parametrize("internal, a_w", [(False, 315.0), (True, 157.5)])
def test_reverted_trains_examples_4_and_5_are_coaxial(internal, a_w):
    """Ex.4 (36, 144 at m 3.5; 35, 105 at m 4.5: a = 315 mm) and Ex.5 (18, 72; 35, 105 internal:
    a = 157.5 mm): input and output share an axis; turning the second mesh off that axis is an error."""
    teeth = (18, 72) if internal else (36, 144)

    def scene(angle):
        gears = (Gear("z1", teeth[0], module=3.5), Gear("z2", teeth[1], module=3.5, shaft="mid"),
                 Gear("z3", 35, module=4.5, shaft="mid"), Gear("z4", 105, module=4.5, internal=internal))
        return Scene(gears, (Mesh("z1", "z2"), Mesh("z3", "z4", angle_deg=angle)), coaxial=(("z1", "z4"),),
                     motion=Motion(inputs={"z1": 1}, output="z4"))

    lay = scene_layout(scene(180.0))
    assert [m.center_distance for m in lay.meshes] == pytest.approx([a_w, a_w], abs=1e-9)
    assert lay.positions["z4"] == pytest.approx(lay.positions["z1"], abs=1e-9)
    assert SceneModel(scene(180.0)).ratio() == (-12 if internal else 12)
    with pytest.raises(SpecError, match="loop through z3-z4 does not close"):
        scene_layout(scene(170.0))


def test_helical_scene_hands_follow_the_meshes():
    """A helical planetary: the sun's hand is given; the planets take the opposite hand (external
    mesh) and the ring the planets' (internal mesh); each solid twists with its own hand."""
    scene = Scene((Gear("sun", 20), Gear("planet", 40, count=3, carrier="carrier"), Gear("ring", 100, internal=True)),
                  (Mesh("sun", "planet"), Mesh("planet", "ring")), module=2.0, helix_angle_deg=12.0, face_width=10.0,
                  motion=Motion(fixed=("ring",), inputs={"sun": 1}, output="carrier"))
    assert scene.helix_angles() == {"sun": 12.0, "planet": -12.0, "ring": -12.0}
    lay = scene_layout(scene)
    assert [lay.gear_spec(n).helix_angle_deg for n in ("sun", "planet", "ring")] == [12.0, -12.0, -12.0]
    # the transverse module sets the carrier radius: a = m_n (z_s + z_p) / (2 cos beta)
    assert lay.radii["planet"] == pytest.approx(2.0 * 60 / (2 * math.cos(math.radians(12.0))), abs=1e-9)
