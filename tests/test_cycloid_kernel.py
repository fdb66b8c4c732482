"""The kernel extensions the cycloidal family needs, tested on their own.

* ``RollingMotion.roll_centre``: contact rolls within half a turn of it (default: unchanged).
* roots ``"front"``/``"back"``: ordered along the outward normal; ``"near"``/``"far"`` by distance.
* a normal line grazing the tool centrode (within rounding) touches it, with one double root.
* ``chain_branches(..., return_root=...)``: out and back walks joined where the roots meet.
* ``Branch`` walked backwards is exact at both ends; ``RollingMotion.tool_pole``.
"""
import math

import numpy as np
import pytest

from gearkit.envelope import Branch, chain_branches
from gearkit.families.cycloidal import DriveSpec
from gearkit.families.cycloidal.disc import generating_motion, pin_tool
from gearkit.motion import RollingMotion
from gearkit.segments import arc

RNG = np.random.default_rng(6)


def _pin_normals(n=200):
    """Points and outward normals of a pin (radius 3) centred at (1, 10), all round."""
    a = np.linspace(0.0, 2 * math.pi, n, endpoint=False)
    normal = np.stack([np.cos(a), np.sin(a)], -1)
    return np.array([1.0, 10.0]) + 3.0 * normal, normal


def test_roll_centre_picks_the_turn():
    p, n = _pin_normals()
    base = RollingMotion(-20.0, -25.0)
    s0, ok = base.contact(p, n, "far")
    c = 25.0
    assert (np.abs(s0[ok]) <= math.pi * c + 1e-9).all()  # default: within half a turn of 0
    for centre in (0.7 * math.pi * c, -2.5 * math.pi * c):
        s1, _ = RollingMotion(-20.0, -25.0, roll_centre=centre).contact(p, n, "far")
        assert (np.abs(s1[ok] - centre) <= math.pi * c + 1e-9).all()
        turns = (s1[ok] - s0[ok]) / (2 * math.pi * c)
        assert turns == pytest.approx(np.round(turns), abs=1e-12)  # the same contact, whole turns apart


def test_front_back_near_far():
    p, n = _pin_normals()
    m = RollingMotion(-20.0, 25.0)
    hits = {}
    for root in ("near", "far", "front", "back"):
        s, ok = m.contact(p, n, root)
        pole = m.tool_pole(s[ok])
        t = np.einsum("ij,ij->i", pole - p[ok], n[ok])  # signed distance along the outward normal
        hits[root] = t
        # every root is on the normal line: the meshing equation
        assert np.abs((pole[:, 0] - p[ok, 0]) * n[ok, 1] - (pole[:, 1] - p[ok, 1]) * n[ok, 0]).max() < 1e-12
    assert (hits["front"] >= hits["back"]).all()
    assert (np.abs(hits["near"]) <= np.abs(hits["far"]) + 1e-12).all()
    with pytest.raises(ValueError):
        m.contact(p, n, "middle")


def test_grazing_normal_touches_with_a_double_root():
    """A normal line tangent to the tool centrode (up to rounding) has one contact, both roots equal."""
    c = 7.0
    m = RollingMotion(-10.0, -c)
    ang = RNG.uniform(0, 2 * math.pi, 50)
    touch = np.stack([c * np.sin(ang), -c + c * np.cos(ang)], -1)  # points on the tool centrode
    tangent = np.stack([np.cos(ang), -np.sin(ang)], -1)
    p = touch + RNG.uniform(-5, 5, 50)[:, None] * tangent  # on the tangent lines
    for normal in (tangent, -tangent):
        near, ok_n = m.contact(p, normal, "near")
        far, ok_f = m.contact(p, normal, "far")
        assert ok_n.all() and ok_f.all()
        assert near == pytest.approx(far, abs=1e-6 * c)


def test_branch_walked_backwards_is_exact_at_both_ends():
    seg = arc((0.0, 5.0), 2.0, 2.0, 0.5, "flank")
    m = RollingMotion(-30.0, None)
    u0, u1 = 0.123456789, 0.987654321
    fwd, back = Branch(seg, m, u0, u1), Branch(seg, m, u1, u0)
    assert back(np.array([1.0]))[0] == pytest.approx(fwd(np.array([0.0]))[0], abs=0.0)
    assert back(np.array([0.0]))[0] == pytest.approx(fwd(np.array([1.0]))[0], abs=0.0)


@pytest.mark.parametrize("args", [(12, 11, 90.0, 7.0, 4.0), (15, 16, 120.0, 10.0, 5.0), (24, 22, 90.0, 7.0, 4.0)])
def test_out_and_back_walks_join(args):
    """The pin's near-root and far-root walks meet where the normal grazes the pin ring's centrode:
    at the chain's end for a disc (dz > 0), at its start for a ring (dz < 0)."""
    spec = DriveSpec(*args)
    chain, motion = pin_tool(spec), generating_motion(spec)
    walk = chain_branches(chain, motion, "near", return_root="far")
    assert [b.root for b in walk] == (["near", "far"] if spec.sign > 0 else ["far", "near"])
    a, b = walk
    gap = np.linalg.norm(a(np.array([1.0]))[0] - b(np.array([0.0]))[0])
    assert gap <= 1e-6 * spec.pin_circle_radius
    # the join is the pin point of the largest contact deviation arcsin |K1|
    assert chain_branches(chain, motion, "near") == (walk[0] if spec.sign > 0 else walk[1],)


def test_tool_pole_is_the_blank_centrode_point():
    m = RollingMotion(-20.0, 30.0)
    s = np.linspace(-15.0, 15.0, 7)
    pole = m.to_blank(m.tool_pole(s), s)
    assert np.hypot(*pole.T) == pytest.approx(20.0, abs=1e-12)  # on the blank's centrode
    assert np.arctan2(pole[:, 0], pole[:, 1]) == pytest.approx(s / 20.0, abs=1e-12)  # rolled arc s
