"""Findings of a gear's inspection dimensions: where the standard formula and the real gear part.

=====================  ==================================================================  ==========
id                     checks                                                              on failure
=====================  ==================================================================  ==========
inspection.span        span W by formula vs measured on the generated tooth (anvils         warn
                       touching the flank, not the fillet or the tip corner)
inspection.over_pins   dimension over pins/balls by formula vs measured                     warn
inspection.chordal     chordal thickness and height by formula vs measured (helical: the    warn
                       virtual-gear approximation of the standard formula)
inspection.face_width  helical gear: face width b > W sin b_b, so the anvils touch         warn
=====================  ==================================================================  ==========

A suffix ``.1`` / ``.2`` names the gear of a pair (``inspection.span.1``).

Examples
--------
>>> from gearkit.families.involute import GearSpec
>>> from gearkit.pair.inspection import inspect_gear
>>> [f.status for f in inspection_findings(inspect_gear(GearSpec(20, 2.0)), tol=2e-3)]
['ok', 'ok', 'ok']
"""
from __future__ import annotations

from gearkit.checks.report import Finding

__all__ = ["inspection_findings"]


def _contact_finding(fid: str, dev: float, tol: float, contact: str, tool: str, text: str) -> Finding:
    """Formula vs measurement of a dimension taken by contact: warn beyond ``tol`` or off the flank."""
    where = "" if contact == "flank" else f"; the {tool} touch the {contact}, not the flank"
    bad = dev > tol or contact != "flank"
    return Finding(fid, "warn" if bad else "ok", dev, tol,
                   text + where + ("; the formula does not describe this gear" if dev > tol else ""), "max")


def inspection_findings(insp, tol: float, face_width: float | None = None, suffix: str = "") -> list:
    """Findings of a :class:`~gearkit.pair.inspection.GearInspection` (``tol`` in mm).

    Parameters
    ----------
    insp : GearInspection
    tol : float, mm
        Largest difference between formula and measurement that passes.
    face_width : float or None, mm
        b of a helical gear, for the anvils' condition (skipped when None or spur).
    suffix : str
        Appended to every id (``".1"`` for gear 1 of a pair).
    """
    dev = insp.deviations
    out = []
    if insp.span is not None:
        s, sm = insp.span, insp.span_measured
        out.append(_contact_finding(f"inspection.span{suffix}", dev["span.W"], tol, insp.span_contact, "anvils",
                                    f"span over k = {s.k}: W = {s.W:.6f} mm (formula), {sm.W:.6f} mm measured on "
                                    f"the generated tooth, measuring circle d_M = {sm.d_M:.4f} mm"))
    p, pm = insp.over_pins, insp.over_pins_measured
    what = "between" if p.internal else "over"
    out.append(_contact_finding(f"inspection.over_pins{suffix}", dev["over_pins.M"], tol, insp.pin_contact, "pins",
                                f"dimension {what} {'balls' if insp.helical else 'pins'} d_p = {p.d_p:.4f} mm: "
                                f"M = {p.M:.6f} mm (formula), {pm.M:.6f} mm measured"))
    c, cm = insp.chordal, insp.chordal_measured
    d = max(dev["chordal.s"], dev["chordal.h"])
    note = " (the virtual-gear approximation of the helical formula)" if insp.helical and d > tol else ""
    out.append(Finding(f"inspection.chordal{suffix}", "warn" if d > tol else "ok", d, tol,
                       f"chordal thickness at d_y = {c.d_y:.4f} mm: s = {c.s:.6f} mm, h = {c.h:.6f} mm (formula); "
                       f"s = {cm.s:.6f} mm, h = {cm.h:.6f} mm measured{note}", "max"))
    if insp.helical and insp.span is not None and face_width is not None:
        need = insp.span.b_min
        out.append(Finding(f"inspection.face_width{suffix}", "warn" if face_width <= need else "ok", face_width, need,
                           f"span anvils need b > W sin b_b = {need:.4f} mm; b = {face_width:g} mm"
                           + (": measure over balls instead" if face_width <= need else ""), "min"))
    return out
