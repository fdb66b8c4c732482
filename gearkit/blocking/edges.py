"""The edge of the area where a margin is defined (the no-pair area), seen from the lines beside it.

A margin ``F`` is undefined (NaN) where no pair exists. A zero of ``F`` beside that area may lie
closer to its edge than any grid node or ray sample: here the edge point between a defined and an
undefined point is found by multisection to round-off (:func:`edge_point`), and ``F`` is sampled
at distances from it shrinking geometrically to round-off (:func:`ladder`): a zero between a
sample and the edge is seen however close to the edge it lies. :func:`across` looks for the
nearest oriented zero along normals (for the continuation of :mod:`gearkit.blocking.ends`),
:func:`toward_edge` the nearest zero towards the edge (for the accuracy measure of the bench).

>>> import numpy as np
>>> F = lambda p, k: np.where(p[:, 0] < 1.0, p[:, 0] - (1.0 - 1e-9), np.nan)  # a zero 1e-9 before the edge
>>> lo, flo, hi, fhi = toward_edge(F, np.array([[0.0, 0.0]]), np.array([-1.0]), np.array([[2.0, 0.0]]), np.array([0]))
>>> bool(flo[0] < 0 < fhi[0]) and bool(1.0 - 1e-8 < lo[0, 0] <= hi[0, 0] < 1.0)
True
"""
from __future__ import annotations

import math

import numpy as np


__all__ = ["edge_point", "toward_edge", "ladder", "nearest_change", "across"]

LADDER = 0.5  #: ratio of the geometric sample distances
FLOOR = 1e-13  #: the smallest sample distance, relative to the window's size
SPLITS = 15  #: points per round of the multisection for the edge of the defined area


def edge_point(F, a, b, which, span, within=None):
    """The last defined point from ``a`` (defined) towards ``b`` (undefined), to ``span * FLOOR``
    (or to ``within``, a length, where that is enough)."""
    a, b = a.copy(), b.copy()
    n = len(a)
    t = np.arange(1, SPLITS + 1) / (SPLITS + 1)
    close = FLOOR * span if within is None else max(float(within), FLOOR * span)
    for _ in range(40):
        if not n or np.max(np.hypot(*(b - a).T)) <= close:
            break
        P = a[:, None, :] + t[None, :, None] * (b - a)[:, None, :]
        v = F(P.reshape(-1, 2), np.repeat(which, SPLITS)).reshape(n, SPLITS)
        bad = ~np.isfinite(v)
        j = np.where(bad.any(axis=1), np.argmax(bad, axis=1), SPLITS)  # first undefined sample
        r = np.arange(n)
        na = np.where((j > 0)[:, None], P[r, np.maximum(j - 1, 0)], a)
        nb = np.where((j < SPLITS)[:, None], P[r, np.minimum(j, SPLITS - 1)], b)
        a, b = na, nb
    return a


def toward_edge(F, m, f0, out, which):
    """For points ``m`` (n, 2) where ``F`` is ``f0`` (defined) and ``out`` where it is not: the
    bracket ``(lo, f(lo), hi, f(hi))`` of the sign change nearest to ``m`` among samples from the
    edge of the defined area towards ``m`` (distances shrinking geometrically to round-off; the
    bracket is ``m``, ``m`` where there is none)."""
    span = float(np.max(np.hypot(*(out - m).T)))
    E = edge_point(F, m, out, which, span)
    toward = m - E
    d = np.concatenate([ladder(1.0, FLOOR / 8), [0.0]])
    P = E[:, None, :] + d[None, :, None] * toward[:, None, :]
    V = F(P.reshape(-1, 2), np.repeat(which, d.size)).reshape(len(m), d.size)
    V[:, 0] = f0
    fin = np.isfinite(V)
    ch = fin[:, :-1] & fin[:, 1:] & ((V[:, :-1] > 0) != (V[:, 1:] > 0))
    j = np.argmax(ch, axis=1)  # the first from m
    r = np.arange(len(m))
    ok = ch[r, j]
    lo = np.where(ok[:, None], P[r, j], m)
    hi = np.where(ok[:, None], P[r, j + 1], m)
    return lo, np.where(ok, V[r, j], f0), hi, np.where(ok, V[r, j + 1], f0)


def ladder(h, floor):
    """Distances h, h LADDER, ... down to ``floor``."""
    n = max(1, int(math.ceil(math.log(max(h / floor, 1.0)) / -math.log(LADDER))) + 1)
    return h * LADDER ** np.arange(n)


def nearest_change(s, v, sigma):
    """Index i of the sign change between samples i, i + 1 (positions ``s`` sorted, values ``v``)
    nearest to s = 0 whose sign goes from -sigma to sigma along s; -1 when none."""
    fin = np.isfinite(v)
    pos = v > 0
    ok = fin[:-1] & fin[1:] & (pos[:-1] != pos[1:]) & (pos[1:] == (sigma > 0))
    idx = np.flatnonzero(ok)
    if not idx.size:
        return -1
    return int(idx[np.argmin(np.minimum(np.abs(s[idx]), np.abs(s[idx + 1])))])


def across(F, Q, N, reach, sig, which, span, floor=None):
    """Along the normals ``N`` through ``Q`` (within ``reach``): per point ``(s, v, c)``, samples at
    positions ``s`` along the normal with values ``v`` and the index ``c`` of the sign change nearest
    to ``Q`` with ``F`` going from ``-sig`` to ``sig`` (-1: none). The samples lie at distances
    shrinking geometrically from ``Q`` down to ``floor`` (default: round-off) and, where the normal
    runs into the undefined area, from that edge towards ``Q`` from round-off up (a zero closer to
    the edge than ``floor`` is seen)."""
    floor = FLOOR * span if floor is None else floor
    plans, pts, ks = [], [], []
    for q, n, h, k in zip(Q, N, reach, which):
        d = ladder(h, floor)
        s = np.concatenate([-d, [0.0], d[::-1]])
        plans.append(s)
        pts.append(q[None] + s[:, None] * n[None])
        ks.append(np.full(s.size, k))
    V = np.split(F(np.concatenate(pts), np.concatenate(ks)), np.cumsum([s.size for s in plans])[:-1])
    out = [[s, v, nearest_change(s, v, sg)] for s, v, sg in zip(plans, V, sig)]
    edge = []  # (entry, s defined, s undefined)
    for e, (s, v, c) in enumerate(out):
        fin = np.isfinite(v)
        bnd = np.flatnonzero(fin[:-1] != fin[1:])
        if c < 0 and bnd.size:
            b = bnd[np.argmin(np.minimum(np.abs(s[bnd]), np.abs(s[bnd + 1])))]
            edge.append((e, s[b] if fin[b] else s[b + 1], s[b + 1] if fin[b] else s[b]))
    if edge:
        idx = np.array([e for e, _, _ in edge])
        A = Q[idx] + np.array([a for _, a, _ in edge])[:, None] * N[idx]
        B = Q[idx] + np.array([b for _, _, b in edge])[:, None] * N[idx]
        E = edge_point(F, A, B, which[idx], span)
        # from the edge to round-off whatever ``floor``: a line meeting the edge at a small angle runs
        # closer to it than any sample about Q (the margins vary as the cube root of the distance)
        d = ladder(1.0, FLOOR * span / max(float(np.max(np.hypot(*(A - E).T))), 1e-300))
        P = E[:, None, :] + d[None, :, None] * (A - E)[:, None, :]
        W = F(P.reshape(-1, 2), np.repeat(which[idx], d.size)).reshape(len(idx), d.size)
        for r, e in enumerate(idx):
            s = np.concatenate([out[e][0], (P[r] - Q[e]) @ N[e]])
            v = np.concatenate([out[e][1], W[r]])
            o = np.argsort(s, kind="stable")
            out[e] = [s[o], v[o], nearest_change(s[o], v[o], sig[e])]
    return out
