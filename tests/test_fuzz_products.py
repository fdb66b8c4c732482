"""Fuzzing the products (hypothesis): pair check, Novikov pair check, cycloid drive check, solids.

Every spec must give a valid result (strict JSON; a pair check never grades a tip larger than the
generated, cut tip; a solid is a watertight manifold whose volume is its section times its width)
or a ``SpecError`` naming a field; anything else is a defect (tests/fuzzkit.py counts the outcomes
and, in the long run, lists every defect with its reproducer)::

    GEARKIT_FUZZ_EXAMPLES=10000 GEARKIT_FUZZ_REPORT=fuzz.jsonl nice python -m pytest tests/test_fuzz_products.py -p no:randomly
"""
import math
from dataclasses import replace

import numpy as np
import pytest
from fuzzkit import assert_clean, fuzz_settings, maybe_hostile, modules, run, strict_json, write_report
from hypothesis import given
from hypothesis import strategies as st

import gearkit as gk


@pytest.fixture(autouse=True, scope="module")
def _report():
    yield
    write_report()


def _tool(desc):
    """A tool from its description ("shaper", args...) / ("rack", args...), built inside the property."""
    if not isinstance(desc, tuple):
        return desc
    kind, *args = desc
    return gk.ShaperCutter(*args) if kind == "shaper" else gk.BasicRack(*args)


@fuzz_settings(12)
@given(data=st.data())
def _pair_check(data):
    kind = data.draw(st.sampled_from(["external", "external", "internal", "rack"]))
    z1 = data.draw(st.integers(6, 80))
    z2 = None if kind == "rack" else z1 + data.draw(st.integers(8 if kind == "internal" else 0, 200))
    m = data.draw(modules)
    kw = dict(teeth1=z1, teeth2=z2, module=m, kind=kind, shift1=data.draw(st.floats(-0.5, 1.0)),
              shift2=0.0 if kind == "rack" else data.draw(st.floats(-0.5, 1.0)),
              helix_angle_deg=data.draw(st.sampled_from([0.0, 15.0])))
    if kind == "internal":
        kw["tool2"] = ("shaper", data.draw(st.integers(8, min(40, z2 - 4))))
    if data.draw(st.booleans()):
        kw["center_distance"] = "tight"
    kw = data.draw(maybe_hostile(kw))
    extra = data.draw(st.floats(-0.2, 0.8))

    def build():
        spec = {**kw, "tool2": _tool(kw.get("tool2"))}
        if spec.get("center_distance") == "tight":
            base = gk.pair_geometry(gk.PairSpec(**{**spec, "center_distance": None}))
            spec = {**spec, "center_distance": base.tight_center_distance + extra * m}
        return gk.check_pair(gk.PairSpec(**spec))

    def check(res):
        strict_json(res.to_dict())
        for gear, prof in zip(res.geometry.gears, res.profiles):
            if not prof.internal:
                assert gear.tip_diameter <= prof.tip_diameter * (1 + 1e-12), "checked tip beyond the cut tip"
            else:  # a ring's tip is its inner circle: the checked one never inside the cut one
                assert gear.tip_diameter >= prof.tip_diameter * (1 - 1e-12), "checked ring tip inside the cut tip"
    run("pair_check", (kw, extra), build, check)


def _novikov_arcs_and_clearance(res):
    """The working-arc findings and the interference scan against the sampled outlines: a design contact
    point the check keeps (or loses) by more than half a degree of rack angle is on (off) the outline,
    and each contact's clearance is the smallest signed distance with the side by ray casting."""
    from matplotlib.path import Path

    from gearkit.distances import distances_to_polyline

    spec, m = res.geometry.spec, res.geometry.module
    tol = res.contacts[0].tol if res.contacts else 1e-5 * m
    for k, prof in enumerate(res.profiles, start=1):
        loop = prof.outline(tol)
        for which in ("convex", "concave"):
            if getattr(prof.spec.rack, which) is None:
                continue
            margin = res.report[f"working_arc.{k}.{which}"].value  # degrees of rack angle
            off = float(distances_to_polyline(prof.contact_point(which)[0][None, :], loop, closed=True)[0])
            if margin > 0.5:  # the point lies 0.5 deg * rho (> 0.01 m) inside the arc's ends
                assert off <= 2 * tol, f"gear {k}'s {which} contact point said kept is {off:.3g} mm off the tooth"
            elif margin < -0.5:
                assert not off <= 2 * tol, f"gear {k}'s {which} contact point said cut away is on the tooth"
    window = 3.0 * math.pi * res.geometry.transverse_module
    coarse = 1e-3 * m  # the side by ray casting in outlines sampled to this: right beyond 2 (coarse + tol)
    for c in res.contacts:
        loops, rough = [], []
        for k, prof in enumerate(res.profiles):
            cs, sn = math.cos(c.rotations[k]), math.sin(c.rotations[k])
            turn, at = np.array([[cs, sn], [-sn, cs]]), np.array([0.0, k * c.center_distance])
            loops.append(prof.outline(tol) @ turn + at)
            rough.append(prof.outline(coarse) @ turn + at)
        pole_y = c.center_distance * spec.teeth1 / (spec.teeth1 + spec.teeth2)
        lo = hi = math.inf  # bounds of the smallest signed distance
        for k in (0, 1):
            pts = loops[k][(np.abs(loops[k][:, 0]) < window) & (np.abs(loops[k][:, 1] - pole_y) < window)]
            if not len(pts):
                continue
            d = distances_to_polyline(pts, loops[1 - k], closed=True)
            far = d > 2 * (coarse + tol)
            signed = np.where(Path(rough[1 - k]).contains_points(pts[far]), -d[far], d[far])
            lo = min(lo, float(signed.min(initial=math.inf)), float(-d[~far].max(initial=-math.inf)))
            hi = min(hi, float(signed.min(initial=math.inf)), float(d[~far].min(initial=math.inf)))
        assert lo - 2 * tol <= c.clearance <= hi + 2 * tol, \
            f"clearance {c.clearance:.3g} mm, the outlines say {lo:.3g} .. {hi:.3g}"


@fuzz_settings(6)
@given(data=st.data())
def _novikov_pair_check(data):
    z1 = data.draw(st.integers(8, 60))
    m = data.draw(modules)
    kw = data.draw(maybe_hostile(dict(teeth1=z1, teeth2=z1 + data.draw(st.integers(0, 100)), module=m,
                                       helix_angle_deg=data.draw(st.floats(8.0, 30.0)),
                                       face_width=data.draw(st.floats(5.0, 40.0)) * m,
                                       racks=data.draw(st.sampled_from(["dca24", "single-arc"])))))
    off = data.draw(st.floats(-0.6, 0.6))

    def build():
        spec = gk.NovikovPairSpec(**kw)
        a = gk.novikov_pair_geometry(spec).reference_center_distance
        return gk.check_novikov(replace(spec, center_distance=a + off * spec.module))

    def check(res):
        strict_json(res.report.to_dict())
        spec = res.geometry.spec
        for c in res.contacts:  # a true contact: on both flanks, outward normals opposite, normal through the pole
            zone = spec.racks.zones[c.zone]
            which = "concave" if zone.convex_gear == 1 else "convex"
            assert all(0.0 <= w <= 1.0 for w in c.flank_params), "contact off the working branches"
            q, n, _, _ = res.profiles[1].working_branch(which).solve(np.array([c.flank_params[1]]))
            cs, sn = math.cos(c.rotations[1]), math.sin(c.rotations[1])
            turn = np.array([[cs, -sn], [sn, cs]])
            p2, m2 = turn @ q[0] + np.array([0.0, c.center_distance]), turn @ n[0]
            assert np.abs(p2 - c.point).max() <= 1e-9 * spec.module, "the flanks do not meet"
            assert float(c.normal @ m2) < -1 + 1e-9, "normals not opposite: interpenetrating flanks"
            pole_y = c.center_distance * spec.teeth1 / (spec.teeth1 + spec.teeth2)
            arm = c.point - np.array([0.0, pole_y])
            assert abs(arm[0] * c.normal[1] - arm[1] * c.normal[0]) <= 1e-9 * spec.module, "normal misses the pole"
        solved = {c.zone for c in res.contacts}
        for k in range(len(spec.racks.zones)):
            assert k in solved or res.report[f"mesh.contact.{k}"].status == "fail", "unmeshed zone not failed"
        _novikov_arcs_and_clearance(res)

    run("novikov_pair_check", (kw, off), build, check)


@fuzz_settings(8)
@given(data=st.data())
def _drive_check(data):
    pins = data.draw(st.integers(4, 40))
    dz = data.draw(st.sampled_from([-2, -1, 1, 2]))
    big_r = data.draw(st.floats(5.0, 200.0))
    kw = data.draw(maybe_hostile(dict(pins=pins, lobes=pins - dz, pin_circle_radius=big_r,
                                       pin_radius=data.draw(st.floats(0.05, 0.6)) * math.pi * big_r / pins,
                                       eccentricity=data.draw(st.floats(0.1, 0.9)) * big_r * abs(dz) / pins)))
    run("drive_check", kw, lambda: gk.check_drive(gk.DriveSpec(**kw), samples=200),
         lambda res: strict_json(res.to_dict()))


@fuzz_settings(8)
@given(data=st.data())
def _solids(data):
    z = data.draw(st.one_of(st.integers(6, 60), st.integers(60, 2000)))
    m = data.draw(modules)
    internal = data.draw(st.booleans()) and z > 30
    beta = 0.0 if internal else data.draw(st.sampled_from([0.0, 0.0, 15.0]))
    gear = dict(teeth=z, module=m, helix_angle_deg=beta, internal=internal,
                tool=gk.ShaperCutter(20) if internal else None)
    solid = data.draw(maybe_hostile(dict(width=data.draw(st.floats(0.5, 20.0)) * m)))
    tol = data.draw(st.sampled_from([2e-3, 5e-3, 2e-2])) * m

    def build():
        prof = gk.tooth_profile(gk.GearSpec(**gear))
        return prof, gk.gear_solid(prof, gk.SolidSpec(**solid), tol=tol)

    def check(built):
        prof, sol = built
        import trimesh

        v, f = sol.manifold.to_mesh().vert_properties, sol.manifold.to_mesh().tri_verts
        mesh = trimesh.Trimesh(np.asarray(v)[:, :3], np.asarray(f), process=True)
        assert mesh.is_watertight
        if beta == 0.0:
            out = prof.outline(tol / 4)
            x, y = out[:, 0], out[:, 1]
            area = abs(0.5 * float(np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y)))
            perimeter = float(np.sum(np.hypot(np.diff(x, append=x[0]), np.diff(y, append=y[0]))))
            if internal:  # the rim: two modules beyond the root circle
                r_out = float(np.hypot(x, y).max()) + 2 * m
                area = math.pi * r_out ** 2 - area
                perimeter += 2 * math.pi * r_out
            # every boundary is a polyline within tol of the exact one: the area moves by <= tol x length
            width = float(solid["width"])  # a numpy scalar is a valid width (pytest.approx refuses float32)
            assert sol.volume == pytest.approx(area * width, abs=tol * perimeter * width)
    run("solids", (gear, solid, tol), build, check)




def test_pair_check():
    _pair_check()
    assert_clean("pair_check")


def test_novikov_pair_check():
    _novikov_pair_check()
    assert_clean("novikov_pair_check")


def test_drive_check():
    _drive_check()
    assert_clean("drive_check")


def test_solids():
    _solids()
    assert_clean("solids")
