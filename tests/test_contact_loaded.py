"""Loaded tooth contact: micro-geometry, mesh stiffness, loaded TE, load sharing, pattern, Harris map.

Oracles: the involute turned by ``Delta / r_b`` (an exact normal offset), ISO 6336-1's published
method-B polynomial written out here, the rigid analysis itself (zero torque), symmetry, and the
deflection of one pair from ISO's single stiffness (Harris map).
"""
import json
import math

import numpy as np
import pytest

from gearkit.cli import main
from gearkit.contact import (Deviations, analyse_loaded, analyse_pair, harris_map, iso_mesh_stiffness,
                             long_tip_relief)
from gearkit.errors import SpecError
from gearkit.families.involute import GearSpec, Modification, tooth_profile
from gearkit.pair import PairSpec, pair_geometry

SPUR = PairSpec(20, 40, 2.0, face_width=20.0)
#: torque giving a line load F_t / b = 100 N/mm on SPUR (ISO 6336-1's lower bound for c_gamma)
T100 = 100.0 * 20.0 * 20.0 / 1e3


def test_profile_modification_turns_the_flank_by_the_deviation_over_the_base_radius():
    c_a, d_ca = 0.02, 42.0
    g0, g1 = GearSpec(20, 2.0), GearSpec(20, 2.0, modification=Modification(tip_relief=c_a, tip_relief_diameter=d_ca))
    p0, p1 = tooth_profile(g0), tooth_profile(g1)
    rb, ra = g0.base_diameter / 2, g0.blank_tip_diameter / 2
    l_start, l_tip = math.sqrt((d_ca / 2) ** 2 - rb ** 2), math.sqrt(ra ** 2 - rb ** 2)
    for r in (20.0, 20.9, 21.3, 21.7, 21.95):
        roll = math.sqrt(r * r - rb * rb)
        delta = c_a * max(roll - l_start, 0.0) / (l_tip - l_start)  # linear relief, by hand
        # both flanks turn by delta / r_b: the arc thickness at r shrinks by 2 r delta / r_b
        assert p0.thickness_at(r) - p1.thickness_at(r) == pytest.approx(2 * r * delta / rb, abs=1e-9)
    tol = 1e-3
    assert p1.achieved(tol) <= tol  # the modified flank keeps the outline's tol contract


def test_modification_rejects_an_ambiguous_start():
    with pytest.raises(SpecError, match="tip_relief_roll"):
        Modification(tip_relief=0.01, tip_relief_diameter=42.0, tip_relief_roll=1.0)
    with pytest.raises(SpecError, match="tip_relief_diameter"):
        Modification(tip_relief=0.01)


def test_unmodified_pair_at_zero_torque_is_the_rigid_analysis_exactly():
    loaded = analyse_loaded(SPUR, 0.0, steps=200)
    rigid = analyse_pair(SPUR, 200)
    assert np.array_equal(loaded.transmission_error, rigid.transmission_error)
    assert loaded.transmission_error_pp == rigid.transmission_error_pp
    # touching pairs averaged over the steps: the rigid contact ratio to the step size
    assert loaded.contact_ratio_loaded == pytest.approx(rigid.contact_ratio, abs=2.0 / 200)


def test_loaded_te_grows_linearly_with_torque_at_low_load():
    low = analyse_loaded(SPUR, [2.0, 4.0], steps=200)
    ratio = np.mean(low[1].transmission_error) / np.mean(low[0].transmission_error)
    # linear springs give 2 exactly; the contact approach's logarithm (d ln delta / d ln w = 1 - 1/(2 L),
    # L = ln(4 h1 h2 / b_H^2) - nu / (1 - nu) >= 8 here, about a third of the compliance) takes at most
    # 1/(2 L) / 3 ~ 2 % off, and the stiffening when the contact lengthens a little more
    assert 2.0 * (1 - 0.05) <= ratio <= 2.0
    assert low[0].transmission_error_pp > 0


def _iso_q(z1, z2, x1, x2, beta_deg=0.0):
    """ISO 6336-1 method B, q' = 1 / c'_th (mm um / N), from its published coefficients."""
    beta = math.radians(beta_deg)
    alpha_t = math.atan(math.tan(math.radians(20.0)) / math.cos(beta))
    beta_b = math.atan(math.tan(beta) * math.cos(alpha_t))
    zn1, zn2 = (z / (math.cos(beta_b) ** 2 * math.cos(beta)) for z in (z1, z2))
    return (0.04723 + 0.15551 / zn1 + 0.25791 / zn2 - 0.00635 * x1 - 0.11654 * x1 / zn1 - 0.00193 * x2
            - 0.24188 * x2 / zn2 + 0.00529 * x1 ** 2 + 0.00182 * x2 ** 2)


@pytest.mark.parametrize("z1, z2, x1, x2, beta, eps", [(20, 40, 0.0, 0.0, 0.0, 1.635), (17, 53, 0.3, -0.1, 12.0, 1.5)])
def test_iso_stiffness_is_the_standards_formula(z1, z2, x1, x2, beta, eps):
    iso = iso_mesh_stiffness(z1, z2, x1, x2, contact_ratio=eps, helix_angle_deg=beta)
    c_b = (1 + 0.5 * (1.2 - 1.25)) * 1.0  # h_fP = 1.25 m_n, alpha_Pn = 20 deg
    single = 1 / _iso_q(z1, z2, x1, x2, beta) * 0.8 * 1.0 * c_b * math.cos(math.radians(beta))
    assert iso.single == pytest.approx(single, rel=1e-12)
    assert iso.mesh == pytest.approx(single * (0.75 * eps + 0.25), rel=1e-12)
    assert iso.mesh_beta == pytest.approx(0.85 * iso.mesh, rel=1e-12)


def test_mean_mesh_stiffness_of_a_steel_pair_is_within_iso_range_and_near_its_value():
    res = analyse_loaded(SPUR, T100, steps=200)
    eps = pair_geometry(SPUR).contact_ratio
    iso = iso_mesh_stiffness(20, 40, contact_ratio=eps)
    assert 14.0 <= res.mesh_stiffness_mean <= 20.0  # ISO 6336-1's range for solid steel spur gears
    assert res.mesh_stiffness_mean == pytest.approx(iso.mesh, rel=0.10)  # a different model: 10 %
    assert res.torque_residual < 1e-9 and res.hertz_change < 1e-6


def test_load_sharing_and_te_are_symmetric_for_a_symmetric_pair():
    n = 240  # a multiple of 4: the pitch-point passage (a quarter pitch) falls on a step
    res = analyse_loaded(PairSpec(30, 30, 2.0, face_width=10.0), 30.0, steps=n)
    te, top = res.transmission_error, res.sharing.max(axis=1)
    idx = np.arange(n)
    # on the conjugate path (both pairs on their involutes, zero rigid gap) the pair's compliance is the
    # same at mirrored positions: symmetric about some step k, te[k - i] == te[k + i]. Beyond the path ends
    # a tip corner touches, and the mate's tip entering is not the mirror of the driver's tip leaving (the
    # TE is the mate's angle): those steps are left out (the larger share leaves the 0.44-0.56 band there)
    inner = (np.abs(top - 0.5) < 0.06)
    errors = []
    for k in range(n):
        a, b = (k - idx) % n, (k + idx) % n
        both = inner[a] & inner[b]
        errors.append(np.max(np.abs(te[a] - te[b])[both]) if both.sum() > n // 10 else np.inf)
    k = int(np.argmin(errors))
    # the contact points are located to ~1e-7 mm (the rigid gap is flat along the flank, so the minimiser
    # is known to the square root of round-off): the compliances there agree to ~1e-8 relative
    rel = 1e-6
    assert errors[k] <= rel * np.max(np.abs(te))
    a, b = (k - idx) % n, (k + idx) % n
    both = inner[a] & inner[b]
    assert np.max(np.abs(top[a] - top[b])[both]) <= rel
    assert top.max() == pytest.approx(1.0)  # the single-pair zone carries everything


def test_tip_relief_tuned_for_the_design_load_minimises_the_te_there():
    design = T100
    g = pair_geometry(SPUR)
    # deflection of one pair carrying the whole load, from ISO's single stiffness c'
    w = design * 1e3 / (g.gears[0].base_diameter / 2) / SPUR.face_width  # N/mm along the line of action
    deflection = w / iso_mesh_stiffness(20, 40, contact_ratio=g.contact_ratio).single * 1e-3  # mm
    reliefs = np.arange(0.0, 0.0201, 0.0025)
    hmap = harris_map(SPUR, [design / 2, design], reliefs, design_torque=design, steps=120)
    assert deflection * 0.6 <= hmap.best_relief <= deflection * 1.4
    j = list(hmap.torques).index(design)
    assert hmap.pp[list(reliefs).index(hmap.best_relief), j] < 0.5 * hmap.pp[0, j]


def test_crowned_helical_pair_under_misalignment_moves_its_pattern_and_raises_the_pressure():
    spec = PairSpec(20, 40, 2.0, helix_angle_deg=15.0, face_width=20.0)
    crowned = (Modification(lead_crowning=0.01), None)
    straight = analyse_loaded(spec, 60.0, modifications=crowned, steps=120, slices=20)
    tilted = analyse_loaded(spec, 60.0, modifications=crowned, steps=120, slices=20,
                            deviations=Deviations(misalignment_out_of_plane=0.02))

    def centre(res):
        load = res.pattern.sum(axis=0)
        return float(np.sum(load * res.zeta) / np.sum(load))
    slice_width = spec.face_width / 20
    assert abs(centre(straight) - spec.face_width / 2) <= slice_width
    # the separation grows towards zeta = b: the load moves towards zeta = 0
    assert centre(tilted) < spec.face_width / 2 - 2 * slice_width
    assert tilted.max_contact_pressure > straight.max_contact_pressure * 1.02


def test_long_tip_relief_spans_the_double_contact_zone():
    m1, m2 = long_tip_relief(SPUR, 0.01)
    g = pair_geometry(SPUR)
    eps_excess = (g.contact_ratio - 1) * g.base_pitch  # (eps_alpha - 1) p_bt on each tip
    assert m1.tip_relief_roll == pytest.approx(eps_excess, rel=1e-9)
    assert m2.tip_relief_roll == pytest.approx(eps_excess, rel=1e-9)


def test_cli_loaded_json_keys_accuracy_and_plots(tmp_path, capsys):
    te, pattern = tmp_path / "te.png", tmp_path / "pattern.png"
    code = main(["contact", "--z1", "20", "--z2", "40", "-m", "2", "--width", "20", "--torque", "40",
                 "--tip-relief", "0.008", "--crowning", "0.005", "--misalignment", "0.01", "--steps", "80",
                 "--slices", "8", "--json", "-o", str(te), "-o", str(pattern)])
    assert code == 0
    out = json.loads(capsys.readouterr().out)
    loaded = out["loaded"]
    assert {"transmission_error_pp", "load_sharing", "contact_ratio_loaded", "max_contact_pressure",
            "mesh_stiffness_mean"} <= set(loaded)
    assert loaded["accuracy"]["steps"] == 80 and loaded["accuracy"]["slices"] == 8
    assert loaded["accuracy"]["slice_width"] == pytest.approx(20.0 / 8)
    assert all(abs(sum(f) - 1.0) < 1e-9 for f in loaded["load_sharing"]["fraction"])
    for f in (te, pattern):
        assert f.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


@pytest.mark.parametrize("extra, field", [(["--tip-relief", "abc"], "--tip-relief"), (["--tip-relief", "0.01@99"],
                                          "--tip-relief"), (["--torque", "-1"], "torque")])
def test_cli_loaded_bad_input_is_one_line_exit_2(extra, field, capsys):
    args = ["contact", "--z1", "20", "--z2", "40", "-m", "2", "--width", "20", "--steps", "16"]
    if "--torque" not in extra:
        args += ["--torque", "10"]
    assert main(args + extra) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and field in err[0]


def test_a_tooth_ahead_by_its_pitch_deviation_carries_the_unloaded_mesh_and_shifts_te_by_it():
    f = [0.0] * 20
    f[18], f[19] = 0.005, -0.005  # tooth 18 stands 5 um ahead, tooth 19 back in place
    base = analyse_loaded(SPUR, 0.0, steps=60, cycles=3)
    dev = analyse_loaded(SPUR, 0.0, steps=60, cycles=3, deviations=Deviations(pitch_deviations1=tuple(f)))
    rb2 = pair_geometry(SPUR).gears[1].base_diameter / 2
    shift = (dev.transmission_error - base.transmission_error) * rb2  # mm along the line of action
    # while tooth 18 (-2 mod 20) is in mesh the mate rests on it, 5 um ahead: TE = -5 um / r_b2
    # (the arm of the contact normal comes from central differences of step 1e-7: ~1e-8 relative)
    assert shift.min() == pytest.approx(-0.005, rel=1e-6)
    assert np.max(shift) <= 1e-12  # a tooth ahead never opens the mesh


def test_runout_adds_a_once_per_turn_te_of_its_amplitude():
    e = 0.01
    # unloaded, every contact lies on the line of action (under load, corner contacts off it tilt the normal)
    turn = analyse_loaded(SPUR, 0.0, steps=40, cycles=20, deviations=Deviations(runout1=e))
    base = analyse_loaded(SPUR, 0.0, steps=40, cycles=20)
    rb2 = pair_geometry(SPUR).gears[1].base_diameter / 2
    shift = (turn.transmission_error - base.transmission_error) * rb2
    # the centre's displacement e, turning once per turn, projected on the line of action: amplitude e
    # sampled every 0.45 deg: the peaks are missed by at most 1 - cos(0.225 deg) < 1e-5
    assert np.ptp(shift) / 2 == pytest.approx(e, rel=1e-5)
    spectrum = np.abs(np.fft.rfft(shift - shift.mean()))
    assert int(np.argmax(spectrum)) == 1  # once per turn


def test_relieved_outline_loses_the_area_of_the_turned_flanks():
    from scipy.integrate import quad

    c_a, d_ca, z = 0.02, 42.0, 20
    g0 = GearSpec(z, 2.0)
    mod = Modification(tip_relief=c_a, tip_relief_diameter=d_ca, relief_shape="arc")
    p0, p1 = tooth_profile(g0), tooth_profile(GearSpec(z, 2.0, modification=mod))
    rb, ra = g0.base_diameter / 2, g0.blank_tip_diameter / 2
    l_start, l_tip = math.sqrt((d_ca / 2) ** 2 - rb ** 2), math.sqrt(ra ** 2 - rb ** 2)
    arc_r = ((l_tip - l_start) ** 2 + c_a ** 2) / (2 * c_a)  # the arc tangent at the start through (L_tip, C_a)

    def delta(r):
        x = math.sqrt(r * r - rb * rb) - l_start
        return arc_r - math.sqrt(arc_r ** 2 - x * x) if x > 0 else 0.0

    # each flank turns by delta / r_b: the polar area r dr times the angle, over the relieved radii
    removed = 2 * z * quad(lambda r: r * delta(r) / rb, d_ca / 2, ra)[0]

    def area(p):
        xy = p.outline(1e-6)
        return 0.5 * abs(np.dot(xy[:, 0], np.roll(xy[:, 1], -1)) - np.dot(xy[:, 1], np.roll(xy[:, 0], -1)))
    # each outline is within 1e-6 mm of its curve: area error below (2/3) tol x perimeter (~260 mm)
    assert area(p0) - area(p1) == pytest.approx(removed, abs=2 * (2 / 3) * 1e-6 * 260)
    assert delta(ra) == pytest.approx(c_a)
