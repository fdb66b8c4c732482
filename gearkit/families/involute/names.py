"""The involute tools' names: :data:`RACK_NAMES` (what a user types, in every command and design
file) and :func:`tool_label` (what every output prints), so a tool is spelled one way everywhere.
"""
from __future__ import annotations

import functools

from gearkit.errors import SpecError
from gearkit.families.involute.tools import ISO53_PROFILES, BasicRack, ShaperCutter

__all__ = ["RACK_NAMES", "named_rack", "tool_label"]

#: the involute basic racks by name, the same in every command and design file ("standard": h_aP* 1,
#: h_fP* 1.25, the largest tip rounding; the ISO 53 profiles A..D)
RACK_NAMES = ("standard", "iso53a", "iso53b", "iso53c", "iso53d")


def named_rack(name: str, pressure_angle_deg: float | None = None, field: str = "rack",
               angle_field: str = "pressure_angle_deg") -> BasicRack:
    """The basic rack called ``name`` (one of :data:`RACK_NAMES`; ``"rack"`` is the older spelling of
    ``"standard"``), at ``pressure_angle_deg`` (default 20; the ISO 53 profiles have 20 only). Errors
    name ``field`` (a bad name) or ``angle_field`` (an angle an ISO 53 profile does not have).

    Examples
    --------
    >>> named_rack("standard", 25.0).pressure_angle_deg, named_rack("iso53b").dedendum
    (25.0, 1.25)
    >>> named_rack("iso53a", 25)
    Traceback (most recent call last):
    ...
    gearkit.errors.SpecError: pressure_angle_deg: the ISO 53 profiles have 20 degrees, not 25; use 'standard' for 25 degrees
    """
    key = str(name).lower()
    alpha = 20.0 if pressure_angle_deg is None else pressure_angle_deg
    if key in ("standard", "rack"):
        return BasicRack(alpha)
    if key not in RACK_NAMES:
        raise SpecError(field, f"{name!r} is not a basic rack; allowed: {', '.join(RACK_NAMES)}")
    if alpha != 20.0:
        raise SpecError(angle_field, f"the ISO 53 profiles have 20 degrees, not {alpha:g}; use 'standard' for {alpha:g} "
                               "degrees")
    return BasicRack.iso53(key[-1])


def tool_label(tool) -> str:
    """The one human spelling of a generating tool, used by every command's text and JSON.

    ``"rack (standard basic rack)"``, ``"rack (ISO 53 A)"``, ``"rack (h_aP* 1, h_fP* 1.4, rho_fP* 0.3)"``
    for a rack of other proportions, ``"shaper cutter z0=20"``; a pressure angle other than 20 degrees
    and a cutter's own shift or addendum other than the defaults are added.

    Examples
    --------
    >>> tool_label(BasicRack()), tool_label(BasicRack.iso53("C")), tool_label(BasicRack(25.0))
    ('rack (standard basic rack)', 'rack (ISO 53 C)', 'rack (standard basic rack, 25 deg)')
    >>> tool_label(BasicRack(dedendum=1.4, fillet_radius=0.3))
    'rack (h_aP* 1, h_fP* 1.4, rho_fP* 0.3)'
    >>> tool_label(ShaperCutter(20)), tool_label(ShaperCutter(24, 25.0, shift=0.1, addendum=1.2))
    ('shaper cutter z0=20', 'shaper cutter z0=24, x0=0.1, h_a0*=1.2, 25 deg')
    """
    angle = [] if tool.pressure_angle_deg == 20.0 else [f"{tool.pressure_angle_deg:g} deg"]
    if isinstance(tool, ShaperCutter):
        extra = [f"x0={tool.shift:g}"] if tool.shift else []
        extra += [f"h_a0*={tool.addendum:g}"] if tool.addendum != 1.25 else []
        extra += [f"h_f0*={tool.dedendum:g}"] if tool.dedendum != 1.25 else []
        extra += [f"rho_a0*={tool.tip_radius:g}"] if tool.tip_radius else []
        return ", ".join([f"shaper cutter z0={tool.teeth}"] + extra + angle)
    if tool == _standard_rack(tool.pressure_angle_deg):
        what = "standard basic rack"
    elif tool.pressure_angle_deg == 20.0 and any(rack == tool for _, rack in _iso53_racks()):
        what = f"ISO 53 {next(k for k, rack in _iso53_racks() if rack == tool)}"
    else:
        what = f"h_aP* {tool.addendum:g}, h_fP* {tool.dedendum:g}, rho_fP* {tool.fillet:.4g}"
        what += f", pr* {tool.protuberance:g}" if tool.protuberance else ""
    return f"rack ({', '.join([what] + angle)})"


@functools.lru_cache(maxsize=64)
def _standard_rack(pressure_angle_deg) -> BasicRack:
    """The standard basic rack at this angle, made once (the pair check labels both tools of every pair
    it builds, and making a rack validates it)."""
    return BasicRack(pressure_angle_deg)


@functools.lru_cache(maxsize=1)
def _iso53_racks() -> tuple:
    """((profile, rack), ...) of the ISO 53 profiles, made once."""
    return tuple((k, BasicRack.iso53(k)) for k in ISO53_PROFILES)
