"""Interference in a simulated mesh: overlap at the ideal position, jamming, and where it happens.

An overlap is measured along the contact normal (mm): on the working side, how far a driver half's
bound lies beyond the ideal position (the working flanks through the pitch point); on the reverse
side, beyond the working position (no admissible position: jamming). Where it happens is read off
the piece labels at the deepest point; a tip circle reaching into the other gear's root circle is
radial and exact (``tip-root``). Overlaps peaking between two steps are found by following each
pair's overlap over the cycle and searching its peak (golden section).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from gearkit.contact.cycle import Cycle

__all__ = ["Interference", "find_interference", "sharpen"]

#: golden-section search for an overlap peaking between steps (0.618^24 ~ 1e-5 of two steps)
_GOLDEN = 0.6180339887498949
_GOLDEN_STEPS = 24


@dataclass(frozen=True)
class Interference:
    """Overlap of the two profiles found over the cycle.

    Attributes
    ----------
    found : bool
    max_depth : float, mm (along the contact normal; 0 when not found)
    area : float, mm^2 (overlap of the outlines at the deepest instant; 0 when not found)
    where : tuple of str (kinds, deepest first)
    driver_angle : float, rad (the deepest instant)
    point : (2,) float64 or None, mm (fixed frame; None for a radial tip-root overlap)
    events : tuple of dict (the deepest instance of each kind)
    """

    found: bool
    max_depth: float = 0.0
    area: float = 0.0
    where: tuple = ()
    driver_angle: float = 0.0
    point: tuple = (0.0, 0.0)
    events: tuple = ()

    def to_dict(self) -> dict:
        return {"found": self.found, "max_depth": self.max_depth, "area": self.area, "where": list(self.where),
                "driver_angle_deg": math.degrees(self.driver_angle),
                "point": None if self.point is None else list(self.point),
                "events": [dict(e) for e in self.events]}


def _labels(mesh, ev, idx, bound):
    """(driver feature, mate feature) at the contacts ``idx`` of ``bound``."""
    p1 = ev.piece1[idx + (bound,)]
    p2 = ev.piece2[idx + (bound,)]
    c1 = ev.corner1[idx + (bound,)]
    c2 = ev.corner2[idx + (bound,)]
    d = np.array(mesh.driver.labels, dtype=object)[np.clip(p1, 0, None)]
    d = np.where(c1 & (d == "flank"), "tip", d)
    m = mesh.mate.label(p2)
    m = np.where(c2, "tip", m)
    return d, m


def _kind(driver_feature, mate_feature) -> str:
    feats = (driver_feature, mate_feature)
    if "fillet" in feats:
        return "tip-fillet"
    if "root" in feats:
        return "tip-root"
    if "tip" in feats:
        return "tip"
    return "flank"


def find_interference(mesh, ev, ref, itol, work_arm, rev_arm, extra=()):
    """Interference events over the cycle (see the module notes); ``extra``: events found between steps."""
    wb = ev.wb
    over = mesh.working * (ref - ev.work) * work_arm  # the first contact ahead of the ideal position
    jam = (ev.lower - ev.upper) * rev_arm
    events = []
    for depth, bound, is_jam in ((over, wb, False), (jam, 1 - wb, True)):
        hit = np.flatnonzero(np.nan_to_num(depth, nan=0.0) > itol)
        if hit.size == 0:
            continue
        idx = ev.extreme(bound)
        d, m = _labels(mesh, ev, idx, bound)
        kinds = np.array([_kind(a, b) for a, b in zip(d, m)])
        groups = [("jamming", hit)] if is_jam else []  # jamming, and what the binding contact is
        groups += [(k, hit[kinds[hit] == k]) for k in dict.fromkeys(kinds[hit].tolist())
                   if not (is_jam and k == "flank")]
        for kind, sel in groups:
            j = int(sel[np.argmax(depth[sel])])
            at = tuple(i[j] for i in idx)
            events.append({"kind": kind, "depth": float(depth[j]), "driver_angle": float(ev.phi[j]),
                           "point": [float(v) for v in ev.point[at + (bound,)]],
                           "driver_feature": str(d[j]), "mate_feature": str(m[j]),
                           "side": "reverse" if bound != wb else "working", "step": j})
    for who, gap in zip(("driver", "mate"), mesh.root_clearances()):
        if -gap > itol:  # a tip circle reaches into the other gear's root circle
            events.append({"kind": "tip-root", "depth": float(-gap), "driver_angle": float(ev.phi[0]),
                           "point": None, "driver_feature": "tip" if who == "driver" else "root",
                           "mate_feature": "root" if who == "driver" else "tip", "side": "radial", "step": 0})
    events += list(extra)
    if not events:
        return Interference(False), None
    events.sort(key=lambda e: -e["depth"])
    events = list({e["kind"]: e for e in reversed(events)}.values())[::-1]  # the deepest of each kind
    events.sort(key=lambda e: -e["depth"])
    top = events[0]
    where = tuple(dict.fromkeys(e["kind"] for e in events))
    point = tuple(top["point"]) if top["point"] is not None else None
    return Interference(True, top["depth"], 0.0, where, top["driver_angle"], point, tuple(events)), top


def sharpen(mesh, ev, ref, shifts, contact_tol, itol):
    """Interference between the steps: each pair's overlap (per bound) is followed over the cycle;
    where it peaks between steps (a strict local maximum whose parabola rises above a tenth of the
    threshold: round-off on a flank in contact does not) the peak
    is found by golden-section search on the driver angle. Returns events as :func:`_interference`."""
    n = len(ev.phi)
    events = []
    for bound in (ev.wb, 1 - ev.wb):
        dep = ev.depth(ref, bound)  # (n, S, K, 2)
        pids = np.unique(ev.pid)
        rows = np.searchsorted(pids, ev.pid)
        series = np.full((len(pids), n), -np.inf)
        for s in range(dep.shape[1]):  # a slice's pairs at one step are distinct (2 tooth + half): no index repeats
            at = (rows[:, s].reshape(n, -1).T, np.arange(n)[None, :])
            series[at] = np.maximum(series[at], dep[:, s].reshape(n, -1).T)
        y0, y1, y2 = series[:, :-2], series[:, 1:-1], series[:, 2:]
        with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
            curv = 2 * y1 - y0 - y2
            peak = y1 + (y2 - y0) ** 2 / (8 * curv)
        cand = np.isfinite(y0) & np.isfinite(y2) & (y1 > y0) & (y1 > y2) & (peak > 0.1 * itol) & (y1 <= itol)
        r, j = np.nonzero(cand)
        if r.size == 0:
            continue
        pid, j = pids[r], j + 1
        lo, hi = ev.phi[j - 1].copy(), ev.phi[j + 1].copy()
        x1 = hi - _GOLDEN * (hi - lo)
        x2 = lo + _GOLDEN * (hi - lo)
        f1 = Cycle(mesh, x1, shifts, contact_tol).pair_depth(ref, bound, pid)
        f2 = Cycle(mesh, x2, shifts, contact_tol).pair_depth(ref, bound, pid)
        for _ in range(_GOLDEN_STEPS):
            right = f2 > f1
            lo = np.where(right, x1, lo)
            hi = np.where(right, hi, x2)
            x1n = np.where(right, x2, hi - _GOLDEN * (hi - lo))
            x2n = np.where(right, lo + _GOLDEN * (hi - lo), x1)
            probe = np.where(right, x2n, x1n)
            fp = Cycle(mesh, probe, shifts, contact_tol).pair_depth(ref, bound, pid)
            f1, f2 = np.where(right, f2, fp), np.where(right, fp, f1)
            x1, x2 = x1n, x2n
        best = np.where(f1 >= f2, x1, x2)
        deep = np.maximum(f1, f2) > itol
        if not deep.any():
            continue
        at = Cycle(mesh, best[deep], shifts, contact_tol)
        for i, p in enumerate(pid[deep]):
            dep_i = at.depth(ref, bound)[i]
            where = np.nonzero((at.pid[i] == p) & (dep_i == dep_i[at.pid[i] == p].max()))
            idx = (np.array([i]),) + tuple(w[:1] for w in where)
            d, m = _labels(mesh, at, idx, bound)
            kinds = [_kind(d[0], m[0])]
            if bound != ev.wb:
                kinds = ["jamming"] + ([] if kinds[0] == "flank" else kinds)
            for kind in kinds:
                events.append({"kind": kind, "depth": float(dep_i[tuple(w[0] for w in where)]),
                               "driver_angle": float(best[deep][i]),
                               "point": [float(v) for v in at.point[idx + (bound,)][0]],
                               "driver_feature": str(d[0]), "mate_feature": str(m[0]),
                               "side": "reverse" if bound != ev.wb else "working", "step": None})
    return events
