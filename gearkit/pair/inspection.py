"""Inspection of one involute gear: span, dimension over pins/balls, chordal thickness, each twice.

:func:`inspect_gear` computes every dimension by the standard formula
(:mod:`gearkit.pair.dimensions`) and measures it on the generated tooth
(:mod:`gearkit.pair.gauging`); the two agree to round-off on a sound involute flank and part where
the formula no longer describes the gear (undercut, a contact on the fillet or the tip corner, the
virtual-gear approximation of a helical gear's chordal height). :mod:`gearkit.checks.inspection`
turns the differences into findings.

Examples
--------
>>> from gearkit.families.involute import GearSpec
>>> insp = inspect_gear(GearSpec(20, 2.0))
>>> insp.span.k, round(insp.span.W, 4), round(insp.span_measured.W, 4)
(3, 15.3209, 15.3209)
"""
from __future__ import annotations

import math

from gearkit.errors import require
from gearkit.pair.dimensions import Chordal, OverPins, Span, chordal, over_pins, span, suggested_pin
from gearkit.pair.gauging import measure_chordal, measure_over_pins, measure_span
from gearkit.pair.tooling import Section, section, thickness_coeff
from gearkit.families.involute import BasicRack
from gearkit.values import frozen

__all__ = ["GearInspection", "gear_section", "gear_thickness_coeff", "inspect_gear"]


def gear_section(spec) -> Section:
    """The normal and transverse constants of a :class:`~gearkit.families.involute.GearSpec`."""
    return section(spec.module, spec.tool.pressure_angle_deg, spec.helix_angle_deg)


def gear_thickness_coeff(spec, thinning: float | None = None) -> float:
    """Actual thickness coefficient Delta of a gear (transverse, m_t units): what its cutter leaves,
    less the tooth thickness allowance ``thinning`` (normal, mm; default the spec's own)."""
    sec = gear_section(spec)
    thin = spec.thinning if thinning is None else float(thinning)
    if isinstance(spec.tool, BasicRack):
        return 2 * spec.shift * math.tan(sec.alpha_n) - thin / spec.module
    return thickness_coeff(sec, spec.teeth, spec.cutter_setting, spec.tool, spec.internal) - thin / spec.module


@frozen
class GearInspection:
    """Inspection dimensions of one gear, by formula and as measured on the generated tooth (mm).

    ``span`` / ``span_measured`` are None for a ring (its teeth are measured between pins).
    ``span_contact`` and ``pin_contact`` name the feature the anvils and pins touch on the real gear.
    """

    helical: bool
    internal: bool
    span: Span | None
    span_measured: Span | None
    span_contact: str | None
    over_pins: OverPins
    over_pins_measured: OverPins
    pin_contact: str
    chordal: Chordal
    chordal_measured: Chordal

    @property
    def deviations(self) -> dict:
        """|formula - measured| (mm) of ``span.W``, ``over_pins.M``, ``chordal.s`` and ``chordal.h``."""
        out = {}
        if self.span is not None:
            out["span.W"] = abs(self.span.W - self.span_measured.W)
        out["over_pins.M"] = abs(self.over_pins.M - self.over_pins_measured.M)
        out["chordal.s"] = abs(self.chordal.s - self.chordal_measured.s)
        out["chordal.h"] = abs(self.chordal.h - self.chordal_measured.h)
        return out

    def to_dict(self) -> dict:
        """JSON-ready: ``span`` {k, W, ...}, ``over_pins`` {d_p, M, ...}, ``chordal`` {s, h, ...}, each with
        its ``measured`` twin (lengths in mm; W and the chordal values in the normal section)."""
        out = {}
        if self.span is not None:
            out["span"] = {**_span(self.span), "measured": {**_span(self.span_measured), "touches": self.span_contact}}
        out["over_pins"] = {**_pins(self.over_pins),
                            "measured": {**_pins(self.over_pins_measured), "touches": self.pin_contact}}
        out["chordal"] = {**_chord(self.chordal), "measured": _chord(self.chordal_measured)}
        return out


def _span(s: Span) -> dict:
    return {"k": s.k, "W": s.W, "W_t": s.W_t, "d_M": s.d_M, "b_min": s.b_min}


def _pins(p: OverPins) -> dict:
    return {"d_p": p.d_p, "M": p.M, "between": p.internal, "d_M": p.d_M, "d_contact": p.d_contact}


def _chord(c: Chordal) -> dict:
    return {"s": c.s, "h": c.h, "d_y": c.d_y}


def _on_tooth(profile, d: float) -> bool:
    """True when the circle ``d`` crosses the flanks below the tip (``d_Nf <= d < d_a``, ring mirrored)."""
    lo, hi = sorted((profile.form_diameter, profile.tip_diameter))
    return lo <= d < hi and not (profile.pointed and d >= profile.tip_diameter * (1 - 1e-9))


def inspect_gear(spec, span_teeth: int | None = None, pin_diameter: float | None = None,
                 chordal_diameter: float | None = None, profile=None) -> GearInspection:
    """Span, over-pins and chordal dimensions of a gear, by formula and measured on its generated tooth.

    Parameters
    ----------
    spec : GearSpec
    span_teeth : int or None
        k; None chooses it as the standards do (anvils nearest ``d + 2 x m_n``).
    pin_diameter : float or None, mm
        Pin/ball diameter; None suggests the one that touches the flanks on ``d + 2 x m_n`` (the
        reference circle for x = 0).
    chordal_diameter : float or None, mm
        Circle of the chordal thickness; None is the reference circle (or ``d + 2 x m_n`` when the
        reference circle misses the flank, e.g. on a heavily shifted gear).
    profile : InvoluteProfile or None
        The generated gear (generated from ``spec`` when not given).

    Returns
    -------
    GearInspection
    """
    if profile is None:
        from gearkit.families.involute import tooth_profile
        profile = tooth_profile(spec)
    sec = gear_section(spec)
    z = spec.teeth
    delta = gear_thickness_coeff(spec)
    x = spec.shift if isinstance(spec.tool, BasicRack) else delta / (2 * math.tan(sec.alpha_n))
    if spec.internal:
        x = -delta / (2 * math.tan(sec.alpha_n))  # the ring's shift by its thickness (rack-cut sense)
        sp = sp_m = touch = None
    else:
        require(span_teeth is None or isinstance(span_teeth, int), "span_teeth",
                f"{span_teeth!r} must be an integer")
        sp = span(sec, z, delta, span_teeth, x)
        sp_m, touch = measure_span(profile, sp.k, sec.beta_b)
    if pin_diameter is None:
        d_c = 2 * (z * sec.mt / 2 + x * sec.mn)
        pin_diameter = suggested_pin(sec, z, delta, spec.internal, max(d_c, z * sec.mt * math.cos(sec.alpha_t) * 1.001))
    pins = over_pins(sec, z, delta, pin_diameter, spec.internal)
    pins_m, pin_touch = measure_over_pins(profile, pins.d_p, sec.beta_b, near=pins.d_M / 2)
    d_a = spec.blank_tip_diameter
    if chordal_diameter is None and not _on_tooth(profile, profile.reference_diameter):
        chordal_diameter = 2 * (z * sec.mt / 2 + x * sec.mn)  # the reference circle misses the tooth
    ch = chordal(sec, z, delta, d_a, spec.internal, chordal_diameter)
    ch_m = measure_chordal(profile, ch.d_y, sec.beta)
    return GearInspection(sec.beta > 0, spec.internal, sp, sp_m, touch, pins, pins_m, pin_touch, ch, ch_m)
