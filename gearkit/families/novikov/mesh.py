"""Meshing a Novikov pair in the transverse plane: where, and at what angle, the teeth touch.

A Novikov pair has no transverse overlap: two transverse sections touch only at the instant the
contact point passes through them, and it is that instant that fixes the contact. In the plane,
with gear 1 turned by phi_1 and gear 2 by its nominal angle plus a play rotation delta, the
contact of one zone solves four equations in ``(w_1, w_2, phi_1, delta)``: the working flanks meet
(two), their outward normals are opposite (one), and the common normal passes through the pole (one: the
instantaneous ratio equals z_1/z_2, the phase at which the travelling 3-D contact point crosses
this section). The flanks are the exact envelope branches of the generated gears, so the solution
is exact. It is the contact nearest the design point: a bounded, damped Newton iteration from there
keeps both flank parameters inside their arcs and the phase within half a pitch; where no such
contact exists the pair does not mesh (:class:`NoContact`); the interference check then samples both outlines around the mesh and measures the
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

from gearkit.chords import chord_distance
from gearkit.curves import cross2, rotate
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
    ``flank_params`` are the contact's parameters (w_1, w_2) on the two working branches
    (:meth:`~gearkit.families.novikov.gear.NovikovProfile.working_branch`), each in [0, 1].
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
    flank_params: tuple


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


def _states(x, branches, theta2_0, ratio, a_w):
    """Placed points and outward unit normals of both flanks at the rows of ``x`` ((k, 4): w1, w2, phi1,
    delta), one batched evaluation per branch; rows where a branch has no envelope point come back NaN."""
    x = np.atleast_2d(x)
    out = []
    for k, ang in ((0, x[:, 2]), (1, theta2_0 - ratio * x[:, 2] + x[:, 3])):
        q, n, _, valid = branches[k].solve(x[:, k])
        q = np.where(valid[:, None], q, np.nan)
        p, m = rotate(q, ang, n)
        out += [p + np.array([0.0, a_w]) if k else p, m]
    return out


def _residuals(x, branches, theta2_0, ratio, a_w, pole):
    """The four contact equations at the rows of ``x``: the flanks meet (two, mm), the normals are opposite
    (one: the angle, rad, from -m2 to m1 -- zero only for opposite normals, never for parallel ones), the
    common normal passes through the pole (one, mm)."""
    p1, m1, p2, m2 = _states(x, branches, theta2_0, ratio, a_w)
    d = p1 - p2
    turn = np.arctan2(cross2(m1, -m2), -np.einsum("ij,ij->i", m1, m2))
    return np.stack([d[:, 0], d[:, 1], turn, cross2(p1 - pole, m1)], -1)


#: Newton step bounds: the flank parameters move at most this much per step (the branches span [0, 1]),
#: the rotations at most this fraction of their angular pitch
_W_STEP, _PITCH_STEP = 0.25, 0.125
#: a step below this (w and rad) that no longer halves is at the round-off floor
_FLOOR = 1e-11
_ARMIJO, _HALVINGS, _ITERATIONS = 1e-4, 30, 60
_DIFF = 1e-7  # central-difference step of the Jacobian (w and rad)
_AT_END = 1e-6  # a flank parameter this near 0 or 1 where the iteration stalls: held at an arc's end


def _solve(x0, args, scale, pitches):
    """Damped, bounded Newton iteration for the contact nearest ``x0``.

    Each step solves the linearised system (Jacobian by central differences, its nine rows in one
    batched evaluation), is shortened to the step bounds, projected onto the branches' domains
    ``0 <= w <= 1``, and halved until the residual norm (lengths in units of ``scale``) decreases
    sufficiently. It stops when no shortened step decreases the residual, or at the round-off floor
    (a step below ``_FLOOR`` no larger than half the previous one). The root is accepted only with
    opposite outward normals, both points inside the domains and the phase within half a pitch of
    the start; otherwise :class:`NoContact`.
    """
    units = np.array([scale, scale, 1.0, scale])

    def res(x):
        return _residuals(x, *args) / units

    x = np.array(x0, dtype=float)
    f = res(x)[0]
    if not np.all(np.isfinite(f)):
        raise NoContact("the working flanks have no envelope point at the design point")
    norm = float(np.linalg.norm(f))
    eye = _DIFF * np.eye(4)
    limit = np.array([_W_STEP, _W_STEP, _PITCH_STEP * pitches[0], _PITCH_STEP * pitches[1]])
    last = np.inf
    for _ in range(_ITERATIONS):
        fd = res(np.concatenate([x + eye, x - eye]))
        jac = (fd[:4] - fd[4:]).T / (2 * _DIFF)
        if not np.all(np.isfinite(jac)):
            break
        step = -np.linalg.lstsq(jac, f, rcond=None)[0]
        step *= min(1.0, float(np.min(limit / np.maximum(np.abs(step), 1e-300))))
        trial = x + (0.5 ** np.arange(_HALVINGS))[:, None] * step
        trial[:, :2] = np.clip(trial[:, :2], 0.0, 1.0)
        norms = np.linalg.norm(res(trial), axis=1)
        ok = np.flatnonzero(norms <= norm * (1.0 - _ARMIJO * 0.5 ** np.arange(_HALVINGS)))
        if not len(ok):
            break
        moved = float(np.abs(trial[ok[0]] - x).max())
        x, norm = trial[ok[0]], float(norms[ok[0]])
        f = res(x)[0]
        if moved < _FLOOR and moved > 0.5 * last or moved == 0.0:
            break
        last = moved
    p1, m1, p2, m2 = (v[0] for v in _states(x, *args[:4]))
    f = res(x)[0]
    if not (np.abs(f).max() <= 1e-9 and float(m1 @ m2) < 0):
        if np.min(np.minimum(x[:2], 1.0 - x[:2])) < _AT_END:
            raise NoContact("the contact runs off the end of a working arc: the arcs would touch beyond it")
        raise NoContact("no point near the design point where the working arcs touch with opposite normals "
                        "and the common normal passes through the pole")
    if abs(x[2] - x0[2]) > 0.5 * pitches[0] or abs(x[3] - x0[3]) > 0.5 * pitches[1]:
        raise NoContact("the nearest contact of the working flanks is on another tooth pair")
    return x


def signed_clearance(points, polygon):
    """Signed distance (mm) of ``points`` from a closed counter-clockwise ``polygon``: negative inside.

    The distance is that of :func:`gearkit.distances.distances_to_polyline` (the edges at the six
    nearest vertices). Its sign is the side of the nearest edge where the nearest point is inside that
    edge; where it is a vertex, the side of the vertex's bisector (the sum of its two edges' unit
    normals): at a corner that turns by more than a right angle (a tooth's tip corner) a point off the
    corner can lie on the inner side of one edge's line and still be outside. One neighbour search
    serves both.

    >>> tip = np.array([[0.0, 0.0], [1.0, 0.0], [0.0, 0.2]])  # a sharp corner at (1, 0)
    >>> round(float(signed_clearance(np.array([[2.0, -0.5]]), tip)[0]), 6)  # outside: sqrt(1 + 0.5**2)
    1.118034
    """
    from scipy.spatial import cKDTree

    poly = np.asarray(polygon, dtype=float)
    poly = poly[np.any(poly != np.roll(poly, 1, axis=0), axis=1)]  # no zero-length edge
    pts = np.asarray(points, dtype=float)
    n = len(poly)
    _, idx = cKDTree(poly).query(pts, k=min(6, n))
    idx = idx.reshape(len(pts), -1)
    best = np.full(len(pts), np.inf)
    edge = np.zeros(len(pts), dtype=int)
    for col in range(idx.shape[1]):
        for off in (0, -1):
            i = (idx[:, col] + off) % n
            dd = chord_distance(poly[i], poly[(i + 1) % n], pts)
            better = dd < best
            best = np.where(better, dd, best)
            edge = np.where(better, i, edge)
    a, b = poly[edge], poly[(edge + 1) % n]
    d = b - a
    t = np.einsum("ij,ij->i", pts - a, d) / np.einsum("ij,ij->i", d, d)
    side = cross2(d, pts - a)  # > 0: on the inner (left) side of the edge
    tang = np.diff(np.vstack([poly[-1:], poly, poly[:1]]), axis=0)
    tang /= np.hypot(*tang.T)[:, None]  # tang[k]: unit direction of the edge into vertex k; tang[k + 1]: out of it
    for at_end, vert in ((t <= 0.0, edge), (t >= 1.0, (edge + 1) % n)):
        inner = tang[vert] + tang[vert + 1]  # the bisector's direction turned a quarter: left of both edges
        side = np.where(at_end, cross2(inner, pts - poly[vert]), side)
    return np.where(side > 0, -best, best)


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
    p1, _, p2, _ = (v[0] for v in _states(x0, branches, theta2_0, ratio, a_w))
    o2 = np.array([0.0, a_w])
    x0[3] = math.atan2(*(p1 - o2)[::-1]) - math.atan2(*(p2 - o2)[::-1])
    x = _solve(x0, args, spec.module, (2 * math.pi / spec.teeth1, 2 * math.pi / spec.teeth2))
    p1, m1, _, _ = (v[0] for v in _states(x, branches, theta2_0, ratio, a_w))
    at = math.atan2(abs(m1[1]), abs(m1[0]))
    ak = math.atan(math.tan(at) * math.cos(spec.beta))
    on = all(profiles[k].on_working_arc(which[k], float(profiles[k].rack_angle(which[k], x[k])), 1e-12)
             for k in (0, 1))
    rotations = (float(x[2]), float(theta2_0 - ratio * x[2] + x[3]))
    tol = 1e-5 * spec.module if tol is None else tol
    clearance, touches = math.inf, 1
    if interference:
        window = 3.0 * math.pi * geo.transverse_module
        clearance, touches = _interference(profiles, rotations, a_w, tol, window)
    radii = (float(np.hypot(*p1)), float(np.hypot(*(p1 - np.array([0.0, a_w])))))
    return MeshContact(zone, a_w, p1, m1, rotations, float(x[3]), at, ak, radii, bool(on), clearance, touches, tol,
                       (float(x[0]), float(x[1])))


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
