"""Scene files (TOML): read a :class:`~gearkit.scene.Scene` from text a user writes.

Layout (every key but ``[gears]`` optional)::

    module = 1.75                     # normal module of gears that give none, mm
    pressure_angle_deg = 20.0
    helix_angle_deg = 0.0             # hand of the first gear; meshes decide the others'
    addendum = 1.0                    # h_a*
    clearance = 0.25                  # c*, the bottom clearance every tip keeps
    face_width = 20.0                 # mm (solids, overlap ratio)
    coaxial = [["input", "output"]]   # members that must share an axis
    [gears]
    sun    = { teeth = 21, shift = 0.438 }
    planet = { teeth = 43, shift = 0.0426, count = 3, carrier = "carrier" }
    ring   = { teeth = 108, internal = true }      # also: shaft, module, angles_deg, helix_angle_deg,
                                                   # thinning, cutter_teeth, rack
    [meshes]
    sun-planet  = ["sun", "planet"]                # or { gears = [..], angle_deg = 90, center_distance = 60 }
    planet-ring = ["planet", "ring"]
    [motion]
    fixed  = ["ring"]
    locked = [["sun", "carrier"]]
    input  = "sun"                                  # or { sun = 1500.0, ring = -300.0 } (speeds)
    output = "carrier"
    [states.first]                                  # alternative fixed/locked sets (brakes, clutches)
    fixed = ["s3"]

Examples
--------
>>> s = scene_from_text('module = 2\\n[gears]\\na = { teeth = 15 }\\nb = { teeth = 30 }\\n'
...                     '[meshes]\\nab = ["a", "b"]\\n[motion]\\ninput = "a"\\noutput = "b"\\n')
>>> [g.teeth for g in s.gears], s.motion.output
([15, 30], 'b')
"""
from __future__ import annotations

from pathlib import Path

from gearkit.errors import SpecError, require
from gearkit.scene.model import Gear, Mesh, Motion, Scene

__all__ = ["load_scene", "scene_from_dict", "scene_from_text"]

_TOP = {"module", "pressure_angle_deg", "helix_angle_deg", "addendum", "clearance", "face_width", "coaxial",
        "gears", "meshes", "motion", "states"}
_GEAR = {"teeth", "shift", "module", "internal", "rack", "shaft", "carrier", "count", "angles_deg",
         "helix_angle_deg", "thinning", "cutter_teeth"}
_MESH = {"gears", "angle_deg", "center_distance"}
_MOTION = {"fixed", "locked", "input", "output"}


def _table(value, where: str) -> dict:
    require(isinstance(value, dict), where, f"must be a table, not {type(value).__name__}")
    return value


def _unknown(table: dict, allowed: set, where: str) -> None:
    extra = sorted(set(table) - allowed)
    require(not extra, where, f"unknown key(s) {', '.join(extra)} (allowed: {', '.join(sorted(allowed))})")


def _names(value, where: str) -> tuple:
    if isinstance(value, str):
        return (value,)
    require(isinstance(value, list) and all(isinstance(v, str) for v in value), where, "must be a list of names")
    return tuple(value)


def _motion(table: dict, where: str) -> Motion:
    _unknown(table, _MOTION, where)
    locked = table.get("locked", [])
    require(isinstance(locked, list), f"{where}.locked", "must be a list of lists of names")
    if locked and all(isinstance(v, str) for v in locked):
        locked = [locked]  # one lock written as a flat list
    locks = tuple(_names(group, f"{where}.locked") for group in locked)
    given = table.get("input", {})
    if isinstance(given, str):
        inputs = ((given, 1.0),)
    else:
        _table(given, f"{where}.input")
        for k, v in given.items():
            require(isinstance(v, (int, float)) and not isinstance(v, bool), f"{where}.input.{k}",
                    f"{v!r} must be a speed (a number)")
        inputs = tuple((k, float(v)) for k, v in given.items())
    output = table.get("output")
    require(output is None or isinstance(output, str), f"{where}.output", "must be a member name")
    return Motion(_names(table.get("fixed", []), f"{where}.fixed"), locks, inputs, output)


def scene_from_dict(data: dict) -> Scene:
    """A scene from the parsed TOML tables (see the module notes); unknown keys raise SpecError."""
    _table(data, "scene")
    _unknown(data, _TOP, "scene")
    gears = []
    for name, spec in _table(data.get("gears", {}), "gears").items():
        _unknown(_table(spec, f"gears.{name}"), _GEAR, f"gears.{name}")
        require("teeth" in spec, f"gears.{name}.teeth", "is required")
        kwargs = dict(spec)
        if "angles_deg" in kwargs:
            kwargs["angles_deg"] = tuple(kwargs["angles_deg"])
        gears.append(Gear(name, **kwargs))
    require(gears, "gears", "a scene needs at least one gear under [gears]")
    meshes = []
    for label, spec in _table(data.get("meshes", {}), "meshes").items():
        if isinstance(spec, dict):
            _unknown(spec, _MESH, f"meshes.{label}")
            pair = _names(spec.get("gears", []), f"meshes.{label}.gears")
            extra = {k: spec[k] for k in ("angle_deg", "center_distance") if k in spec}
        else:
            pair, extra = _names(spec, f"meshes.{label}"), {}
        require(len(pair) == 2, f"meshes.{label}", f"{list(pair)!r} must name two gears")
        meshes.append(Mesh(pair[0], pair[1], **extra))
    motion = _motion(_table(data.get("motion", {}), "motion"), "motion")
    states = tuple((k, _motion(_table(v, f"states.{k}"), f"states.{k}"))
                   for k, v in _table(data.get("states", {}), "states").items())
    coaxial = data.get("coaxial", [])
    require(isinstance(coaxial, list), "coaxial", "must be a list of lists of member names")
    kwargs = {k: data[k] for k in ("module", "pressure_angle_deg", "helix_angle_deg", "addendum", "clearance",
                                   "face_width") if k in data}
    return Scene(tuple(gears), tuple(meshes), motion=motion, states=states,
                 coaxial=tuple(_names(g, "coaxial") for g in coaxial), **kwargs)


def scene_from_text(text: str) -> Scene:
    """A scene from TOML text."""
    import tomllib

    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise SpecError("scene", f"not valid TOML ({exc})") from None
    return scene_from_dict(data)


def load_scene(path) -> Scene:
    """Read a scene file (TOML); a missing or unreadable file raises SpecError naming it."""
    p = Path(path)
    try:
        text = p.read_text(encoding="utf-8")
    except OSError as exc:
        raise SpecError(str(p), f"cannot read the scene file: {exc.strerror or exc}") from None
    except UnicodeDecodeError:
        raise SpecError(str(p), "not a TOML text file (not UTF-8)") from None
    try:
        return scene_from_text(text)
    except SpecError as exc:
        raise SpecError(f"{p.name}: {exc.field}", str(exc).split(": ", 1)[-1]) from None
