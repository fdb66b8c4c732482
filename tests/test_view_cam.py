"""The cam page against the cam's own geometry: the contact point lies on the turned cam and on the
follower as placed; a translating follower only translates, by the motion law's lift."""
import math

import numpy as np
import pytest

from gearkit.distances import distances_to_polyline
from gearkit.families.cam import CamSpec, MotionProgram, cam_profile
from gearkit.view.cam import cam_view

FINE = 1e-5  # mm: chord tolerance of the exact reference outline
#: a contact's distance from the turned exact outline: the reference's chords (with the sampler's
#: overshoot), the rounding of the point (7.1e-6 mm) and of the pose (5e-8 rad x 50 mm)
ON = 3 * FINE
ROUND = 1e-5  # mm: the page rounds coordinates to 1e-5 mm, poses to 1e-7


def _turn(points, pose):
    a, x, y = pose
    c, s = math.cos(a), math.sin(a)
    return np.asarray(points) @ np.array([[c, s], [-s, c]]) + (x, y)


@pytest.mark.parametrize("contact", ["roller", "flat"])
def test_contact_on_the_turned_cam_and_the_placed_follower(contact):
    spec = CamSpec(40.0, MotionProgram.rise_dwell_return(10.0, 90.0, 30.0, 90.0), contact=contact,
                   roller_radius=8.0 if contact == "roller" else 0.0)
    data = cam_view(spec, frames=36)
    cam, follower = data["anim"]["bodies"]
    prof = cam_profile(spec)
    exact = prof.outline(FINE)
    s = spec.motion.evaluate(2 * np.pi * np.arange(36) / 36)[0]
    for f in range(36):
        q = np.asarray(data["anim"]["contacts"][f]).reshape(-1, 2)
        assert distances_to_polyline(q, _turn(exact, cam["poses"][f]), closed=True).max() <= ON
        if contact == "roller":  # at one roller radius from the roller's centre as placed
            centre = _turn(np.asarray(prof.reference)[None], follower["poses"][f])[0]
            assert np.hypot(*(q[0] - centre)) == pytest.approx(8.0, abs=2 * ROUND)
        # a translating follower does not turn, and rises by the law's lift
        assert follower["poses"][f][0] == pytest.approx(follower["poses"][0][0], abs=2e-7)
        assert follower["poses"][f][2] - follower["poses"][0][2] == pytest.approx(s[f] - s[0], abs=2e-7)
    assert [p["name"] for p in data["parts3d"]] == (["cam", "roller"] if contact == "roller" else ["cam"])


def test_cam_cli_writes_the_page(tmp_path):
    from gearkit.cli import main

    page = tmp_path / "cam.html"
    assert main(["cam", "--prime-radius", "40", "--roller-radius", "8", "--rise", "10", "--rise-deg", "90",
                 "--return-deg", "90", "-o", str(page)]) == 0
    text = page.read_text()
    assert "window.GEARKIT_DATA" in text and '"follower"' in text
