"""Tooth contact analysis over a mesh cycle: transmission error, contact ratio, backlash, interference.

Quasi-static, unloaded, rigid: at every driver angle the mate rests against the working bound
(:mod:`gearkit.contact.mesh`). From the bounds of :func:`gearkit.contact.solver.solve`:

* **Transmission error** ``TE = delta_work - delta_ref`` (mate units: rad, or mm for a rack),
  ``delta_ref`` the position with the working flanks through the pitch point
  (:meth:`~gearkit.contact.mesh.Mesh.reference`): zero for conjugate flanks.
* **Pairs in contact**: driver halves whose working bound is within ``contact_tol`` (a normal
  distance, mm) of the mate's position. The **simulated contact ratio** is their time average
  over one mesh cycle (one driver pitch); the instants where a pair enters or leaves contact
  are refined by bisection, so the average does not depend on the step count.
* **Backlash**: the free play ``delta_upper - delta_lower`` as an arc on the mate's working
  pitch circle (circular; a length for a rack) and along the contact normal (normal); the
  smallest over the cycle.
* **Interference**: overlap at the ideal position deeper than ``interference_tol`` (a driver
  half whose bound lies beyond ``delta_ref``), or no position at all (``delta_lower >
  delta_upper``: jamming). Its depth is measured along the contact normal; where it happens is
  read off the piece labels at the deepest point (``tip-fillet``; ``tip``: a tip corner off the
  path of contact, as in the secondary tip interference of internal pairs; ``flank``;
  ``jamming``) and, for ``tip-root``, from the tip and root circles (both turn about fixed
  centres, so their radial overlap is exact).
* **Helical gears**: the face width is cut into ``slices`` transverse sections, slice ``k`` at
  ``zeta_k`` turned by the lead (``phi + zeta_k tan(beta) / r``, ``r`` the driver's reference
  radius). The mate's position is the working extreme over all slices; a tooth pair is in
  contact when any slice is, giving the total contact ratio; the slice contacts make the
  contact lines.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from gearkit.contact.mesh import Mesh
from gearkit.contact.solver import solve
from gearkit.errors import require

__all__ = ["ContactAnalysis", "Interference", "simulate"]

#: bisection steps for the instants a pair enters or leaves contact (2^-16 of a step)
_BISECT = 16


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
    point : (2,) float64, mm (fixed frame)
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
                "driver_angle_deg": math.degrees(self.driver_angle), "point": list(self.point),
                "events": [dict(e) for e in self.events]}


@dataclass(frozen=True)
class ContactAnalysis:
    """Result of :func:`simulate` (arrays over the ``steps`` driver angles of one mesh cycle).

    Mate units are rad for a gear and mm for a rack (``units``).
    """

    mesh: Mesh = field(repr=False)
    driver_angle: np.ndarray = field(repr=False)
    transmission_error: np.ndarray = field(repr=False)
    pairs_in_contact: np.ndarray = field(repr=False)
    contact_ratio: float
    total_contact_ratio: float
    backlash: float
    backlash_normal: float
    backlash_angle: np.ndarray = field(repr=False)
    interference: Interference
    reference: float
    contacts: dict = field(repr=False)
    units: str = "rad"
    slices: int = 1
    face_width: float = 0.0
    contact_tol: float = 0.0
    interference_tol: float = 0.0

    @property
    def transmission_error_max(self) -> float:
        """Largest |TE| over the cycle (mate units)."""
        return float(np.max(np.abs(self.transmission_error)))

    @property
    def transmission_error_pp(self) -> float:
        """Peak-to-peak TE over the cycle (mate units)."""
        return float(np.ptp(self.transmission_error))

    def to_dict(self) -> dict:
        """JSON-ready summary (lengths mm, angles rad unless the key says deg)."""
        from gearkit.checks.report import json_number

        te_max = self.transmission_error_max
        if self.units == "mm":  # a rack's TE as the driver's angle
            te_max /= self.mesh.pitch_radii[0]
        counts = self.pairs_in_contact
        out = {
            "kind": self.mesh.kind, "steps": int(len(self.driver_angle)), "slices": self.slices,
            "tolerance": self.mesh.tol, "contact_tol": self.contact_tol, "interference_tol": self.interference_tol,
            "contact_ratio_simulated": self.contact_ratio,
            "transmission_error_max": json_number(te_max),
            "transmission_error_pp": json_number(self.transmission_error_pp),
            "transmission_error_units": "rad",
            "backlash": json_number(self.backlash), "backlash_normal": json_number(self.backlash_normal),
            "pairs_in_contact": {"min": int(counts.min()), "max": int(counts.max()), "mean": float(counts.mean())},
            "interference": self.interference.to_dict(),
        }
        if self.slices > 1:
            out["total_contact_ratio_simulated"] = self.total_contact_ratio
            out["face_width"] = self.face_width
        return out


# ----------------------------------------------------------------------------- evaluation
class _Eval:
    """Bounds at driver angles ``phi`` (n,) over the slice shifts (S,), reduced per angle."""

    def __init__(self, mesh: Mesh, phi, shifts, contact_tol):
        self.phi = np.asarray(phi, dtype=float)
        n, s = len(self.phi), len(shifts)
        b = solve(mesh, (self.phi[:, None] + shifts[None, :]).ravel(), contact_tol)
        kk = b.teeth.shape[1]

        def grid(a):
            return a.reshape((n, s, kk) + a.shape[2:])
        self.teeth = grid(b.teeth)
        self.value, self.exact, self.arm = grid(b.value), grid(b.exact), grid(b.arm)
        self.point, self.normal = grid(b.point), grid(b.normal)
        self.piece1, self.piece2, self.rho2 = grid(b.piece1), grid(b.piece2), grid(b.rho2)
        self.corner1, self.corner2 = grid(b.corner1), grid(b.corner2)
        self.upper = self.value[..., 0].min(axis=(1, 2, 3))
        self.lower = -self.value[..., 1].min(axis=(1, 2, 3))
        wb = 0 if mesh.working == 1 else 1
        self.wb = wb
        self.work = self.upper if wb == 0 else self.lower
        v = self.value[..., wb]
        flat = v.reshape(n, -1).argmin(axis=1)
        best = v.reshape(n, -1)[np.arange(n), flat]
        arm_best = self.arm[..., wb].reshape(n, -1)[np.arange(n), flat]
        gap = (v - best[:, None, None, None]) * self.arm[..., wb]
        # a bound is known to about noise / arm (rad): a contact whose normal nearly passes through the
        # mate's centre (a crest) sets a position that is uncertain by much more than a firm one
        noise = (mesh.noise * self.arm[..., wb] / arm_best[:, None, None, None])
        self.touch = self.exact[..., wb] & (gap <= contact_tol + noise)  # (n, S, K, 2)
        self.ids = np.where(self.touch, 2 * self.teeth[..., None] + np.arange(2), np.iinfo(np.int64).min)

    def pair_sets(self):
        """The set of pair ids (2 tooth + half) in contact at each angle."""
        return [set(r[r != np.iinfo(np.int64).min].tolist()) for r in self.ids.reshape(len(self.phi), -1)]

    def extreme(self, bound):
        """Index tuples ``(n, s, k, h)`` of the extreme contact of ``bound`` at every angle."""
        v = self.value[..., bound].reshape(len(self.phi), -1)
        flat = np.argmin(v, axis=1)
        return (np.arange(len(self.phi)),) + np.unravel_index(flat, self.value.shape[1:4])


def _contact_ratio(mesh, phi, ev, shifts, contact_tol):
    """Time average of the pairs in contact over ``phi[0] .. phi[-1]`` (one cycle), transitions bisected."""
    sets = ev.pair_sets()
    period = phi[-1] - phi[0]
    total = 0.0
    todo = []  # (lo angle, hi angle, pair id, in at lo)
    for j in range(len(phi) - 1):
        a, b = sets[j], sets[j + 1]
        total += len(a & b) * (phi[j + 1] - phi[j])
        for pid in a ^ b:
            todo.append((phi[j], phi[j + 1], pid, pid in a))
    if todo:
        lo = np.array([t[0] for t in todo])
        hi = np.array([t[1] for t in todo])
        pid = np.array([t[2] for t in todo])
        start_in = np.array([t[3] for t in todo])
        for _ in range(_BISECT):
            mid = 0.5 * (lo + hi)
            mid_sets = _Eval(mesh, mid, shifts, contact_tol).pair_sets()
            inside = np.array([p in s for p, s in zip(pid.tolist(), mid_sets)])
            same = inside == start_in
            lo, hi = np.where(same, mid, lo), np.where(same, hi, mid)
        cut = 0.5 * (lo + hi)
        starts = np.array([t[0] for t in todo])
        ends = np.array([t[1] for t in todo])
        total += float(np.sum(np.where(start_in, cut - starts, ends - cut)))
    return total / period


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


def _interference(mesh, ev, ref, itol, work_arm, rev_arm):
    """Interference events over the cycle (see the module notes)."""
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
                           "point": [float("nan")] * 2, "driver_feature": "tip" if who == "driver" else "root",
                           "mate_feature": "root" if who == "driver" else "tip", "side": "radial", "step": 0})
    if not events:
        return Interference(False), None
    events.sort(key=lambda e: -e["depth"])
    top = events[0]
    where = tuple(dict.fromkeys(e["kind"] for e in events))
    return Interference(True, top["depth"], 0.0, where, top["driver_angle"], tuple(top["point"]),
                        tuple(events)), top


def simulate(mesh: Mesh, steps: int = 2000, *, contact_tol: float | None = None,
             interference_tol: float | None = None, face_width: float = 0.0, helix_angle_deg: float = 0.0,
             slices: int = 1, start: float = 0.0) -> ContactAnalysis:
    """Mesh ``mesh`` over one cycle (one driver pitch) at ``steps`` driver angles.

    Parameters
    ----------
    mesh : Mesh
    steps : int, >= 8
    contact_tol : float or None, mm
        A pair is in contact when its normal clearance is at most this. Default: ``1e-12`` of the
        larger of the module and the pitch radii, just above round-off: the geometric contact.
        (Where flanks part, their clearance grows with the square of the distance, so a larger
        value lengthens every contact by about ``sqrt(2 contact_tol R)``, R the relative radius of
        curvature; a deflection-sized value approximates contact under load.)
    interference_tol : float or None, mm
        Overlaps up to this depth are not reported (default ``1e-4`` module, the pair check's).
    face_width : float, mm, and helix_angle_deg : float
        Helical gears: the driver's helix angle at its reference circle.
    slices : int
        Transverse sections across the face width (both faces included); 1 for spur.
    start : float, rad
        First driver angle of the cycle.

    Returns
    -------
    ContactAnalysis
    """
    require(isinstance(steps, (int, np.integer)) and 8 <= steps <= 1_000_000, "steps",
            f"{steps!r} must be an integer in [8, 1000000]")
    require(isinstance(slices, (int, np.integer)) and 1 <= slices <= 1000, "slices",
            f"{slices!r} must be an integer in [1, 1000]")
    require(math.isfinite(face_width) and face_width >= 0, "face_width", f"{face_width!r} must be >= 0 mm")
    require(math.isfinite(helix_angle_deg) and abs(helix_angle_deg) < 80, "helix_angle_deg",
            f"{helix_angle_deg!r} must be in (-80, 80) degrees")
    m = mesh.module
    ctol = 1e-12 * max([m] + [r for r in mesh.pitch_radii if math.isfinite(r)]) if contact_tol is None \
        else float(contact_tol)
    itol = 1e-4 * m if interference_tol is None else float(interference_tol)
    require(math.isfinite(ctol) and ctol >= 0, "contact_tol", f"{contact_tol!r} must be >= 0 mm")
    require(math.isfinite(itol) and itol >= 0, "interference_tol", f"{interference_tol!r} must be >= 0 mm")
    helical = slices > 1 and face_width > 0 and helix_angle_deg != 0
    if helical:
        r_ref = (mesh.gear1.reference_diameter or 2 * mesh.pitch_radii[0]) / 2
        zeta = np.linspace(0.0, face_width, slices)
        shifts = zeta * math.tan(math.radians(abs(helix_angle_deg))) / r_ref
    else:
        zeta = np.zeros(1)
        shifts = np.zeros(1)
    phi = start + mesh.pitch1 * np.arange(steps + 1) / steps
    ev = _Eval(mesh, phi, shifts, ctol)
    eps_total = _contact_ratio(mesh, phi, ev, shifts, ctol)
    if helical:
        ev0 = _Eval(mesh, phi, np.zeros(1), ctol)
        eps = _contact_ratio(mesh, phi, ev0, np.zeros(1), ctol)
    else:
        eps = eps_total
    ref = mesh.reference()
    if ref is None:
        ref = float(np.median(ev.work))
    w_idx = ev.extreme(ev.wb)
    r_idx = ev.extreme(1 - ev.wb)
    work_arm = ev.arm[w_idx + (ev.wb,)]
    rev_arm = ev.arm[r_idx + (1 - ev.wb,)]
    play = ev.upper - ev.lower
    r_w2 = 1.0 if mesh.kind == "rack" else mesh.pitch_radii[1]
    inter, top = _interference(mesh, ev, ref, itol, work_arm, rev_arm)
    if top is not None:
        from gearkit.contact.overlap import overlap_area

        j = top["step"]
        delta = ref if top["side"] == "working" else ev.work[j]
        area = overlap_area(mesh, ev.phi[j] + shifts[int(w_idx[1][j])], delta)
        inter = Interference(True, inter.max_depth, area, inter.where, inter.driver_angle, inter.point, inter.events)
    counts = np.array([len(s) for s in ev.pair_sets()])
    contacts = _contacts(ev, zeta)
    n = steps
    return ContactAnalysis(
        mesh=mesh, driver_angle=phi[:n], transmission_error=(ev.work - ref)[:n], pairs_in_contact=counts[:n],
        contact_ratio=float(eps), total_contact_ratio=float(eps_total),
        backlash=float(np.min(play) * r_w2), backlash_normal=float(np.min(play * rev_arm)),
        backlash_angle=play[:n], interference=inter, reference=float(ref), contacts=contacts,
        units="mm" if mesh.kind == "rack" else "rad", slices=len(shifts), face_width=float(face_width),
        contact_tol=ctol, interference_tol=itol)


def _contacts(ev, zeta):
    """Flat arrays of the working contacts: step, slice, tooth, half, point, normal, zeta."""
    n_, s_, k_, h_ = np.nonzero(ev.touch[:-1])
    at = (n_, s_, k_, h_, ev.wb)
    return {"step": n_, "slice": s_, "tooth": ev.teeth[n_, s_, k_], "half": h_,
            "point": ev.point[at], "normal": ev.normal[at], "zeta": zeta[s_],
            "driver_radius": np.hypot(ev.point[at][:, 0], ev.point[at][:, 1]), "mate_radius": ev.rho2[at]}
