"""TOML design files for ``gearkit check``: a pair, its tools and the check limits.

Format (every key optional unless marked; lengths in mm, angles in degrees)::

    kind = "external"            # external | internal | rack
    module = 2.0                 # required: normal module m_n
    pressure_angle_deg = 20.0
    helix_angle_deg = 0.0
    face_width = 20.0
    addendum = 1.0               # h_a*
    tip_rule = "shortened"       # shortened | standard
    center_distance = 60.0       # operating a_w; alone it solves the shifts (see split)
    split = "balanced"           # x1 | equal | balanced (with center_distance)
    ring_shift = "iso"           # iso | cutter: how an internal pair's gear2.shift is read

    [gear1]                      # required (gear2 too, except for a rack pair)
    teeth = 18                   # required
    shift = 0.3
    tip_diameter = 41.2
    thinning = 0.05
    tool = "iso53a"              # standard | iso53a..iso53d (as --rack; "rack" = standard) | a table:
    # tool = { type = "shaper", teeth = 20, addendum = 1.3 }
    # tool = { type = "rack", dedendum = 1.25, fillet_radius = 0.3 }

    [limits]
    min_tip_thickness = 0.25
    min_contact_ratio = 1.2
    min_tip_clearance = 0.1

With ``center_distance``: no shifts given -> they are solved and split by ``split``; only
``gear1.shift`` -> x2 follows; both -> the pair runs at that centre distance.
"""
from __future__ import annotations

from dataclasses import replace

from gearkit.checks.limits import CheckLimits
from gearkit.errors import SpecError
from gearkit.pair import PairSpec, shifts_for_center_distance
from gearkit.families.involute import BasicRack, ShaperCutter, named_rack

__all__ = ["load_design", "design_from_dict"]

_TOP = {"kind", "module", "pressure_angle_deg", "helix_angle_deg", "face_width", "addendum", "tip_rule",
        "center_distance", "split", "gear1", "gear2", "limits", "ring_shift"}
_GEAR = {"teeth", "shift", "tip_diameter", "thinning", "tool"}
_RACK = {"type", "pressure_angle_deg", "addendum", "dedendum", "fillet_radius", "protuberance",
         "protuberance_angle_deg"}
_SHAPER = {"type", "teeth", "pressure_angle_deg", "shift", "addendum", "dedendum", "tip_radius"}


def _unknown(table: dict, allowed: set, where: str):
    extra = sorted(set(table) - allowed)
    if extra:
        raise SpecError(f"{where}{extra[0]}", f"unknown key; allowed: {', '.join(sorted(allowed))}")


def _tool(value, where: str, alpha):
    if value is None:
        return None
    if isinstance(value, str):
        return named_rack(value, alpha, field=where)
    if not isinstance(value, dict):
        raise SpecError(where, "must be a string or a table")
    kind = value.get("type")
    fields = {k: v for k, v in value.items() if k != "type"}
    if alpha is not None:
        fields.setdefault("pressure_angle_deg", alpha)
    if kind == "rack":
        _unknown(value, _RACK, where + ".")
        return BasicRack(**fields)
    if kind == "shaper":
        _unknown(value, _SHAPER, where + ".")
        if "teeth" not in fields:
            raise SpecError(where + ".teeth", "a shaper cutter needs its tooth number")
        return ShaperCutter(**fields)
    raise SpecError(where + ".type", f"{kind!r} is not 'rack' or 'shaper'")


def design_from_dict(data: dict) -> tuple:
    """``(PairSpec, CheckLimits)`` from the parsed design (see the module docstring)."""
    _unknown(data, _TOP, "")
    kind = data.get("kind", "external")
    if "module" not in data:
        raise SpecError("module", "is required (normal module m_n, mm)")
    gears = []
    for n in (1, 2):
        table = data.get(f"gear{n}")
        if table is None:
            if n == 1 or kind != "rack":
                raise SpecError(f"gear{n}", "the table is missing")
            gears.append({})
            continue
        if not isinstance(table, dict):
            raise SpecError(f"gear{n}", "must be a table")
        _unknown(table, _GEAR, f"gear{n}.")
        if n == 2 and kind == "rack" and "teeth" in table:
            raise SpecError("gear2.teeth", "a rack has no tooth number")
        if "teeth" not in table and not (n == 2 and kind == "rack"):
            raise SpecError(f"gear{n}.teeth", "is required")
        gears.append(table)
    g1, g2 = gears
    alpha = data.get("pressure_angle_deg")
    spec = PairSpec(
        g1["teeth"], g2.get("teeth"), data["module"], g1.get("shift", 0.0), g2.get("shift", 0.0), kind, alpha,
        data.get("helix_angle_deg", 0.0), data.get("face_width"), _tool(g1.get("tool"), "gear1.tool", alpha),
        _tool(g2.get("tool"), "gear2.tool", alpha), data.get("addendum", 1.0), data.get("tip_rule", "shortened"),
        g1.get("tip_diameter"), g2.get("tip_diameter"), None, g1.get("thinning", 0.0), g2.get("thinning", 0.0),
        data.get("ring_shift", "iso"))
    a_w = data.get("center_distance")
    split = data.get("split")
    if a_w is None:
        if split is not None:
            raise SpecError("split", "applies only with center_distance")
    elif "shift" in g1 and "shift" in g2:
        if split is not None:
            raise SpecError("split", "both shifts are given: nothing to split")
        spec = replace(spec, center_distance=a_w)
    elif "shift" in g2:
        raise SpecError("gear2.shift", "with center_distance give gear1.shift (x2 follows), both, or neither")
    else:
        if "shift" in g1 and split not in (None, "x1"):
            raise SpecError("split", f"gear1.shift is given, so the split is 'x1', not {split!r}")
        spec = shifts_for_center_distance(spec, a_w, "x1" if "shift" in g1 else (split or "balanced"))
    lim = data.get("limits", {})
    if not isinstance(lim, dict):
        raise SpecError("limits", "must be a table")
    _unknown(lim, {"min_tip_thickness", "min_contact_ratio", "min_tip_clearance"}, "limits.")
    return spec, CheckLimits(**lim)


def load_design(path) -> tuple:
    """Read a TOML design file: ``(PairSpec, CheckLimits)``; any problem is a :class:`SpecError`."""
    from gearkit.export import read_toml

    data = read_toml(path, "design")
    return design_from_dict(data)
