"""Page data of two profiles in mesh: a pair or a cycloid drive, turning, with its contacts and solids.

The animation replays the tooth contact analysis (:func:`gearkit.contact.simulate`): over one
mesh cycle (one driver pitch) the driver turns by ``phi`` and the mate rests where the
simulation put it (its ideal position plus the transmission error); the cycle is repeated
``cycles`` times with the driver advanced by a pitch each time, so the gears turn on. Frame:
the contact analysis's (driver on the origin, the mate's centre on the y axis), or with
``fixed="mate"`` the mate's (a cycloid drive's pin ring stands still and the disc wobbles
round it). The solids in the 3D view move with the same poses.
"""
from __future__ import annotations

import math

import numpy as np

from gearkit.view.page import COLORS, findings_rows, flat, mesh_part

#: frames per mesh cycle of a page
FRAMES = 48


def _rot(a):
    c, s = np.cos(a), np.sin(a)
    return np.stack([np.stack([c, -s], -1), np.stack([s, c], -1)], -2)


def _loops(profile, tol, rim: float | None):
    """Closed loops of a body in its own frame: a gear's outline (a ring: with its rim circle);
    a rack: a bar under the tooth row."""
    if getattr(profile, "teeth", None) is None:  # a rack: teeth towards +y, datum y = 0
        n = 61
        row = profile.outline(tol, teeth=n) - np.array([(n // 2) * profile.pitch, 0.0])
        back = float(row[:, 1].min()) - 2.5 * profile.module
        return [np.concatenate([row, [[row[-1, 0], back], [row[0, 0], back]]])]
    loops = [profile.outline(tol)]
    if profile.internal:
        t = np.linspace(0.0, 2.0 * math.pi, 241)[:-1]
        loops.insert(0, rim * np.stack([np.cos(t), np.sin(t)], -1))
    return loops


def mesh_animation(analysis, cycles: int, fixed: str = "driver", names=("driver", "mate"), tol=None) -> dict:
    """The ``anim`` object of a page from a :class:`~gearkit.contact.ContactAnalysis`.

    Parameters
    ----------
    analysis : ContactAnalysis (its steps are the frames of one cycle)
    cycles : int, cycles shown (the driver turns by ``cycles`` pitches)
    fixed : "driver" (the analysis frame) or "mate" (the mate stands still)
    names : the two bodies' names
    tol : float, mm, chord tolerance of the drawn outlines (default 2e-3 module)
    """
    mesh = analysis.mesh
    m = mesh.module
    tol = 2e-3 * m if tol is None else tol
    steps = len(analysis.driver_angle)
    k = np.arange(cycles * steps)
    phi = analysis.driver_angle[k % steps] + (k // steps) * mesh.pitch1
    delta = analysis.reference + analysis.transmission_error[k % steps]
    move = mesh.beta0 + mesh.ratio * phi + delta
    rack = mesh.kind == "rack"
    zeros = np.zeros_like(phi)
    driver = np.stack([phi, zeros, zeros], -1)
    if rack:
        mate = np.stack([np.full_like(phi, math.pi), move, np.full_like(phi, mesh.a)], -1)
    else:
        mate = np.stack([move, np.full_like(phi, mesh.centre2[0]), np.full_like(phi, mesh.centre2[1])], -1)
    c = analysis.contacts
    first = c["zeta"] == c["zeta"].min() if len(c["zeta"]) else np.zeros(0, bool)
    per_step = [c["point"][(c["step"] == i) & first] for i in range(steps)]
    points = [per_step[i % steps] for i in range(len(phi))]
    if fixed == "mate" and not rack:
        gamma = move - move[0]
        centre = np.asarray(mesh.centre2, dtype=float)
        back = _rot(-gamma)
        driver = np.column_stack([phi - gamma, (back @ (-centre))[:, :] + centre])
        mate = np.column_stack([move - gamma, np.tile(centre, (len(phi), 1))])
        points = [(p - centre) @ back[i].T + centre for i, p in enumerate(points)]
    rim2 = None
    if not rack and mesh.gear2.internal:
        rim2 = mesh.gear2.root_diameter / 2.0 + 2.0 * m
    rim1 = mesh.gear1.root_diameter / 2.0 + 2.0 * m if mesh.gear1.internal else None
    bodies = []
    for name, prof, poses, rim, colour in ((names[0], mesh.gear1, driver, rim1, COLORS[0]),
                                            (names[1], mesh.gear2, mate, rim2, COLORS[1])):
        body = {"name": name, "color": "#1d2b44", "fill": colour + "88",
                "loops": [flat(lp) for lp in _loops(prof, tol, rim)], "poses": np.round(poses, 7).tolist()}
        if getattr(prof, "teeth", None) is not None and not prof.internal:
            body["mark"] = [0.0, round(0.55 * prof.root_diameter / 2.0, 5)]
        bodies.append(body)
    path = np.concatenate(points[:steps] if fixed != "mate" else points) if any(len(p) for p in points) else \
        np.zeros((0, 2))
    rack_units = analysis.units == "mm"
    te = analysis.transmission_error * (1e3 if rack_units else 1e6)
    x = np.degrees(analysis.driver_angle - analysis.driver_angle[0])
    anim = {"frames": int(len(phi)), "fps": 24, "bodies": bodies, "contacts": [flat(p) for p in points],
            "path": flat(path[:: max(1, len(path) // 4000)]),
            "trace": {"label": "transmission error, " + ("µm (rack travel)" if rack_units else "µrad (mate)"),
                      "xlabel": "driver angle in the cycle, deg", "x": flat(x, 6), "y": flat(te, 6),
                      "label2": "pairs in contact", "y2": [int(v) for v in analysis.pairs_in_contact]},
            "caption": f"{mesh.kind} mesh, {cycles} cycles of {steps} steps", "tol": tol}
    p = mesh.pitch_point if fixed != "mate" else mesh.pitch_point
    anim["focus"] = [round(float(p[0]), 5), round(float(p[1]), 5), round(10.0 * m, 5)]
    if rack:
        r = mesh.gear1.tip_diameter / 2.0
        anim["bounds"] = [-1.6 * r, -1.15 * r, 1.6 * r, mesh.a + 4.0 * m]
    return anim


def pair_view(spec, limits=None, width: float | None = None, cycles: int | None = None, tol: float | None = None):
    """Page data of an involute pair (:class:`~gearkit.pair.PairSpec`): mesh, solids, design check.

    Examples
    --------
    >>> from gearkit.pair import PairSpec
    >>> data = pair_view(PairSpec(13, 17, 2.0), cycles=1)
    >>> data["anim"]["frames"], [p["name"] for p in data["parts3d"]]
    (48, ['pinion', 'wheel'])
    """
    from gearkit.checks import CheckLimits, check_pair
    from gearkit.contact import analyse_pair
    from gearkit.solids import pair_assembly

    check = check_pair(spec, limits or CheckLimits())
    analysis = analyse_pair(spec, FRAMES, slices=1)
    g = check.geometry
    b = width or spec.face_width or 6.0 * spec.module
    cycles = cycles if cycles is not None else (min(spec.teeth1, 40) if spec.kind != "rack" else 6)
    kind = spec.kind
    names = ("pinion", {"external": "wheel", "internal": "ring", "rack": "rack"}[kind])
    anim = mesh_animation(analysis, cycles, names=names)
    asm = pair_assembly(spec, b, tol if tol is not None else 0.02 * spec.module)
    parts = [mesh_part(p, COLORS[i], body=i) for i, p in enumerate(asm.parts)]
    z2 = "rack" if kind == "rack" else f"z2 = {spec.teeth2}"
    summary = [["centre distance a_w", f"{g.center_distance:.4f} mm"],
               ["contact ratio (formula)", f"{g.contact_ratio:.4f}"],
               ["contact ratio (simulated)", f"{analysis.contact_ratio:.4f}"],
               ["transmission error p-p", f"{analysis.transmission_error_pp:.3e} {analysis.units}"],
               ["backlash (simulated)", f"{analysis.backlash:.4f} mm"],
               ["interference", "none" if not analysis.interference.found else
                f"{analysis.interference.max_depth:.4g} mm deep ({', '.join(analysis.interference.where)})"],
               ["face width (solids)", f"{b:g} mm"]]
    return {"title": f"gearkit: {kind} pair z1 = {spec.teeth1}, {z2}, m = {spec.module:g} mm",
            "subtitle": f"x1 = {spec.shift1:g}, x2 = {spec.shift2:g}, beta = {spec.helix_angle_deg:g} deg; "
                        "the generated teeth meshed by the contact simulation",
            "summary": summary, "findings": findings_rows(check.report.findings), "anim": anim, "parts3d": parts}


def drive_view(spec, width: float | None = None, cycles: int | None = None, tol: float | None = None,
               samples: int = 400):
    """Page data of a cycloid-pin-wheel drive (:class:`~gearkit.families.cycloidal.DriveSpec`): the
    disc wobbling in the fixed pin ring, its contacts, the solids and the drive's check.

    Examples
    --------
    >>> from gearkit.families.cycloidal import DriveSpec
    >>> data = drive_view(DriveSpec(8, 7, 40.0, 3.0, 1.5), cycles=1)
    >>> [b["name"] for b in data["anim"]["bodies"]], len(data["parts3d"])
    (['disc', 'pins'], 2)
    """
    from gearkit.checks.cycloidal import check_drive
    from gearkit.contact import Mesh, pin_ring, simulate
    from gearkit.families.cycloidal import disc_profile
    from gearkit.solids.drive import disc_solid
    from gearkit.solids import SolidSpec, gear_solid

    result = check_drive(spec, samples=samples)
    ring = pin_ring(spec.pins, spec.pin_circle_radius, spec.pin_radius, internal=spec.tooth_difference > 0)
    mesh = Mesh(disc_profile(spec), ring, spec.eccentricity)
    analysis = simulate(mesh, FRAMES)
    b = width or max(2.0 * spec.pin_radius, 0.1 * spec.pin_circle_radius)
    cycles = cycles if cycles is not None else spec.pins
    anim = mesh_animation(analysis, cycles, fixed="mate", names=("disc", "pins"))
    tol = tol if tol is not None else 0.01 * spec.eccentricity
    disc = disc_solid(spec, b, tol)
    pins = gear_solid(ring, SolidSpec(b), tol, name="pin ring")
    parts = [mesh_part(disc, COLORS[0], body=0), mesh_part(pins, COLORS[1], body=1)]
    summary = [[k.replace("_", " "), f"{v:.6g}" if isinstance(v, float) else str(v)]
               for k, v in result.values.items() if isinstance(v, (int, float)) and not isinstance(v, bool)]
    summary.append(["contact ratio (simulated)", f"{analysis.contact_ratio:.4f}"])
    return {"title": f"gearkit: cycloidal drive, {spec.pins} pins, {spec.lobes} lobes",
            "subtitle": f"R_Z = {spec.pin_circle_radius:g}, r_Z = {spec.pin_radius:g}, e = {spec.eccentricity:g} mm; "
                        "the pin ring stands still, the disc turns on its eccentric",
            "summary": summary, "findings": findings_rows(result.report.findings), "anim": anim, "parts3d": parts}
