"""Kernel building blocks against closed forms: involute function, tool chains, the meshing
equation (closed form vs Newton), loop removal."""
import math

import numpy as np
import pytest

from gearkit.curves import bracketed_root, inv, inv_inverse, polyline_self_intersections
from gearkit.errors import SpecError
from gearkit.motion import RollingMotion
from gearkit.families.involute import BasicRack, ShaperCutter
from gearkit.segments import transform_chain

DEG = math.pi / 180


def test_involute_function_reference_values():
    # reference digest §1.1: inv 20° = 0.0149044, inv 26°13'49" = 0.0349129, inv 41°12'02" = 0.156365
    assert inv(20 * DEG) == pytest.approx(0.0149044, abs=5e-8)
    assert inv((26 + 13 / 60 + 49 / 3600) * DEG) == pytest.approx(0.0349129, abs=5e-8)
    assert inv((41 + 12 / 60 + 2 / 3600) * DEG) == pytest.approx(0.156365, abs=1e-6)  # angle printed to 1"


def test_inverse_involute_accurate_from_micro_radian_to_85_degrees():
    alpha = np.concatenate([np.geomspace(1e-6, 0.05, 200), np.linspace(0.05, 85 * DEG, 400)])
    back = inv_inverse(inv(alpha))
    assert np.max(np.abs(back - alpha)) < 1e-14
    # the small-angle series agrees with the direct formula where both are accurate
    a = np.linspace(0.02, 0.05, 50)
    assert np.allclose(inv(a), np.tan(a) - a, rtol=1e-12, atol=0)


def test_bracketed_root_converges_and_rejects_bad_bracket():
    r = bracketed_root(lambda x: math.cos(x) - x, 0.0, 1.0)
    assert abs(math.cos(r) - r) < 1e-15
    with pytest.raises(ValueError):
        bracketed_root(lambda x: x * x + 1, -1.0, 1.0)


def _chain_is_continuous(chain, atol=1e-12):
    ends = [s.endpoints()[0] for s in chain]
    return all(np.allclose(a[1], b[0], atol=atol) for a, b in zip(ends[:-1], ends[1:]))


@pytest.mark.parametrize("rack", [BasicRack(), BasicRack.iso53("D"), BasicRack(25.0, 1.0, 1.3, 0.2),
                                  BasicRack(20.0, 1.0, 1.4, 0.1, protuberance=0.02)])
def test_rack_chain_is_continuous_with_material_on_the_right(rack):
    chain = rack.half_tooth(2.0, 0.6, 0.05)
    assert _chain_is_continuous(chain)
    # the flank's outward normal points away from the cutter tooth centre (u = p/2), i.e. to -u
    flank = next(s for s in chain if s.label == "flank")
    _, _, n = flank.evaluate(np.array([0.5]))
    assert n[0, 0] < 0
    # G1 at the rounding: flank direction equals the rounding's end direction (no corner there)
    k = [s.label for s in chain].index("fillet")
    t_end = chain[k].evaluate(np.array([1.0]))[1][0]
    t_next = chain[k + 1].evaluate(np.array([0.0]))[1][0]
    assert np.allclose(t_end, t_next, atol=1e-12)


def test_cutter_chain_is_continuous_and_transforms_keep_it_so():
    chain = ShaperCutter(20, tip_radius=0.1).half_tooth(2.0, 20 * DEG)
    assert _chain_is_continuous(chain)
    mirrored = transform_chain(chain, np.diag([-1.0, 1.0]), (3.0, -1.0))
    assert _chain_is_continuous(mirrored)
    # reflection keeps the material on the right: normals are mirrored too
    p0, _, n0 = chain[2].evaluate(np.array([0.3]))
    last = mirrored[len(chain) - 1 - 2]
    p1, _, n1 = last.evaluate(np.array([0.7]))
    assert np.allclose(p1, p0 * [-1, 1] + [3, -1])
    assert np.allclose(n1, n0 * [-1, 1])


@pytest.mark.parametrize("motion", [RollingMotion(-20.0, None), RollingMotion(-20.0, 8.0),
                                    RollingMotion(-30.0, -12.0), RollingMotion(-12.0, -30.0)])
def test_meshing_equation_closed_form_equals_newton_and_normal_passes_through_pole(motion):
    rng = np.random.default_rng(1)
    p = rng.uniform([-1.5, -1.5], [1.5, 1.5], (200, 2))
    ang = rng.uniform(-math.pi, math.pi, 200)
    n = np.stack([np.cos(ang), np.sin(ang)], -1)
    s, valid = motion.contact(p, n)
    keep = valid & (np.abs(n[:, 1]) > 0.2)
    s_newton = motion.contact_newton(p[keep], n[keep], s0=s[keep] + 0.05)
    assert np.allclose(s_newton, s[keep], atol=1e-10)
    # Willis / envelope condition: in the blank frame the normal at the contact passes through the pole
    q = motion.to_blank(p[keep], s[keep])
    nb = motion.rotate_to_blank(n[keep], s[keep])
    pole = motion.to_blank(np.zeros((keep.sum(), 2)) + 0.0, np.zeros(keep.sum()))  # pole at s = 0 ...
    # ... moves along the blank centrode: recompute it at each s from the tool side
    from gearkit.motion import _centrode
    c_t, _ = _centrode(motion.tool_centre, s[keep])
    pole = motion.to_blank(c_t, s[keep])
    cross = (pole - q)[:, 0] * nb[:, 1] - (pole - q)[:, 1] * nb[:, 0]
    assert np.max(np.abs(cross)) < 1e-12


def test_polyline_self_intersections_finds_a_figure_eight_crossing():
    t = np.linspace(0, 2 * np.pi, 401)
    pts = np.stack([np.sin(t), np.sin(2 * t) / 2], -1)
    i, j, ti, tj = polyline_self_intersections(pts[:-1])
    hits = pts[i] + ti[:, None] * (pts[i + 1] - pts[i])
    assert len(i) >= 1 and np.allclose(hits, 0.0, atol=1e-3)
    # a straight line has none
    assert len(polyline_self_intersections(np.stack([t, 2 * t], -1))[0]) == 0


@pytest.mark.parametrize("kwargs, field", [
    (dict(pressure_angle_deg=0.0), "pressure_angle_deg"),
    (dict(pressure_angle_deg=45.0), "pressure_angle_deg"),
    (dict(dedendum=0.9), "dedendum"),
    (dict(fillet_radius=0.6), "fillet_radius"),
    (dict(pressure_angle_deg=40.0, dedendum=1.25), "dedendum"),
    (dict(dedendum=1.4, fillet_radius=0.3, protuberance=0.02), "fillet_radius"),
])
def test_bad_racks_name_the_field(kwargs, field):
    with pytest.raises(SpecError) as exc:
        BasicRack(**kwargs)
    assert exc.value.field == field
    assert str(exc.value).startswith(field + ": ") and len(str(exc.value)) > len(field) + 20


def test_roots_found_side_by_side_are_each_found_alone_in_as_many_calls_as_the_longest():
    """:func:`gearkit.roots.bracketed_roots` takes each root's own rounds side by side: every root equals
    the one it finds alone to the last bit, the calls are as many as the most rounds one root takes alone
    (one root here is exact at its first estimate, another needs several), and every root lies within the
    stopping tolerance ``xtol (1 + |x|)`` of the closed-form root (oracle)."""
    from gearkit.roots import bracketed_roots

    funcs = [lambda x: np.cos(x) - x, lambda x: x * x - 2.0, lambda x: 2.0 * x - 1.0, lambda x: x ** 3 - 0.001]
    brackets = [(0.0, 1.0), (0.0, 2.0), (0.0, 1.0), (0.0, 1.0)]
    xtol = 1e-15

    def counted(funcs, calls):
        def evaluate(which, points):
            calls.append(len(which))
            return [funcs[i](np.asarray(x)) for i, x in zip(which, points)]
        return evaluate

    alone, rounds = [], []
    for f, (a, b) in zip(funcs, brackets):
        calls = []
        alone.append(bracketed_roots(counted([f], calls), [(a, b, f(a), f(b))], xtol)[0])
        rounds.append(len(calls))
    calls = []
    together = bracketed_roots(counted(funcs, calls), [(a, b, f(a), f(b)) for f, (a, b) in zip(funcs, brackets)], xtol)
    assert together == alone and len(calls) == max(rounds) and min(rounds) == 1
    assert sum(calls) == sum(rounds)  # a root that is done asks no more
    cos_root = bracketed_root(lambda x: math.cos(x) - x, 0.0, 1.0, xtol=1e-16)  # the scalar method's root
    exact = [cos_root, math.sqrt(2.0), 0.5, 0.1]
    assert all(abs(r - e) <= 2 * xtol * (1.0 + abs(e)) for r, e in zip(together, exact))


@pytest.mark.parametrize("seed", range(4))
def test_roots_side_by_side_hold_a_sign_change_within_the_tolerance_whatever_the_function(seed):
    """Every root :func:`gearkit.roots.bracketed_roots` returns has a sign change of its function within
    ``xtol (1 + |x|)`` (checked by evaluating at both ends of that interval: the proof its bracket gives),
    on smooth, steep, flat (a high power) and jumping functions, and for each the rounds stay within those
    of trisection (a threefold shrink a round)."""
    from gearkit.roots import bracketed_roots

    rng = np.random.default_rng(seed)
    xtol = 1e-15
    funcs, brackets = [], []
    for k in range(40):
        r = float(rng.uniform(-3.0, 3.0))
        kind = k % 4
        if kind == 0:
            f = (lambda r, s: lambda x: np.sin(s * (x - r)))(r, float(rng.uniform(0.1, 1.5)))
        elif kind == 1:
            f = (lambda r, s: lambda x: np.tanh(s * (x - r)) + 1e-3 * (x - r))(r, float(10 ** rng.uniform(0, 6)))
        elif kind == 2:
            f = (lambda r: lambda x: (x - r) ** 7)(r)
        else:
            f = (lambda r: lambda x: np.where(x < r, -1.0, 1.0) * (1.0 + np.abs(x)))(r)
        a, b = r - float(rng.uniform(0.0, 2.0)), r + float(rng.uniform(1e-3, 2.0))
        funcs.append(f)
        brackets.append((a, b, float(f(a)), float(f(b))))
    calls = []

    def evaluate(which, points):
        calls.append(len(which))
        return [funcs[i](np.asarray(x)) for i, x in zip(which, points)]
    roots = bracketed_roots(evaluate, brackets, xtol)
    for f, x in zip(funcs, roots):
        eps = xtol * (1.0 + abs(x))
        lo, hi = float(f(x - eps)), float(f(x + eps))
        assert float(f(x)) == 0.0 or (lo > 0) != (hi > 0) or lo == 0.0 or hi == 0.0
    widest = max(b - a for a, b, _, _ in brackets)
    assert len(calls) <= math.ceil(math.log(widest / xtol) / math.log(3.0)) + 1


@pytest.mark.parametrize("tool", [BasicRack(20.0), ShaperCutter(18)], ids=["rack", "shaper"])
def test_branches_evaluated_together_give_each_branch_as_it_gives_itself(tool):
    """The branches of one motion are solved in one call (:func:`gearkit.envelope.solve_together`, and
    their turning): each branch's points, rolls, tangents and angle parts are those it gives alone, to
    the last bit; and the envelope points satisfy the meshing equation (the normal through the pole,
    checked on the tool side by :meth:`RollingMotion.contact_newton`, an independent solver)."""
    from gearkit.envelope import chain_branches, solve_together, turning_together
    from gearkit.families.involute import GearSpec
    from gearkit.families.involute.gear import _tool_chain_and_motion

    chain, motion = _tool_chain_and_motion(GearSpec(17, 1.0, 0.1, tool=tool))
    branches = chain_branches(chain, motion)
    ws = [np.linspace(0.0, 1.0, 7 + 3 * k) ** (1 + k % 2) for k in range(len(branches))]
    for br, w, (q, s, valid), turned in zip(branches, ws, solve_together(branches, ws), turning_together(branches, ws)):
        q1, _, s1, v1 = br.solve(w, normals=False)
        assert np.array_equal(q, q1) and np.array_equal(s, s1, equal_nan=True) and np.array_equal(valid, v1)
        alone = br.turning(w)
        assert all(np.array_equal(a, b) for a, b in zip(turned, alone))
        u = br.u0 * (1.0 - w) + br.u1 * w
        p, _, n = br.segment.evaluate(u)
        newton = motion.contact_newton(p[valid], n[valid], s0=s[valid])
        assert np.allclose(newton, s[valid], rtol=0, atol=1e-9)


@pytest.mark.parametrize("points, teeth", [(3, 5), (600, 7), (1342, 40)], ids=["blocks", "short ring", "one a call"])
def test_turned_copies_are_the_rotation_formula_to_the_byte(points, teeth):
    """:func:`gearkit.profile.turn_copies` writes ``cos a (x, y) + sin a (-y, x)`` a block of copies or one copy
    at a time: byte for byte the rotation ``(c x - s y, s x + c y)`` written out plainly, and each copy at the
    radii of the tooth, turned by ``2 pi k / teeth`` (oracle: the polar angles)."""
    from gearkit.profile import turn_copies

    tooth = np.random.default_rng(points).normal(size=(points, 2)) * 20.0
    ang = 2.0 * np.pi * np.arange(teeth) / teeth
    c, s = np.cos(ang)[:, None], np.sin(ang)[:, None]
    plain = np.stack([c * tooth[None, :, 0] - s * tooth[None, :, 1], s * tooth[None, :, 0] + c * tooth[None, :, 1]], -1)
    ring = turn_copies(tooth, teeth)
    assert ring.tobytes() == plain.reshape(-1, 2).tobytes()
    copies = ring.reshape(teeth, points, 2)
    assert np.allclose(np.hypot(*copies.T).T, np.hypot(*tooth.T), rtol=1e-14)
    turn = np.arctan2(copies[..., 1], copies[..., 0]) - np.arctan2(tooth[:, 1], tooth[:, 0])
    assert np.allclose(np.exp(1j * turn), np.exp(1j * ang)[:, None], rtol=0, atol=1e-12)
