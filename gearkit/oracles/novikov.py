"""Swept-tool oracle for circular-arc (Novikov) racks: the independent check of the envelope path.

Like :mod:`gearkit.oracles.involute` (whose polygon booleans it reuses, and nothing else), this shares no
code with the envelope kernel or with :mod:`gearkit.families.novikov.racks`: the rack is given as a
*drawing* (the digest's recipe: lines and arcs of the right flank of one basic-rack tooth, normal
section, module units, tooth axis at x = 0, tip towards +y), sampled here, mirrored into cutter
teeth, stretched by 1/cos(beta) into the transverse section, rolled along the blank in the
textbook's form and subtracted from the blank one position at a time. The result is scalloped;
the scallops shrink as the square of the roll step (the cutter's convex edges are rounded).

Drawing primitives (angles in radians, traversed from the first to the second)::

    ("line", x0, y0, x1, y1)
    ("arc", cx, cy, r, t0, t1)      # point (cx + r cos t, cy + r sin t)
"""
from __future__ import annotations

import math

import numpy as np

from gearkit.oracles.involute import cut_blank

__all__ = ["drawing_of", "cutter_outline", "swept_arc_rack_gear"]


def drawing_of(rack) -> list:
    """The drawing of an :class:`~gearkit.families.novikov.racks.ArcRack` as plain primitives."""
    return [(s.kind, *s.data) for s in rack.geometry.drawing]


def _sample(drawing, chord):
    """Points of the half profile from the tooth axis to the space axis, every chord within ``chord``."""
    out = []
    for prim in drawing:
        if prim[0] == "line":
            _, x0, y0, x1, y1 = prim
            pts = np.array([[x0, y0], [x1, y1]], dtype=float)
        elif prim[0] == "arc":
            _, cx, cy, r, t0, t1 = prim
            n = 2
            if r > 0:
                step = 2.0 * math.acos(max(-1.0, 1.0 - chord / r))
                n = max(2, int(math.ceil(abs(t1 - t0) / step)) + 1)
            t = np.linspace(t0, t1, n)
            pts = np.stack([cx + r * np.cos(t), cy + r * np.sin(t)], -1)
        else:
            raise ValueError(f"unknown drawing primitive {prim[0]!r}")
        out.append(pts if not out else pts[1:])
    return np.concatenate(out)


def cutter_outline(drawing, module: float, helix_angle_deg: float, centres, chord: float):
    """Closed outline (mm, transverse section) of the cutter teeth centred at ``centres`` (module units).

    The cutter is the complement of the basic rack: its teeth fill the rack's spaces. Above the
    basic rack's tip line nothing of the cutter can touch a blank whose tip circle is at most
    d + 2 h_a m, so the cutter is left open there (its walls rise vertically from the tip corners).
    """
    half = _sample(drawing, chord / module)
    h_a = half[0, 1]
    top = h_a + 1.0
    lower = []
    for c in centres:
        left = half + np.array([c - math.pi / 2, 0.0])           # gear tooth's right flank, down to the root
        right = (half * np.array([-1.0, 1.0]))[::-1] + np.array([c + math.pi / 2, 0.0])
        tooth = np.concatenate([left[1:], right[1:-1]])             # from the tip corner to the next tip corner
        lower.append(np.concatenate([[[tooth[0, 0], top]], tooth, [[tooth[-1, 0], top]]]))
    lower = np.concatenate(lower)
    closing = np.array([[lower[-1, 0], top + 1.0], [lower[0, 0], top + 1.0]])
    outline = np.concatenate([lower, closing])
    stretch = 1.0 / math.cos(math.radians(helix_angle_deg))
    return outline * np.array([module * stretch, module])


def swept_arc_rack_gear(teeth, module, drawing, tip_radius, step, helix_angle_deg=0.0, chord=None):
    """Gear left by a circular-arc rack cutter sampled at roll steps of ``step`` (mm on the pitch line).

    Parameters
    ----------
    teeth : int
    module : float, mm (normal module)
    drawing : sequence of primitives (see the module docstring) or an ArcRack
    tip_radius : float, mm (the blank)
    step : float, mm
    helix_angle_deg : float (the transverse section is generated)

    Returns
    -------
    list of (n, 2) float64 contours (mm), gear centre at the origin, tooth 0 centred on +y.
    """
    if hasattr(drawing, "geometry"):
        drawing = drawing_of(drawing)
    chord = 1e-6 * module if chord is None else chord
    stretch = 1.0 / math.cos(math.radians(abs(helix_angle_deg)))
    r = teeth * module * stretch / 2.0
    p_t = math.pi * module * stretch
    body = cutter_outline(drawing, module, abs(helix_angle_deg), (-math.pi / 2, math.pi / 2), chord)
    # a cutter tooth centred at c always cuts the space at c; it engages while its tip is inside the blank
    r_tip = r + float(body[:, 1].min())
    reach = math.sqrt(max(tip_radius ** 2 - r_tip ** 2, 0.0)) + p_t
    rolls = np.linspace(-reach, reach, int(math.ceil(2 * reach / step)) + 1)
    polys = []
    for roll in rolls:
        phi = roll / r
        c, s = math.cos(phi), math.sin(phi)
        u, v = body[:, 0] + roll, body[:, 1]
        polys.append(np.stack([u * c - (r + v) * s, u * s + (r + v) * c], -1))
    return cut_blank(tip_radius, polys, chord)
