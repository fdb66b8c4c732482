"""Fuzzing every family and product (hypothesis): valid geometry measured independently, or a clear SpecError.

Each property draws a spec over a wide physical range; about 15 % of the specs get one hostile
field (inf, nan, 1e300, 1e-300, 0, a negative, a string, None, a bool, a numpy scalar). Every spec
must give either

- a valid result: finite; the half tooth sampled to ``tol`` is within ``tol`` of the exact pieces,
  measured independently by dense re-evaluation (``DENSE`` points per piece); the outline closes
  without crossing itself (racks); a pointed tip has thickness 0, never a negative one; the
  summary and check reports are strict JSON (``json.dumps(allow_nan=False)``, parsed back with a
  hook that refuses NaN/Infinity); a pair check never grades a tip larger than the generated (cut)
  tip; a solid is a watertight manifold whose volume is its section times its width; or
- a ``SpecError`` that names a field and says why.

Any other exception is a defect and fails the test. Numpy floating-point warnings are errors.

Fast by default (a few dozen specs per property, ~1 min CPU in all). For a long run set
``GEARKIT_FUZZ_EXAMPLES`` (e.g. 10000 specs per property) and ``GEARKIT_FUZZ_REPORT=FILE`` to
append one JSON line per property: ``{"property", "tried", "valid", "spec_error"}`` (a defect
stops the run with the failing spec, so a finished run has 0 defects)::

    GEARKIT_FUZZ_EXAMPLES=10000 GEARKIT_FUZZ_REPORT=fuzz.jsonl python -m pytest tests/test_fuzz.py -p no:randomly
"""
import json
import math
import os
from collections import Counter

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import gearkit as gk
from gearkit.accuracy import distances_to_polyline
from gearkit.curves import polyline_self_intersections
from gearkit.errors import SpecError

#: specs per property (the long run: GEARKIT_FUZZ_EXAMPLES=10000)
EXAMPLES = int(os.environ.get("GEARKIT_FUZZ_EXAMPLES", "0")) or None
LONG = EXAMPLES is not None
REPORT = os.environ.get("GEARKIT_FUZZ_REPORT")
#: dense re-evaluation points per exact piece (independent deviation measure)
DENSE = 4001
#: the dense measure is itself a polyline of the exact curve: it may read up to its own chord
#: error below the true deviation, never above; allow that much plus round-off
MEASURE_SLACK = 1e-3


def _settings(fast: int, slow_factor: float = 1.0):
    n = fast if not LONG else max(fast, int(EXAMPLES * slow_factor))
    return settings(max_examples=n, deadline=None, derandomize=not LONG, database=None,
                    suppress_health_check=list(HealthCheck))


COUNTS: dict = {}


@pytest.fixture(autouse=True, scope="module")
def _report():
    yield
    if REPORT:
        with open(REPORT, "a") as fh:
            for name, c in sorted(COUNTS.items()):
                fh.write(json.dumps({"property": name, "tried": c["tried"], "valid": c["valid"],
                                     "spec_error": c["spec_error"], "defect": 0}) + "\n")


def _progress(name, c):
    """Every 500 specs of a long run, one line of counts to ``REPORT.progress`` (watch a run live)."""
    if REPORT and c["tried"] % 500 == 0:
        with open(REPORT + ".progress", "a") as fh:
            fh.write(json.dumps({"property": name, **c}) + "\n")


def _run(name, build, check):
    """Build under raised numpy errors; a SpecError must name a field; count the outcome."""
    c = COUNTS.setdefault(name, Counter())
    c["tried"] += 1
    _progress(name, c)
    old = np.seterr(all="raise")
    try:
        try:
            obj = build()
        except SpecError as exc:
            assert exc.field and len(str(exc)) > len(exc.field) + 8, f"terse SpecError: {exc}"
            c["spec_error"] += 1
            return
        check(obj)
        c["valid"] += 1
    finally:
        np.seterr(**old)


def _strict_json(obj):
    text = json.dumps(obj, allow_nan=False)

    def refuse(token):
        raise AssertionError(f"non-standard JSON number {token}")
    return json.loads(text, parse_constant=refuse)


HOSTILE = st.sampled_from([math.inf, -math.inf, math.nan, 1e300, -1e300, 1e-300, 0.0, -1.0, 1e-12, "1", None,
                           True, np.float64(2.5), np.int64(7), np.float32(0.3)])


@st.composite
def _maybe_hostile(draw, kwargs):
    """``kwargs`` with, for ~15 % of draws, one value replaced by a hostile one."""
    kwargs = dict(kwargs)
    if draw(st.integers(0, 99)) < 15:
        key = draw(st.sampled_from(sorted(kwargs)))
        kwargs[key] = draw(HOSTILE)
    return kwargs


modules = st.floats(0.01, 100.0).map(lambda m: float(f"{m:.5g}"))
tols = st.sampled_from([1e-2, 1e-3, 1e-4, 1e-5])


def _tool(desc):
    """A tool from its description ("shaper", args...) / ("rack", args...), built inside the property."""
    if not isinstance(desc, tuple):
        return desc
    kind, *args = desc
    return gk.ShaperCutter(*args) if kind == "shaper" else gk.BasicRack(*args)


def _to_edges(points, polyline):
    """Exact distance of each point to a polyline: against every edge (brute force, for few points)."""
    a, e = polyline[None, :-1], np.diff(polyline, axis=0)[None]
    q = points[:, None, :]
    t = np.clip(np.einsum("pei,pei->pe", q - a, np.broadcast_to(e, (len(points),) + e.shape[1:]))
                / np.maximum(np.einsum("pei,pei->pe", e, e), 1e-300), 0.0, 1.0)
    return np.linalg.norm(q - (a + t[..., None] * e), axis=-1).min(axis=1)


def _check_half(prof, tol):
    half, achieved = prof.half_points(tol)
    assert np.isfinite(half).all() and achieved <= tol
    w = np.linspace(0.0, 1.0, DENSE)
    exact = np.concatenate([p(w) for p in prof.half.pieces])
    d = distances_to_polyline(exact, half)  # via nearest vertices: may overestimate where the curve folds
    far = np.flatnonzero(d > 0.5 * tol)  # those against every edge, exactly
    for chunk in np.array_split(far, max(1, len(far) // 256)):
        if len(chunk):
            d[chunk] = _to_edges(exact[chunk], half)
    true = float(d.max())
    assert true <= tol * (1 + MEASURE_SLACK), f"sampled half tooth is {true:.3g} off at tol {tol:.3g}"
    return half


def _check_gear(prof, tol):
    _check_half(prof, tol)
    assert prof.tip_thickness >= 0.0 and math.copysign(1.0, prof.tip_thickness) > 0
    assert prof.tip_thickness == 0.0 or not prof.pointed  # a smooth crest (dz = 1 disc) has 0 too
    if hasattr(prof, "summary"):
        _strict_json(prof.summary(tol))


# -- families -------------------------------------------------------------------------------------
@st.composite
def involute_kwargs(draw):
    internal = draw(st.booleans())
    alpha = draw(st.sampled_from([14.5, 20.0, 25.0, 30.0]))
    if internal:
        z0 = draw(st.integers(8, 40))
        tool = ("shaper", z0, alpha, draw(st.floats(-0.3, 0.5)))
        z = z0 + draw(st.integers(4, 400))
        beta = 0.0
    else:
        tool = ("rack", alpha, 1.0, draw(st.sampled_from([1.1, 1.25, 1.4])), None,
                draw(st.sampled_from([0.0, 0.0, 0.0, 0.05, 0.1])))
        z = draw(st.one_of(st.integers(3, 80), st.integers(80, 5000)))
        beta = draw(st.sampled_from([0.0, 10.0, 30.0]))
    return draw(_maybe_hostile(dict(teeth=z, module=draw(modules), shift=draw(st.floats(-1.5, 2.5)),
                                    helix_angle_deg=beta, internal=internal, tool=tool,
                                    thinning=draw(st.sampled_from([0.0, 0.0, 0.05])))))


@_settings(40)
@given(kw=involute_kwargs(), tol_m=tols)
def test_involute(kw, tol_m):
    def build():
        return gk.tooth_profile(gk.GearSpec(**{**kw, "tool": _tool(kw["tool"])}))
    _run("involute", build, lambda prof: _check_gear(prof, tol_m * prof.module))


@st.composite
def rack_kwargs(draw):
    if draw(st.booleans()):
        tool = ("shaper", draw(st.integers(8, 60)))
    else:
        tool = ("rack", draw(st.sampled_from([15.0, 20.0, 25.0])), 1.0, draw(st.sampled_from([1.25, 1.3, 1.4])),
                None, draw(st.sampled_from([0.0, 0.0, 0.05, 0.1, 0.15])))
    return draw(_maybe_hostile(dict(module=draw(modules), tool=tool,
                                    helix_angle_deg=draw(st.sampled_from([0.0, 15.0, 30.0])))))


@_settings(30)
@given(kw=rack_kwargs(), tol_m=tols, teeth=st.integers(1, 4))
def test_rack(kw, tol_m, teeth):
    def check(prof):
        tol = tol_m * prof.module
        _check_half(prof, tol)
        out = prof.outline(tol, teeth=teeth)
        assert len(polyline_self_intersections(out)[0]) == 0, "the rack outline crosses itself"
        assert np.allclose(out[-1] - out[0], [teeth * prof.pitch, 0.0], atol=1e-9 * prof.module)
    _run("rack", lambda: gk.rack_profile(gk.RackSpec(**{**kw, "tool": _tool(kw["tool"])})), check)


@_settings(15)
@given(data=st.data(), tol_m=tols)
def test_novikov(data, tol_m):
    system = gk.rack_system(data.draw(st.sampled_from(["dca24", "single-arc"])))
    rack = getattr(system, data.draw(st.sampled_from(["rack1", "rack2"])))
    kw = data.draw(_maybe_hostile(dict(teeth=data.draw(st.integers(3, 400)), module=data.draw(modules),
                                       helix_angle_deg=data.draw(st.floats(5.0, 40.0)))))
    _run("novikov", lambda: gk.novikov_tooth_profile(gk.NovikovGearSpec(rack=rack, **kw)),
         lambda prof: _check_gear(prof, tol_m * prof.module))


@_settings(30)
@given(data=st.data(), tol_m=tols)
def test_cycloid_disc(data, tol_m):
    pins = data.draw(st.integers(3, 80))
    dz = data.draw(st.sampled_from([-3, -2, -1, 1, 2, 3]))
    big_r = data.draw(st.floats(1.0, 500.0))
    kw = data.draw(_maybe_hostile(dict(pins=pins, lobes=pins - dz, pin_circle_radius=big_r,
                                       pin_radius=data.draw(st.floats(0.02, 0.7)) * math.pi * big_r / pins,
                                       eccentricity=data.draw(st.floats(0.02, 0.98)) * big_r * abs(dz) / pins)))
    _run("cycloid_disc", lambda: gk.disc_profile(gk.DriveSpec(**kw)),
         lambda prof: _check_gear(prof, tol_m * prof.module))


@_settings(30)
@given(data=st.data(), tol_m=tols)
def test_pin_gear(data, tol_m):
    z1 = data.draw(st.integers(3, 80))
    m = data.draw(modules)
    kw = data.draw(_maybe_hostile(dict(module=m, pins=z1, wheel_teeth=data.draw(st.integers(3, 300)),
                                       pin_radius=data.draw(st.floats(0.02, 0.98)) * m * z1 / 2 * math.sin(math.pi / z1),
                                       addendum=data.draw(st.floats(0.3, 2.0)))))
    _run("pin_gear", lambda: gk.pin_gear_wheel(gk.PinGearSpec(**kw)),
         lambda prof: _check_gear(prof, tol_m * prof.module))


@_settings(20)
@given(data=st.data(), tol_m=tols)
def test_cycloid_pair_gear(data, tol_m):
    z1 = data.draw(st.integers(4, 120))
    kw = data.draw(_maybe_hostile(dict(module=data.draw(modules), pinion_teeth=z1,
                                       wheel_teeth=z1 + data.draw(st.integers(0, 300)),
                                       clock=data.draw(st.booleans()))))
    which = data.draw(st.sampled_from([1, 2]))
    _run("cycloid_pair_gear", lambda: gk.cycloid_gear(gk.CycloidPairSpec(**kw), which),
         lambda prof: _check_gear(prof, tol_m * prof.module))


# -- products -------------------------------------------------------------------------------------
@_settings(12, 0.1)
@given(data=st.data())
def test_pair_check(data):
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
    kw = data.draw(_maybe_hostile(kw))

    def build():
        spec = {**kw, "tool2": _tool(kw.get("tool2"))}
        if spec.get("center_distance") == "tight":
            base = gk.pair_geometry(gk.PairSpec(**{**spec, "center_distance": None}))
            spec = {**spec, "center_distance": base.tight_center_distance + data.draw(st.floats(-0.2, 0.8)) * m}
        return gk.check_pair(gk.PairSpec(**spec))

    def check(res):
        _strict_json(res.to_dict())
        for gear, prof in zip(res.geometry.gears, res.profiles):
            if not prof.internal:
                assert gear.tip_diameter <= prof.tip_diameter * (1 + 1e-12), "checked tip beyond the cut tip"
    _run("pair_check", build, check)


@_settings(6, 0.02)
@given(data=st.data())
def test_novikov_pair_check(data):
    z1 = data.draw(st.integers(8, 60))
    m = data.draw(modules)
    kw = data.draw(_maybe_hostile(dict(teeth1=z1, teeth2=z1 + data.draw(st.integers(0, 100)), module=m,
                                       helix_angle_deg=data.draw(st.floats(8.0, 30.0)),
                                       face_width=data.draw(st.floats(5.0, 40.0)) * m)))
    off = data.draw(st.floats(-0.6, 0.6))

    def build():
        spec = gk.NovikovPairSpec(**kw)
        a = gk.novikov_pair_geometry(spec).reference_center_distance
        from dataclasses import replace
        return gk.check_novikov(replace(spec, center_distance=a + off * spec.module))

    _run("novikov_pair_check", build, lambda res: _strict_json(res.report.to_dict()))


@_settings(8, 0.05)
@given(data=st.data())
def test_drive_check(data):
    pins = data.draw(st.integers(4, 40))
    dz = data.draw(st.sampled_from([-2, -1, 1, 2]))
    big_r = data.draw(st.floats(5.0, 200.0))
    kw = data.draw(_maybe_hostile(dict(pins=pins, lobes=pins - dz, pin_circle_radius=big_r,
                                       pin_radius=data.draw(st.floats(0.05, 0.6)) * math.pi * big_r / pins,
                                       eccentricity=data.draw(st.floats(0.1, 0.9)) * big_r * abs(dz) / pins)))
    _run("drive_check", lambda: gk.check_drive(gk.DriveSpec(**kw), samples=200),
         lambda res: _strict_json(res.to_dict()))


@_settings(8, 0.05)
@given(data=st.data())
def test_solids(data):
    z = data.draw(st.one_of(st.integers(6, 60), st.integers(60, 2000)))
    m = data.draw(modules)
    internal = data.draw(st.booleans()) and z > 30
    beta = 0.0 if internal else data.draw(st.sampled_from([0.0, 0.0, 15.0]))
    gear = dict(teeth=z, module=m, helix_angle_deg=beta, internal=internal,
                tool=gk.ShaperCutter(20) if internal else None)
    solid = data.draw(_maybe_hostile(dict(width=data.draw(st.floats(0.5, 20.0)) * m)))
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
            assert sol.volume == pytest.approx(area * solid["width"], abs=tol * perimeter * solid["width"])
    _run("solids", build, check)


@_settings(10, 0.02)
@given(data=st.data())
def test_gear_command_line(data, capsys):
    from gearkit.cli import main

    argv = ["gear", "-z", str(data.draw(st.sampled_from(["40", "7", "300", "0", "x", "1e9"]))),
            "-m", str(data.draw(st.sampled_from(["1", "0.05", "inf", "-2", "nan"]))),
            "-x", str(data.draw(st.sampled_from(["0", "1.3", "-0.8", "2.5", "1e300"]))), "--json"]
    if data.draw(st.booleans()):
        argv += ["--tol", data.draw(st.sampled_from(["1e-3", "1e-12", "0", "inf"]))]
    c = COUNTS.setdefault("gear_command_line", Counter())
    c["tried"] += 1
    _progress("gear_command_line", c)
    try:
        code = main(argv)
    except SystemExit as exc:  # argparse refuses a malformed number: exit 2
        code = exc.code
    out = capsys.readouterr()
    assert code in (0, 2), out.err
    if code == 0:
        _strict_json(json.loads(out.out))
        c["valid"] += 1
    else:
        assert "Traceback" not in out.err and "error: " in out.err.strip().splitlines()[-1]
        c["spec_error"] += 1
