"""Design checks of external and rack pairs: each check on both sides of its limit.

Limits come from the reference digest (1.6, 1.7, 2.2, 3.3); each check is evaluated at the
limit -/+ ``SIDE`` in the shift, where ``SIDE = 1e-3`` is far above the solvers' accuracy
(1e-12) and the kernel's detection threshold, and far below any other limit nearby.
"""
import json
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.optimize import brentq, minimize_scalar

from gearkit.checks import CheckLimits, CheckReport, Finding, check_pair, min_teeth_undercut
from gearkit.errors import SpecError
from gearkit.pair import PairSpec, pair_geometry
from gearkit.families.involute import BasicRack, ShaperCutter

SIDE = 1e-3


def status(spec, finding, **kw):
    return check_pair(spec, **kw).report[finding].status


# ----------------------------------------------------------------------------- report types
def test_report_status_is_the_worst_finding():
    ok = Finding("a", "ok", 1.0, 0.0, "fine", "min")
    warn = Finding("b", "warn", 1.0, 2.0, "low", "min")
    fail = Finding("c", "fail", -1.0, 0.0, "bad", "min")
    assert CheckReport(()).status == "ok"
    assert CheckReport((ok, warn)).status == "warn" and CheckReport((ok, warn)).ok
    r = CheckReport((ok, warn, fail))
    assert r.status == "fail" and not r.ok
    assert r.failures == (fail,) and r.warnings == (warn,)
    assert r["b"] is warn and "c" in r and "z" not in r
    with pytest.raises(KeyError):
        r["z"]
    assert json.loads(json.dumps(r.to_dict()))["findings"][2]["status"] == "fail"
    assert Finding("d", "ok", math.inf, None, "unbounded").to_dict()["value"] is None


@pytest.mark.parametrize("kwargs,field", [
    (dict(id="a", status="bad", value=1.0, limit=None, message=""), "status"),
    (dict(id="a", status="ok", value=float("nan"), limit=None, message=""), "value"),
    (dict(id="a", status="ok", value=1.0, limit=None, message="", sense="up"), "sense"),
])
def test_finding_validation(kwargs, field):
    with pytest.raises(SpecError) as err:
        Finding(**kwargs)
    assert err.value.field == field


def test_duplicate_ids_and_limits_validation():
    f = Finding("a", "ok", 1.0, 0.0, "")
    with pytest.raises(SpecError):
        CheckReport((f, f))
    with pytest.raises(SpecError) as err:
        CheckLimits(min_contact_ratio=0.9)
    assert err.value.field == "min_contact_ratio"
    with pytest.raises(SpecError) as err:
        check_pair(PairSpec(20, 40, 1.0), geometry="sketch")
    assert err.value.field == "geometry"


# ----------------------------------------------------------------------------- 12/24, x = 0
def swept_form_radius(z, x=0.0, m=1.0, alpha_deg=20.0, ha=1.0, c=0.25):
    """Form radius of an undercut rack-cut spur gear by a swept-tool simulation (independent of the
    kernel): the largest radius at which the rack's tip rounding, swept along the rolling motion
    (digest 1.4, [K] fillet formulation), still cuts into the involute flank."""
    al = math.radians(alpha_deg)
    r = z * m / 2
    rb = r * math.cos(al)
    rho = c * m / (1 - math.sin(al))
    vc = x * m - (ha + c) * m + rho
    uc = math.pi * m / 4 - (ha + c) * m * math.tan(al) - rho * (1 - math.sin(al)) / math.cos(al)

    def centre(phi):
        return np.array([(uc + r * phi) * np.cos(phi) - (r + vc) * np.sin(phi),
                         (uc + r * phi) * np.sin(phi) + (r + vc) * np.cos(phi)])

    def flank(radius):
        ar = math.acos(rb / radius)
        half = (math.pi / 2 + 2 * x * math.tan(al)) / z + (math.tan(al) - al) - (math.tan(ar) - ar)
        th = math.pi / z - half
        return np.array([radius * math.sin(th), radius * math.cos(th)])

    phis = np.linspace(-1.5, 1.5, 100001)
    path = centre(phis)

    def clearance(radius):
        p = flank(radius)
        i = int(np.argmin(np.hypot(*(path - p[:, None]))))
        res = minimize_scalar(lambda t: float(np.hypot(*(centre(t) - p))), method="bounded",
                              bounds=(phis[max(i - 1, 0)], phis[min(i + 1, phis.size - 1)]), options={"xatol": 1e-14})
        return res.fun - rho

    return brentq(clearance, rb * (1 + 1e-9), r, xtol=1e-12)


def test_standard_12_24_pair_is_undercut_interfering_with_real_contact_ratio():
    """Issue item 4: z = 12/24, alpha = 20 deg, x = 0."""
    res = check_pair(PairSpec(12, 24, 1.0))
    rep, g = res.report, res.geometry
    assert rep["undercut.1"].status == "warn" and rep["undercut.2"].status == "ok"
    assert rep["interference.1"].status == "fail" and not res.ok
    # the real path starts where the generated involute begins (swept-tool oracle), not at A
    r_form = swept_form_radius(12)
    assert g.gears[0].form_diameter == pytest.approx(2 * r_form, abs=1e-9)
    rb1, ra1 = 6 * math.cos(math.radians(20)), 7.0
    real = (math.sqrt(ra1 ** 2 - rb1 ** 2) - math.sqrt(r_form ** 2 - rb1 ** 2)) / (math.pi * math.cos(math.radians(20)))
    assert g.contact_ratio == pytest.approx(real, abs=1e-9)
    assert rep["contact_ratio"].value == g.contact_ratio
    # the textbook value of the uncut involutes (3.131) is larger, and not what is reported
    a = math.radians(20)
    textbook = sum(z / (2 * math.pi) * (math.sqrt((ra / (z / 2 * math.cos(a))) ** 2 - 1) - math.tan(a))
                   for z, ra in ((12, 7.0), (24, 13.0)))
    assert g.contact_ratio_nominal == pytest.approx(textbook, rel=1e-12)
    assert g.contact_ratio < textbook - 0.2
    assert res.to_dict()["contact_ratio"]["transverse"] == pytest.approx(real, abs=1e-9)


# ----------------------------------------------------------------------------- each check, both sides
def test_undercut_both_sides():
    """z = 13: x_min = 0.239644 (digest 1.6); the generated gear decides the status."""
    x_min = 0.239644
    below = check_pair(PairSpec(13, 40, 1.0, x_min - SIDE, 0.0)).report["undercut.1"]
    above = check_pair(PairSpec(13, 40, 1.0, x_min + SIDE, 0.0)).report["undercut.1"]
    assert (below.status, above.status) == ("warn", "ok")
    assert below.limit == pytest.approx(x_min, abs=5e-7)


def test_min_teeth_both_sides():
    assert min_teeth_undercut(BasicRack(), 0.0) == pytest.approx(17.0973, abs=5e-5)
    assert status(PairSpec(17, 40, 1.0), "min_teeth.1") == "warn"
    assert status(PairSpec(18, 40, 1.0), "min_teeth.1") == "ok"
    # helical (3.105): z_min = 2 h_a* cos(b) / sin^2(a_t) = 14.2802 for b = 20 deg 30'
    assert min_teeth_undercut(BasicRack(), 0.0, helix_angle_deg=20.5) == pytest.approx(14.2802, abs=5e-5)


@pytest.mark.parametrize("xi,limit,lower,upper", [(0.589210, 0.25, "ok", "warn"), (0.876691, 0.25, "warn", "fail"),
                                                  (0.389332, 0.4, "ok", "warn")])
def test_pointing_both_sides(xi, limit, lower, upper):
    """Digest 1.7, z = 13 without tip shortening: s_a = 0.25 m at x = 0.589210, 0 at 0.876691, 0.4 m at 0.389332."""
    lim = CheckLimits(min_tip_thickness=limit)

    def at(x):
        return check_pair(PairSpec(13, 60, 1.0, x, 0.0, tip_rule="standard"), lim).report["pointing.1"]

    assert (at(xi - SIDE).status, at(xi + SIDE).status) == (lower, upper)
    assert at(xi).value == pytest.approx(0.0 if upper == "fail" else limit, abs=5e-6)


@pytest.mark.parametrize("xi,lower,upper", [(0.422776, "ok", "warn"), (0.791114, "warn", "fail")])
def test_contact_ratio_both_sides(xi, lower, upper):
    """Digest 2.2, z1 = 13, z2 = 16, x1 = x2: eps_alpha = 1.2 at 0.422776 and 1 at 0.791114
    (no undercut or interference there, so the real ratio is the tip-to-tip one)."""
    def at(x):
        return check_pair(PairSpec(13, 16, 1.0, x, x)).report["contact_ratio"]

    assert (at(xi - SIDE).status, at(xi + SIDE).status) == (lower, upper)


def test_contact_ratio_iso_lines_are_tip_to_tip_values():
    """Digest 2.2 along x2 = 0: the nominal eps_alpha is 1.2 at x1 = 0.747509 and 1 at 1.32908. Near the
    second, the wheel's tip already reaches below the pinion's form circle: the real ratio is lower
    and the interference check fails."""
    def nominal(x):
        return pair_geometry(PairSpec(13, 16, 1.0, x, 0.0)).contact_ratio_nominal

    assert brentq(lambda x: nominal(x) - 1.2, 0.6, 0.9, xtol=1e-12) == pytest.approx(0.747509, abs=5e-7)
    assert brentq(lambda x: nominal(x) - 1.0, 1.2, 1.4, xtol=1e-12) == pytest.approx(1.32908, abs=5e-6)
    res = check_pair(PairSpec(13, 16, 1.0, 1.32908 - SIDE, 0.0))
    assert res.geometry.contact_ratio < 1.0 <= res.geometry.contact_ratio_nominal
    assert res.report["interference.1"].status == "fail"


def test_fillet_interference_both_sides():
    """Digest 2.2: rho_p2 = rho_l2 at x1 = -0.466913 for z1 = 13, z2 = 16, x2 = x2min = 0.0641778."""
    def at(x):
        return check_pair(PairSpec(13, 16, 1.0, x, 0.0641778)).report["interference.2"]

    assert (at(-0.466913 + SIDE).status, at(-0.466913 - SIDE).status) == ("ok", "fail")
    assert status(PairSpec(20, 40, 1.0), "interference.1") == "ok"


def test_tip_clearance_both_sides():
    """20/40, m = 2, x = 0: a_w = 60, r_f2 = 37.5, so c1 = 22.5 - r_a1; warn below 0.1 m, fail below 0.
    The pinion is cut by a rack of dedendum 1.4 (its root line at r + 1.4 m = 22.8): a tip beyond the
    mate's root exists (the standard rack, h_fP* = 1.25, cuts any blank down to 22.5: clearance 0)."""
    def at(c):
        return check_pair(PairSpec(20, 40, 2.0, tip_diameter1=2 * (22.5 - c),
                                   tool1=BasicRack(dedendum=1.4))).report["tip_clearance.1"]

    assert (at(0.2 + SIDE).status, at(0.2 - SIDE).status) == ("ok", "warn")
    assert (at(SIDE).status, at(-SIDE).status) == ("warn", "fail")
    assert at(0.3).value == pytest.approx(0.3, abs=1e-12)


def test_backlash_both_sides():
    tight = pair_geometry(PairSpec(20, 40, 2.0, 0.3, 0.1)).center_distance
    assert status(PairSpec(20, 40, 2.0, 0.3, 0.1, center_distance=tight + SIDE), "backlash") == "ok"
    assert status(PairSpec(20, 40, 2.0, 0.3, 0.1, center_distance=tight - SIDE), "backlash") == "fail"


def test_rack_pair_and_helical_pair_pass():
    rack = check_pair(PairSpec(14, None, 2.0, 0.2, kind="rack"))
    assert rack.ok and rack.report["interference.2"].sense == "max"
    assert len(rack.to_dict()["gears"]) == 1
    helical = check_pair(PairSpec(8, 14, 6.0, 0.480424, 0.0320283, helix_angle_deg=20.5, face_width=54.0))
    assert helical.report["contact_ratio"].status == "warn"  # eps_alpha = 1.10997 < 1.2
    assert "eps_gamma = 2.1132" in helical.report["contact_ratio"].message


def test_formula_and_generated_geometry_agree_without_undercut():
    spec = PairSpec(19, 37, 3.0, 0.25, -0.1, helix_angle_deg=10.0)
    a, b = check_pair(spec), check_pair(spec, geometry="formula")
    # the generated geometry adds the inspection findings (measured on the generated teeth)
    shared = [f for f in a.report if not f.id.startswith("inspection.")]
    assert [f.status for f in shared] == [f.status for f in b.report]
    assert [f.value for f in shared] == pytest.approx([f.value for f in b.report], abs=1e-8)
    assert {f.id for f in a.report if f.id.startswith("inspection.")} >= {"inspection.span.1", "inspection.span.2"}


@settings(max_examples=60, deadline=None)
@given(kind=st.sampled_from(["external", "internal", "rack"]), z1=st.integers(3, 60), dz=st.integers(1, 80),
       x1=st.floats(-1.0, 1.5), x2=st.floats(-1.0, 1.5), beta=st.sampled_from([0.0, 12.0, 35.0]),
       z0=st.integers(6, 40), mode=st.sampled_from(["formula", "generated"]))
def test_every_spec_gives_a_report_or_a_spec_error(kind, z1, dz, x1, x2, beta, z0, mode):
    """DESIGN 4 (extremes): a spec either yields a complete report or raises SpecError naming a field."""
    z2 = None if kind == "rack" else z1 + dz
    try:
        tool2 = ShaperCutter(min(z0, z2 - 4), addendum=1.3) if kind == "internal" else None
        res = check_pair(PairSpec(z1, z2, 2.0, x1, x2, kind, helix_angle_deg=beta, tool2=tool2), geometry=mode)
    except SpecError as exc:
        assert exc.field and str(exc).startswith(exc.field)
        return
    data = json.loads(json.dumps(res.to_dict(), allow_nan=False))
    assert data["ok"] == all(f["status"] != "fail" for f in data["findings"])
    assert {"undercut.1", "pointing.1", "contact_ratio", "interference.1", "interference.2"} <= \
        {f["id"] for f in data["findings"]}
