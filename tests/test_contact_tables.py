"""The contact simulation on tables of the teeth agrees with the simulation on the exact pieces.

``Mesh(..., tables=True)`` (the default) searches and minimises on piecewise polynomial copies of
both teeth (:mod:`gearkit.contact.table`) and evaluates each final contact on the exact pieces;
``tables=False`` evaluates the exact pieces throughout (the path before the tables). Oracle: that
exact path, and the formula contact ratio.

Named tolerances (derived, not measured):

* ``mesh.noise / mesh.arm_scale`` (rad; mm for a rack): the mesh's own statement of how well a
  contact's position is known (round-off along the normal over the smallest arm). Both paths
  evaluate the final contact on the same exact pieces at minimisers that agree to Brent's tolerance
  (1e-8 of a parameter, a value change of its square), so their TE and backlash agree within it.
* ``RATIO = 1e-6``: the simulated contact ratio's own resolution (its step-count independence test).
* ``LOCATE = 1e-6 m``: where along the flanks a contact lies (the argument of a minimum: known to
  about the square root of round-off), as in the contact tests.
* ``ARM = 1e-7``: relative accuracy of a contact normal's arm on the exact path (central differences
  on the exact pieces, as the contact tests' normal backlash); the tables take it from their
  derivative.
* ``TABLE_TOL`` of the outer radius: the tables' stated accuracy, checked against the exact pieces
  at random points.
"""
import math

import numpy as np
import pytest

from gearkit.contact import Mesh, pair_mesh, simulate
from gearkit.contact.loaded import loaded_cycle
from gearkit.contact.table import TABLE_TOL
from gearkit.curves import inv
from gearkit.families.involute import Modification, ShaperCutter
from gearkit.pair import PairSpec, pair_geometry

RATIO = 1e-6
LOCATE = 1e-6
ARM = 1e-7
#: a medium-worn shaper (x_c = 0.3), as the internal contact tests (digest 3.2)
SHAPER = ShaperCutter(20, addendum=1.3)

PAIRS = {
    "standard 20/40 m=2": (PairSpec(20, 40, 2.0), {}),
    "shifted 18/41": (PairSpec(18, 41, 1.0, 0.3, -0.1), {}),
    "undercut 12/24": (PairSpec(12, 24, 1.0), {}),
    "backlash 20/40": (PairSpec(20, 40, 1.0, center_distance=30.05), {}),
    "rack, x = 0.2": (PairSpec(20, None, 1.0, 0.2, kind="rack"), {}),
    "internal 46/49 x2 = 0.52": (PairSpec(46, 49, 1.0, 0.0, 0.52, kind="internal", shift_convention="cutter",
                                          tool1=SHAPER, tool2=SHAPER), {}),
    "helical 20/40, 6 slices": (PairSpec(20, 40, 2.0, helix_angle_deg=15.0, face_width=20.0),
                                {"face_width": 20.0, "helix_angle_deg": 15.0, "slices": 6}),
}

#: pairs whose simulated contact ratio is the formula's (the contact tests' oracle)
FORMULA = ("standard 20/40 m=2", "shifted 18/41", "internal 46/49 x2 = 0.52", "helical 20/40, 6 slices")


def _exact(mesh):
    return Mesh(mesh.gear1, mesh.gear2, mesh.a, tables=False)


@pytest.mark.parametrize("name", sorted(PAIRS))
def test_tables_agree_with_the_exact_pieces(name):
    spec, kw = PAIRS[name]
    mesh = pair_mesh(spec)
    fast, exact = simulate(mesh, 64, **kw), simulate(_exact(mesh), 64, **kw)
    position = mesh.noise / mesh.arm_scale
    assert np.abs(fast.transmission_error - exact.transmission_error).max() <= position
    r_w2 = 1.0 if mesh.kind == "rack" else mesh.pitch_radii[1]
    assert abs(fast.backlash - exact.backlash) <= position * r_w2
    assert fast.contact_ratio == pytest.approx(exact.contact_ratio, abs=RATIO)
    assert fast.total_contact_ratio == pytest.approx(exact.total_contact_ratio, abs=RATIO)
    assert np.array_equal(fast.pairs_in_contact, exact.pairs_in_contact)
    assert fast.interference.found == exact.interference.found
    assert np.abs(fast.contacts["point"] - exact.contacts["point"]).max() <= LOCATE * spec.module
    if name in FORMULA:  # the formula, on the fast path (undercut shortens the 12/24 pair's)
        assert fast.contact_ratio == pytest.approx(pair_geometry(spec).contact_ratio, abs=1e-3)


def test_tables_are_within_their_stated_accuracy():
    mesh = pair_mesh(PairSpec(20, 40, 2.0))
    outer = max(abs(mesh.mate.rho_tip), abs(mesh.mate.rho_root), mesh.driver.radius_range[1])
    assert 0 < mesh.table_deviation <= TABLE_TOL * outer
    rng = np.random.default_rng(7)
    k = rng.integers(0, len(mesh.driver.pieces), 20000)
    t = rng.random(20000)
    drv = mesh.driver
    assert np.abs(drv.evaluate(k, t) - drv.evaluate(k, t, exact=True)).max() <= 2 * TABLE_TOL * outer
    rho = rng.uniform(mesh.mate.rho_root, mesh.mate.rho_tip, 20000)
    w_fast = mesh.mate.width(rho)[0]
    w_exact = mesh.mate.width(rho, exact=True)[0]
    assert (np.abs(w_fast - w_exact) * rho).max() <= 2 * TABLE_TOL * outer


def test_loaded_analysis_agrees_with_the_exact_pieces():
    """The loaded cycle reads the rigid kernel's gaps: a tip-relieved pinion under 100 N/mm."""
    spec = PairSpec(20, 40, 2.0, face_width=20.0)
    mods = (Modification(tip_relief=0.01, tip_relief_diameter=42.0), None)
    mesh = pair_mesh(spec, modifications=mods)
    args = dict(face_width=20.0, zeta=np.array([10.0]), shifts=np.zeros(1), lead=np.zeros(1), steps=64)
    fast, exact = loaded_cycle(mesh, 40.0, **args), loaded_cycle(_exact(mesh), 40.0, **args)
    position = mesh.noise / mesh.arm_scale
    assert np.abs(fast.rigid_transmission_error - exact.rigid_transmission_error).max() <= position
    # the loads solve a linear system on those gaps and the contact normals' arms, which the exact path
    # takes from central differences (ARM relative) and the tables from their derivative
    te = np.abs(exact.transmission_error).max()
    assert np.abs(fast.transmission_error - exact.transmission_error).max() <= position + ARM * te
    assert fast.contact_ratio_loaded == pytest.approx(exact.contact_ratio_loaded, abs=RATIO)
    # the stiffness is load over approach along the normals, so it inherits the arms' relative accuracy
    assert math.isclose(fast.mesh_stiffness_mean, exact.mesh_stiffness_mean, rel_tol=ARM)


@pytest.mark.parametrize("spec, z2, x2", [(PairSpec(20, 40, 2.0), 40, 0.0), (PairSpec(18, 41, 1.0, 0.3, -0.1), 41, -0.1)],
                         ids=["z40", "z41 x=-0.1"])
def test_the_mates_exact_width_is_the_closed_form_involute(spec, z2, x2):
    """``HalfWidth.exact`` (the exact pieces every reported contact is valued on): on the involute flank the half
    space width is ``pi / z - psi(rho)``, ``psi = (pi / 2 + 2 x tan alpha) / z + inv alpha - inv alpha_rho``,
    ``cos alpha_rho = r_b / rho`` (closed form), within ``ulps`` units in the last place of the tip radius."""
    ulps = 16
    half = pair_mesh(spec).mate
    alpha = math.radians(20.0)
    r_b = spec.module * z2 / 2 * math.cos(alpha)
    rho = np.random.default_rng(5).uniform(max(half.rho_root, r_b), half.rho_tip, 20000)
    w, piece, _, _ = half.exact(rho)
    flank = np.array(half.labels)[np.maximum(piece, 0)] == "flank"
    assert flank.sum() > rho.size // 2
    r = rho[flank]
    psi = (math.pi / 2 + 2 * x2 * math.tan(alpha)) / z2 + inv(alpha) - inv(np.arccos(r_b / r))
    assert (np.abs(w[flank] - (math.pi / z2 - psi)) * r).max() <= ulps * np.finfo(float).eps * half.rho_tip


def test_components_gathered_together_are_each_ones_horner_sum_to_the_bit():
    """The tables gather every component's coefficients in one array operation and sum the value's and both
    derivatives' polynomials side by side (the shorter ones led by zeros): against each point's own Horner sum
    (``_horner``, the tables' fitting check) and the stored first-derivative coefficients (``evaluate`` with
    ``derivative``), to the bit; the three sums of one point agree with the slope ``derivatives`` returns."""
    from gearkit.contact.table import _horner

    mesh = pair_mesh(PairSpec(20, 40, 2.0))
    drv = mesh.driver.table
    rng = np.random.default_rng(5)
    k = rng.integers(0, len(mesh.driver.pieces), 3000)
    t = rng.random(3000)
    j, s = drv._locate(k, t)
    p, d = drv.evaluate(k, t, derivative=True)
    assert np.array_equal(p, _horner(drv._coef.transpose(2, 1, 0)[j], s))
    assert np.array_equal(d, _horner(drv._dcoef.transpose(2, 1, 0)[j], s) * drv._inv[j][:, None])
    value, first, _ = drv.derivatives(k, t)
    assert np.array_equal(np.stack(value, -1), p) and np.array_equal(np.stack(first, -1), d)


def test_table_derivatives_are_their_polynomials_derivatives():
    """The tables' slopes for Newton's steps (``CurveTable.derivatives``, ``WidthTable.derivatives``: the first and
    second derivatives of each sub-interval's polynomial, from its coefficients gathered once) against
    ``numpy.polynomial``'s derivatives of the same polynomials, evaluated by ``polyval``: equal within Horner's
    round-off, ``2 D eps`` times the sum of the terms' magnitudes (degree ``D``), scaled as the derivatives are."""
    from numpy.polynomial import polynomial as P

    from gearkit.contact.table import DEGREE

    mesh = pair_mesh(PairSpec(20, 40, 2.0))
    rng = np.random.default_rng(9)
    eps = np.finfo(float).eps

    def expected(coef, s, order, scale):
        c = P.polyder(coef, order) if order else coef
        bound = 2 * DEGREE * eps * P.polyval(np.abs(s), np.abs(c), tensor=False)
        return P.polyval(s, c, tensor=False) * scale ** order, bound * scale ** order

    drv = mesh.driver.table
    k = rng.integers(0, len(mesh.driver.pieces), 5000)
    t = rng.random(5000)
    j, s = drv._locate(k, t)
    got = drv.derivatives(k, t)
    for comp in range(2):
        coef = drv._coef[comp][:, j]
        for order in range(3):
            want, bound = expected(coef, s, order, drv._inv[j])
            assert np.all(np.abs(got[order][comp] - want) <= bound)
    mate = mesh.mate.table
    rho = rng.uniform(mesh.mate.rho_root, mesh.mate.rho_tip, 5000)
    j, row, x, s = mate._locate(rho)
    plain = ~mate._grazing[row]  # in rho itself (next to a stationary end the chain rule follows)
    got = mate.derivatives(rho)
    coef = mate._coef[0][:, j]
    for order in range(3):
        want, bound = expected(coef, s, order, mate._inv[j])
        assert np.all(np.abs(got[order] - want)[plain] <= bound[plain])
    assert plain.mean() > 0.5
