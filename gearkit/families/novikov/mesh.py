"""Meshing a Novikov pair in the transverse plane: where, and at what angle, the teeth touch.

A Novikov pair has no transverse overlap: two transverse sections touch only at the instant the
contact point passes through them, and it is that instant that fixes the contact. In the plane,
with gear 1 turned by phi_1 and gear 2 by its nominal angle plus a play rotation delta, the
contact of one zone solves four equations in ``(w_1, w_2, phi_1, delta)``: the working flanks meet
(two), their normals are parallel (one), and the common normal passes through the pole (one: the
instantaneous ratio equals z_1/z_2, the phase at which the travelling 3-D contact point crosses
this section). The flanks are the exact envelope branches of the generated gears, so the solution
is exact; the interference check then samples both outlines around the mesh and measures the
clearance everywhere else.

Frames: gear 1's centre at the origin, gear 2's at ``(0, a_w)``, the pole at
``(0, a_w z_1 / (z_1 + z_2))``, both gears as generated (tooth 0 on +y) and turned about their centres.
Because every transverse section of a helical gear is the same profile turned, the contact found
in one section is the contact in every section it travels through: its height does not change
along the face (:func:`contact_trace`).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from gearkit.distances import distances_to_polyline
from gearkit.errors import GeometryError
from gearkit.families.novikov.gear import tooth_profile
from gearkit.families.novikov.pair import NovikovPairSpec, novikov_pair_geometry

__all__ = ["MeshContact", "mesh_contact", "meshed_outlines", "contact_trace", "section_clearance", "signed_clearance"]


@dataclass(frozen=True)
class MeshContact:
    """A solved contact of one zone (lengths mm, angles rad; fixed frame, see the module docstring).

    ``rotations`` = (phi_1, gear 2's angle); ``play`` is delta, gear 2's rotation beyond its nominal
    angle that closes the backlash. ``contact_angle_transverse`` is the angle of the common normal
    with the pitch-circle tangent; ``contact_angle`` the same in the normal section
    (tan a_k = tan a_t cos beta). ``radii`` are the contact radii on gear 1 and gear 2; ``on_arcs``
    says whether the point lies on the working arcs that survive on both generated teeth.
    ``clearance`` is the smallest signed distance between the two outlines away from the contact
    (negative: interference), ``touches`` the number of separate places where they touch.
    """

    zone: int
    center_distance: float
    point: np.ndarray
    normal: np.ndarray
    rotations: tuple
    play: float
    contact_angle_transverse: float
    contact_angle: float
    radii: tuple
    on_arcs: bool
    clearance: float
    touches: int
    tol: float


class NoContact(GeometryError):
    """The working flanks do not meet at this centre distance: the pair does not mesh there (a
    finding of the check, not bad input)."""


def _rot(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s], [s, c]])


def _setup(spec: NovikovPairSpec, zone: int, a_w: float):
    geo = novikov_pair_geometry(spec)
    zn = spec.racks.zones[zone]
    profiles = (tooth_profile(spec.gear(1)), tooth_profile(spec.gear(2)))
    which = ("convex", "concave") if zn.convex_gear == 1 else ("concave", "convex")
    branches = tuple(profiles[k].working_branch(which[k]) for k in (0, 1))
    r1, r2 = geo.pitch_radii
    u_t = zn.mesh_offset * spec.module / math.cos(spec.beta)
    theta2_0 = math.pi + u_t / r2
    ratio = r1 / r2
    pole = np.array([0.0, a_w * spec.teeth1 / (spec.teeth1 + spec.teeth2)])
    return geo, zn, profiles, which, branches, theta2_0, ratio, pole


def _state(x, branches, theta2_0, ratio, a_w):
    w1, w2, phi1, delta = x
    q1, n1, _, _ = branches[0].solve(np.array([w1]))
    q2, n2, _, _ = branches[1].solve(np.array([w2]))
    r1m, r2m = _rot(phi1), _rot(theta2_0 - ratio * phi1 + delta)
    p1, m1 = r1m @ q1[0], r1m @ n1[0]
    p2, m2 = r2m @ q2[0] + np.array([0.0, a_w]), r2m @ n2[0]
    return p1, m1, p2, m2


def _residual(x, branches, theta2_0, ratio, a_w, pole):
    p1, m1, p2, m2 = _state(x, branches, theta2_0, ratio, a_w)
    d = p1 - p2
    return np.array([d[0], d[1], m1[0] * m2[1] - m1[1] * m2[0],
                     (p1[0] - pole[0]) * m1[1] - (p1[1] - pole[1]) * m1[0]])


def _solve(x0, args, scale):
    x = np.array(x0, dtype=float)
    h = np.array([1e-7, 1e-7, 1e-7, 1e-7])
    for _ in range(60):
        f = _residual(x, *args)
        jac = np.empty((4, 4))
        for k in range(4):
            e = np.zeros(4)
            e[k] = h[k]
            jac[:, k] = (_residual(x + e, *args) - _residual(x - e, *args)) / (2 * h[k])
        step = np.linalg.solve(jac, f)
        x = x - step
        if np.abs(step).max() < 1e-15 and np.abs(f[:2]).max() < 1e-12 * scale:
            break
    if np.abs(_residual(x, *args)[:2]).max() > 1e-9 * scale:
        raise NoContact("the contact of the working flanks could not be solved")
    return x


def signed_clearance(points, polygon):
    """Signed distance (mm) of ``points`` from a closed counter-clockwise ``polygon``: negative inside.

    The sign comes from the side of the nearest edge (a sampled smooth outline has no reflex
    vertex that could mislead it at the sampling tolerance).
    """
    from scipy.spatial import cKDTree

    poly = np.asarray(polygon, dtype=float)
    pts = np.asarray(points, dtype=float)
    n = len(poly)
    dist = distances_to_polyline(pts, poly, closed=True)
    _, idx = cKDTree(poly).query(pts, k=min(4, n))
    best = np.full(len(pts), np.inf)
    side = np.zeros(len(pts))
    for col in range(idx.shape[1]):
        for off in (0, -1):
            i = (idx[:, col] + off) % n
            a, b = poly[i], poly[(i + 1) % n]
            d = b - a
            t = np.clip(np.einsum("ij,ij->i", pts - a, d) / np.einsum("ij,ij->i", d, d), 0.0, 1.0)
            foot = a + t[:, None] * d
            dd = np.linalg.norm(pts - foot, axis=1)
            cr = d[:, 0] * (pts - a)[:, 1] - d[:, 1] * (pts - a)[:, 0]
            better = dd < best - 1e-15
            best = np.where(better, dd, best)
            side = np.where(better, cr, side)
    return np.where(side > 0, -dist, dist)


def _runs(mask):
    """Number of cyclic runs of True in a boolean array."""
    if mask.all():
        return 1
    return int(np.count_nonzero(mask & ~np.roll(mask, 1)))


def _interference(profiles, rotations, a_w, tol, window):
    """Smallest signed clearance (mm) between the placed outlines within ``window`` of the pole, and the
    number of separate places along gear 2's outline that touch (within 20 tol)."""
    outs = []
    for k, prof in enumerate(profiles):
        pts = prof.outline(tol) @ _rot(rotations[k]).T
        outs.append(pts + np.array([0.0, a_w]) if k == 1 else pts)
    pole_y = a_w * profiles[0].teeth / (profiles[0].teeth + profiles[1].teeth)
    worst, touches = math.inf, 0
    touch_eps = max(20 * tol, 1e-6 * profiles[0].module)
    for k in (0, 1):
        mine, other = outs[k], outs[1 - k]
        sel = np.flatnonzero((np.abs(mine[:, 0]) < window) & (np.abs(mine[:, 1] - pole_y) < window))
        if not len(sel):
            continue
        d = np.full(len(mine), np.inf)
        d[sel] = signed_clearance(mine[sel], other)
        worst = min(worst, float(d[sel].min()))
        if k == 1:
            touches = _runs(d <= touch_eps)
    return worst, touches


def mesh_contact(spec: NovikovPairSpec, zone: int = 0, center_distance: float | None = None,
                 tol: float | None = None, interference: bool = True) -> MeshContact:
    """Solve the contact of ``zone`` of the pair at centre distance ``center_distance`` (default: the spec's).

    Parameters
    ----------
    spec : NovikovPairSpec
    zone : int, index into ``spec.racks.zones`` (0: gear 1 convex; 1: gear 1 concave, double-arc only)
    center_distance : float or None, mm
    tol : float or None, mm; sampling tolerance of the interference check (default 1e-5 m_n)
    interference : bool; False skips the outline sampling (clearance = inf, touches = 1)
    """
    geo = novikov_pair_geometry(spec)
    a_w = geo.center_distance if center_distance is None else float(center_distance)
    if not 0 <= zone < len(spec.racks.zones):
        raise GeometryError(f"the {spec.racks.name} pair has {len(spec.racks.zones)} contact zone(s), not {zone + 1}")
    geo, zn, profiles, which, branches, theta2_0, ratio, pole = _setup(spec, zone, a_w)
    alpha = spec.racks.rack1.alpha
    w1 = profiles[0].branch_param(which[0], alpha)
    w2 = profiles[1].branch_param(which[1], alpha)
    s1 = float(branches[0].solve(np.array([w1]))[2][0])
    x0 = np.array([w1, w2, s1 / geo.pitch_radii[0], 0.0])
    args = (branches, theta2_0, ratio, a_w, pole)
    # close the play first with the flanks held at their design points, then solve the full system
    p1, _, p2, _ = _state(x0, branches, theta2_0, ratio, a_w)
    o2 = np.array([0.0, a_w])
    x0[3] = math.atan2(*(p1 - o2)[::-1]) - math.atan2(*(p2 - o2)[::-1])
    x = _solve(x0, args, spec.module)
    p1, m1, _, _ = _state(x, branches, theta2_0, ratio, a_w)
    at = math.atan2(abs(m1[1]), abs(m1[0]))
    ak = math.atan(math.tan(at) * math.cos(spec.beta))
    on = True
    for k in (0, 1):
        win = profiles[k].working_window(which[k])
        ang = float(profiles[k].rack_angle(which[k], x[k]))
        on &= win is not None and win[0] - 1e-12 <= ang <= win[1] + 1e-12
    rotations = (float(x[2]), float(theta2_0 - ratio * x[2] + x[3]))
    tol = 1e-5 * spec.module if tol is None else tol
    clearance, touches = math.inf, 1
    if interference:
        window = 3.0 * math.pi * geo.transverse_module
        clearance, touches = _interference(profiles, rotations, a_w, tol, window)
    radii = (float(np.hypot(*p1)), float(np.hypot(*(p1 - np.array([0.0, a_w])))))
    return MeshContact(zone, a_w, p1, m1, rotations, float(x[3]), at, ak, radii, bool(on), clearance, touches, tol)


def contact_trace(spec: NovikovPairSpec, contact: MeshContact, rotation: float = 0.0):
    """Axial positions (mm, within the face width) of the contacts of ``contact``'s zone when gear 1
    has turned by ``rotation`` (rad) from the contact's phase, one per tooth in mesh.

    A right-hand gear 1 turned by phi brings the section at ``z = r_1 phi / tan(beta)`` to the
    contact phase; teeth repeat every axial pitch. Every such section touches at ``contact.point``
    (the transverse sections are congruent), so the contact height is the same along the face.
    """
    geo = novikov_pair_geometry(spec)
    if geo.helix_angle == 0:
        return np.zeros(0)
    z0 = geo.pitch_radii[0] * rotation / math.tan(geo.helix_angle)
    p_x = geo.axial_pitch
    k = np.arange(math.floor(-z0 / p_x) - 1, math.ceil((spec.face_width - z0) / p_x) + 2)
    z = z0 + k * p_x
    return z[(z >= 0) & (z <= spec.face_width)]


def meshed_outlines(spec: NovikovPairSpec, tol: float | None = None, zone: int = 0,
                    center_distance: float | None = None):
    """Both outlines placed in mesh at ``zone``'s contact: gear 1 about the origin, gear 2 about
    ``(0, a_w)``; a list of two ``(n, 2)`` float64 arrays (mm), counter-clockwise, within ``tol``
    (default 1e-3 m_n) of the generated teeth."""
    tol = 1e-3 * spec.module if tol is None else tol
    c = mesh_contact(spec, zone, center_distance, interference=False)
    loops = []
    for k in (0, 1):
        pts = tooth_profile(spec.gear(k + 1)).outline(tol) @ _rot(c.rotations[k]).T
        loops.append(pts + np.array([0.0, c.center_distance]) if k else pts)
    return loops


def section_clearance(spec: NovikovPairSpec, contact: MeshContact, z: float, tol: float | None = None):
    """The transverse section at axial position ``z`` (mm) of the helical pair set up at ``contact``.

    At ``z = 0`` the sections are those of ``contact``; along the face gear 1 (right hand) turns by
    ``z tan(beta) / r_1`` and gear 2 (left hand) by ``-z tan(beta) / r_2``, i.e. every section is the
    transverse mesh at another phase. Returns the smallest signed distance (mm) of gear 2's outline
    from gear 1's near the mesh, and the point (fixed frame, mm) where it occurs.
    """
    geo = novikov_pair_geometry(spec)
    tol = 1e-5 * spec.module if tol is None else tol
    k = math.tan(geo.helix_angle) * z
    rot = (contact.rotations[0] + k / geo.pitch_radii[0], contact.rotations[1] - k / geo.pitch_radii[1])
    out = [tooth_profile(spec.gear(j + 1)).outline(tol) @ _rot(rot[j]).T for j in (0, 1)]
    out[1] = out[1] + np.array([0.0, contact.center_distance])
    window = 3.0 * math.pi * geo.transverse_module
    pole_y = contact.center_distance * spec.teeth1 / (spec.teeth1 + spec.teeth2)
    near = (np.abs(out[1][:, 0]) < window) & (np.abs(out[1][:, 1] - pole_y) < window)
    d = signed_clearance(out[1][near], out[0])
    i = int(np.argmin(d))
    return float(d[i]), out[1][near][i]
