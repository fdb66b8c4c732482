"""Loaded tooth contact: the driver's torque shared between the tooth pairs by compatibility.

The rigid analysis (:class:`gearkit.contact.cycle.Cycle`, on the generated teeth with their profile
modifications) gives, at every driver angle, face slice and tooth pair, the pair's separation
``g`` along its contact normal from the rigid working position, the contact point and the arm
``a`` of its normal about the mate's centre. Across the face (``S`` slices at their centres, width
``b / S``) the lead modifications of both gears and the mesh misalignment add to ``g``.

Under the mate torque ``T_2`` the mate turns on by ``Theta`` (rad) beyond its rigid position; a
slice of pair ``i`` is pressed by ``Theta a_i - g_i`` where positive, carrying
``w_i = (Theta a_i - g_i) / q_i`` per unit length, ``q_i`` its compliance (both teeth's bending,
shear, compression and foundation at their contact radii plus the contact approach,
:mod:`gearkit.contact.stiffness`). Equilibrium ``sum w_i a_i b / S = T_2`` is piecewise linear in
``Theta`` and solved exactly per driver angle (sorted breakpoints); the contact approach, which is
non-linear in ``w``, is iterated to a fixed point. At zero torque ``Theta`` is the smallest
``g / a``: zero for an unmodified pair, whose rigid results are returned unchanged.

Loaded transmission error ``TE = TE_rigid + s Theta`` (mate rad, ``s`` the working direction of
:class:`~gearkit.contact.mesh.Mesh`); mesh stiffness ``sum_i 1 / q_i`` over the pressed slices per
unit face width (secant, N/(mm um)); load sharing per tooth pair; the loaded contact ratio (mean
number of loaded pairs); the peak Hertzian pressure; the contact pattern (largest load per unit
length over the driver's roll angle and the face).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from gearkit.contact.cycle import Cycle
from gearkit.contact.stiffness import Material, ToothCompliance, hertz_approach, hertz_pressure
from gearkit.errors import check_fields, is_real, require

__all__ = ["Deviations", "LoadedAnalysis", "loaded_cycle"]

#: fixed-point iterations of the contact approach (it changes by < 1e-6 relative after about 5)
_HERTZ_ITER = 8
#: ISO 6336-1's C_M: measured over theoretical stiffness of solid gears
ISO_CORRECTION = 0.8
#: bins of the contact pattern along the driver's roll angle
_PATTERN_BINS = 48


@dataclass(frozen=True)
class Deviations:
    """Mounting deviations of a pair (mm).

    ``center_distance``: added to the operating centre distance (the design one keeps solving the
    shifts). ``misalignment_in_plane`` (f_Sigma_delta) and ``misalignment_out_of_plane``
    (f_Sigma_beta): axis deviations over the face width, projected on the line of action as
    ``f_ma = f_Sigma_delta sin alpha_wt + f_Sigma_beta cos alpha_wt``, a separation that grows
    linearly across the face (``+f_ma / 2`` at ``zeta = b``).

    ``runout1``, ``runout2``: eccentricity of each gear (mm), its centre displaced by the run-out
    towards the gear's own angle ``runout_phase*_deg`` (turning with the gear; 0: towards tooth 0's
    centre line at the start). ``pitch_deviations1``, ``pitch_deviations2``: single pitch deviations
    ``f_pt`` per tooth (mm, along the line of action; ``z`` values, tooth ``i`` against tooth ``i - 1``):
    tooth ``k`` stands ``F_k = f_1 + ... + f_k`` ahead of its place (tooth 0 the datum), which closes
    its pair's separation by ``F_k``. The mate tooth meshing with driver tooth ``k`` is numbered
    ``-k mod z2``. Run-out and pitch deviations repeat once per turn: analyse several cycles to see them.
    """

    center_distance: float = 0.0
    misalignment_in_plane: float = 0.0
    misalignment_out_of_plane: float = 0.0
    runout1: float = 0.0
    runout2: float = 0.0
    runout_phase1_deg: float = 0.0
    runout_phase2_deg: float = 0.0
    pitch_deviations1: tuple = ()
    pitch_deviations2: tuple = ()

    def __post_init__(self):
        check_fields(self)
        for name in ("center_distance", "misalignment_in_plane", "misalignment_out_of_plane", "runout1", "runout2"):
            v = getattr(self, name)
            require(is_real(v) and abs(v) <= 10.0, name, f"{v!r} must be a length in [-10, 10] mm")
        for name in ("runout_phase1_deg", "runout_phase2_deg"):
            require(is_real(getattr(self, name)), name, f"{getattr(self, name)!r} must be an angle in degrees")
        for name in ("pitch_deviations1", "pitch_deviations2"):
            v = getattr(self, name)
            require(isinstance(v, (tuple, list, np.ndarray)), name, f"{v!r} must be a list of lengths in mm")
            v = tuple(v)
            require(all(is_real(f) and abs(f) <= 1.0 for f in v), name, "must be lengths in [-1, 1] mm, one per tooth")
            object.__setattr__(self, name, v)

    @property
    def has_turn(self) -> bool:
        """Deviations that vary from tooth to tooth (run-out, pitch deviations)."""
        return bool(self.runout1 or self.runout2 or any(self.pitch_deviations1) or any(self.pitch_deviations2))

    def separation(self, mesh, teeth, phi, normal):
        """Separation change (mm) of driver teeth ``teeth`` ``(n, ...)`` at driver angles ``phi`` ``(n,)``
        with contact normals ``normal`` ``(n, ..., 2)`` (unit, out of the driver): run-out and pitch."""
        out = np.zeros(teeth.shape)
        shape = (len(phi),) + (1,) * (teeth.ndim - 1)
        for e, phase, sign, angle in ((self.runout1, self.runout_phase1_deg, -1.0, phi),
                                      (self.runout2, self.runout_phase2_deg, 1.0, mesh.ratio * phi)):
            if e:  # the centre's displacement, turning with the gear (angles from +y, counter-clockwise)
                a = (angle + math.radians(phase)).reshape(shape)
                d = np.stack([-e * np.sin(a), e * np.cos(a)], -1)
                out += sign * np.einsum("...i,...i->...", np.broadcast_to(d, normal.shape), normal)
        for devs, z, index in ((self.pitch_deviations1, mesh.z1, teeth), (self.pitch_deviations2, mesh.z2, -teeth)):
            if any(devs):
                require(len(devs) == z, "pitch_deviations", f"give one deviation per tooth ({z}), not {len(devs)}")
                position = np.concatenate([[0.0], np.cumsum(devs[1:])])
                out -= position[np.mod(index, z)]
        return out

    def mesh_misalignment(self, working_pressure_angle: float) -> float:
        """``f_ma`` (mm over the face width) at the working transverse pressure angle (rad)."""
        return (self.misalignment_in_plane * math.sin(working_pressure_angle)
                + self.misalignment_out_of_plane * math.cos(working_pressure_angle))


@dataclass(frozen=True)
class LoadedAnalysis:
    """Result of :func:`loaded_cycle` (arrays over the ``steps`` driver angles of ``cycles`` mesh cycles).

    ``load`` is ``(steps, S, P)`` N/mm per unit length for the ``P`` driver teeth ``pair_teeth``;
    ``sharing`` ``(steps, P)`` their fraction of the total; ``pattern`` ``(bins, S)`` the largest
    load per unit length over the driver's roll angle ``pattern_roll_deg`` and the slices ``zeta``.
    """

    torque: float
    driver_angle: np.ndarray = field(repr=False)
    transmission_error: np.ndarray = field(repr=False)
    rigid_transmission_error: np.ndarray = field(repr=False)
    load: np.ndarray = field(repr=False)
    pair_teeth: np.ndarray = field(repr=False)
    sharing: np.ndarray = field(repr=False)
    mesh_stiffness: np.ndarray = field(repr=False)
    contact_pressure: np.ndarray = field(repr=False)
    pattern: np.ndarray = field(repr=False)
    pattern_roll_deg: np.ndarray = field(repr=False)
    zeta: np.ndarray = field(repr=False)
    contact_ratio_loaded: float = 0.0
    face_width: float = 0.0
    steps: int = 0
    slices: int = 1
    cycles: int = 1
    refined_range: float = 0.0
    hertz_change: float = 0.0
    torque_residual: float = 0.0

    @property
    def transmission_error_pp(self) -> float:
        """Peak-to-peak loaded TE over the cycle (mate rad)."""
        return float(np.ptp(self.transmission_error))

    @property
    def max_contact_pressure(self) -> float:
        """Largest Hertzian pressure over the cycle, MPa."""
        return float(self.contact_pressure.max())

    @property
    def mesh_stiffness_mean(self) -> float:
        """Mean mesh stiffness over the cycle, N/(mm um) per mm of face width."""
        return float(self.mesh_stiffness.mean())

    def to_dict(self, samples: int = 50) -> dict:
        """The JSON ``loaded`` object (TE in µrad, pressure MPa, stiffness N/mm/µm), sharing sampled."""
        n = len(self.driver_angle)
        at = np.unique(np.linspace(0, n - 1, min(samples, n)).round().astype(int))
        return {
            "torque": self.torque,
            "transmission_error_pp": self.transmission_error_pp * 1e6,
            "load_sharing": {"driver_angle_deg": [round(float(np.degrees(self.driver_angle[i])), 9) for i in at],
                             "pair_teeth": [int(t) for t in self.pair_teeth],
                             "fraction": [[round(float(v), 9) for v in self.sharing[i]] for i in at]},
            "contact_ratio_loaded": self.contact_ratio_loaded,
            "max_contact_pressure": self.max_contact_pressure,
            "mesh_stiffness_mean": self.mesh_stiffness_mean,
            "accuracy": {"steps": self.steps, "slices": self.slices, "cycles": self.cycles,
                         "angle_step_deg": float(np.degrees(self.driver_angle[1] - self.driver_angle[0])),
                         "slice_width": self.face_width / self.slices, "refined_range": self.refined_range,
                         "hertz_change": self.hertz_change, "torque_residual": self.torque_residual},
        }


class _Gaps:
    """The rigid cycle reduced to what the loaded solution needs, flat per driver angle ``(n, E)``."""

    def __init__(self, mesh, phi, zeta, shifts, contact_range, lead, deviations=None):
        ev = Cycle(mesh, phi, shifts, contact_range)
        n, wb = len(phi) - 1, ev.wb
        s_rigid = ev.excess.shape[1]
        slices = len(zeta)
        tile = slices if s_rigid == 1 else 1

        def per(a):  # (n + 1, S_rigid, K, 2, ...) -> (n, S, K, 2, ...)
            a = a[:n]
            return np.repeat(a, tile, axis=1) if tile > 1 else a
        # refined contacts whose normal has a working arm about the mate's centre (a normal through the
        # centre, as at a tip touching a root, cannot carry the mate's torque)
        exact = per(ev.exact[..., wb]) & (per(ev.arm[..., wb]) >= mesh.arm_scale)
        gap = np.where(exact, np.maximum(per(ev.excess), 0.0), np.inf) + lead[None, :, None, None]
        if deviations is not None and deviations.has_turn:
            teeth = np.broadcast_to(per(ev.teeth)[..., None], exact.shape)
            normal = np.nan_to_num(per(ev.normal[..., wb, :]))
            gap = gap + deviations.separation(mesh, teeth, phi[:n], normal)
        self.rigid_te = ev.work[:n]
        self.gap = gap.reshape(n, -1)
        self.arm = np.where(exact, per(ev.arm[..., wb]), 1.0).reshape(n, -1)
        point = per(ev.point[..., wb, :])
        self.r1 = np.hypot(point[..., 0], point[..., 1]).reshape(n, -1)
        self.r2 = np.abs(per(ev.rho2[..., wb])).reshape(n, -1)
        self.tooth = np.broadcast_to(per(ev.teeth)[..., None], exact.shape).reshape(n, -1)
        self.slice = np.broadcast_to(np.arange(slices)[None, :, None, None], exact.shape).reshape(n, -1)
        self.contact_range = contact_range


def _solve(gap, arm, comp_lin, hertz, torque2, width, scale):
    """Mate turn ``Theta`` per row and loads, with the contact approach ``hertz(w)`` iterated."""
    w = np.zeros(gap.shape)
    theta = np.zeros(gap.shape[0])
    change = 0.0
    nominal = None
    for it in range(_HERTZ_ITER if torque2 > 0 else 1):
        if nominal is None:
            q = comp_lin
        else:
            w_eff = np.where(w > 0, w, nominal)
            q = comp_lin + hertz(w_eff) / w_eff / scale
        c = width / q  # N/mm of approach per slice
        bp = gap / arm
        order = np.argsort(bp, axis=1)
        bps = np.take_along_axis(bp, order, 1)
        ca = np.take_along_axis(c * arm * arm, order, 1)
        cg = np.take_along_axis(c * arm * gap, order, 1)
        ca = np.where(np.isfinite(bps), ca, 0.0)
        cg = np.where(np.isfinite(bps), cg, 0.0)
        big_a, big_b = np.cumsum(ca, 1), np.cumsum(cg, 1)
        # force at each breakpoint from the pairs before it; the solution lies after the last one below T
        with np.errstate(invalid="ignore"):
            f_at = np.concatenate([np.zeros((len(bp), 1)), bps[:, 1:] * big_a[:, :-1] - big_b[:, :-1]], 1)
        k = np.sum(np.where(np.isfinite(bps), f_at <= torque2, False), axis=1) - 1
        k = np.maximum(k, 0)
        rows = np.arange(len(bp))
        new = (torque2 + big_b[rows, k]) / big_a[rows, k]
        change = float(np.max(np.abs(new - theta)) / max(float(np.max(np.abs(new))), 1e-300)) if it else 1.0
        theta = new
        press = np.maximum(theta[:, None] * arm - gap, 0.0)
        w = np.where(np.isfinite(gap), press / q, 0.0)
        if nominal is None:  # the first guess of the contact approach: the load of one slice in full
            nominal = np.maximum(torque2 / (width * np.maximum(arm, 1e-300)), 1e-300)
    return theta, w, q, change


def loaded_cycle(mesh, torque, *, face_width: float, zeta, shifts, lead, material: Material | None = None,
                 helix_angle_deg: float = 0.0, steps: int = 2000, start: float = 0.0,
                 correction: float = ISO_CORRECTION, deviations: Deviations | None = None, cycles: int = 1):
    """Loaded contact of ``mesh`` (an external pair) over one cycle under the driver ``torque`` (N m).

    Parameters
    ----------
    mesh : Mesh (kind ``external``; both profiles external involute gears)
    torque : float or sequence of float, N m, >= 0, on the driver (a sequence: one rigid cycle, solved at
        every torque; returns a list)
    face_width : float, mm; zeta : (S,) slice centres, mm; shifts : (S,) or (1,) their driver turn
        from the lead (rad; one value for a spur pair); lead : (S,) float64, mm, separation added per
        slice (lead modifications and misalignment)
    material : Material (default steel)
    steps : int, driver angles per cycle
    deviations : Deviations or None
        Its run-out and pitch deviations (the centre distance and misalignment are the caller's: in the
        mesh and in ``lead``).
    cycles : int, consecutive mesh cycles (driver pitches) analysed
    correction : float
        Factor on the model's stiffness: ISO 6336-1's ``C_M`` (0.8) between the theoretical
        stiffness of solid teeth and the measured one (1: the bare model).

    Returns
    -------
    LoadedAnalysis, or a list of them for a sequence of torques
    """
    require(mesh.kind == "external", "kind", f"loaded contact analysis handles external pairs (got {mesh.kind})")
    torques = [torque] if np.ndim(torque) == 0 else list(torque)
    for t in torques:
        require(is_real(t) and 0 <= t <= 1e7, "torque", f"{t!r} must be in [0, 1e7] N m")
    require(is_real(correction) and 0 < correction <= 1, "correction", f"{correction!r} must be in (0, 1]")
    require(isinstance(steps, (int, np.integer)) and 8 <= steps <= 1_000_000, "steps",
            f"{steps!r} must be an integer in [8, 1000000]")
    require(isinstance(cycles, (int, np.integer)) and 1 <= cycles <= 10_000, "cycles",
            f"{cycles!r} must be an integer in [1, 10000]")
    material = material or Material()
    zeta = np.asarray(zeta, dtype=float)
    lead = np.asarray(lead, dtype=float)
    width = face_width / len(zeta)
    scale = correction * math.cos(math.radians(abs(helix_angle_deg)))  # as ISO 6336-1's C_M cos(beta)
    t2_max = max(torques) * 1e3 / abs(mesh.ratio)  # N mm on the mate
    c1, c2 = ToothCompliance(mesh.gear1, material), ToothCompliance(mesh.gear2, material)
    # approach scale: the whole load on one pair at a soft 4 N/(mm um), plus the lead separations
    reach = t2_max / (mesh.gear2.base_diameter / 2 * face_width * 4e3) + float(np.ptp(lead)) + 1e-4 * mesh.module
    if deviations is not None:
        reach += 2 * (abs(deviations.runout1) + abs(deviations.runout2)) + sum(
            np.abs(np.cumsum(d)).max(initial=0.0) for d in (deviations.pitch_deviations1, deviations.pitch_deviations2))
    total = steps * cycles
    phi = start + cycles * mesh.pitch1 * np.arange(total + 1) / total
    for _ in range(4):
        g = _Gaps(mesh, phi, zeta, np.asarray(shifts, dtype=float), reach, lead, deviations)
        l1 = np.sqrt(np.maximum(g.r1 ** 2 - c1.base_radius ** 2, 1e-12))
        l2 = np.sqrt(np.maximum(g.r2 ** 2 - c2.base_radius ** 2, 1e-12))
        g.rel = l1 * l2 / (l1 + l2)
        h1 = c1.lever(np.clip(g.r1, c1.radius[0], c1.radius[-1]))
        h2 = c2.lever(np.clip(g.r2, c2.radius[0], c2.radius[-1]))

        def hertz(w, _r=g.rel, _h1=h1, _h2=h2):
            return hertz_approach(w, _r, _h1, _h2, material)
        comp = (c1(g.r1) + c2(g.r2)) / scale
        sols = [_solve(g.gap, g.arm, comp, hertz, t * 1e3 / abs(mesh.ratio), width, scale) for t in torques]
        # a half left unrefined is farther than ``reach``: it stays clear while the approach is below that
        theta_max = max(float(np.max(sol[0])) for sol in sols)
        floor = float(np.min(g.gap[np.isfinite(g.gap)], initial=0.0))  # deviations may take gaps below zero
        if theta_max * float(np.max(g.arm[np.isfinite(g.gap)])) <= reach + min(float(lead.min()), floor):
            break
        reach *= 4
    ref = mesh.reference()
    if ref is None:
        ref = float(np.median(g.rigid_te))
    g.rigid = g.rigid_te - ref
    out = [_result(mesh, g, c1, material, t, sol, phi, zeta, face_width, width, reach, cycles)
           for t, sol in zip(torques, sols)]
    return out[0] if np.ndim(torque) == 0 else out


def _result(mesh, g, c1, material, torque, sol, phi, zeta, face_width, width, reach, cycles) -> LoadedAnalysis:
    theta, w, q, change = sol
    torque2 = torque * 1e3 / abs(mesh.ratio)
    te = g.rigid + mesh.working * theta if np.any(theta != 0) else g.rigid
    n, s_count = g.gap.shape[0], len(zeta)
    touch = np.isfinite(g.gap) & (theta[:, None] * g.arm - g.gap >= 0)
    teeth = np.unique(g.tooth[touch])
    load = np.zeros((n, s_count, len(teeth)))
    on = np.zeros((n, len(teeth)), bool)
    for j, t in enumerate(teeth):
        mine = g.tooth == t
        on[:, j] = np.any(mine & touch, axis=1)
        for s in range(s_count):
            load[:, s, j] = np.sum(np.where(mine & (g.slice == s), w, 0.0), axis=1)
    per_pair = load.sum(1)
    total = per_pair.sum(1, keepdims=True)
    sharing = np.divide(per_pair, total, out=np.zeros_like(per_pair), where=total > 0)
    pressed = w > 0
    stiffness = np.sum(np.where(pressed, width / q, 0.0), 1) / face_width * 1e-3  # N/(mm um)
    pressure = np.max(np.where(pressed, hertz_pressure(w, g.rel, material), 0.0), 1)
    residual = float(np.max(np.abs(np.sum(w * width * g.arm, 1) - torque2))) / torque2 if torque else 0.0
    rb = c1.base_radius
    roll = np.degrees(np.sqrt(np.maximum(g.r1 ** 2 - rb ** 2, 0.0)) / rb)
    lo, hi = np.degrees(np.sqrt(np.maximum(c1.radius[[0, -1]] ** 2 - rb ** 2, 0.0)) / rb)
    edges = np.linspace(lo, hi, _PATTERN_BINS + 1)
    pattern = np.zeros((_PATTERN_BINS, s_count))
    b = np.clip(np.searchsorted(edges, roll[pressed]) - 1, 0, _PATTERN_BINS - 1)
    np.maximum.at(pattern, (b, g.slice[pressed]), w[pressed])
    return LoadedAnalysis(
        torque=float(torque), driver_angle=phi[:n], transmission_error=te, rigid_transmission_error=g.rigid,
        load=load, pair_teeth=teeth, sharing=sharing, mesh_stiffness=stiffness, contact_pressure=pressure,
        pattern=pattern, pattern_roll_deg=0.5 * (edges[1:] + edges[:-1]), zeta=zeta,
        contact_ratio_loaded=float(on.sum(1).mean()), face_width=float(face_width), steps=len(phi) - 1,
        slices=int(s_count), cycles=int(cycles), refined_range=float(reach), hertz_change=float(change),
        torque_residual=residual)
