"""Blocking lines across an undercut onset: the form circle breaks its slope at x = x_min, so do the
lines that read it; the traced line keeps within 2 tol of its zeros there (the ladder's contract).

The zeros are found independently of any trace: Brent's method on the margin along short segments
x2 = const across the line, at shifts from 1e-9 to 1e-4 on both sides of the onset, which comes
from the closed form x_min = h_a* - z sin^2(alpha) / 2 (rack-cut, ISO normal shift).
"""
import math

import numpy as np
import pytest
from scipy.optimize import brentq

from gearkit.blocking import blocking_contour
from gearkit.blocking.arrays import margins
from gearkit.blocking.onsets import onset_vertices, undercut_onsets
from gearkit.pair import PairSpec

TOL = 1e-9  #: the finest row of the ladder, where the gap beside the onset showed (7.8e-9)
CONTRACT = 2.0  #: achieved / tol (issue 19)
ROOT_TOL = 1e-15  #: Brent's method, x units: far below TOL
BRACKET = 1e-5  #: half width of the segment across the line (its chords near the onset are shorter)
OFFSETS = np.concatenate([-np.logspace(-9, -4, 30), [0.0], np.logspace(-9, -4, 30)])


def _x_min(z: int) -> float:
    return 1.0 - z * math.sin(math.radians(20.0)) ** 2 / 2


def _distance(q, poly) -> float:
    a, b = poly[:-1], poly[1:]
    t = np.clip(np.einsum("ij,ij->i", q - a, b - a) / np.einsum("ij,ij->i", b - a, b - a), 0.0, 1.0)
    return float(np.hypot(*(a + t[:, None] * (b - a) - q).T).min())


def test_onsets_are_the_closed_form_x_min():
    from gearkit.blocking.field import PairField

    onsets = undercut_onsets(PairField(PairSpec(12, 30, 1.0)))
    assert [a for a, _ in onsets] == [0, 1]
    assert onsets[0][1] == pytest.approx(_x_min(12), abs=1e-12)
    assert onsets[1][1] == pytest.approx(_x_min(30), abs=1e-12)


def test_interference_2_within_twice_tol_across_the_undercut_onset():
    c = blocking_contour(PairSpec(12, 30, 1.0), tol=TOL, lines=["interference.2"])
    x_min2 = _x_min(30)
    assert x_min2 == pytest.approx(-0.75467, abs=1e-5)
    comps = c.line("interference.2").components
    checked = 0
    worst = 0.0
    for x2 in x_min2 + OFFSETS:
        for poly in comps:
            s = poly[:, 1] - x2
            hit = np.flatnonzero(s[:-1] * s[1:] <= 0)
            if not hit.size:
                continue
            i = hit[0]
            t = s[i] / (s[i] - s[i + 1]) if s[i] != s[i + 1] else 0.0
            x1 = poly[i, 0] + t * (poly[i + 1, 0] - poly[i, 0])

            def f(u, _x2=x2):
                return margins(c.field, np.array([u]), np.array([_x2]), ["interference.2"])["interference.2"][0]
            root = brentq(f, x1 - BRACKET, x1 + BRACKET, xtol=ROOT_TOL)
            worst = max(worst, _distance(np.array([root, x2]), poly))
            checked += 1
    assert checked >= len(OFFSETS)
    assert worst <= CONTRACT * TOL, f"traced line {worst / TOL:.2f} tol from a zero beside x2 = x_min2"


def test_margin_is_smooth_on_each_side_of_the_onset():
    """The form circle's roll length is read without round-off beside the onset: the zero x1(x2) of
    interference.2 is straight to second order on each side over 1e-6 (read off the form diameter, it
    stepped by 4e-8)."""
    c = blocking_contour(PairSpec(12, 30, 1.0), tol=1e-4, lines=["interference.2"])
    x_min2 = _x_min(30)
    for side in (-1.0, 1.0):
        x2 = x_min2 + side * np.linspace(1e-8, 1e-6, 9)
        x1 = np.array([brentq(lambda u, v=v: margins(c.field, np.array([u]), np.array([v]),
                                                      ["interference.2"])["interference.2"][0], 0.03, 0.06,
                              xtol=ROOT_TOL) for v in x2])
        fit = np.polyfit(x2 - x_min2, x1, 1)
        assert np.abs(np.polyval(fit, x2 - x_min2) - x1).max() < 1e-12


def test_onset_vertex_is_the_corner():
    def F(p, k):
        return p[:, 1] - np.abs(p[:, 0] - 0.3)  # a corner at x1 = 0.3
    lines = [(0, np.array([[-1.0, 1.3], [0.0, 0.3], [1.0, 0.7]]), np.ones(3))]
    out = onset_vertices(F, lines, [(0, 0.3)], {0}, 1e-13)
    assert out[0][1][2] == pytest.approx([0.3, 0.0], abs=1e-12)
    assert len(out[0][1]) == 4
    assert onset_vertices(F, lines, [(0, 0.3)], set(), 1e-13)[0][1].shape == (3, 2)  # not a kinked curve


def test_onset_vertex_beside_the_no_pair_edge_is_the_near_zero():
    """A chord crossing an onset close above the no-pair edge: the zero on the onset line lies between
    the crossing and the edge, where every even sample of the search is undefined, and a second zero
    of the same margin lies farther the other way. The vertex is the near zero (the far one turned the
    chord into a 0.11 long spur across another line). Closed form: F = (y - Y0 - |x| / 2)(Y1 - y) for
    y > 0 (undefined below), zeros on x = 0 at y = Y0 and y = Y1."""
    y0, y1 = 1e-3, 0.2

    def F(p, k):
        return np.where(p[:, 1] > 0.0, (p[:, 1] - y0 - 0.5 * np.abs(p[:, 0])) * (y1 - p[:, 1]), np.nan)
    chord = np.array([[-0.1, y0 + 0.05], [0.1, y0 + 0.05]])  # both ends on the first factor's zeros
    out = onset_vertices(F, [(0, chord, np.ones(2))], [(0, 0.0)], {0}, 1e-14)
    assert len(out[0][1]) == 3
    assert np.allclose(out[0][1][1], [0.0, y0], rtol=0.0, atol=1e-13)
