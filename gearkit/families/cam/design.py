"""TOML design files of ``gearkit cam``: a cam, its follower and its motion program.

Format (lengths in mm, angles in degrees; keys as in :class:`~gearkit.families.cam.CamSpec`)::

    [cam]
    prime_radius = 40.0            # required
    follower = "translating"       # translating | rocker
    contact = "roller"             # roller | knife | flat
    roller_radius = 8.0
    offset = 0.0
    pivot_distance = 90.0          # rocker
    arm_length = 60.0              # rocker
    efficiency = 1.0               # the friction digest's power model
    friction = 0.0                 # the textbook's friction-angle model
    pressure_angle_limit_deg = 30.0
    groove = false

    [[motion]]                     # required, in order from phi = 0; a closing dwell is added
    kind = "rise"                  # rise | dwell | return
    span_deg = 90.0
    lift = 10.0
    law = "cycloidal"              # see gearkit.families.cam.laws.LAWS
    # table = [[0, 0], [0.5, 0.6], [1, 1]]   # for law = "table"

    [[motion]]
    kind = "dwell"
    span_deg = 30.0
"""
from __future__ import annotations


from gearkit.errors import SpecError
from gearkit.families.cam.laws import MotionProgram, MotionSegment
from gearkit.families.cam.spec import CamSpec

__all__ = ["cam_from_dict", "load_cam_design"]

_CAM = {"prime_radius", "follower", "contact", "roller_radius", "offset", "pivot_distance", "arm_length",
        "efficiency", "friction", "pressure_angle_limit_deg", "groove"}
_SEGMENT = {"kind", "span_deg", "lift", "law", "table"}


def cam_from_dict(data: dict) -> CamSpec:
    """A :class:`CamSpec` from the parsed TOML (unknown keys are errors naming them).

    Examples
    --------
    >>> spec = cam_from_dict({"cam": {"prime_radius": 40, "roller_radius": 8},
    ...                       "motion": [{"kind": "rise", "span_deg": 90, "lift": 10},
    ...                                  {"kind": "return", "span_deg": 90, "lift": 10}]})
    >>> spec.motion.stroke, spec.roller_radius
    (10.0, 8.0)
    """
    if not isinstance(data, dict) or set(data) - {"cam", "motion"}:
        raise SpecError("design", f"unknown tables {sorted(set(data) - {'cam', 'motion'})}; allowed: cam, motion")
    cam = data.get("cam")
    if not isinstance(cam, dict):
        raise SpecError("cam", "the design needs a [cam] table")
    extra = set(cam) - _CAM
    if extra:
        raise SpecError(f"cam.{sorted(extra)[0]}", f"unknown key; allowed: {', '.join(sorted(_CAM))}")
    motion = data.get("motion")
    if not isinstance(motion, list) or not motion:
        raise SpecError("motion", "the design needs [[motion]] segments")
    segs = []
    for k, seg in enumerate(motion):
        if not isinstance(seg, dict) or set(seg) - _SEGMENT:
            bad = sorted(set(seg) - _SEGMENT) if isinstance(seg, dict) else ["?"]
            raise SpecError(f"motion[{k}].{bad[0]}", f"unknown key; allowed: {', '.join(sorted(_SEGMENT))}")
        args = dict(seg)
        if "table" in args:
            args["table"] = tuple(tuple(p) for p in args["table"])
        try:
            segs.append(MotionSegment(**{"lift": 0.0, **args}))
        except TypeError as exc:
            raise SpecError(f"motion[{k}]", f"{exc}") from None
    values = dict(cam)
    for key in ("prime_radius", "roller_radius", "offset", "pivot_distance", "arm_length", "efficiency", "friction",
                "pressure_angle_limit_deg"):
        if isinstance(values.get(key), int) and not isinstance(values.get(key), bool):
            values[key] = float(values[key])
    if "prime_radius" not in values:
        raise SpecError("cam.prime_radius", "required")
    return CamSpec(motion=MotionProgram(tuple(segs)), **values)


def load_cam_design(path) -> CamSpec:
    """Read a TOML cam design file; any problem is a :class:`SpecError` naming it."""
    from gearkit.export import read_toml

    data = read_toml(path, "design")
    return cam_from_dict(data)
