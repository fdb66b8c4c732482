"""The swept-tool oracle: cut the blank with the tool at many positions and see what is left.

This is the independent check of the envelope kernel and shares no code with it: the tool
outlines are rebuilt here from the tool parameters, the kinematics are written out again in
the textbook's form, and the cutting is done by 2D polygon booleans (the blank minus the
union of all tool positions). It is slow and approximate: the cut surface is scalloped,
with scallops that shrink as the square of the roll step. Tests hold the envelope against
it, and ``gearkit bench`` measures how it converges.
"""
from __future__ import annotations

import math

import numpy as np

from gearkit.families.involute import BasicRack, ShaperCutter


def _cross_section(polys):
    import manifold3d

    return manifold3d.CrossSection([np.asarray(p, dtype=float) for p in polys])


def _cut(blank, tool_positions):
    """The blank minus every tool position, one boolean at a time (each against a small polygon)."""
    import manifold3d

    for poly in tool_positions:
        blank = blank - manifold3d.CrossSection([poly])
    return [np.asarray(c) for c in blank.to_polygons()]


def _circle(radius, chord):
    n = max(64, int(math.ceil(math.pi / math.acos(max(-1.0, 1.0 - chord / radius)))))
    t = np.linspace(0.0, 2 * np.pi, n, endpoint=False)
    return np.stack([radius * np.cos(t), radius * np.sin(t)], -1)


def cut_blank(tip_radius: float, tool_positions, chord: float) -> list:
    """A disc blank of ``tip_radius`` (a polygon within ``chord`` of its circle) minus every polygon of
    ``tool_positions`` (each ``(n, 2)`` mm): the uncut contours, ``(n, 2)`` arrays. Every swept-tool
    oracle (one per family) ends here."""
    return _cut(_cross_section([_circle(tip_radius, chord)]), tool_positions)


def _arc_points(cx, cy, r, a0, a1, chord):
    n = max(2, int(math.ceil(abs(a1 - a0) * r / max(math.sqrt(8 * r * chord), 1e-12))) + 1) if r > 0 else 1
    t = np.linspace(a0, a1, n)
    return np.stack([cx + r * np.cos(t), cy + r * np.sin(t)], -1)


def rack_polygon(rack: BasicRack, m: float, shift: float, thinning: float, centres, chord: float):
    """Closed outline of a generating rack (normal section) with cutter teeth at ``centres`` (mm).

    Teeth point to -v, the datum line is at ``v = shift``; neighbouring teeth are joined by the
    cutter's root line ``v = shift + h_fP m`` and the body is closed above it.
    """
    a = math.radians(rack.pressure_angle_deg)
    half_datum = math.pi * m / 4 + thinning / 2
    tip_v = shift - rack.dedendum * m
    root_v = shift + rack.dedendum * m
    top_v = root_v + 2 * m
    rho = rack.fillet * m
    vc = tip_v + rho
    outline = []
    for centre in centres:
        # right flank: u = centre + half_datum + (v - shift) tan a; rounding centre at depth tip_v + rho
        uc = centre + half_datum + (vc - shift) * math.tan(a) - rho / math.cos(a)
        right_arc = _arc_points(uc, vc, rho, -math.pi / 2, -a, chord)
        right_root = [centre + half_datum + (root_v - shift) * math.tan(a), root_v]
        left_arc = right_arc[::-1] * np.array([-1.0, 1.0]) + np.array([2 * centre, 0.0])
        left_root = [2 * centre - right_root[0], root_v]
        outline += [[left_root], left_arc, right_arc, [right_root]]
    first, last = outline[0][0], outline[-1][0]
    outline += [[[last[0], top_v]], [[first[0], top_v]]]
    return np.concatenate(outline)


def swept_rack_gear(teeth, module, shift, rack: BasicRack, tip_radius, step, helix_angle_deg=0.0,
                    thinning=0.0, chord=None):
    """Gear left by a rack cutter sampled at roll steps of ``step`` (mm along the pitch line).

    Returns the boundary contours of the cut blank as a list of ``(n, 2)`` arrays (mm), gear
    centre at the origin, tooth 0 centred on +y. Helical gears use the transverse section
    of the rack (a stretch of the normal section along the pitch line by 1/cos beta).
    """
    chord = 1e-6 * module if chord is None else chord
    beta = math.radians(abs(helix_angle_deg))
    stretch = 1.0 / math.cos(beta)
    r = teeth * module * stretch / 2.0
    p_t = math.pi * module * stretch
    body = rack_polygon(rack, module, shift * module, thinning, (-0.5 * math.pi * module, 0.5 * math.pi * module),
                        chord) * np.array([stretch, 1.0])
    depth = (rack.addendum + rack.dedendum) * module
    reach = 2.0 * math.sqrt(2.0 * r * depth + depth ** 2) + 2 * p_t
    n = int(math.ceil(2 * reach / step)) + 1
    rolls = np.linspace(-reach, reach, n)
    polys = []
    for roll in rolls:
        phi = roll / r
        c, s = math.cos(phi), math.sin(phi)
        u = body[:, 0] + roll
        v = body[:, 1]
        # textbook form: X = (u + r phi) cos phi - (r + v) sin phi, Y = (u + r phi) sin phi + (r + v) cos phi
        polys.append(np.stack([u * c - (r + v) * s, u * s + (r + v) * c], -1))
    return cut_blank(tip_radius, polys, chord)


def cutter_polygon(cutter: ShaperCutter, m: float, alpha: float, tooth0_angle: float, chord: float,
                   teeth=(-2, -1, 0, 1), m_radial=None):
    """Outline of a sharp-tipped shaper cutter: a wedge holding the teeth ``teeth`` (indices from tooth 0 at
    ``tooth0_angle``), closed through the cutter centre at the origin.

    ``m`` is the module of the section (transverse), ``m_radial`` the one radial sizes are given in
    (normal; defaults to ``m``).
    """
    if cutter.tip_radius:
        raise ValueError("the oracle models sharp-tipped cutters only (tip_radius = 0)")
    mr = m if m_radial is None else m_radial
    z0 = cutter.teeth
    rb = m * z0 * math.cos(alpha) / 2
    ra = m * z0 / 2 + mr * (cutter.shift + cutter.addendum)
    rf = m * z0 / 2 + mr * (cutter.shift - cutter.dedendum)
    big = (math.pi / 2 + 2 * cutter.shift * (mr / m) * math.tan(alpha)) / z0 + (math.tan(alpha) - alpha)
    t_lo = math.sqrt(max(rf / rb, 1.0) ** 2 - 1.0)
    t_hi = math.sqrt((ra / rb) ** 2 - 1.0)
    n_fl = max(20, int(math.ceil((t_hi - t_lo) / math.sqrt(8 * chord / (rb * t_hi)))) + 1)
    t = np.linspace(t_lo, t_hi, n_fl)
    rho = rb * np.sqrt(1 + t * t)
    half = big - (t - np.arctan(t))
    if rf < rb:
        rho = np.concatenate([[rf], rho])
        half = np.concatenate([[big], half])
    out = []
    pitch = 2 * math.pi / z0
    for n_k, k in enumerate(teeth):
        c = tooth0_angle + k * pitch
        right = np.stack([rho * np.cos(c - half), rho * np.sin(c - half)], -1)
        left = np.stack([rho * np.cos(c + half), rho * np.sin(c + half)], -1)[::-1]
        tip = _arc_points(0.0, 0.0, ra, c - half[-1], c + half[-1], chord)[1:-1]
        out += [right, tip, left]
        if n_k + 1 < len(teeth):
            out.append(_arc_points(0.0, 0.0, rf, c + half[0], c + pitch - half[0], chord)[1:-1])
    out.append(np.zeros((1, 2)))
    return np.concatenate(out)


def swept_shaper_gear(teeth, module, shift, cutter: ShaperCutter, tip_radius, step, internal=False,
                      rim_radius=None, chord=None):
    """Gear left by a shaper cutter (spur), roll steps of ``step`` mm on the machine pitch circle.

    ``shift`` is the cutter's radial setting (machine centre distance a_0 = m(z +- z0)/2 + x m).
    Internal gears are cut from an annulus between ``tip_radius`` and ``rim_radius``.
    """
    chord = 1e-6 * module if chord is None else chord
    alpha = math.radians(cutter.pressure_angle_deg)
    z0 = cutter.teeth
    sign = -1 if internal else 1
    a0 = module * (teeth + sign * z0) / 2 + shift * module
    r_w = a0 * teeth / (teeth + sign * z0)
    if internal:
        outline = cutter_polygon(cutter, module, alpha, math.pi / 2 + math.pi / z0, chord)
        centre_y = r_w - a0 * z0 / (teeth - z0)
    else:
        outline = cutter_polygon(cutter, module, alpha, -math.pi / 2 + math.pi / z0, chord)
        centre_y = a0
    reach = 2 * math.pi * r_w / teeth + 2 * math.sqrt(2 * abs(r_w) * 2.5 * module) + 2 * math.pi * module
    n = int(math.ceil(2 * reach / step)) + 1
    polys = []
    for roll in np.linspace(-reach, reach, n):
        phi = roll / r_w
        turn = phi * teeth / z0 * (1 if internal else -1)
        # blank frame: undo the blank's turn phi
        ctr = np.array([-math.sin(-phi) * centre_y, math.cos(-phi) * centre_y])
        ang = turn - phi
        c, s = math.cos(ang), math.sin(ang)
        pts = np.stack([outline[:, 0] * c - outline[:, 1] * s, outline[:, 0] * s + outline[:, 1] * c], -1) + ctr
        polys.append(pts)
    if internal:
        rim = rim_radius if rim_radius is not None else tip_radius + 4 * module
        blank = _cross_section([_circle(rim, chord), _circle(tip_radius, chord)[::-1]])
    else:
        blank = _cross_section([_circle(tip_radius, chord)])
    return _cut(blank, polys)


def tooth_zone_points(contours, teeth, tip_radius, margin=0.0, internal=False):
    """Vertices of oracle contours that belong to tooth 0's flanks and its neighbouring spaces
    (the tip-circle polygon's own vertices are left out)."""
    pts = np.concatenate(contours)
    rho = np.hypot(pts[:, 0], pts[:, 1])
    psi = np.arctan2(pts[:, 0], pts[:, 1])
    keep = (np.abs(psi) <= math.pi / teeth - margin) & (np.abs(rho - tip_radius) > 1e-5 * tip_radius)
    return pts[keep]


def swept_gear(spec, step: float, chord: float | None = None):
    """The swept-tool cut of an involute gear spec (rack- or shaper-cut): boundary contours, mm.

    Slow and approximate by design (scallops shrink with ``step``, mm of roll); use it to see
    the cut a real cutter's discrete strokes make, or to check the envelope.
    """
    from gearkit.families.involute import GearSpec

    if not isinstance(spec, GearSpec):
        raise TypeError("swept_gear takes a GearSpec")
    ra = spec.blank_tip_diameter / 2
    if isinstance(spec.tool, BasicRack):
        # the allowance feeds the tool in (ISO 21771 x_E): the rack sits lower, not thicker
        x_e = spec.shift - spec.thinning / (2 * spec.module * math.tan(math.radians(spec.tool.pressure_angle_deg)))
        return swept_rack_gear(spec.teeth, spec.module, x_e, spec.tool, ra, step,
                               helix_angle_deg=spec.helix_angle_deg, chord=chord)
    if spec.beta:
        raise ValueError("the oracle cuts spur gears with shaper cutters only")
    # the shaper's radial setting (a ring's ISO shift is cut by the setting derived for its thickness)
    return swept_shaper_gear(spec.teeth, spec.module, spec.cutter_setting, spec.tool, ra, step,
                             internal=spec.internal, chord=chord)
