"""Tooth contact analysis over a mesh cycle: transmission error, contact ratio, backlash, interference.

Quasi-static, unloaded, rigid: at every driver angle the mate rests against the working bound
(:mod:`gearkit.contact.mesh`). From the bounds of :func:`gearkit.contact.solver.solve`:

* **Transmission error** ``TE = delta_work - delta_ref`` (mate units: rad, or mm for a rack),
  ``delta_ref`` the position with the working flanks through the pitch point
  (:meth:`~gearkit.contact.mesh.Mesh.reference`): zero for conjugate flanks.
* **Pairs in contact**: driver halves whose working bound is within ``contact_tol`` (a normal
  distance, mm) of the mate's position. The **simulated contact ratio** is their time average
  over one mesh cycle (one driver pitch); the instants where a pair enters or leaves contact
  are found between the steps, so the average does not depend on the step count. It counts what
  touches: where conjugate action lapses (eps_alpha < 1) the mate falls back onto an edge
  contact, which counts (the transmission error shows the lapse), so it never drops below 1.
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

from gearkit.contact.cycle import Cycle, contact_ratio
from gearkit.contact.interference import Interference, find_interference, sharpen
from gearkit.contact.mesh import Mesh
from gearkit.errors import require
from gearkit.export import json_number

__all__ = ["ContactAnalysis", "Interference", "limits", "simulate"]



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

    def contact_lines(self, step: int) -> dict:
        """The contacts at driver angle ``step`` as lines across the face width: ``{(tooth, half): (k, 3)
        float64 mm}``, points ``(x, y, zeta)`` (fixed frame, axial position) ordered by ``zeta``. A
        spur pair's lines are single points."""
        c = self.contacts
        at = np.flatnonzero(c["step"] == step)
        out = {}
        for i in at[np.lexsort((c["zeta"][at], c["half"][at], c["tooth"][at]))]:
            key = (int(c["tooth"][i]), int(c["half"][i]))
            out.setdefault(key, []).append([*c["point"][i], c["zeta"][i]])
        return {k: np.array(v) for k, v in out.items()}

    def to_dict(self) -> dict:
        """JSON-ready summary (lengths mm, angles rad unless the key says deg)."""
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
    require(math.isfinite(helix_angle_deg) and abs(helix_angle_deg) < 60, "helix_angle_deg",
            f"{helix_angle_deg!r} must be in (-60, 60) degrees")
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
    ev = Cycle(mesh, phi, shifts, ctol)
    eps_total = contact_ratio(mesh, phi, ev, shifts, ctol)
    if helical:
        ev0 = Cycle(mesh, phi, np.zeros(1), ctol)
        eps = contact_ratio(mesh, phi, ev0, np.zeros(1), ctol)
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
    extra = sharpen(mesh, ev, ref, shifts, ctol, itol)
    inter, top = find_interference(mesh, ev, ref, itol, work_arm, rev_arm, extra)
    if top is not None and top["side"] != "radial":
        from gearkit.contact.overlap import overlap_area

        at = Cycle(mesh, np.array([top["driver_angle"]]), shifts, ctol)
        k = int(at.extreme(at.wb)[1][0])
        delta = ref if top["side"] == "working" else float(at.work[0])
        area = overlap_area(mesh, top["driver_angle"] + shifts[k], delta)
        inter = Interference(True, inter.max_depth, area, inter.where, inter.driver_angle, inter.point, inter.events)
    counts = ev.pair_counts()
    contacts = _contacts(ev, zeta)
    n = steps
    return ContactAnalysis(
        mesh=mesh, driver_angle=phi[:n], transmission_error=(ev.work - ref)[:n], pairs_in_contact=counts[:n],
        contact_ratio=float(eps), total_contact_ratio=float(eps_total),
        backlash=float(np.min(play) * r_w2), backlash_normal=float(np.min(play * rev_arm)),
        backlash_angle=play[:n], interference=inter, reference=float(ref), contacts=contacts,
        units="mm" if mesh.kind == "rack" else "rad", slices=len(shifts), face_width=float(face_width),
        contact_tol=ctol, interference_tol=itol)


def limits(mesh: Mesh, phi):
    """Where the mate stops, turned either way, at driver angles ``phi`` ``(n,)`` (rad).

    Returns ``(upper, lower)``: the mate positions (mate units, from the ideal motion) of first
    contact in each direction; ``upper - lower`` is the free play (negative: the teeth overlap at
    every position). A quick query, without the cycle's contact ratio or interference analysis.
    """
    ev = Cycle(mesh, np.atleast_1d(np.asarray(phi, dtype=float)), np.zeros(1), 1e-12 * mesh.module)
    return ev.upper, ev.lower


def _contacts(ev, zeta):
    """Flat arrays of the working contacts: step, slice, tooth, half, point, normal, zeta."""
    n_, s_, k_, h_ = np.nonzero(ev.touch[:-1])
    at = (n_, s_, k_, h_, ev.wb)
    return {"step": n_, "slice": s_, "tooth": ev.teeth[n_, s_, k_], "half": h_,
            "point": ev.point[at], "normal": ev.normal[at], "zeta": zeta[s_],
            "driver_radius": np.hypot(ev.point[at][:, 0], ev.point[at][:, 1]), "mate_radius": ev.rho2[at]}
