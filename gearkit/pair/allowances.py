"""Tooth thickness allowances and centre-distance tolerance: generating shifts, backlash range, and the
inspection dimensions at the upper and lower allowance (ISO 21771).

An allowance ``A_sn`` (normal, mm, <= 0: the tooth is thinner than nominal) is cut by feeding the tool
in: the gear is generated at ``x_E = x + A_sn / (2 m_n tan a_n)``, and its root and form circles move
with it (a :class:`~gearkit.families.involute.GearSpec` cuts ``thinning = -A_sn`` that way). Each gear
has an upper (``A_sne``, thickest) and a lower (``A_sni``, thinnest) allowance; the centre distance an
upper ``A_ae`` and a lower ``A_ai``. The smallest backlash comes from the thickest teeth at the
tightest centre distance, the largest from the thinnest teeth at the loosest one.

Examples
--------
>>> from gearkit.pair import PairSpec
>>> r = allowance_report(PairSpec(30, 40, 1.0), Allowances((-0.04, -0.08), (-0.04, -0.08), (0.02, -0.02)))
>>> round(r["gears"][0]["upper"]["x_E"], 6), round(r["gears"][0]["upper"]["root_diameter"], 4)
(-0.05495, 27.3901)
"""
from __future__ import annotations

from dataclasses import dataclass, replace

from gearkit.errors import SpecError, check_fields, is_real, require
from gearkit.families.involute import BasicRack
from gearkit.pair.dimensions import over_pins, span
from gearkit.pair.geometry import gear_specs, pair_geometry
from gearkit.pair.inspection import gear_section, gear_thickness_coeff, inspect_gear
from gearkit.pair.spec import PairSpec

__all__ = ["Allowances", "allowance_report"]


@dataclass(frozen=True)
class Allowances:
    """Allowances of a pair, mm: ``gear1`` and ``gear2`` are ``(A_sne, A_sni)`` (upper, lower normal tooth
    thickness allowances, ``0 >= A_sne >= A_sni``), ``center_distance`` is ``(A_ae, A_ai)`` (upper, lower)."""

    gear1: tuple = (0.0, 0.0)
    gear2: tuple = (0.0, 0.0)
    center_distance: tuple = (0.0, 0.0)

    def __post_init__(self):
        check_fields(self)
        for name in ("gear1", "gear2", "center_distance"):
            value = getattr(self, name)
            require(isinstance(value, tuple) and len(value) == 2 and all(is_real(v) for v in value), name,
                    f"{value!r} must be (upper, lower) in mm")
            object.__setattr__(self, name, (float(value[0]), float(value[1])))
            value = getattr(self, name)
            require(value[0] >= value[1], name, f"upper {value[0]!r} must be >= lower {value[1]!r}")
        for name in ("gear1", "gear2"):
            require(getattr(self, name)[0] <= 0.0, name, "a tooth thickness allowance is <= 0 (the tooth "
                    "thinner than nominal)")


def _gear_at(spec: PairSpec, gear, which: int, allowance: float, k: int | None, d_p: float) -> dict:
    """x_E, root diameter, span and over-pins of gear ``which`` cut with the allowance (mm)."""
    thin = -allowance
    if thin and not isinstance(gear.tool, BasicRack):
        raise SpecError(f"gear{which}", "thickness allowances apply to rack-cut gears; set a shaper-cut "
                        "gear's thickness by its shift")
    cut = replace(gear, thinning=thin)
    sec = gear_section(cut)
    delta = gear_thickness_coeff(cut)
    out = {"allowance": allowance, "x_E": cut.generating_shift,
           "root_diameter": cut.reference_diameter + 2 * cut.module * (cut.generating_shift - cut.tool.dedendum)
           if isinstance(cut.tool, BasicRack) else None}
    if not cut.internal:
        s = span(sec, cut.teeth, delta, k)
        out["span"] = {"k": s.k, "W": s.W}
    p = over_pins(sec, cut.teeth, delta, d_p, cut.internal)
    out["over_pins"] = {"d_p": p.d_p, "M": p.M}
    return out


def allowance_report(spec: PairSpec, allowances: Allowances) -> dict:
    """Per gear the generating shifts, roots, spans and over-pins dimensions at the upper and lower
    allowance; for the pair the backlash range (transverse on the working circle and normal), mm.

    The span number and pin diameter are those of the nominal gear (a drawing gives one k and one
    pin). ``spec``'s own thinning and centre distance are the nominal ones the allowances add to.
    """
    require(spec.kind != "rack", "kind", "allowances are reported for gear pairs (not rack pairs)")
    nominal = pair_geometry(spec)
    gears = []
    for i, gear in enumerate(gear_specs(spec)):
        base = replace(gear, thinning=0.0)
        insp = inspect_gear(base)
        k = insp.span.k if insp.span is not None else None
        upper, lower = (allowances.gear1, allowances.gear2)[i]
        gears.append({"upper": _gear_at(spec, base, i + 1, upper, k, insp.over_pins.d_p),
                      "lower": _gear_at(spec, base, i + 1, lower, k, insp.over_pins.d_p)})
    a_w = nominal.center_distance
    a_hi, a_lo = allowances.center_distance
    internal = spec.kind == "internal"
    # the tightest mesh: thickest teeth; the centre distance that closes the mesh (external: smaller,
    # ring: larger)
    tight = replace(spec, thinning1=-allowances.gear1[0], thinning2=-allowances.gear2[0],
                    center_distance=a_w + (a_hi if internal else a_lo))
    loose = replace(spec, thinning1=-allowances.gear1[1], thinning2=-allowances.gear2[1],
                    center_distance=a_w + (a_lo if internal else a_hi))
    g_min, g_max = pair_geometry(tight), pair_geometry(loose)
    return {"gears": gears,
            "backlash": {"min": g_min.backlash, "max": g_max.backlash,
                         "normal_min": g_min.backlash_normal, "normal_max": g_max.backlash_normal},
            "center_distance": {"nominal": a_w, "upper": a_w + a_hi, "lower": a_w + a_lo}}
