"""The scene page against the scene's kinematics: planets keep their distance from the central axis
while the carrier turns them round, and the input turns at the rate asked."""
import math
from pathlib import Path

import numpy as np
import pytest

from gearkit.scene import Gear, Mesh, Motion, Scene, SceneModel, load_scene
from gearkit.view.scene import scene_view


def test_two_gears_turn_at_the_ratio():
    s = Scene((Gear("a", 20), Gear("b", 30)), (Mesh("a", "b"),), motion=Motion(inputs={"a": 1}))
    data = scene_view(SceneModel(s), frames=12, turn_deg=60.0)
    a, b = (np.asarray(body["poses"]) for body in data["anim"]["bodies"])
    assert np.diff(a[:, 0]) == pytest.approx(np.full(11, math.radians(5.0)), abs=2e-7)
    assert np.diff(b[:, 0]) == pytest.approx(np.full(11, -math.radians(5.0) * 20 / 30), abs=2e-7)
    assert [f["id"].split(":")[0] for f in data["findings"]][:1] == [s.meshes[0].label]


def test_planets_ride_their_carrier():
    model = SceneModel(load_scene(Path(__file__).parent.parent / "examples" / "planetary.toml"))
    data = scene_view(model, frames=9)
    bodies = data["anim"]["bodies"]
    planets = [np.asarray(b["poses"]) for b in bodies if b["name"].startswith("planet")]
    assert len(planets) == 3
    radii = np.array([np.hypot(p[:, 1], p[:, 2]) for p in planets])
    assert np.ptp(radii) <= 1e-6  # every copy, every frame: the carrier radius
    assert len(data["parts3d"]) == len(bodies)


def test_scene_cli_page_and_step_names(tmp_path):
    """``gearkit scene FILE -o scene.html`` writes the page with every placed copy."""
    from gearkit.cli import main

    scene = tmp_path / "two.toml"
    scene.write_text((Path(__file__).parent.parent / "examples" / "planetary.toml").read_text())
    page = tmp_path / "scene.html"
    assert main(["scene", str(scene), "-o", str(page)]) in (0, 1)
    assert '"planet#2"' in page.read_text()


def test_scene_step_names_every_part(tmp_path):
    pytest.importorskip("OCP.BRepBuilderAPI", reason="the optional B-rep kernel: pip install 'gearkit[step]'")
    from gearkit.solids.step import read_step

    s = Scene((Gear("a", 12), Gear("b", 17)), (Mesh("a", "b"),), motion=Motion(inputs={"a": 1}), face_width=4.0)
    SceneModel(s, tol=0.01).export(tmp_path / "two.step")
    assert [name for name, _ in read_step(tmp_path / "two.step")] == ["a", "b"]
