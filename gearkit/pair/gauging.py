"""Inspection dimensions measured on the generated tooth: what the instruments read on the real gear.

The second method beside the standard formulas of :mod:`gearkit.pair.dimensions`. Nothing here
assumes an involute: the anvils, pins and caliper touch the exact half tooth the cutter left
(:class:`~gearkit.profile.ToothProfile`), fillet, undercut, tip corner and all. On an involute
flank both agree to round-off; where they differ the standard formula no longer describes the
gear (the anvils or pins touch the fillet or the tip corner, an undercut flank, a trimmed tip).

* **Span**: two parallel planes over ``k`` teeth, normal to the span's axis of symmetry; each
  touches the outermost point of the outer flank (the largest projection of the real tooth on the
  plane normal). Helical gears: ``W = W_t cos b_b`` (the anvils' planes contain the base helix's
  generators).
* **Pins / balls**: a circle of radius ``d_p / (2 cos b_b)`` (a ball's transverse equivalent on a
  helicoid) on the space's centre line, lowered (ring: raised) until it first touches the tooth.
* **Chordal**: the chord whose ends lie on the circle ``d_y``, its height below the real tip; for a
  helical gear in the plane normal to the tooth's centre helix at the reference cylinder (the
  transverse section swept along the helix and cut by that plane).
"""
from __future__ import annotations

import math

import numpy as np

from gearkit.errors import require
from gearkit.pair.dimensions import Chordal, OverPins, Span

__all__ = ["measure_span", "measure_over_pins", "measure_chordal"]

_GRID = 161  # samples per piece before refining an extreme (pieces are smooth between joins)


def _refine(piece, lo: float, hi: float, score, fallback: float, memo: dict | None = None):
    """Refine a sampled maximum of ``score`` on ``piece`` between parameters ``lo`` and ``hi``.

    ``memo`` (parameter -> the piece's ``(1, 2)`` point there, per piece) keeps the points evaluated,
    for a caller that refines many scores on the same pieces (the searches start alike)."""
    from gearkit.roots import fminbound

    known = {} if memo is None else memo.setdefault(id(piece), {})

    def at(w):
        key = float(w).hex()  # exactly this parameter (0.0 and -0.0 apart)
        if key not in known:
            known[key] = piece(np.array([w]))
        return known[key]

    x, fun = fminbound(lambda w: -float(score(at(w))[0]), lo, hi, xatol=1e-14)
    w = x if -fun > float(score(at(fallback))[0]) else fallback
    point = at(w)[0]
    return float(score(point[None])[0]), point, piece.label


def _extreme(pieces, score, samples=None, memo: dict | None = None):
    """Largest ``score(points)`` over the pieces: (value, point, label), refined to ~1e-14 of the parameter.

    ``samples``: the pieces' points at the grid (:func:`_grid_points`), and ``memo`` the points the
    refinements evaluated (:func:`_refine`), when the caller scores the same pieces many times."""
    t = np.linspace(0.0, 1.0, _GRID)
    best = (-math.inf, None, 0)
    for k, piece in enumerate(pieces):
        values = score(piece(t) if samples is None else samples[k])
        i = int(np.argmax(values))
        if values[i] > best[0]:
            best = (float(values[i]), piece, i)
    _, piece, i = best
    return _refine(piece, t[max(i - 1, 0)], t[min(i + 1, _GRID - 1)], score, float(t[i]), memo)


def _grid_points(pieces) -> list:
    """Each piece's points at the search grid of :func:`_extreme`."""
    t = np.linspace(0.0, 1.0, _GRID)
    return [piece(t) for piece in pieces]


def _first_peak(pieces, score):
    """The first local maximum of ``score`` walking the half tooth from the tip towards the root:
    where an anvil resting on the tooth from outside touches it (value, point, label)."""
    t = np.linspace(0.0, 1.0, _GRID)
    values = np.concatenate([score(piece(t)) for piece in pieces])
    scale = float(np.max(np.abs(values)))
    falls = np.nonzero(np.diff(values) < -1e-12 * scale)[0]  # round-off at the joins is no fall
    i = int(falls[0]) if falls.size else values.size - 1
    k, j = divmod(i, _GRID)
    piece = pieces[k]
    # the peak sits on the join, the previous piece's end clearly above (a tie at a shared point is
    # round-off: it stays with the piece the walk is on, so the label does not flip with the last bit)
    if j == 0 and k > 0 and values[i - 1] > values[i] + 1e-12 * scale:
        k, j, piece = k - 1, _GRID - 1, pieces[k - 1]
    return _refine(piece, t[max(j - 1, 0)], t[min(j + 1, _GRID - 1)], score, float(t[j]))


def _corner(profile, point, label: str) -> str:
    """``"tip corner"`` when a contact sits on the tip circle's edge, else the touched feature's label."""
    r_tip = profile.tip_diameter / 2
    return "tip corner" if abs(float(np.hypot(*point)) - r_tip) <= 1e-9 * r_tip else label


def measure_span(profile, k: int, beta_b: float = 0.0) -> tuple[Span, str]:
    """Span over ``k`` teeth measured on the generated external gear.

    Returns
    -------
    span : Span
        ``d_M`` is the circle through the real contact point.
    label : str
        The feature the anvils touch (``"flank"`` on a sound gear; ``"tip"``, ``"fillet"``... otherwise).
    """
    z = profile.teeth
    require(not profile.internal, "span_teeth", "a span is measured on external gears (use over_pins for a ring)")
    require(isinstance(k, int) and 1 <= k <= (z + 1) // 2, "span_teeth",
            f"k = {k!r} must be an integer in [1, {(z + 1) // 2}] for z = {z}")
    theta = math.pi * (k - 1) / z
    u = np.array([math.cos(theta), math.sin(theta)])
    half, point, label = _first_peak(profile.half.pieces, lambda p: p @ u)
    w_t = 2 * half
    label = _corner(profile, point, label)
    w = w_t * math.cos(beta_b)
    return Span(k, w, w_t, 2 * float(np.hypot(*point)), w * math.sin(beta_b)), label


def _path_clear(grid, e, r0: float, r1: float, rho: float) -> bool:
    """True when a pin of radius ``rho`` moving along ``e`` from radius ``r1`` to ``r0`` meets no grid
    point of the tooth (none nearer the path than ``rho``, to 1e-9 of it): ``r0`` is its first contact."""
    pts = np.concatenate(grid)
    t = np.clip(pts @ e, min(r0, r1), max(r0, r1))
    return float(np.hypot(*(pts - t[:, None] * e).T).min()) >= rho * (1.0 - 1e-9)


def measure_over_pins(profile, d_p: float, beta_b: float = 0.0, near: float | None = None) -> tuple[OverPins, str]:
    """Dimension over (between, for a ring) two pins/balls of diameter ``d_p`` on the generated gear.

    ``near`` (mm, optional): the pin centre's expected radius (the formula's ``d_M / 2``). The
    contact is first sought within 1e-6 ``d_p`` of it and kept when the pin's path in from outside
    is clear of the tooth up to there (it is the first contact); otherwise, and without ``near``,
    the pin is lowered from outside the tip in quarter-radius steps until it touches.

    Returns
    -------
    over_pins : OverPins
    label : str
        The feature the pin touches.
    """
    from gearkit.roots import brentq
    require(math.isfinite(d_p) and d_p > 0, "pin_diameter", f"{d_p!r} must be a positive length in mm")
    z = profile.teeth
    rho = d_p / (2 * math.cos(beta_b))
    e = np.array([math.sin(math.pi / z), math.cos(math.pi / z)])  # centre line of the space
    pieces = profile.half.pieces
    grid = _grid_points(pieces)  # every gap() searches the same grid first
    memo = {}  # and the refinements of nearby centres start at the same points of the tooth

    known = {}

    def gap(radius):
        if radius not in known:  # brentq re-evaluates its bracket's ends
            centre = radius * e
            known[radius] = math.sqrt(-_extreme(pieces, lambda p: -np.sum((p - centre) ** 2, axis=-1), grid,
                                                memo)[0]) - rho
        return known[radius]

    r_tip = profile.tip_diameter / 2
    step = -rho / 4 if not profile.internal else rho / 4
    start = r_tip + 1.01 * rho if not profile.internal else r_tip - 1.01 * rho
    require(start > 0, "pin_diameter", f"d_p = {d_p:g} mm does not fit inside the ring's tip circle")
    r_m = None
    if near is not None and math.isfinite(near) and near > 1e-6 * d_p:
        lo, hi = near - 1e-6 * d_p, near + 1e-6 * d_p
        if (gap(lo) > 0) != (gap(hi) > 0):
            r_m = brentq(gap, lo, hi, xtol=1e-13, rtol=4 * np.finfo(float).eps)
            r_m = r_m if _path_clear(grid, e, r_m, start, rho) else None
    if r_m is None:
        a, fa = start, gap(start)
        for _ in range(400):
            b = a + step
            require(b > 0, "pin_diameter", f"a pin of d_p = {d_p:g} mm falls through the tooth space")
            fb = gap(b)
            if fb <= 0:
                break
            a, fa = b, fb
        else:  # pragma: no cover - 400 quarter-radius steps cross any tooth
            raise AssertionError("the pin never touched the tooth")
        r_m = brentq(gap, min(a, b), max(a, b), xtol=1e-13, rtol=4 * np.finfo(float).eps)
    centre = r_m * e
    _, point, label = _extreme(pieces, lambda p: -np.sum((p - centre) ** 2, axis=-1), grid, memo)
    label = _corner(profile, point, label)
    centres = 2 * r_m * (math.cos(math.pi / (2 * z)) if z % 2 else 1.0)
    m = centres - d_p if profile.internal else centres + d_p
    return OverPins(float(d_p), m, 2 * r_m, 2 * float(np.hypot(*point)), profile.internal), label


def _normal_section(points, beta: float, r0: float):
    """Map transverse points of a helical tooth (tooth centre on +y) into the plane normal to the tooth's
    centre helix at the reference cylinder ``r0``: returns in-plane (u, v), v along +y.

    A point ``p`` of the transverse section lies on the flank at every axial position ``zeta``, turned
    by ``phi = zeta tan b / r0``; the plane ``-sin b X + cos b Z = 0`` cuts it where Newton finds ``zeta``.
    """
    x, y = points[:, 0], points[:, 1]
    k = math.tan(beta) / r0
    zeta = x * math.sin(beta) * math.cos(beta)
    for _ in range(50):
        phi = k * zeta
        c, s = np.cos(phi), np.sin(phi)
        g = -math.sin(beta) * (x * c - y * s) + math.cos(beta) * zeta
        dg = -math.sin(beta) * k * (-x * s - y * c) + math.cos(beta)
        step = g / dg
        zeta = zeta - step
        if np.all(np.abs(step) < 1e-15 * (1 + r0)):
            break
    phi = k * zeta
    big_x = x * np.cos(phi) - y * np.sin(phi)
    return big_x * math.cos(beta) + zeta * math.sin(beta), x * np.sin(phi) + y * np.cos(phi)


def measure_chordal(profile, d_y: float | None = None, helix_angle: float = 0.0) -> Chordal:
    """Chordal thickness and height of the generated tooth at the circle ``d_y`` (default: reference).

    The chord joins the two flank points on ``d_y``; its height is measured from the real tip on the
    tooth's centre line. ``helix_angle`` (rad): the chord lies in the normal section.
    """
    d = profile.reference_diameter
    d_y = d if d_y is None else float(d_y)
    r_y = d_y / 2
    try:
        s_arc = profile.thickness_at(r_y)
    except ValueError:
        s_arc = None
    require(s_arc is not None, "chordal_diameter", f"d_y = {d_y:.6g} mm misses the tooth flank")
    psi = s_arc / (2 * r_y)
    point = np.array([[r_y * math.sin(psi), r_y * math.cos(psi)]])
    r_a = profile.tip_diameter / 2
    if helix_angle:
        u, v = _normal_section(point, abs(helix_angle), d / 2)
        u, v = float(u[0]), float(v[0])
    else:
        u, v = float(point[0, 0]), float(point[0, 1])
    return Chordal(2 * u, v - r_a if profile.internal else r_a - v, d_y)
