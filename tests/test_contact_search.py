"""The contact solver's search in blocks and its offset without fmod: the same answers as the plain ways.

Oracles: the search over the whole batch at once (one block) for the blocked search (the bounds
must agree to the bit: every value is made by the same operations on the same numbers), and
``np.fmod`` for the mate's offset from its space centre.
"""
import numpy as np
import pytest

from gearkit.contact import pair_mesh, simulate
from gearkit.contact import search as search_module
from gearkit.contact.solver import solve
from gearkit.pair import PairSpec


@pytest.mark.parametrize("spec", [PairSpec(20, 40, 2.0), PairSpec(20, None, 1.0, 0.2, kind="rack")],
                         ids=["20/40", "rack"])
def test_the_search_in_blocks_is_the_search_at_once(spec, monkeypatch):
    mesh = pair_mesh(spec)
    phi = np.linspace(-0.4, 0.4, 301)
    monkeypatch.setattr(search_module, "_BLOCK", 1 << 30)  # the whole batch in one block
    whole = solve(mesh, phi, 1e-9)
    monkeypatch.setattr(search_module, "_BLOCK", 200)  # a few driver angles a block
    blocks = solve(mesh, phi, 1e-9)
    for field in whole.__dataclass_fields__:
        assert np.array_equal(getattr(whole, field), getattr(blocks, field), equal_nan=True), field


def test_a_cycle_in_blocks_is_the_cycle_at_once(monkeypatch):
    mesh = pair_mesh(PairSpec(18, 41, 1.0, 0.3, -0.1))
    monkeypatch.setattr(search_module, "_BLOCK", 1 << 30)
    whole = simulate(mesh, 200)
    monkeypatch.setattr(search_module, "_BLOCK", 500)
    blocks = simulate(mesh, 200)
    assert blocks.contact_ratio == whole.contact_ratio
    assert np.array_equal(blocks.transmission_error, whole.transmission_error)
    assert np.array_equal(blocks.pairs_in_contact, whole.pairs_in_contact)


@pytest.mark.parametrize("spec", [PairSpec(20, 40, 2.0), PairSpec(17, 1000, 1.0),
                                  PairSpec(20, None, 1.0, 0.2, kind="rack")], ids=["z40", "z1000", "rack"])
def test_the_offset_from_the_space_centre_is_fmods(spec):
    """The mate's offset ``u`` (formed without fmod) against ``np.fmod`` on values where the division
    rounds: every multiple of the pitch up to 3000 pitches either way and the three floats on each
    side of it, random values, zeros, the pitch itself and its half, nan and inf."""
    mesh = pair_mesh(spec)
    pitch = mesh.pitch2
    base = np.arange(-3000, 3001) * pitch
    values = [base, np.random.default_rng(3).uniform(-3000 * pitch, 3000 * pitch, 20000),
              np.array([0.0, -0.0, pitch, -pitch, pitch / 2, -pitch / 2, 5e-324, -5e-324, 1e-300])]
    for way in (np.inf, -np.inf):
        near = base
        for _ in range(3):
            near = np.nextafter(near, way)
            values.append(near)
    psi = np.concatenate(values)
    r = np.fmod(psi, pitch)
    expected = np.where(r < 0, r + pitch, r) - pitch / 2
    assert np.array_equal(mesh.space_offset(psi), expected)
    angle = np.abs(psi) <= np.pi  # an angle of arctan2: the quotient's range is known beforehand
    assert np.array_equal(mesh.space_offset(psi[angle], polar=True), expected[angle])
    with np.errstate(invalid="ignore"):
        odd = np.array([np.nan, np.inf, -np.inf, 1e300, -1e300, 1.0])
        r = np.fmod(odd, pitch)
        assert np.array_equal(mesh.space_offset(odd), np.where(r < 0, r + pitch, r) - pitch / 2, equal_nan=True)


def test_the_driver_probes_are_the_table_at_the_minimisers_parameters():
    """``Boundary.probes``: each polyline interval's parameters spaced as the minimiser spaces them
    (``a + f (b - a)``, ``f`` from 0 to 1) and the table's points there, read afresh."""
    mesh = pair_mesh(PairSpec(18, 41, 1.0, 0.3, -0.1))
    drv = mesh.driver
    t, x, y = drv.probes(7)
    frac = np.linspace(0.0, 1.0, 7)
    assert np.array_equal(t, drv.ta + frac[:, None] * (drv.tb - drv.ta))
    p = drv.table.evaluate(np.broadcast_to(drv.piece, t.shape), t)
    assert np.array_equal(x, p[..., 0]) and np.array_equal(y, p[..., 1])


@pytest.mark.parametrize("spec", [PairSpec(20, 40, 2.0), PairSpec(20, None, 1.0, 0.2, kind="rack")],
                         ids=["20/40", "rack"])
def test_the_mates_radius_alone_is_the_radius_of_both_coordinates(spec):
    """``Mesh.to_mate_radius`` (no offset formed) against ``to_mate_xy``'s radius, to the bit, and against the
    oracle of the plain geometry: a gear's radial coordinate is the distance from the mate's centre, whatever
    the turn (within round-off of the coordinates); a rack's is the height below the centre distance."""
    mesh = pair_mesh(spec)
    rng = np.random.default_rng(5)
    x, y = rng.uniform(-30, 30, (2, 500))
    phi = rng.uniform(-1, 1, 500)
    rho = mesh.to_mate_radius(x, y, phi)
    assert np.array_equal(rho, mesh.to_mate_xy(x, y, phi)[0])
    if mesh.kind == "rack":
        assert np.array_equal(rho, mesh.a - y)
    else:
        dx, dy = x - mesh.centre2[0], y - mesh.centre2[1]
        # the turn's products and sums and the turn's cosine and sine: a few units in the last place of the
        # largest coordinate each
        roundoff = 8 * np.finfo(float).eps * np.abs(np.stack([dx, dy])).max()
        assert np.abs(rho - np.hypot(dx, dy)).max() <= roundoff


def test_each_halfs_winner_by_reduction_is_the_sorts():
    """The refinement's winner of each half (group): the first of its least values, a group of nans its first row.
    Oracle: a stable sort by group then value, as before the reduction, on random groups (sorted, as the search
    hands them over, and unsorted) with equal values, signed zeros, infinities and nans."""
    from gearkit.contact.solver import _winners

    rng = np.random.default_rng(11)
    for trial in range(3000):
        n = int(rng.integers(0, 40))
        half = rng.integers(0, 8, n) if trial % 3 == 0 else np.sort(rng.integers(0, 8, n))
        value = rng.choice([0.0, -0.0, 0.5, 1.0, np.inf, -np.inf, np.nan], n)
        order = np.lexsort((value, half))
        first = np.ones(n, bool)
        first[1:] = half[order][1:] != half[order][:-1]
        assert np.array_equal(_winners(value, half), order[first])
