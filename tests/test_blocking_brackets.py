"""Roots on segments (gearkit.blocking.brackets.segment_roots) against closed-form roots.

The functions are cubics in the distance along a fixed direction, ``s + c s^3`` with ``s = (p - p0) . n``
(c >= 0: one real zero, at p0), so the exact root on each segment is where the segment crosses that
line. ``tol`` is the solver's stated accuracy (max-norm in x, the unit the chords are measured in).
"""
import numpy as np
import pytest

from gearkit.blocking.brackets import segment_roots

TOL = 1e-6


def _problem(seed, n=400):
    rng = np.random.default_rng(seed)
    ang = rng.uniform(0, 2 * np.pi, n)
    nrm = np.column_stack([np.cos(ang), np.sin(ang)])  # the zero line's normal, one per segment
    p0 = rng.uniform(-1, 1, (n, 2))
    curv = rng.choice([0.0, 1.0, 30.0, 1000.0], n)
    length = 10 ** rng.uniform(-3, 0, n)
    ta = rng.uniform(0.02, 0.98, n)  # where along the segment the zero lies
    dirs = nrm + rng.uniform(-0.7, 0.7, (n, 2))  # the segment's direction, not parallel to the line
    dirs /= np.hypot(*dirs.T)[:, None]
    a = p0 - ta[:, None] * length[:, None] * dirs
    b = a + length[:, None] * dirs

    def f(p, which):
        s = np.einsum("ij,ij->i", p - p0[which], nrm[which])
        return s + curv[which] * s ** 3

    f.normal = nrm  # the gradient at the root (s = 0)
    idx = np.arange(n)
    exact = a + (np.einsum("ij,ij->i", p0 - a, nrm) / np.einsum("ij,ij->i", b - a, nrm))[:, None] * (b - a)
    return f, a, b, f(a, idx), f(b, idx), idx, exact


@pytest.mark.parametrize("seed", range(4))
@pytest.mark.parametrize("tol", [1e-4, 1e-6, 1e-9])
def test_roots_within_tol_of_the_closed_form(seed, tol):
    f, a, b, fa, fb, idx, exact = _problem(seed)
    r = segment_roots(f, a, b, fa, fb, tol, idx)
    assert np.all(np.abs(r - exact).max(axis=1) <= tol)


@pytest.mark.parametrize("seed", range(4))
@pytest.mark.parametrize("tol", [1e-6, 1e-9])
def test_guard_closes_brackets_in_few_rounds(seed, tol):
    """On mildly curved margins (|F| at the ends within 10 % of linear, as along a chord's normal) the
    guard beside each estimate closes the bracket from the far side: regula falsi alone moves one end
    only, and on these problems took 17-100 rounds and 4.2-4.7 evaluations a root."""
    f, a, b, fa, fb, idx, exact = _problem(seed)
    lin = np.maximum(np.abs(fa) / np.hypot(*(a - exact).T), np.abs(fb) / np.hypot(*(b - exact).T))
    sel = np.flatnonzero(lin <= 1.1)
    calls = []

    def counted(p, which):
        calls.append(len(p))
        return f(p, which)

    r = segment_roots(counted, a[sel], b[sel], fa[sel], fb[sel], tol, idx[sel])
    assert np.all(np.abs(r - exact[sel]).max(axis=1) <= tol)
    assert len(calls) <= 16, calls
    assert sum(calls) <= 4.0 * len(sel), (sum(calls), len(sel))


def test_undefined_stretch_and_exact_zeros():
    """NaN on part of the segment (the root outside it) and roots hit exactly: still within tol."""
    f, a, b, fa, fb, idx, exact = _problem(7)
    t_root = np.hypot(*(exact - a).T) / np.hypot(*(b - a).T)

    def g(p, which):
        v = f(p, which)
        t = np.hypot(*(p - a[which]).T) / np.hypot(*(b[which] - a[which]).T)
        hole = (which % 3 == 0) & (np.abs(t - t_root[which]) > 0.3) & (t > 0.01) & (t < 0.99)
        return np.where(hole, np.nan, v)

    r = segment_roots(g, a, b, fa, fb, TOL, idx)
    assert np.all(np.abs(r - exact).max(axis=1) <= TOL)
    # a root on a segment's end, or the midpoint exactly a root: returned as it is
    mid = 0.5 * (a + b)
    r = segment_roots(lambda p, w: np.einsum("ij,ij->i", p - mid[w], b[w] - a[w]), a, b, -np.ones(len(a)),
                      np.ones(len(a)), TOL, idx)
    assert np.all(np.abs(r - mid).max(axis=1) <= TOL)


@pytest.mark.parametrize("seed", range(3))
def test_slope_at_the_root_not_across_the_segment(seed):
    """``slopes=True``: the derivative of F along the segment at its root, against the closed form: at
    the root (s = 0) the gradient of s + c s^3 is n, so |dF/ds| along the segment's unit direction d is
    |n . d|. Read off a bracket about tol wide, it holds to 1 % where the secant across the segment's
    ends is up to many times larger (the curved margins, c = 30 and 1000, as beside a saddle); the
    roots are those returned without slopes."""
    f, a, b, fa, fb, idx, exact = _problem(seed)
    r, g = segment_roots(f, a, b, fa, fb, TOL, idx, slopes=True)
    d = (b - a) / np.hypot(*(b - a).T)[:, None]
    exact_slope = np.abs(np.einsum("ij,ij->i", f.normal, d))
    assert np.array_equal(r, segment_roots(f, a, b, fa, fb, TOL, idx))
    assert np.all(np.abs(g / exact_slope - 1.0) <= 0.01)
    secant = np.abs(fb - fa) / np.hypot(*(b - a).T)
    assert np.count_nonzero(secant > 2.0 * exact_slope) > 20  # the segment's secant would be far off
