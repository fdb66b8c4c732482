"""Tooth geometry for the meshing simulation: the driver's boundary and the mate's half-width.

Both come straight from a profile's exact half tooth (``profile.half.pieces``: labelled curves
``t in [0, 1] -> points``, from the tip at the tooth centre line to the space centre, tooth 0
centred on +y). Every value the simulation reports is evaluated on those pieces; the search
for it may run on their tables (``table``, set by the mesh: :mod:`gearkit.contact.table`).

* :class:`Boundary` (the driver, gear 1): the pieces and a search polyline through them
  (every chord within ``tol``), as intervals ``[ta, tb]`` of one piece between consecutive
  samples.
* :class:`HalfWidth` (the mate, gear 2): the tooth as a function of the radial coordinate.
  In the mate's frame a point has a radial coordinate ``rho`` (radius about the mate's centre;
  for a rack the height above its datum line) and a periodic coordinate ``psi`` (polar angle
  from the tooth centre line towards +x; for a rack the distance x). The half tooth is a
  single-valued ``psi = h(rho)`` between the tip and the root (radius monotone along it; tip
  and root arcs about the centre are its ends), so the space around a point at ``rho`` is
  ``|u| <= w(rho) = P/2 - h(rho)`` (``P`` the pitch in ``psi``; ``u`` measured from the space
  centre). Beyond the tip ``w = inf`` (no tooth there); inside the root circle there is no
  space, ``w < 0`` (growing with the depth). :meth:`HalfWidth.exact` solves ``rho(t) = rho`` on the
  pieces by the secant method from a table, to machine precision.
"""
from __future__ import annotations

import numpy as np

from gearkit.accuracy import adaptive_sample
from gearkit.curves import polar_from_y
from gearkit.errors import GeometryError

__all__ = ["Boundary", "HalfWidth", "evaluate_pieces", "linear_from_y"]

#: relative radial extent below which a piece is an arc about the centre (tip or root arc)
_FLAT = 1e-11
#: secant iterations of the radius inversion (it converges in 2 to 4 from the table; bisection
#: steps, when the secant leaves the bracket, make sure of the rest)
_SECANT = 60


def linear_from_y(points):
    """Rack counterpart of :func:`~gearkit.curves.polar_from_y`: height y and position x."""
    p = np.asarray(points, dtype=float)
    return p[..., 1], p[..., 0]


def evaluate_pieces(pieces, k, t):
    """Points of ``pieces[k[i]]`` at ``t[i]`` (arrays of the same shape), ``(..., 2)`` float64."""
    k = np.asarray(k)
    t = np.asarray(t, dtype=float)
    out = np.empty(t.shape + (2,))
    for kk in np.flatnonzero(np.bincount(k.ravel(), minlength=len(pieces))):  # the pieces present (few, numbered)
        sel = k == kk
        out[sel] = pieces[int(kk)](t[sel])
    return out


def _curvature(points):
    """Curvature estimate (1/mm) on each chord of a polyline: the larger turning rate at its ends."""
    d = np.diff(points, axis=0)
    length = np.linalg.norm(d, axis=1)
    ang = np.arctan2(d[:, 1], d[:, 0])
    turn = np.abs(np.mod(np.diff(ang) + np.pi, 2 * np.pi) - np.pi) / np.maximum(
        0.5 * (length[1:] + length[:-1]), 1e-300)
    node = np.concatenate([[0.0], turn, [0.0]])
    node[0], node[-1] = node[1] if len(node) > 2 else 0.0, node[-2] if len(node) > 2 else 0.0
    return np.maximum(node[:-1], node[1:])


def _pieces_of(profile):
    pieces = [pc for pc in profile.half.pieces if pc.w1 != pc.w0]
    if not pieces:
        raise GeometryError("the profile has an empty half tooth")
    return tuple(pieces)


class Boundary:
    """The driver's exact half tooth and its search polyline.

    Attributes
    ----------
    pieces : tuple of Piece (tip to space centre)
    labels : tuple of str
    points : (M + 1, 2) float64, mm, the samples (piece ends included, shared at joins)
    piece, ta, tb : (M,) the piece and parameter range of interval ``m`` (samples ``m``, ``m + 1``)
    corner_end : (M + 1,) bool, sample ``m`` is a join that is not smooth (a corner of the tooth)
    """

    def __init__(self, profile, tol: float):
        self.pieces = _pieces_of(profile)
        self.table = None
        self.labels = tuple(pc.label for pc in self.pieces)
        joins = tuple(profile.half.joins) if len(profile.half.joins) == len(profile.half.pieces) - 1 else ()
        pts, kk, ta, tb, corner = [], [], [], [], [bool(getattr(profile.half, "pointed", False))]
        for k, pc in enumerate(self.pieces):
            w, p, _ = adaptive_sample(pc, tol)
            pts.append(p if k == 0 else p[1:])
            kk.append(np.full(len(w) - 1, k))
            ta.append(w[:-1])
            tb.append(w[1:])
            corner += [False] * (len(w) - 2) + [k + 1 < len(self.pieces) and (not joins or joins[k] != "smooth")]
        self.points = np.concatenate(pts)
        self.piece = np.concatenate(kk)
        self.ta = np.concatenate(ta)
        self.tb = np.concatenate(tb)
        self.corner_end = np.array(corner)
        radius = np.hypot(self.points[:, 0], self.points[:, 1])
        self.radius_range = (float(radius.min()), float(radius.max()))
        #: chord length of every interval, mm
        self.chord = np.linalg.norm(np.diff(self.points, axis=0), axis=1)

    def evaluate(self, k, t, exact: bool = False):
        """Points (own frame, right half) of pieces ``k`` at parameters ``t``: exact, or from the
        table (:class:`~gearkit.contact.table.CurveTable`) once the mesh has set one."""
        if self.table is not None and not exact:
            return self.table.evaluate(k, t)
        return evaluate_pieces(self.pieces, k, t)

    def probes(self, count: int):
        """Table points at ``count`` parameters evenly spaced over every polyline interval (its ends
        included), as the minimiser spaces them: ``(t, x, y)``, each ``(count, M)``; made once per table."""
        cache = self.__dict__.setdefault("_probes", {})
        if count not in cache or cache[count][0] is not self.table:  # (kept with the table it was read off)
            frac = np.linspace(0.0, 1.0, count)
            t = self.ta[None, :] + frac[:, None] * (self.tb - self.ta)[None, :]
            x, y = self.table.evaluate_xy(np.broadcast_to(self.piece, t.shape).ravel(), t.ravel())
            cache[count] = (self.table, t, x.reshape(t.shape), y.reshape(t.shape))
        return cache[count][1:]


class HalfWidth:
    """Half width ``w(rho)`` of the mate's tooth space (see the module notes).

    Parameters
    ----------
    profile : ToothProfile-like (``half.pieces``) of the mate
    pitch : float, the period of ``psi`` (rad: 2 pi / z; mm for a rack)
    coords : callable, points -> (rho, psi): ``polar_from_y`` or :func:`linear_from_y`
    tol : float, mm, chord tolerance of the start table
    """

    def __init__(self, profile, pitch: float, coords, tol: float):
        self.pieces = _pieces_of(profile)
        #: a :class:`~gearkit.contact.table.WidthTable` once the mesh has set one (see :meth:`width`)
        self.table = None
        self.labels = tuple(pc.label for pc in self.pieces)
        self.pitch = float(pitch)
        self.coords = coords
        rows = []
        for k, pc in enumerate(self.pieces):
            ends = coords(pc(np.array([0.0, 0.5, 1.0])))[0]
            if np.ptp(ends) <= _FLAT * max(abs(ends).max(), 1.0):
                continue  # an arc about the centre: the tip or the root, an end of the function
            w, p, _ = adaptive_sample(pc, tol)
            rho, psi = coords(p)
            rows.append((k, w, rho, psi, _curvature(p)))
        if not rows:
            raise GeometryError("the mate's half tooth has no flank (every piece is an arc about its centre)")
        rho_all = np.concatenate([r[2] for r in rows])
        steps = np.diff(rho_all)
        span = abs(rho_all[-1] - rho_all[0])
        if not (np.all(steps >= -1e-12 * span) or np.all(steps <= 1e-12 * span)):
            raise GeometryError("the mate's tooth is not single-valued in radius (an overhang): the contact "
                                "simulation needs a mate whose flank radius is monotone from tip to root; "
                                "swap the gears")
        self.rho_tip, self.rho_root = float(rho_all[0]), float(rho_all[-1])
        #: round-off of a radial coordinate (mm): where a crossing of the tip circle has converged
        self.noise = 4e-16 * max(abs(self.rho_tip), abs(self.rho_root), 1.0)
        self.outward = 1.0 if self.rho_tip > self.rho_root else -1.0
        self.w_tip = self.pitch / 2 - float(rows[0][3][0])
        self.w_root = self.pitch / 2 - float(rows[-1][3][-1])
        self.tip_label = self.labels[rows[0][0]]
        # intervals between consecutive samples, ordered by increasing rho
        k_i = np.concatenate([np.full(len(r[1]) - 1, r[0]) for r in rows])
        t0 = np.concatenate([r[1][:-1] for r in rows])
        t1 = np.concatenate([r[1][1:] for r in rows])
        r0 = np.concatenate([r[2][:-1] for r in rows])
        r1 = np.concatenate([r[2][1:] for r in rows])
        w0 = self.pitch / 2 - np.concatenate([r[3][:-1] for r in rows])
        w1 = self.pitch / 2 - np.concatenate([r[3][1:] for r in rows])
        if self.outward > 0:  # tip first means decreasing rho: reverse everything
            k_i, t0, t1, r0, r1, w0, w1 = (a[::-1] for a in (k_i, t1, t0, r1, r0, w1, w0))
        keep = r1 > r0
        self._k, self._t0, self._t1, self._r0, self._r1 = k_i[keep], t0[keep], t1[keep], r0[keep], r1[keep]
        self._w0, self._w1 = w0[keep], w1[keep]
        self._grid_r = np.concatenate([self._r0, self._r1[-1:]])
        self._grid_w = np.concatenate([self._w0, self._w1[-1:]])
        kap = np.concatenate([r[4] for r in rows])  # per interval, in chain order
        self._kappa = (kap[::-1] if self.outward > 0 else kap)[keep]
        # where the flank meets its end circle tangentially (a rounded crest, a fillet running into
        # the root) rho(t) is stationary: near there the radius is matched through sqrt(|rho - end|)
        self._anchor = np.full(len(self._k), np.nan)
        #: the tip is a rounded crest (the flank meets the tip circle tangentially)
        self.crest = False
        for end, first in ((self.rho_tip, rows[0]), (self.rho_root, rows[-1])):
            k, w = first[0], first[1]
            at, step = (w[0], 1e-6) if first is rows[0] else (w[-1], -1e-6)
            pc = self.pieces[k]
            p0, p1 = pc(np.array([at])), pc(np.array([at + step * (w[-1] - w[0])]))
            radial = abs(coords(p1)[0][0] - coords(p0)[0][0]) / max(np.linalg.norm(p1 - p0), 1e-300)
            if radial < 1e-3:
                near = np.argsort(np.minimum(abs(self._r0 - end), abs(self._r1 - end)))[:3]
                self._anchor[near] = end
                self.crest = self.crest or first is rows[0]
        # the largest curvature of each table interval and its neighbours
        last = len(self._kappa) - 1
        idx = np.arange(len(self._kappa))
        self._kappa3 = np.maximum(np.maximum(self._kappa[np.maximum(idx - 1, 0)], self._kappa),
                                  self._kappa[np.minimum(idx + 1, last)])
        #: radial scale turning a depth below the root into an angle-like space width
        self.root_scale = abs(self.rho_root) if coords is polar_from_y else 1.0
        # the arm of the flank's normal at the nodes, from the neighbouring chords' slopes dw/drho
        slope = np.abs(self._w1 - self._w0) / (self._r1 - self._r0)
        node_slope = np.maximum(np.concatenate([slope[:1], slope]), np.concatenate([slope, slope[-1:]]))
        s = np.abs(self._grid_r) if self.root_scale != 1.0 else np.ones_like(self._grid_r)
        self._arm_node = s / np.sqrt(1.0 + (s * node_slope) ** 2)
        for end in (self.rho_tip, self.rho_root):  # a stationary end: the normal runs through the centre
            if np.isfinite(self._anchor).any() and np.any(self._anchor == end):
                self._arm_node[np.argmin(np.abs(self._grid_r - end))] = 0.0
        # per interval, for the interpolations of the search (:meth:`coarse`, :meth:`arm`)
        self._graze = np.isfinite(self._anchor)
        self._inv = 1.0 / (self._r1 - self._r0)
        self._dw = self._w1 - self._w0
        with np.errstate(divide="ignore"):
            step = np.diff(self._grid_r)
            self._inv_grid = np.where(step > 0, 1.0 / np.where(step > 0, step, 1.0), 0.0)
        self._darm = np.diff(self._arm_node)

    # -- regions ------------------------------------------------------------------------------
    def free(self, rho):
        """True beyond the tip (no tooth of the mate at this radial coordinate)."""
        return np.asarray(rho) > self.rho_tip if self.outward > 0 else np.asarray(rho) < self.rho_tip

    def _body(self, rho):
        return np.asarray(rho) < self.rho_root if self.outward > 0 else np.asarray(rho) > self.rho_root

    def _body_width(self, rho):
        # inside the root circle everything is material: no space (w < 0; it jumps from w_root)
        return self.outward * (rho - self.rho_root) / self.root_scale

    def coarse(self, rho, at=None):
        """``w(rho)`` interpolated in the table (linearly in ``sqrt(|rho - end|)`` next to a stationary
        end, where ``w`` has a square-root behaviour); inf beyond the tip. ``at``: :meth:`lookup` of
        ``rho``, when the caller has it."""
        rho = np.asarray(rho, dtype=float)
        j, off = self.lookup(rho) if at is None else at
        frac = (rho - self._r0[j]) * self._inv[j]
        g = np.nonzero(self._graze[j])
        if g[0].size:
            jg = j[g]
            a = self._anchor[jg]
            sq = np.sqrt(np.abs(rho[g] - a)), np.sqrt(np.abs(self._r0[jg] - a)), np.sqrt(np.abs(self._r1[jg] - a))
            with np.errstate(invalid="ignore", divide="ignore"):
                frac[g] = np.nan_to_num((sq[0] - sq[1]) / (sq[2] - sq[1]))
        np.minimum(np.maximum(frac, 0.0, out=frac), 1.0, out=frac)  # (np.clip's wrapper costs more)
        w = self._w0[j] + frac * self._dw[j]
        if off.any():
            w = np.where(self._body(rho), self._body_width(rho), w)
            w = np.where(self.free(rho), np.inf, w)
        return w

    def lookup(self, rho):
        """The table interval of each ``rho`` and whether it is off the flank (beyond the tip or inside
        the root circle): shared by :meth:`coarse`, :meth:`arm` and :meth:`curvature`."""
        j = np.minimum(np.maximum(np.searchsorted(self._r0, rho, side="right") - 1, 0), len(self._r0) - 1)
        return j, self.free(rho) | self._body(rho)

    def exact(self, rho, guess=None, tangent=False):
        """``w(rho)`` on the exact pieces.

        The radius is matched by the secant method from the table interval's ends (a bracket that
        every evaluation narrows; bisection when a step leaves it), to round-off.

        Parameters
        ----------
        rho : float64 array
        guess : (piece, t, rho_at_t) arrays or None
            A nearby solution (e.g. the previous one of an iteration), used as the first point.
        tangent : bool or bool array (``rho``'s shape)
            Also return the piece's unit tangent at the solution (two more evaluations), everywhere or where True.

        Returns
        -------
        w : float64 array (inf beyond the tip)
        piece : int array, the piece at ``rho`` (-1 beyond the tip, -2 inside the root circle)
        t : float64 array, its parameter
        tangent : (..., 2) float64 or None, unit tangent in the mate frame (zero off the flank)
        """
        rho = np.asarray(rho, dtype=float)
        shape = rho.shape
        rho = rho.ravel()
        w = np.full(rho.shape, np.inf)
        piece = np.full(rho.shape, -1)
        t_out = np.zeros(rho.shape)
        body = self._body(rho)
        w[body] = self._body_width(rho[body])
        piece[body] = -2
        inside = np.flatnonzero(~body & ~self.free(rho))
        tan = None if tangent is False else np.zeros(rho.shape + (2,))
        if inside.size:
            r = rho[inside]
            j = np.clip(np.searchsorted(self._r0, r, side="right") - 1, 0, len(self._r0) - 1)
            k = self._k[j]
            lo, hi = self._t0[j].copy(), self._t1[j].copy()  # rho(lo) <= r <= rho(hi)
            anchor = self._anchor[j]
            grazing = np.isfinite(anchor)
            anchor = np.where(grazing, anchor, 0.0)

            def g(x):  # the radius, or sqrt(|rho - end|) near a stationary end (increasing in rho)
                d = x - anchor
                return np.where(grazing, np.sign(d) * np.sqrt(np.abs(d)), x)

            target = g(r)
            fa, fb = g(self._r0[j]) - target, g(self._r1[j]) - target
            ta, tb = lo.copy(), hi.copy()
            if guess is not None:
                gk, gt, gr = (np.asarray(x).ravel()[inside] for x in guess)
                ok = (gk == k) & ((gt - lo) * (gt - hi) < 0)
                near = np.abs(fa) <= np.abs(fb)
                ta = np.where(ok, np.where(near, lo, hi), ta)
                fa = np.where(ok, np.where(near, fa, fb), fa)
                tb = np.where(ok, gt, tb)
                fb = np.where(ok, g(gr) - target, fb)
            t = np.where(np.abs(fa) < np.abs(fb), ta, tb)
            psi = np.zeros(len(r))
            todo = np.arange(len(r))
            for _ in range(_SECANT):
                with np.errstate(divide="ignore", invalid="ignore"):
                    tn = tb[todo] - fb[todo] * (tb[todo] - ta[todo]) / (fb[todo] - fa[todo])
                bad = ~np.isfinite(tn) | ((tn - lo[todo]) * (tn - hi[todo]) > 0)
                tn = np.where(bad, 0.5 * (lo[todo] + hi[todo]), tn)
                p = evaluate_pieces(self.pieces, k[todo], tn)
                rr, ps = self.coords(p)
                d = rr - anchor[todo]
                f = np.where(grazing[todo], np.sign(d) * np.sqrt(np.abs(d)), rr) - target[todo]
                t[todo], psi[todo] = tn, ps
                lo[todo] = np.where(f <= 0, tn, lo[todo])
                hi[todo] = np.where(f >= 0, tn, hi[todo])
                step = np.abs(tn - tb[todo])
                ta[todo], fa[todo] = tb[todo], fb[todo]
                tb[todo], fb[todo] = tn, f
                scale = np.where(grazing[todo], np.sqrt(np.maximum(np.abs(r[todo]), 1.0)),
                                 np.maximum(np.abs(r[todo]), 1.0))
                done = ((np.abs(f) <= 2e-16 * scale) | (step <= 1e-15 * np.maximum(np.abs(tn), 1.0))
                        | (lo[todo] == hi[todo]))
                todo = todo[~done]
                if todo.size == 0:
                    break
            w[inside] = self.pitch / 2 - psi
            piece[inside] = k
            t_out[inside] = t
            if tangent is not False:
                at = np.flatnonzero(np.broadcast_to(tangent, shape).ravel()[inside])
                h = 1e-6 * (self._t1[j[at]] - self._t0[j[at]])
                d = evaluate_pieces(self.pieces, k[at], t[at] + h) - evaluate_pieces(self.pieces, k[at], t[at] - h)
                norm = np.linalg.norm(d, axis=-1, keepdims=True)
                tan[inside[at]] = np.divide(d, norm, out=np.zeros_like(d), where=norm > 0)
        return (w.reshape(shape), piece.reshape(shape), t_out.reshape(shape),
                None if tan is None else tan.reshape(shape + (2,)))

    def width(self, rho, guess=None, tangent=False, exact=False):
        """:meth:`exact`, or the table's ``w`` once the mesh has set one (``t`` then None)."""
        if self.table is None or exact:
            return self.exact(rho, guess, tangent)
        w, piece, tan = self.table.width(rho, tangent)
        return w, piece, None, tan

    def arm(self, rho, at=None):
        """Estimated arm (mm; for a rack the normal's x component) of the flank's normal about the mate's
        centre at ``rho``: small where the normal runs through the centre (a crest, the root).
        Interpolated between the table's nodes (linearly: below the square-root rise off a crest)."""
        rho = np.asarray(rho, dtype=float)
        j, off = self.lookup(rho) if at is None else at
        frac = (rho - self._grid_r[j]) * self._inv_grid[j]
        np.minimum(np.maximum(frac, 0.0, out=frac), 1.0, out=frac)
        return np.where(off, self.off_arm(rho), self._arm_node[j] + frac * self._darm[j])

    def off_arm(self, rho):
        """:meth:`arm` off the flank (beyond the tip, inside the root circle): the radial scale, a new array."""
        return np.abs(rho) if self.root_scale != 1.0 else np.ones(np.shape(rho))

    def curvature(self, rho, at=None):
        """Largest curvature (1/mm) of the mate's flank near ``rho`` (0 off the flank)."""
        rho = np.asarray(rho, dtype=float)
        j, off = self.lookup(rho) if at is None else at
        return np.where(off, 0.0, self._kappa3[j])

    def label(self, piece):
        """Label of each piece index (``"tip"`` beyond the tip, ``"root"`` inside the root circle)."""
        names = np.array(self.labels + ("root", "tip"), dtype=object)
        return names[np.asarray(piece)]

