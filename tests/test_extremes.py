"""Stability at the extremes of the involute spec space.

A matrix over z (3 ... 10000), x (-1 ... +2, with the exact undercut and pointing limits and
+-1e-12 around them), alpha (10 ... 35 deg), beta (0 ... 60 deg), m (0.01 ... 1000 mm) and
internal tooth differences down to the smallest valid: every spec yields valid geometry or a
``SpecError`` naming its field. Valid geometry means: finite, the half tooth's exact pieces join
(no gap), it stays inside its wedge 0 <= psi <= pi/z, one tooth is a simple polyline, the
outline is closed, counter-clockwise and z-fold symmetric, and its area lies between the root
and tip disks. Oracles: the closed-form undercut limit and form circle, the closed-form tip
thickness (pointing limit), the rack as z -> infinity, and exact scaling.
(The inverse involute's accuracy is tested in test_kernel.py.)
"""
import dataclasses
import math

import numpy as np
import pytest

from gearkit.curves import inv, polar_from_y, polyline_self_intersections
from gearkit.errors import SpecError
from gearkit.families.involute import GearSpec, tooth_profile
from gearkit.families.involute import BasicRack, ShaperCutter

#: relative round-off allowance for exact geometry (lengths relative to the tip radius)
REL = 1e-12
#: a piece's end meets the next piece's start within this (relative): the pieces are exact curves
JOIN_REL = 1e-9
#: sampling tolerance of the outlines checked here, in modules
TOL_M = 1e-3
SPEC_FIELDS = {f.name for f in dataclasses.fields(GearSpec)}


def _tool(desc):
    kind, *args = desc
    return BasicRack(*args) if kind == "rack" else ShaperCutter(*args)


def make(**kw):
    """GearSpec -> profile, or the SpecError it raises (which must name a field and say why).

    ``tool`` is given as a description ("rack", alpha, h_aP*, h_fP*) or ("shaper", z0, alpha)."""
    try:
        if "tool" in kw:
            kw = dict(kw, tool=_tool(kw["tool"]))
        return tooth_profile(GearSpec(**kw))
    except SpecError as exc:
        field = exc.field.split(".")[0].split("[")[0]
        assert field in SPEC_FIELDS | {"pressure_angle_deg", "addendum", "dedendum", "fillet_radius", "teeth", "cutter"}, f"SpecError names an unknown field: {exc}"
        message = str(exc).split(": ", 1)[1]
        assert len(message) > 10, f"SpecError message too terse: {exc}"
        return exc


def assert_valid(prof, tol=None):
    z, m = prof.teeth, prof.module
    tol = TOL_M * m if tol is None else tol
    scale = max(prof.tip_diameter, prof.root_diameter) / 2
    pieces = prof.half.pieces
    ends = [(p(np.array([0.0]))[0], p(np.array([1.0]))[0]) for p in pieces]
    for (a0, a1), (b0, b1) in zip(ends[:-1], ends[1:]):
        assert np.linalg.norm(a1 - b0) <= JOIN_REL * scale, "consecutive pieces must join"
    half, achieved = prof.half_points(tol)
    assert np.isfinite(half).all() and achieved <= tol
    rho, psi = polar_from_y(half)
    assert psi.min() >= -REL * 10 and psi.max() <= math.pi / z + REL * 10, "the half tooth leaves its wedge"
    tooth = prof.tooth_points(tol)
    assert len(polyline_self_intersections(tooth)[0]) == 0, "one tooth must be a simple polyline"
    out = prof.outline(tol)
    assert np.isfinite(out).all()
    n_t = len(out) // z
    assert n_t * z == len(out)
    # z-fold symmetry: rotating by one pitch maps the outline onto itself, shifted by one tooth
    ang = 2 * math.pi / z
    c, s = math.cos(ang), math.sin(ang)
    sample = out[:: max(1, len(out) // 5000)][:5000]
    idx = (np.arange(len(out))[:: max(1, len(out) // 5000)][:5000] + n_t) % len(out)
    rot = np.stack([c * sample[:, 0] - s * sample[:, 1], s * sample[:, 0] + c * sample[:, 1]], -1)
    assert np.abs(rot - out[idx]).max() <= 1e-9 * scale
    # closed and counter-clockwise, area between the root and tip disks
    x, y = out[:, 0], out[:, 1]
    area = 0.5 * float(np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y))
    r_lo, r_hi = sorted((prof.tip_diameter / 2, prof.root_diameter / 2))
    assert math.pi * r_lo ** 2 * (1 - REL) < area < math.pi * r_hi ** 2 * (1 + REL)


CASES = []
CASES += [dict(teeth=z, module=1.0, shift=x) for z in (3, 4, 5, 6, 8, 12, 17, 30, 100, 1000, 10000)
          for x in (-1.0, -0.5, 0.0, 0.5, 1.0, 1.5, 2.0)]
CASES += [dict(teeth=z, module=1.0, shift=x, tool=("rack", a, 1.0, hf)) for a, hf in
          ((10.0, 1.25), (12.5, 1.25), (15.0, 1.25), (25.0, 1.25), (30.0, 1.25), (35.0, 1.1), (35.0, 1.25))
          for z in (3, 8, 20, 200) for x in (0.0, 0.6)]
CASES += [dict(teeth=z, module=1.0, shift=0.3, helix_angle_deg=b) for b in (15.0, 30.0, 45.0, 59.5)
          for z in (4, 20, 300)]
CASES += [dict(teeth=z, module=m, shift=0.2) for m in (0.01, 0.1, 10.0, 100.0, 1000.0) for z in (5, 25)]
CASES += [dict(teeth=z0 + dz, module=1.0, shift=x, internal=True, tool=("shaper", z0))
          for z0 in (8, 12, 20, 40) for dz in (3, 4, 5, 6, 10) for x in (0.0, 0.5)]
CASES += [dict(teeth=z, module=1.0, shift=x, internal=True, tool=("shaper", 20, a))
          for a in (14.5, 25.0, 30.0) for z in (26, 80) for x in (-0.3, 0.0)]


@pytest.mark.parametrize("kw", CASES, ids=lambda kw: ",".join(f"{k}={v}" for k, v in kw.items()))
def test_every_spec_gives_valid_geometry_or_a_clear_spec_error(kw):
    prof = make(**kw)
    if not isinstance(prof, SpecError):
        assert_valid(prof)


def test_the_matrix_mostly_yields_geometry():
    """The matrix must exercise geometry, not only errors: most specs in it are buildable."""
    built = sum(not isinstance(make(**kw), SpecError) for kw in CASES)
    assert built >= 0.8 * len(CASES)


@pytest.mark.parametrize("z0", [8, 20, 40])
def test_internal_tooth_difference_below_the_smallest_valid_is_a_spec_error(z0):
    with pytest.raises(SpecError, match="tool.teeth"):
        GearSpec(z0 + 3, 1.0, internal=True, tool=ShaperCutter(z0))


@pytest.mark.parametrize("kw", [dict(teeth=2, module=1.0), dict(teeth=10, module=0.0),
                                dict(teeth=10, module=float("nan")), dict(teeth=10, module=1.0, shift=float("inf")),
                                dict(teeth=10, module=1.0, helix_angle_deg=80.0), dict(teeth=10.5, module=1.0)])
def test_invalid_input_raises_a_spec_error_naming_the_field(kw):
    with pytest.raises(SpecError) as info:
        GearSpec(**kw)
    assert info.value.field in SPEC_FIELDS


# -- scale invariance ----------------------------------------------------------------------
@pytest.mark.parametrize("z, x", [(3, 0.5), (8, -0.3), (13, 0.0), (40, 1.0), (1000, 0.0)])
def test_geometry_scales_exactly_from_0_01_to_1000_mm(z, x):
    small, big = tooth_profile(GearSpec(z, 0.01, x)), tooth_profile(GearSpec(z, 1000.0, x))
    assert [p.label for p in small.half.pieces] == [p.label for p in big.half.pieces]
    w = np.linspace(0.0, 1.0, 257)
    scale = big.tip_diameter / 2 / 1000.0
    for ps, pb in zip(small.half.pieces, big.half.pieces):
        assert np.abs(ps(w) / 0.01 - pb(w) / 1000.0).max() <= REL * scale
    assert small.undercut == big.undercut and small.pointed == big.pointed


# -- continuity across the undercut limit ----------------------------------------------------
ALPHA = math.radians(20.0)


def _undercut_limit(z):
    """x_min: the rack's straight flank ends exactly on the line of action's end (textbook)."""
    rack = BasicRack()
    h_lim = rack.dedendum - rack.fillet * (1 - math.sin(ALPHA))  # depth where the straight flank ends
    return h_lim - z * math.sin(ALPHA) ** 2 / 2, h_lim


def _form_radius_closed_form(z, x):
    """r_Nf for x >= x_min: the involute generated by the straight flank ends where its end point
    meets the line of action, at sqrt(r_b^2 + (r sin a - (h_lim - x)/sin a)^2) (m = 1)."""
    _, h_lim = _undercut_limit(z)
    r, rb = z / 2, z * math.cos(ALPHA) / 2
    return math.hypot(rb, r * math.sin(ALPHA) - (h_lim - x) / math.sin(ALPHA))


@pytest.mark.parametrize("z", [7, 13, 16])
def test_form_diameter_is_continuous_across_the_undercut_limit(z):
    x_min, _ = _undercut_limit(z)
    rb = z * math.cos(ALPHA) / 2
    deltas = [-1e-3, -1e-6, -1e-9, -1e-12, 0.0, 1e-12, 1e-9, 1e-6, 1e-3, 1e-2]
    forms = []
    for d in deltas:
        prof = tooth_profile(GearSpec(z, 1.0, x_min + d))
        assert_valid(prof)
        r_f = prof.form_diameter / 2
        forms.append(r_f)
        if d >= 0:  # closed form above the limit (no undercut: the flank is the whole involute)
            assert not prof.undercut
            assert r_f == pytest.approx(_form_radius_closed_form(z, x_min + d), abs=1e-12 * rb)
        else:  # below it the trochoid cuts the flank near the base circle: no jump, no spike
            assert rb - 1e-12 * rb <= r_f <= rb + 1e-5
    # near the limit the form circle is the base circle to round-off on both sides
    near = [f for f, d in zip(forms, deltas) if abs(d) <= 1e-9]
    assert max(near) - min(near) <= 1e-12 * rb
    assert tooth_profile(GearSpec(z, 1.0, x_min - 0.05)).undercut  # clearly below: undercut


@pytest.mark.parametrize("z", [7, 13])
def test_profile_changes_continuously_across_the_undercut_limit(z):
    x_min, _ = _undercut_limit(z)
    w = np.linspace(0.0, 1.0, 65)
    below, above = tooth_profile(GearSpec(z, 1.0, x_min - 1e-12)), tooth_profile(GearSpec(z, 1.0, x_min + 1e-12))
    # compare the sampled tooth boundaries both ways: a 2e-12 change in x moves nothing visibly
    pb = np.concatenate([p(w) for p in below.half.pieces])
    pa = np.concatenate([p(w) for p in above.half.pieces])
    from gearkit.distances import distances_to_polyline

    dense_a = above.half_points(1e-9)[0]
    dense_b = below.half_points(1e-9)[0]
    assert distances_to_polyline(pb, dense_a).max() <= 1e-8
    assert distances_to_polyline(pa, dense_b).max() <= 1e-8


# -- the pointing limit ------------------------------------------------------------------------
def _tip_thickness_closed_form(z, x):
    d = z
    da = d + 2 * (1 + x)
    aa = math.acos(d * math.cos(ALPHA) / da)
    return da * (math.pi / (2 * z) + 2 * x * math.tan(ALPHA) / z + inv(ALPHA) - inv(aa))


def _pointing_limit(z):
    lo, hi = 0.0, 3.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if _tip_thickness_closed_form(z, mid) > 0 else (lo, mid)
    return 0.5 * (lo + hi)


@pytest.mark.parametrize("z", [5, 10, 20, 40])
def test_tip_thickness_goes_continuously_to_zero_at_the_pointing_limit(z):
    x_p = _pointing_limit(z)
    for d in (-1e-3, -1e-9, -1e-12, 1e-12, 1e-9, 1e-3):
        prof = tooth_profile(GearSpec(z, 1.0, x_p + d))
        assert_valid(prof)
        expected = max(_tip_thickness_closed_form(z, x_p + d), 0.0)
        assert prof.tip_thickness == pytest.approx(expected, abs=1e-11)
        assert prof.pointed == (d > 0)
    assert tooth_profile(GearSpec(z, 1.0, x_p - 1e-3)).tip_diameter == pytest.approx(z + 2 * (1 + x_p - 1e-3),
                                                                                     rel=REL)
    assert tooth_profile(GearSpec(z, 1.0, x_p + 1e-3)).tip_diameter < z + 2 * (1 + x_p + 1e-3)


# -- the tooth converges to the rack's as z grows -----------------------------------------------
def test_tooth_converges_to_the_rack_tooth_as_z_grows():
    from gearkit.distances import distances_to_polyline
    from gearkit.families.involute.rack import RackSpec, rack_profile

    rack = rack_profile(RackSpec(1.0))  # the basic rack's own profile: the gear's counterpart at z = inf
    exact_rack = np.concatenate([p(np.linspace(0.0, 1.0, 2001)) for p in rack.half.pieces])
    devs = []
    for z in (100, 1000, 10000):
        gear = tooth_profile(GearSpec(z, 1.0))
        rho, psi = polar_from_y(np.concatenate([p(np.linspace(0.0, 1.0, 2001)) for p in gear.half.pieces]))
        unrolled = np.stack([z / 2 * psi, rho - z / 2], -1)  # arc length on the pitch circle, height
        devs.append(float(distances_to_polyline(unrolled, exact_rack).max()))
    # first order in 1/z: ten times the teeth, a tenth of the deviation
    assert devs[0] / devs[1] == pytest.approx(10.0, rel=0.15)
    assert devs[1] / devs[2] == pytest.approx(10.0, rel=0.05)
    assert devs[2] < 3.0 / 10000


# -- meshed extremes: watertight, and Cavalieri's volume ---------------------------------------
MESHED = [dict(teeth=3, module=1.0, shift=0.5), dict(teeth=1000, module=1.0), dict(teeth=6, module=0.01, shift=-0.5),
          dict(teeth=6, module=1000.0, shift=-0.5), dict(teeth=20, module=1.0, shift=0.3, helix_angle_deg=59.5),
          dict(teeth=24, module=1.0, internal=True, tool=("shaper", 20))]


@pytest.mark.parametrize("kw", MESHED, ids=lambda kw: ",".join(f"{k}={v}" for k, v in kw.items()))
def test_extreme_gears_mesh_watertight_with_the_profile_area_times_width(kw):
    from gearkit.solids import SolidSpec, gear_solid

    prof = make(**kw)
    assert not isinstance(prof, SpecError)
    m = prof.module
    tol, width = 1e-2 * m, 2.0 * m
    spec = SolidSpec(width, outer_diameter=prof.root_diameter + 4 * m) if prof.internal else SolidSpec(width)
    solid = gear_solid(prof, spec, tol=tol)
    vertices, faces = solid.arrays()
    assert np.isfinite(vertices).all()
    # watertight and consistently oriented: every directed edge appears once, its reverse once
    edges = np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]])
    keys = edges[:, 0].astype(np.int64) * len(vertices) + edges[:, 1]
    rev = edges[:, 1].astype(np.int64) * len(vertices) + edges[:, 0]
    assert len(np.unique(keys)) == len(keys)
    assert np.array_equal(np.sort(keys), np.sort(rev))
    # Cavalieri: every transverse section is the profile (turned), so volume = section area x width
    out = prof.outline(tol)
    x, y = out[:, 0], out[:, 1]
    area = 0.5 * float(np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y))
    if prof.internal:
        area = math.pi * (prof.root_diameter / 2 + 2 * m) ** 2 - area
    # the mesh's outline is sampled to tol as well: its area differs by at most tol x perimeter
    perimeter = float(np.linalg.norm(np.diff(np.vstack([out, out[:1]]), axis=0), axis=1).sum())
    assert solid.volume == pytest.approx(area * width, abs=2 * tol * perimeter * width)
