"""Circular-arc racks: the construction against the reference digest's drawing recipes and validation
vectors (recomputed there independently), validation with reasons, presets as data, TOML files."""
import math
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from gearkit.errors import SpecError
from gearkit.families.novikov.presets import (PRESETS_FILE, RackSystem, load_rack_system, rack_presets, rack_system,
                                              rack_system_from_dict)
from gearkit.families.novikov.racks import ArcRack, ArcSpec

D = math.radians
#: the digest prints 5 decimals (4 for angles in degrees)
PRINTED = 0.6e-5
PRINTED_DEG = 0.6e-4
DELTA1 = 6 + 20 / 60 + 52 / 3600  # 6 deg 20' 52"


def dca(transition="relief-arc", **kw):
    args = dict(contact_angle_deg=24.0, addendum=0.9, dedendum=1.1, convex=ArcSpec(1.30, 0.0163, 0.6289),
                concave=ArcSpec(1.42, 0.0325, 0.7086), transition=transition)
    if transition == "relief-arc":
        args.update(transition_radius=0.5196, transition_angle_deg=DELTA1)
    args.update(kw)
    return ArcRack(**args)


def _arc_deg(seg):
    cx, cy, r, a0, a1 = seg.data
    return (cx, cy, r, math.degrees(a0), math.degrees(a1))


def _close(actual, expected, length_tol=PRINTED, angle_tol=PRINTED_DEG, angles=()):
    for k, (a, e) in enumerate(zip(actual, expected)):
        tol = angle_tol if k in angles else length_tol
        a_wrapped = (a - e + 180) % 360 - 180 + e if k in angles else a
        assert a_wrapped == pytest.approx(e, abs=tol), (k, a, e)


def test_dca24_preset_is_the_digest_closure_c_recipe():
    rack = rack_system("dca24").rack1
    assert rack.transition_angle_deg == pytest.approx(DELTA1, abs=1e-12)
    assert rack == dca(transition_angle_deg=rack.transition_angle_deg, name="dca24", title=rack.title,
                       provenance=rack.provenance)
    d = rack.geometry.drawing
    assert [s.kind for s in d] == ["line", "arc", "arc", "arc", "arc"]
    _close(d[0].data, (0.0, 0.9, 0.32455, 0.9))
    _close(_arc_deg(d[1]), (-0.6289, 0.0163, 1.30, 42.8256, 6.3478), angles=(3, 4))
    _close(_arc_deg(d[2]), (1.17954, 0.21748, 0.5196, -173.6522, -125.2418), angles=(3, 4))
    _close(_arc_deg(d[3]), (2.2794, 0.0325, 1.42, 189.7055, 225.8323), angles=(3, 4))
    _close(_arc_deg(d[4]), (math.pi / 2, -0.69699, 0.40301, -134.1677, -90.0), angles=(3, 4))
    pts = rack.geometry.points()
    np.testing.assert_allclose(pts[2], (0.66313, 0.16003), atol=PRINTED)  # E1
    np.testing.assert_allclose(pts[3], (0.87972, -0.20689), atol=PRINTED)  # E2


def test_dca24_validation_vectors():
    rack = dca()
    np.testing.assert_allclose(rack.contact_point("convex"), (0.55871, 0.54506), atol=PRINTED)
    np.testing.assert_allclose(rack.contact_point("concave"), (0.98216, -0.54507), atol=PRINTED)
    assert rack.contact_thickness() == pytest.approx(1.11742, abs=PRINTED)
    assert rack.contact_space() == pytest.approx(1.17727, abs=PRINTED)
    assert rack.backlash == pytest.approx(0.05985, abs=PRINTED)
    assert rack.geometry.tip_land == pytest.approx(0.32455, abs=PRINTED)
    assert rack.geometry.root_radius == pytest.approx(0.40301, abs=PRINTED)
    # closure C working windows: convex 6.35 .. 42.83 deg, concave 9.71 .. 45.83 deg
    np.testing.assert_allclose(np.degrees(rack.geometry.convex_window), (6.3478, 42.8256), atol=PRINTED_DEG)
    np.testing.assert_allclose(np.degrees(rack.geometry.concave_window), (9.7055, 45.8323), atol=PRINTED_DEG)


def test_closure_a_common_tangent_recipe():
    d = dca("common-tangent").geometry.drawing
    assert [s.kind for s in d] == ["line", "arc", "line", "arc", "arc"]
    _close(_arc_deg(d[1]), (-0.6289, 0.0163, 1.30, 42.8256, 21.0520), angles=(3, 4))
    _close(d[2].data, (0.58433, 0.48328, 0.95417, -0.47759))
    _close(_arc_deg(d[3]), (2.2794, 0.0325, 1.42, 201.0520, 225.8323), angles=(3, 4))


def test_single_arc_preset_follows_the_digest_construction():
    system = rack_system("single-arc")
    pinion, wheel = system.racks
    assert system.kind == "single-arc" and pinion.kind == "convex" and wheel.kind == "concave"
    # the digest's illustration (s_1 = 1.5, no backlash): K = (0.54904, 0.75), O_1 = (-0.75, 0) on the pitch line
    ill = ArcRack(30.0, 1.2, 0.3, ArcSpec(1.5, 0.0, 0.75), None, "flank-line", None, 5.0, 0.2)
    np.testing.assert_allclose(ill.contact_point("convex"), (0.54904, 0.75), atol=PRINTED)
    # the wheel (own frame: the digest's common frame turned 180 deg about (pi/4, 0))
    w = wheel.geometry
    common = lambda p: (math.pi / 2 - p[0], -p[1])  # noqa: E731
    np.testing.assert_allclose(common(wheel.centre("concave")), (-0.87990, -0.075), atol=PRINTED)
    np.testing.assert_allclose(common(w.points()[1]), (0.76839, 0.0), atol=PRINTED)  # tip edge
    np.testing.assert_allclose(np.degrees(w.concave_window), (2.6053, 52.6393), atol=1e-3)  # apex rounded 1e-5
    assert w.root_radius == pytest.approx(0.2, abs=1e-4)
    # built-in backlash: the pinion thinned by 0.04
    assert system.zones[0].backlash == pytest.approx(0.04, abs=PRINTED)
    assert system.zones[0].height == pytest.approx(0.75, abs=PRINTED)


@pytest.mark.parametrize("rack", [dca(), dca("common-tangent"), *rack_system("single-arc").racks])
def test_drawing_is_continuous_monotone_and_tangent_where_intended(rack):
    d = rack.geometry.drawing
    for a, b in zip(d[:-1], d[1:]):
        pa, ta = a.endpoints()
        pb, tb = b.endpoints()
        assert np.linalg.norm(pa[1] - pb[0]) < 1e-12
        turn = math.degrees(math.asin(np.clip(ta[1][0] * tb[0][1] - ta[1][1] * tb[0][0], -1, 1)))
        corner = a.label == "tip" or (a.label == "relief" and b.label == "flank" and a.kind == "arc")
        if not corner:
            assert abs(turn) < 1e-9, (a.label, b.label, turn)
        else:  # tip edge and the relief's ridge are convex corners of the rack tooth (right turns)
            assert turn < -1.0
    p0, t0 = d[0].endpoints()
    pn, tn = d[-1].endpoints()
    assert p0[0][0] == 0.0 and pn[1][0] == pytest.approx(math.pi / 2, abs=1e-12)
    assert abs(t0[0][1]) < 1e-12 and abs(tn[1][1]) < 1e-12  # horizontal on both axes: G1 with the mirror
    # the profile is a graph y(x), falling from the tip to the root
    pts = np.concatenate([s.evaluate(np.linspace(0, 1, 200))[0] for s in d])
    assert np.all(np.diff(pts[:, 0]) >= -1e-12) and np.all(np.diff(pts[:, 1]) <= 1e-12)


@pytest.mark.parametrize("rack", [dca(), rack_system("single-arc").rack1, rack_system("single-arc").rack2])
def test_tool_chain_is_continuous_with_the_cutter_on_the_right(rack):
    m = 3.0
    chain = rack.half_tooth(m)
    for a, b in zip(chain[:-1], chain[1:]):
        assert np.linalg.norm(a.endpoints()[0][1] - b.endpoints()[0][0]) < 1e-12 * m
    start, _ = chain[0].endpoints()
    end, _ = chain[-1].endpoints()
    assert start[0][0] > math.pi * m / 2 and end[1][0] < 0.0  # past the space axis and the tooth axis
    p, _, n = chain[0].evaluate(np.linspace(0, 1, 2001))
    low = int(np.argmin(p[:, 1]))
    assert p[low, 1] == pytest.approx(-rack.dedendum * m, abs=1e-6 * m)  # the cutter tip cuts the root line
    assert n[low, 1] < -0.99999  # ... and its outward normal points into the blank (-v)
    assert end[1][1] > rack.addendum * m  # the cutter root clears the gear tip


def _raises(field, words, **kw):
    with pytest.raises(SpecError) as exc:
        kw.pop("_build")() if "_build" in kw else dca(**kw)
    assert exc.value.field == field
    for w in words:
        assert w in str(exc.value)


def test_invalid_racks_raise_with_the_reason():
    # arcs that do not meet: the relief arc is too small to reach the concave arc
    _raises("transition_radius", ["does not reach the concave arc"], transition_radius=0.05)
    # the concave arc must be larger than the convex one
    _raises("concave.radius", ["must exceed"], concave=ArcSpec(1.25, 1.25 * math.sin(D(24)) - 0.54506, 0.5))
    # negative built-in backlash (l_f too large)
    _raises("concave.centre_offset", ["backlash", "must be positive"], concave=ArcSpec(1.42, 0.0325, 0.80))
    # contact heights that disagree
    _raises("concave.centre_shift", ["contact heights disagree"], concave=ArcSpec(1.42, 0.05, 0.7086))
    # a flank perpendicular to the pitch line
    _raises("transition_angle_deg", ["generates no"], transition_angle_deg=0.0)
    # a pointed rack tooth and a root fillet too large for the space
    _raises("convex.centre_offset", ["pointed"], convex=ArcSpec(1.30, 0.0163, 1.20),
            concave=ArcSpec(1.42, 0.0325, 1.25))
    _raises("root_radius", ["full root radius"], root_radius=0.5)
    _raises("transition", ["relief-arc"], transition="none")


def test_invalid_single_arc_pairs_raise_with_the_reason():
    pinion, wheel = rack_system("single-arc").racks
    # a pinion arc larger than the wheel's, through the same contact point K
    k = pinion.contact_point("convex")
    big = ArcRack(30.0, 1.2, 0.3, ArcSpec(1.7, k[1] - 1.7 * 0.5, 1.7 * math.cos(D(30)) - k[0]), None, "flank-line",
                  None, 5.0, 0.2)
    with pytest.raises(SpecError, match="must exceed"):
        RackSystem(big, wheel)
    tight = ArcRack(30.0, 1.2, 0.3, ArcSpec(1.5, 0.0, 0.70), None, "flank-line", None, 5.0, 0.2)
    with pytest.raises(SpecError, match="backlash"):
        RackSystem(tight, wheel)
    with pytest.raises(SpecError, match="do not make a pair"):
        RackSystem(pinion, dca())
    with pytest.raises(SpecError, match="contact angles differ"):
        RackSystem(dca(), dca(contact_angle_deg=25.0, concave=ArcSpec(1.42, 1.42 * math.sin(D(25))
                                                                       - (1.3 * math.sin(D(25)) + 0.0163), 0.65)))


@settings(max_examples=50, deadline=None)
@given(alpha=st.floats(18, 32), ra=st.floats(1.0, 1.8), d_rho=st.floats(0.05, 0.3), xa=st.floats(-0.05, 0.05),
       half_s=st.floats(0.45, 0.65), j=st.floats(-0.02, 0.1), dha=st.floats(0.2, 0.6), dhf=st.floats(0.4, 0.8),
       rj=st.floats(0.3, 0.8), d1=st.floats(0.1, 0.9), z=st.integers(6, 80))
def test_every_double_arc_rack_is_valid_geometry_or_a_clear_spec_error(alpha, ra, d_rho, xa, half_s, j, dha, dhf,
                                                                        rj, d1, z):
    """Design-like parameters (about a third of them valid): each gives a rack whose profile is a falling
    graph from the tip line to the root line, cutting a gear with both working arcs, or a SpecError
    naming a field."""
    from gearkit.families.novikov import NovikovGearSpec, tooth_profile

    a = D(alpha)
    rf = ra + d_rho
    hk = ra * math.sin(a) + xa
    la = ra * math.cos(a) - half_s
    try:
        rack = ArcRack(alpha, hk + dha, hk + dhf, ArcSpec(ra, xa, la),
                       ArcSpec(rf, rf * math.sin(a) - hk, la + d_rho * math.cos(a) - j / 2), "relief-arc", rj,
                       2.0 + d1 * (alpha - 10.0))
    except SpecError as exc:
        assert exc.field and len(str(exc)) > len(exc.field) + 10
        return
    assert rack.backlash > 0
    d = rack.geometry.drawing
    pts = np.concatenate([s.evaluate(np.linspace(0, 1, 50))[0] for s in d])
    assert np.isfinite(pts).all()
    assert np.all(np.diff(pts[:, 0]) >= -1e-9) and np.all(np.diff(pts[:, 1]) <= 1e-9)
    assert pts[0, 1] == pytest.approx(rack.addendum) and pts[-1, 1] == pytest.approx(-rack.dedendum)
    try:
        prof = tooth_profile(NovikovGearSpec(z, 1.0, rack, 10.0))
    except SpecError:
        return
    assert prof.tip_diameter <= prof.blank_tip_diameter + 1e-9
    assert np.isfinite(prof.outline(1e-3)).all()


def test_presets_are_labelled_unverified_and_named():
    presets = rack_presets()
    assert set(presets) >= {"dca24", "single-arc"}
    for name, system in presets.items():
        assert system.name == name and not system.verified
        assert "verify against the standard before production" in system.provenance
        assert all(r.name == name and not r.verified for r in system.racks)


def test_a_verified_preset_is_a_data_change(tmp_path):
    text = PRESETS_FILE.read_text().split("[single-arc]")[0]
    text = text.replace("[dca24", "[my-standard").replace("verified = false", "verified = true")
    f = tmp_path / "my-standard.toml"
    f.write_text("\n".join(line for line in text.splitlines() if not line.startswith("[my-standard]")
                           and not line.startswith("title") and not line.startswith("provenance")
                           and not line.startswith("relief") and not line.startswith("they pass")
                           and not line.startswith("thickness") and not line.startswith("UNVERIFIED")
                           ).replace("[my-standard.rack]", "[rack]"))
    system = rack_system(str(f))
    assert system.verified and system.name == "my-standard"
    assert [r.geometry for r in system.racks] == [r.geometry for r in rack_system("dca24").racks]


def test_rack_files_report_bad_content(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text("[rack]\ncontact_angle_deg = 24\naddendum = 0.9\n")
    with pytest.raises(SpecError, match="dedendum"):
        load_rack_system(bad)
    bad.write_text("[rack]\ncontact_angle_deg = 24\naddendum = 0.9\ndedendum = 1.1\nwidth = 3\n")
    with pytest.raises(SpecError, match="unknown keys"):
        load_rack_system(bad)
    bad.write_text("[rack\n")
    with pytest.raises(SpecError, match="not valid TOML"):
        load_rack_system(bad)
    with pytest.raises(SpecError, match="no rack file"):
        load_rack_system(tmp_path / "missing.toml")
    with pytest.raises(SpecError, match="unknown rack"):
        rack_system("dca27")
    with pytest.raises(SpecError) as exc:
        rack_system_from_dict({"rack": {"contact_angle_deg": 24.0, "addendum": 0.9, "dedendum": 1.1,
                                        "convex": {"radius": -1.0}}})
    assert exc.value.field == "rack.convex.radius"
    assert Path(PRESETS_FILE).is_file()


def test_a_rack_file_is_written_as_a_preset_is(tmp_path):
    """A preset's block copied from the presets file, renamed, loads as that preset (issue 13); a file of
    several systems is refused naming the form; ``standard`` names the default preset."""
    text = PRESETS_FILE.read_text()
    block = text[text.index("[dca24]"):text.index("[single-arc]")].replace("[dca24", "[mine")
    f = tmp_path / "copy.toml"
    f.write_text(block)
    system = rack_system(str(f))
    assert system.name == "mine" and not system.verified
    assert [r.geometry for r in system.racks] == [r.geometry for r in rack_system("dca24").racks]
    f.write_text(text)  # the whole presets file: two systems
    with pytest.raises(SpecError, match="must hold one rack system"):
        load_rack_system(f)
    assert rack_system("standard") is rack_system("dca24")
