"""Rack systems of Novikov pairs, their presets (data) and TOML rack files.

A :class:`RackSystem` names the circular-arc rack of each gear of a pair and checks that they
mate: one double-arc rack for both gears (two lines of action, one hob), or a convex rack for one
gear and a concave rack for the other (single-arc, one line of action). Each *contact zone* pairs
a convex arc of one rack with the concave arc of the other; the zones must share the contact angle
and height, the concave arc must be the larger (rho_f > rho_a) and the pair must have backlash.

Presets live in ``gearkit/data/novikov_racks.toml`` (one table per preset). A user's rack file is
written the same way: one named table (copy a preset's block and edit it), the table's name being the
rack system's name; the older form, the same keys at the file's top level, is read too::

    [my-rack]

    title = "my rack"
    verified = false
    [my-rack.rack]               # or [my-rack.pinion] + [my-rack.wheel]
    contact_angle_deg = 24.0
    addendum = 0.9
    dedendum = 1.1
    transition = "relief-arc"    # relief-arc | common-tangent | flank-line | none
    transition_radius = 0.5196
    transition_angle_deg = 6.3478
    root_radius = 0.4            # omit for the full radius
    convex = { radius = 1.30, centre_shift = 0.0163, centre_offset = 0.6289 }
    concave = { radius = 1.42, centre_shift = 0.0325, centre_offset = 0.7086 }
"""
from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path

from gearkit.errors import SpecError, check_fields, require
from gearkit.families.novikov.racks import HEIGHT_TOL, ArcRack, ArcSpec

__all__ = ["RackSystem", "Zone", "rack_presets", "rack_system", "load_rack_system", "rack_system_from_dict"]

#: the rack system of a Novikov pair unless another is named (``--rack standard`` names it too)
DEFAULT_RACK = "dca24"
PRESETS_FILE = Path(__file__).resolve().parents[2] / "data" / "novikov_racks.toml"
_RACK_KEYS = {"contact_angle_deg", "addendum", "dedendum", "convex", "concave", "transition", "transition_radius",
              "transition_angle_deg", "root_radius"}
_ARC_KEYS = {"radius", "centre_shift", "centre_offset"}
_SYSTEM_KEYS = {"title", "provenance", "verified", "rack", "pinion", "wheel"}


@dataclass(frozen=True)
class Zone:
    """One contact zone: the convex arc of gear ``convex_gear`` against the concave arc of the other.

    Module units. ``height`` is h_k (above the convex gear's pitch line); ``backlash`` j is the
    normal-section horizontal play of the pair's racks at that height; ``rho_diff`` = rho_f - rho_a;
    ``mesh_offset`` is where the mate rack's tooth centre sits (x, in the convex gear's rack frame)
    when the zone closes.
    """

    index: int
    convex_gear: int
    height: float
    rho_diff: float
    backlash: float
    mesh_offset: float


@dataclass(frozen=True)
class RackSystem:
    """The racks of a Novikov pair: ``rack1`` cuts gear 1 (pinion), ``rack2`` gear 2 (wheel)."""

    rack1: ArcRack
    rack2: ArcRack
    name: str = "custom"
    title: str = ""
    provenance: str = "user"
    verified: bool = False

    def __post_init__(self):
        check_fields(self)
        for k in (1, 2):
            require(isinstance(getattr(self, f"rack{k}"), ArcRack), f"rack{k}", "must be an ArcRack")
        kinds = (self.rack1.kind, self.rack2.kind)
        require(kinds == ("double-arc", "double-arc") or set(kinds) == {"convex", "concave"}, "rack2",
                f"racks of kinds {kinds[0]} and {kinds[1]} do not make a pair: use double-arc racks for both "
                "gears, or a convex rack for one gear and a concave rack for the other")
        require(self.rack1.contact_angle_deg == self.rack2.contact_angle_deg, "rack2.contact_angle_deg",
                f"the racks' contact angles differ ({self.rack1.contact_angle_deg} and "
                f"{self.rack2.contact_angle_deg} deg)")
        zones = self.zones
        if len(zones) == 2:
            gap = abs(zones[0].mesh_offset - zones[1].mesh_offset)
            require(gap <= HEIGHT_TOL, "rack2",
                    f"the two lines of action do not close together (mesh offsets differ by {gap:.6f}): a "
                    "double-arc pair needs racks whose contacts close at the same position")

    @property
    def kind(self) -> str:
        """``"double-arc"`` or ``"single-arc"``."""
        return "double-arc" if self.rack1.kind == "double-arc" else "single-arc"

    @property
    def zones(self) -> tuple:
        """The contact zones (validated): convex of gear 1 / concave of gear 2 first."""
        out = []
        for cg in (1, 2):
            cvx, ccv = (self.rack1, self.rack2) if cg == 1 else (self.rack2, self.rack1)
            if cvx.convex is None or ccv.concave is None:
                continue
            field_ = f"rack{3 - cg}.concave"
            d_rho = ccv.concave.radius - cvx.convex.radius
            require(d_rho > 0.0, field_ + ".radius",
                    f"rho_f = {ccv.concave.radius} must exceed the mating rho_a = {cvx.convex.radius}: the concave "
                    "arc must be larger than the convex one (equal radii run in line contact)")
            h_a, h_f = cvx.contact_height("convex"), ccv.contact_height("concave")
            require(abs(h_a - h_f) <= HEIGHT_TOL, field_ + ".centre_shift",
                    f"the contact heights of the mating arcs disagree: convex {h_a:.6f}, concave {h_f:.6f} "
                    f"(module units); they must agree within {HEIGHT_TOL:g}")
            j = ccv.contact_space() - cvx.contact_thickness()
            require(j > 0.0, field_ + ".centre_offset",
                    f"the built-in backlash j* = {j:.6f} must be positive (thin the convex tooth: larger l_a, or "
                    "widen the concave space: smaller l_f)")
            # mate tooth centre (turned 180 deg about (c, 0)) when the convex flank touches the concave one
            offset = float(cvx.contact_point("convex")[0] + ccv.contact_point("concave")[0])
            out.append(Zone(len(out), cg, 0.5 * (h_a + h_f), d_rho, j, offset))
        require(bool(out), "rack2", "the racks have no convex arc facing a concave arc")
        return tuple(out)

    @property
    def racks(self) -> tuple:
        return (self.rack1, self.rack2)


# ----------------------------------------------------------------------------- TOML

def _arc_from(d, where):
    if d is None:
        return None
    require(isinstance(d, dict), where, "must be a table with radius, centre_shift, centre_offset")
    extra = set(d) - _ARC_KEYS
    require(not extra, where, f"unknown keys {sorted(extra)}; allowed: {sorted(_ARC_KEYS)}")
    require("radius" in d, where + ".radius", "is required")
    try:
        return ArcSpec(**d)
    except SpecError as exc:
        raise exc.renamed(f"{where}.{exc.field}") from None


def _rack_from(d, where, labels):
    require(isinstance(d, dict), where, "must be a table of rack parameters")
    extra = set(d) - _RACK_KEYS
    require(not extra, where, f"unknown keys {sorted(extra)}; allowed: {sorted(_RACK_KEYS)}")
    for key in ("contact_angle_deg", "addendum", "dedendum"):
        require(key in d, f"{where}.{key}", "is required")
    kw = {k: v for k, v in d.items() if k not in ("convex", "concave")}
    try:
        return ArcRack(convex=_arc_from(d.get("convex"), where + ".convex"),
                       concave=_arc_from(d.get("concave"), where + ".concave"), **kw, **labels)
    except SpecError as exc:
        if exc.field.startswith(where):
            raise
        raise exc.renamed(f"{where}.{exc.field}") from None
    except TypeError as exc:
        raise SpecError(where, str(exc)) from None


def rack_system_from_dict(d: dict, name: str = "custom") -> RackSystem:
    """A :class:`RackSystem` from a parsed TOML table (see the module docstring)."""
    require(isinstance(d, dict), name, "must be a table")
    extra = set(d) - _SYSTEM_KEYS
    require(not extra, name, f"unknown keys {sorted(extra)}; allowed: {sorted(_SYSTEM_KEYS)}")
    labels = {"name": name, "title": str(d.get("title", "")), "provenance": str(d.get("provenance", "user")),
              "verified": bool(d.get("verified", False))}
    if "rack" in d:
        require("pinion" not in d and "wheel" not in d, name, "give [rack] or [pinion] + [wheel], not both")
        rack = _rack_from(d["rack"], "rack", labels)
        return RackSystem(rack, rack, **labels)
    require("pinion" in d and "wheel" in d, name, "needs a [rack] table, or [pinion] and [wheel] tables")
    return RackSystem(_rack_from(d["pinion"], "pinion", labels), _rack_from(d["wheel"], "wheel", labels), **labels)


@lru_cache(maxsize=1)
def rack_presets() -> dict:
    """The preset rack systems by name (from ``gearkit/data/novikov_racks.toml``)."""
    from gearkit.export import read_toml

    data = read_toml(PRESETS_FILE, "rack")
    return {name: rack_system_from_dict(table, name) for name, table in data.items()}


def load_rack_system(path) -> RackSystem:
    """Read a rack system from a TOML file (format in the module docstring): one named table, as a
    preset is written in ``gearkit/data/novikov_racks.toml``, or the same keys at the top level."""
    p = Path(path)
    if not p.is_file():
        raise SpecError("rack", f"no rack file {str(p)!r}")
    from gearkit.export import read_toml

    data = read_toml(p, "rack")
    if set(data) & _SYSTEM_KEYS:  # the keys at the top level: the file is the system, named by its stem
        return rack_system_from_dict(data, p.stem)
    tables = [k for k, v in data.items() if isinstance(v, dict)]
    if len(data) != 1 or len(tables) != 1:
        raise SpecError("rack", f"{str(p)!r} must hold one rack system: one table [NAME] with [NAME.rack] (or "
                                f"[NAME.pinion] and [NAME.wheel]), as a preset is written; found "
                                f"{', '.join(map(repr, data)) or 'nothing'}")
    return rack_system_from_dict(data[tables[0]], tables[0])


def rack_system(name_or_path=DEFAULT_RACK) -> RackSystem:
    """A preset by name (``"dca24"``, ``"single-arc"``; ``"standard"`` is the default, dca24, as in every
    command's ``--rack standard``) or a rack system read from a ``.toml`` file."""
    if isinstance(name_or_path, RackSystem):
        return name_or_path
    key = str(name_or_path)
    presets = rack_presets()
    if key == "standard":  # every command's --rack standard: its default rack
        key = DEFAULT_RACK
    if key in presets:
        return presets[key]
    if key.endswith(".toml"):
        return load_rack_system(key)
    raise SpecError("rack", f"unknown rack {key!r}; presets: {', '.join(presets)}, or a .toml file")

