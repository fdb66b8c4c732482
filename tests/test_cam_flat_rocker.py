"""What the check reports of a flat rocker: the smallest radius of curvature where it is bounded, "unbounded below"
(JSON null and the angles, never a huge finite number) where the face stops turning against the cam and turns
back, and the pressure angle only where the prescribed contact lies ahead of the pivot.

Oracle: the cam is the envelope of the face's lines. A rocker's face lies along its arm through the pivot
``(l0, 0)``, so its distance from the cam axis is ``p = l0 sin Psi``, ``Psi = asin(r0/l0) + s/l``, and it turns
against the cam at ``theta' = -(1 + s'/l)``. The radius of curvature of the envelope of lines with support
``p(theta)`` is ``rho = p + d2p/dtheta2 = p + (p'' theta' - p' theta'') / theta'^3`` (derivatives over the cam
angle). The contact is the foot of the perpendicular from the relative pole, on the line of centres at
``l0 / (1 + s'/l)`` from the pivot, onto the face: ``l0 cos Psi / (1 + s'/l)`` from the pivot along the arm
(negative: behind it). Where it is ahead, the face's force (normal to the face) and the contact's velocity
(normal to the arm) are parallel: the pressure angle is zero. All of it is written out here from the motion
laws' closed forms, none of it the product's envelope or check code.
"""
import json
import math

import numpy as np
import pytest
from scipy.optimize import brentq

from gearkit.checks.cam import check_cam
from gearkit.cli import main
from gearkit.families.cam import CamSpec, MotionProgram

ROCKER = dict(follower="rocker", contact="flat")


def law(name, x):
    """Shape ``f(x)`` of a rise over ``x`` in [0, 1] and its first two derivatives (the textbook's laws)."""
    if name == "polynomial_345":
        return (10 * x**3 - 15 * x**4 + 6 * x**5, 30 * x**2 - 60 * x**3 + 30 * x**4, 60 * x - 180 * x**2 + 120 * x**3)
    if name == "harmonic":
        return (1 - np.cos(np.pi * x)) / 2, np.pi / 2 * np.sin(np.pi * x), np.pi**2 / 2 * np.cos(np.pi * x)
    if name == "cycloidal":
        return (x - np.sin(2 * np.pi * x) / (2 * np.pi), 1 - np.cos(2 * np.pi * x),
                2 * np.pi * np.sin(2 * np.pi * x))
    assert name == "constant_velocity"
    return x, np.ones_like(x), np.zeros_like(x)


def motion(lift, rise_deg, dwell_deg, return_deg, name, phi):
    """``s, s', s''`` (mm, per rad) of rise, far dwell, return, near dwell at cam angles ``phi`` (rad)."""
    b1, d, b2 = (math.radians(v) for v in (rise_deg, dwell_deg, return_deg))
    phi = np.mod(phi, 2 * math.pi)
    out = np.zeros((3,) + phi.shape)
    rise, ret = phi < b1, (phi >= b1 + d) & (phi < b1 + d + b2)
    out[0, (phi >= b1) & (phi < b1 + d)] = lift
    f = law(name, phi[rise] / b1)
    out[:, rise] = [lift * f[0], lift * f[1] / b1, lift * f[2] / b1**2]
    f = law(name, (phi[ret] - b1 - d) / b2)
    out[:, ret] = [lift * (1 - f[0]), -lift * f[1] / b2, -lift * f[2] / b2**2]
    return out


def rho_formula(kw, mo, phi):
    """The envelope's radius of curvature at cam angles ``phi`` and the face's turning rate ``1 + s'/l``."""
    s, v, a = motion(*mo, phi)
    l, l0 = kw["arm_length"], kw["pivot_distance"]
    psi = math.asin(kw["prime_radius"] / l0) + s / l
    p, dp = l0 * np.sin(psi), l0 * np.cos(psi) * v / l
    ddp = -l0 * np.sin(psi) * (v / l) ** 2 + l0 * np.cos(psi) * a / l
    dt, ddt = -(1 + v / l), -a / l
    return p + (ddp * dt - dp * ddt) / dt**3, 1 + v / l


#: flat rockers whose face swings faster than the cam turns, each way (tests/test_cam_flat.py STEEP)
TURNING_BACK = [
    (dict(prime_radius=20.0, pivot_distance=24.0, arm_length=27.13), (35.0, 20.0, 1.75, 20.0, "polynomial_345")),
    (dict(prime_radius=8.0, pivot_distance=20.33, arm_length=10.17), (26.7, 92.2, 0.0, 93.0, "harmonic")),
]
#: the roots of 1 + s'/l are closed by brentq to this, rad; the check's bisection closes to round-off
ROOT_XTOL = 1e-13
#: agreement of the angles where the face turns back, degrees: both are roots to round-off of the same s'
ANGLE_TOL = 1e-9


def cli_args(kw, mo):
    lift, rise, dwell, ret, name = mo
    return ["cam", "--contact", "flat", "--rocker", "--prime-radius", str(kw["prime_radius"]), "--pivot-distance",
            str(kw["pivot_distance"]), "--arm-length", str(kw["arm_length"]), "--rise", str(lift), "--rise-deg",
            str(rise), "--dwell-deg", str(dwell), "--return-deg", str(ret), "--law", name]


@pytest.mark.parametrize("kw, mo", TURNING_BACK)
def test_a_face_turning_back_has_a_radius_of_curvature_unbounded_below(kw, mo, capsys):
    grid = np.linspace(0.0, 2 * math.pi, 20001)
    _, turn = rho_formula(kw, mo, grid)
    k = np.nonzero(np.sign(turn[:-1]) != np.sign(turn[1:]))[0]
    roots = [brentq(lambda x: rho_formula(kw, mo, np.array([x]))[1][0], grid[i], grid[i + 1], xtol=ROOT_XTOL)
             for i in k]
    assert len(roots) == 2
    for r in roots:  # the formula runs off to both infinities either side of each root
        below, above = rho_formula(kw, mo, np.array([r - 1e-7, r + 1e-7]))[0]
        assert min(abs(below), abs(above)) > 1e6 * kw["prime_radius"] and below * above < 0
    res = check_cam(CamSpec(motion=MotionProgram.rise_dwell_return(*mo), **ROCKER, **kw))
    found = res.values["curvature_unbounded_deg"]
    assert np.allclose(found, np.degrees(roots), rtol=0.0, atol=ANGLE_TOL)
    convexity = res.report["convexity"]
    assert convexity.status == "fail" and convexity.value == -math.inf and "unbounded below" in convexity.message
    assert res.values["min_curvature_radius"] is None and convexity.to_dict()["value"] is None
    # strict JSON (no Infinity, no NaN) from the command, and the words in its text
    assert main(cli_args(kw, mo) + ["--json"]) == 1
    out = json.loads(capsys.readouterr().out, parse_constant=lambda c: pytest.fail(f"{c} in the JSON"))
    assert out["min_curvature_radius"] is None and np.allclose(out["curvature_unbounded_deg"], found, atol=0.0)
    assert next(f for f in out["findings"] if f["id"] == "convexity")["value"] is None
    assert main(cli_args(kw, mo)) == 1
    text = capsys.readouterr().out
    assert "min radius of curvature, mm   unbounded below" in text and "-unbounded" in text
    assert "e+0" not in text.split("convexity")[1].split("\n")[0]


#: flat rockers whose face always turns against the cam: a slow cycloidal one; constant velocity (the face
#: turns back at once at the return's velocity jumps, where the differences once straddled the kink and
#: read -9.8e7 mm); harmonic (acceleration jumps: the differences across them read -78.9 mm)
BOUNDED = [
    (dict(prime_radius=30.0, pivot_distance=80.0, arm_length=60.0), (5.0, 90.0, 20.0, 90.0, "cycloidal")),
    (dict(prime_radius=29.920755273305605, pivot_distance=35.90490632796673, arm_length=17.952453163983364),
     (14.960377636652803, 29.920755273305605, 29.920755273305605, 20.0, "constant_velocity")),
    (dict(prime_radius=30.0, pivot_distance=80.0, arm_length=60.0), (8.0, 60.0, 20.0, 60.0, "harmonic")),
]
#: the check reads rho on a 0.05 degree grid: it misses a smooth minimum by at most rho'' (grid/2)^2 / 2, and its
#: central differences (step 2e-4 rad) add h^2 rho'''' / 6; both below 1e-5 of r0 + stroke on these cams
SAMPLING = 1e-5


@pytest.mark.parametrize("kw, mo", BOUNDED)
def test_the_smallest_radius_of_curvature_of_a_flat_rocker_is_the_formula(kw, mo):
    res = check_cam(CamSpec(motion=MotionProgram.rise_dwell_return(*mo), **ROCKER, **kw))
    rho, turn = rho_formula(kw, mo, np.linspace(0.0, 2 * math.pi, 400001))
    assert res.values["curvature_unbounded_deg"] == [] and math.isfinite(res.values["min_curvature_radius"])
    assert abs(res.values["min_curvature_radius"] - rho.min()) <= SAMPLING * (kw["prime_radius"] + mo[0])
    assert res.report["convexity"].value == res.values["min_curvature_radius"]


#: flat rockers whose prescribed contact passes behind the pivot: the steep one (the far dwell's arm beyond
#: 90 degrees, then the face turning back on the return) and the constant-velocity one (turning back over
#: the return)
BEHIND = [TURNING_BACK[0], BOUNDED[1]]
#: the pressure angle where the contact is ahead of the pivot: zero, to the round-off of an atan2, degrees
ZERO_DEG = 1e-9


def contact_ahead(kw, mo, phi):
    """Where the prescribed contact lies along the arm from the pivot, mm (negative: behind it)."""
    s, v, _ = motion(*mo, phi)
    l, l0 = kw["arm_length"], kw["pivot_distance"]
    return l0 * np.cos(math.asin(kw["prime_radius"] / l0) + s / l) / (1 + v / l)


@pytest.mark.parametrize("kw, mo", BEHIND + [BOUNDED[0]])
def test_a_flat_rockers_pressure_angle_is_read_where_the_contact_is_ahead_of_the_pivot(kw, mo, capsys):
    spec = CamSpec(motion=MotionProgram.rise_dwell_return(*mo), **ROCKER, **kw)
    res = check_cam(spec)
    lift, rise, dwell, ret, _ = mo
    spans = {"rise": (0.0, rise), "return": (rise + dwell, rise + dwell + ret)}
    reported = res.values["contact_behind_pivot_deg"]
    expected = []
    for kind, (a, b) in spans.items():
        assert res.values["pressure_angle_max_deg"][kind] <= ZERO_DEG
        finding = res.report[f"pressure_angle.{kind}"]
        assert finding.value <= ZERO_DEG and finding.status == "ok"
        deg = np.linspace(a, b, 100001)
        back = contact_ahead(kw, mo, np.radians(deg)) <= 0.0
        edges = np.flatnonzero(np.diff(np.concatenate([[0], back.astype(int), [0]])))
        runs = [[deg[i], deg[j - 1]] for i, j in zip(edges[::2], edges[1::2])]
        expected += runs
        assert ("behind the pivot" in finding.message) == bool(runs)
    # the check reads each phase on 1201 angles: its runs end within one of its steps of the formula's
    step = max(rise, ret) / 1200
    assert len(reported) == len(expected)
    assert np.allclose(reported, expected, rtol=0.0, atol=step * (1 + 1e-9)) if expected else reported == []
    # the shortfall finding covers every such stretch: the follower leaves its law there
    for a, b in reported:
        assert any(c - 0.05 - 1e-9 <= a and b <= d + 0.05 + 1e-9 for c, d in res.values["departure_deg"])
    if expected:
        assert res.report["undercut"].status == "fail"
    assert main(cli_args(kw, mo) + ["--json"]) == (1 if expected else 0)
    out = json.loads(capsys.readouterr().out)
    assert out["contact_behind_pivot_deg"] == reported
