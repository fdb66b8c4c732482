"""The envelope solver: where each tool point touches the blank, for every tool segment.

One implementation serves every family. For a tool segment and a generating motion, the
meshing equation ``n . v_rel = 0`` (the tool point's normal passes through the instant centre)
is solved and the contact point is carried into the blank frame. It is solved for either
unknown:

* ``along="tool"`` (gears): per tool point, for the roll at which it touches, in closed form
  (:meth:`gearkit.motion.RollingMotion.contact`);
* ``along="motion"`` (cams, and any tool whose points touch over a whole range of the motion,
  such as a roller during a dwell): per instant of the motion, for the tool point that touches,
  in closed form on lines and circular arcs (the foot of the normal from the instant centre).

The result is a :class:`Branch`: an exact parametric curve in the blank frame, evaluated to
machine precision wherever it is asked.
"""
from __future__ import annotations

import math
from itertools import accumulate

import numpy as np

from gearkit.motion import RollingMotion
from gearkit.segments import Segment
from gearkit.values import frozen


@frozen
class Branch:
    """Envelope of one tool segment over a sub-range ``[u0, u1]`` of its parameter.

    ``evaluate(w)`` with ``w in [0, 1]`` gives blank-frame points; ``label`` is the gear
    feature this branch forms (from the tool segment).
    """

    segment: Segment
    motion: RollingMotion
    u0: float = 0.0
    u1: float = 1.0
    root: str = "near"
    along: str = "tool"

    @property
    def label(self) -> str:
        return self.segment.label

    def solve(self, w, normals: bool = True):
        """Contact of the tool points at ``w`` (``normals=False`` skips the blank normals).

        Returns
        -------
        points : (n, 2) float64, blank frame, mm
        normals : (n, 2) float64, unit outward normals of the blank surface (into the tool)
        s : (n,) float64, roll (or motion parameter) at contact
        valid : (n,) bool, False where the normal misses the tool centrode (along the motion: where
            the foot of the normal from the instant centre falls off the segment)
        """
        u = _tool_parameters(self, w)
        if self.along == "motion":
            s = u
            u, valid = touching(self.segment, self.motion.tool_pole(s), self.root)
            p, _, n = self.segment.evaluate(u)
        else:
            p, _, n = self.segment.evaluate(u)
            s, valid = self.motion.contact(p, n, self.root)
        s0 = np.where(valid, s, 0.0)
        if not normals:
            return self.motion.carry(p, s0)[0], None, s, valid
        q, _, n = self.motion.carry(p, s0, n)
        return q, -n, s, valid

    def __call__(self, w):
        """Blank-frame points at ``w`` (the exact curve)."""
        return self.solve(w, normals=False)[0]

    @property
    def joint(self):
        """Branches with one key are evaluated in one call (:meth:`together`): one motion and root, along the
        tool; None along the motion (each on its own)."""
        return (id(self.motion), self.root) if self.along == "tool" else None  # the motion itself, not its equal

    def together(self, branches, ws):
        """Points of several branches of this one's :attr:`joint` key, each at its parameters ``ws``: the tool
        points of each evaluated on their own, the meshing equation solved and the contacts carried into the
        blank frame once for all (point by point: each branch's points to the last bit as it gives them alone)."""
        return [q for q, _, _ in solve_together(branches, ws)]

    def turning_together(self, branches, ws):
        """:meth:`turning` of several branches of this one's :attr:`joint` key, as :meth:`together` (None for
        a branch whose segment gives no monotone angle)."""
        return turning_together(branches, ws)

    def turning(self, w):
        """Points, unit tangents and the tangent's angle in two monotone parts, or None (see below).

        The envelope touches the tool, so its tangent is the tool's tangent carried into the blank:
        its angle is the tool tangent's angle (:meth:`gearkit.segments.Segment.turning`, monotone in
        ``u``) plus the motion's rotation at the contact roll, ``(1/c_b - 1/c_t) s`` (linear in ``s``).
        The roll is monotone along a tool segment: every normal of a line, an arc (through its centre),
        an involute (tangent to its base circle) or a cycloid (through its rolling point) meets the tool
        centrode once on the side taken, in the order of the segment. Returns ``parts`` ``(n, 2)``:
        each monotone in ``w``, their sum the tangent's angle up to a constant -- what
        :func:`gearkit.refine.refine_sample` bounds a chord's deviation by. None along the motion
        (a cam's follower: its contact turns both ways with the pressure angle).
        """
        if self.along != "tool":
            return None
        return turning_together([self], [w])[0]


def _tool_parameters(branch, w):
    w = np.asarray(w, dtype=float)
    if not w.ndim:  # np.atleast_1d's reshape, without its dispatch
        w = w.reshape(1)
    if branch.u1 == 1.0 and branch.u0 == 0.0 and math.copysign(1.0, branch.u0) == 1.0:
        # +0 (1 - w) + 1 w is w itself to the bit (+ 0.0: a -0 sums to +0 there too)
        return w + 0.0
    return branch.u0 * (1.0 - w) + branch.u1 * w  # exact at both ends (u0 > u1 walks backwards)


def _joined(arrays):
    return arrays[0] if len(arrays) == 1 else np.concatenate(arrays)


def _parted(sizes, *arrays):
    """The arrays cut into consecutive parts of ``sizes``: one tuple per part."""
    if len(sizes) == 1:
        return [arrays]
    ends = list(accumulate(sizes))
    return [tuple(a[i - n:i] for a in arrays) for n, i in zip(sizes, ends)]


def solve_together(branches, ws, carry: bool = True):
    """``(points, s, valid)`` of each branch (one motion and root, along the tool) at its parameters ``ws``,
    as :meth:`Branch.solve` gives them without normals: contact, pose and turn into the blank once for all
    (``carry=False``: the contact alone, the points None)."""
    first = branches[0]
    tool = [br.segment.evaluate(_tool_parameters(br, w)) for br, w in zip(branches, ws)]
    p, n = _joined([t[0] for t in tool]), _joined([t[2] for t in tool])
    s, valid = first.motion.contact(p, n, first.root)
    if not carry:
        return [(None, *part) for part in _parted([len(t[0]) for t in tool], s, valid)]
    q = first.motion.carry(p, np.where(valid, s, 0.0))[0]
    return _parted([len(t[0]) for t in tool], q, s, valid)


def turning_together(branches, ws):
    """:meth:`Branch.turning` of each branch (one motion and root, along the tool) at its parameters ``ws``:
    contact, pose and turn into the blank once for all; None for a branch whose segment gives no angle."""
    turned = [br.segment.turning(_tool_parameters(br, w)) for br, w in zip(branches, ws)]
    have = [i for i, t in enumerate(turned) if t is not None]
    out = [None] * len(branches)
    if not have:
        return out
    first = branches[have[0]]
    p, t, tool_angle = (_joined([turned[i][j] for i in have]) for j in range(3))
    s, valid = first.motion.contact(p, np.stack([-t[..., 1], t[..., 0]], -1), first.root)
    q, angle, t = first.motion.carry(p, np.where(valid, s, 0.0), t)
    for i, part in zip(have, _parted([len(turned[i][0]) for i in have], q, t,
                                     np.stack([tool_angle, angle], -1))):
        out[i] = part
    return out


def touching(segment: Segment, poles, root: str = "near"):
    """Parameter of the point of ``segment`` whose normal line passes through each pole (tool frame).

    Closed forms: on a line, the foot of the perpendicular from the pole; on a circular arc of
    centre ``c``, the point ``c + r m`` with ``m = (pole - c)/|pole - c|`` (``root="near"``: the side
    facing the pole) or ``-m`` (``"far"``); a corner (``r = 0``) touches at its point, the normal
    along ``m``. The segment's affine map must be a similarity (true of every tool a cam uses).

    Returns
    -------
    u : (n,) float64 in [0, 1] (clipped where invalid)
    valid : (n,) bool, the contact lies on the segment
    """
    pole = np.atleast_2d(np.asarray(poles, dtype=float))
    a11, a12, a21, a22, b1, b2 = segment.affine
    mat = np.array([[a11, a12], [a21, a22]])
    scale = float(np.sqrt(abs(np.linalg.det(mat))))
    if not np.allclose(mat.T @ mat, scale * scale * np.eye(2), rtol=1e-12, atol=1e-15):
        raise ValueError("touching: the segment's affine map must be a similarity")
    local = (pole - np.array([b1, b2])) @ np.linalg.inv(mat).T  # poles in the primitive's frame
    eps = 1e-12
    if segment.kind == "line":
        x0, y0, x1, y1 = segment.data
        d = np.array([x1 - x0, y1 - y0])
        u = ((local - np.array([x0, y0])) @ d) / float(d @ d)
    elif segment.kind == "arc":
        cx, cy, r, a0, a1 = segment.data
        m = local - np.array([cx, cy])
        if root == "far":
            m = -m
        elif root != "near":
            raise ValueError(f"root must be 'near' or 'far' along the motion, not {root!r}")
        ang = np.arctan2(m[:, 1], m[:, 0])
        lo = min(a0, a1)
        ang = lo + np.mod(ang - lo + eps, 2.0 * np.pi) - eps
        u = (ang - a0) / (a1 - a0)
    else:
        raise ValueError(f"touching: no closed form on a {segment.kind!r} segment (lines and arcs only)")
    if segment.reverse:
        u = 1.0 - u
    valid = np.isfinite(u) & (u >= -eps) & (u <= 1.0 + eps)
    return np.clip(np.where(np.isfinite(u), u, 0.0), 0.0, 1.0), valid


#: parameters a whole tool segment is first solved at, to find where the meshing equation has a solution
_RUN_GRID = np.linspace(0.0, 1.0, 65)


def _valid_runs(branch: Branch, valid):
    """Sub-ranges of ``[0, 1]`` where the meshing equation has a solution (``valid`` on ``_RUN_GRID``), ends
    bisected."""
    w = _RUN_GRID
    if valid.all():
        return [(0.0, 1.0)]
    runs = []
    edges = np.flatnonzero(np.diff(valid.astype(int)))

    def bisect(a, b):  # valid(a) != valid(b)
        va = bool(branch.solve([a], normals=False)[3][0])
        for _ in range(60):
            m = 0.5 * (a + b)
            if bool(branch.solve([m], normals=False)[3][0]) == va:
                a = m
            else:
                b = m
        return a if va else b
    bounds = [bisect(w[i], w[i + 1]) for i in edges]
    marks = [0.0] + bounds + [1.0]
    state = bool(valid[0])
    for a, b in zip(marks[:-1], marks[1:]):
        if state and b > a:
            runs.append((a, b))
        state = not state
    return runs


def chain_branches(chain, motion: RollingMotion, root: str = "near", return_root: str | None = None):
    """Branches for a chain of tool segments, split where the meshing equation has no root.

    With ``return_root`` the chain is walked twice, once with each root, and the two walks are
    joined into one continuous curve where they meet: at the chain's end (out with ``root``,
    back with ``return_root``) or at its start (back with ``return_root``, then out with
    ``root``), whichever end the two walks share. This is the envelope of a tool whose points
    touch the blank twice per pass (a pin cutting a cycloidal disc touches near the root with
    the near root and near the crest with the far one); the walks meet where the normal line
    is tangent to the tool centrode, which must be an end of the chain.
    """
    out = []
    wholes = [Branch(seg, motion, root=root) for seg in chain]
    solved = solve_together(wholes, [_RUN_GRID] * len(wholes), carry=False) if wholes else []  # where valid
    for seg, whole, (_, _, valid) in zip(chain, wholes, solved):
        for a, b in _valid_runs(whole, valid):
            out.append(whole if (a, b) == (0.0, 1.0) else Branch(seg, motion, a, b, root))
    if return_root is None:
        return tuple(out)
    back = chain_branches(chain, motion, return_root)
    if not out or not back:
        return tuple(out) + tuple(back)
    returning = [Branch(br.segment, motion, br.u1, br.u0, return_root) for br in reversed(back)]
    gap_end = np.linalg.norm(out[-1](1.0)[0] - back[-1](1.0)[0])
    gap_start = np.linalg.norm(out[0](0.0)[0] - back[0](0.0)[0])
    return tuple(out + returning) if gap_end <= gap_start else tuple(returning + out)
