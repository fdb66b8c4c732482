"""The margins only an internal pair has, on arrays: exit jamming, plunge trimming and the tip sweep
(:mod:`gearkit.pair.internal`'s functions at many shift pairs at once), read off the pair geometry
``g`` of :mod:`gearkit.blocking.arrays` (its working centre distance, tips, roots and thicknesses).

>>> import numpy as np
>>> from gearkit.blocking.arrays import margins
>>> from gearkit.blocking.field import PairField
>>> from gearkit.families.involute.tools import ShaperCutter
>>> from gearkit.pair import PairSpec
>>> f = PairField(PairSpec(46, 49, 1.0, kind="internal", tool2=ShaperCutter(20)))
>>> m = margins(f, np.array([0.0]), np.array([1.0]), ["exit_jamming", "trimming.plunge"])
>>> bool(np.isfinite(m["exit_jamming"][0]) and np.isfinite(m["trimming.plunge"][0]))
True
"""
from __future__ import annotations

import math

import numpy as np

from gearkit.curves import inv
from gearkit.pair.internal import SWEEP_RESOLUTION
from gearkit.pair.sweep import SWEEP_ENOUGH, sweep_depth
from gearkit.pair.tooling import half_angle

__all__ = ["exit_jamming", "plunge_gap", "tip_clearance_margin"]

PLUNGE_SAMPLES = 97  #: samples of the plunge-trimming gap (over a quarter wave of the shaper's corner: at
#: most two extrema), then Newton on the derivative from the smallest; the check samples 801


def exit_jamming(g):
    """:func:`~gearkit.pair.internal.exit_jamming_margin`, arrays (rad)."""
    a, ra1 = g.a_w, g.ra1
    ra2 = np.maximum(g.ra2, g.rb2)
    with np.errstate(invalid="ignore", divide="ignore"):
        c1 = (ra2 ** 2 - ra1 ** 2 - a ** 2) / (2 * a * ra1)
        c2 = (ra2 ** 2 - ra1 ** 2 + a ** 2) / (2 * a * ra2)
        d1 = np.arccos(np.clip(c1, -1.0, 1.0))
        d2 = np.arccos(np.clip(c2, -1.0, 1.0))
        aa1 = np.arccos(g.rb1 / ra1)
        aa2 = np.arccos(g.rb2 / ra2)
        out = (g.z1 * (inv(aa1) + d1) + (g.z2 - g.z1) * inv(g.alpha_w)
               - g.z2 * (inv(aa2) + d2))
    return np.where(ra2 >= ra1 + a, np.inf, out)


def plunge_gap(g, sel=None):
    """min (X2 - X0) of :func:`~gearkit.pair.internal.plunge_trimming` (mm) at the points ``sel``:
    ``PLUNGE_SAMPLES`` samples, then Newton on the derivative from the smallest one (to round-off)."""
    sec = g.sec
    cutter = g.field._tools[1]
    z2, z0 = g.z2, cutter.teeth
    r2 = np.maximum(g.ra2, g.rb2)
    t2 = g.t2
    if sel is not None:
        r2, t2 = r2[sel], np.asarray(t2)[sel]
    with np.errstate(invalid="ignore"):
        d2 = math.pi / z2 - half_angle(sec, z2, t2, r2, True)
    ra0 = z0 * sec.mt / 2 + (cutter.shift + cutter.addendum) * sec.mn
    d0 = float(half_angle(sec, z0, 2 * cutter.shift * math.tan(sec.alpha_n), float(ra0), False))
    k = z2 / z0
    hi = math.pi / (2 * k)
    phi = np.linspace(0.0, hi, PLUNGE_SAMPLES)
    r2c, d2c = r2[:, None], d2[:, None]
    vals = r2c * np.sin(phi[None] + d2c) - ra0 * np.sin(k * phi[None] + d0)
    vals = np.where(np.isnan(vals), np.inf, vals)
    i = np.argmin(vals, axis=1)
    best = vals[np.arange(len(i)), i]
    p = phi[i]
    lo_b, hi_b = phi[np.maximum(i - 1, 0)], phi[np.minimum(i + 1, PLUNGE_SAMPLES - 1)]
    for _ in range(12):
        g1 = r2 * np.cos(p + d2) - ra0 * k * np.cos(k * p + d0)
        g2 = -r2 * np.sin(p + d2) + ra0 * k * k * np.sin(k * p + d0)
        with np.errstate(invalid="ignore", divide="ignore"):
            p = np.clip(np.where(g2 > 0, p - g1 / g2, p), lo_b, hi_b)
    val = r2 * np.sin(p + d2) - ra0 * np.sin(k * p + d0)
    return np.where(val < best, val, best)


def tip_clearance_margin(g, sel=None):
    """``SWEEP_RESOLUTION`` minus the tip sweep's depth (m_n) at the points ``sel``: the check's
    :func:`~gearkit.pair.internal.tip_sweep_depth`, the same function on arrays (exact down to
    ``-SWEEP_ENOUGH``, below it an upper bound)."""
    pick = (lambda v: np.asarray(v)) if sel is None else (lambda v: np.asarray(v)[sel])
    mn = g.sec.mn
    with np.errstate(invalid="ignore"):
        rl1 = np.maximum(g.rb1, np.hypot(g.rb1, g.rhoF1))
        rw2 = g.rb2 / np.cos(g.alpha_w)
    depth, _ = sweep_depth(g.sec, g.z1, g.z2, pick(g.a_w), pick(g.ra1),
                           pick(np.maximum(g.ra2, g.rb2)), pick(rl1), pick(g.rf2), pick(g.t1),
                           pick(g.t2), pick(rw2), SWEEP_RESOLUTION * mn,
                           (SWEEP_RESOLUTION + SWEEP_ENOUGH) * mn)
    return SWEEP_RESOLUTION - depth / mn
