"""One validation path for every spec (issue 20, class 9): a property over every input dataclass.

Every frozen dataclass that validates its inputs in ``__post_init__`` goes through
:func:`gearkit.errors.check_fields` (the one type gate), asserted by reading the source; and a
hypothesis property replaces one field of a valid spec by a hostile value (a string, None, a bool,
inf, nan, 1e300, a numpy scalar, a list): the result is either a spec holding plain Python values
(numpy scalars stored as numbers) or a ``SpecError`` naming a field, never another exception.
"""
import dataclasses
import importlib
import inspect
import math
import pkgutil

import numpy as np
import pytest

import gearkit
import gearkit as gk
from gearkit.errors import SpecError
from gearkit.families.cam import CamSpec, MotionProgram, MotionSegment
from gearkit.pair.allowances import Allowances
from gearkit.scene import Gear, Mesh, Motion, Scene, SynthesisLimits

#: dataclasses with a ``__post_init__`` that are not user input: kernel values built by gearkit
#: itself (a motion, a kinematic relation or train, a finding or report, a motion program, which is
#: a list of MotionSegment specs that are gated themselves)
NOT_INPUT = {"RollingMotion", "Relation", "Train", "Finding", "CheckReport", "MotionProgram"}


def _dataclasses_with_post_init():
    out = {}
    for info in pkgutil.walk_packages(gearkit.__path__, "gearkit."):
        if info.name == "gearkit.__main__" or any(f".{part}" in info.name for part in ("cli", "bench", "view")):
            continue
        mod = importlib.import_module(info.name)
        for name, obj in vars(mod).items():
            if (inspect.isclass(obj) and obj.__module__ == info.name and dataclasses.is_dataclass(obj)
                    and "__post_init__" in vars(obj)):
                out[name] = obj
    return out


def test_every_input_dataclass_goes_through_check_fields():
    found = _dataclasses_with_post_init()
    assert {"GearSpec", "PairSpec", "Scene", "Gear", "CamSpec", "Deviations", "Allowances"} <= set(found)
    missing = sorted(name for name, cls in found.items()
                     if name not in NOT_INPUT and "check_fields(" not in inspect.getsource(cls.__post_init__))
    assert missing == []


#: a valid instance of every input spec, as (constructor, keyword arguments)
VALID = {
    "GearSpec": (gk.GearSpec, dict(teeth=20, module=2.0, shift=0.1)),
    "RackSpec": (gk.RackSpec, dict(module=1.0)),
    "BasicRack": (gk.BasicRack, dict(pressure_angle_deg=20.0)),
    "ShaperCutter": (gk.ShaperCutter, dict(teeth=20)),
    "Modification": (gk.Modification, dict(tip_relief=0.01, tip_relief_roll=2.0)),
    "PairSpec": (gk.PairSpec, dict(teeth1=20, teeth2=40, module=1.0, shift1=0.2)),
    "CheckLimits": (gk.CheckLimits, dict()),
    "Allowances": (Allowances, dict(gear1=(-0.02, -0.05))),
    "DriveSpec": (gk.DriveSpec, dict(pins=12, lobes=11, pin_circle_radius=90.0, pin_radius=7.0, eccentricity=4.0)),
    "PinGearSpec": (gk.PinGearSpec, dict(module=1.0, pins=10, wheel_teeth=20, pin_radius=0.1)),
    "CycloidPairSpec": (gk.CycloidPairSpec, dict(module=1.0, pinion_teeth=10, wheel_teeth=20)),
    "NovikovPairSpec": (gk.NovikovPairSpec, dict(teeth1=20, teeth2=40, module=1.0, helix_angle_deg=15.0,
                                                 face_width=20.0)),
    "NovikovLimits": (gk.NovikovLimits, dict()),
    "SolidSpec": (gk.SolidSpec, dict(width=5.0)),
    "Deviations": (gk.Deviations, dict(runout1=0.01, pitch_deviations1=(0.001, -0.001))),
    "Material": (gk.Material, dict()),
    "CamSpec": (CamSpec, dict(prime_radius=40.0, motion=MotionProgram.rise_dwell_return(10.0, 90.0, 30.0, 90.0),
                              roller_radius=8.0)),
    "MotionSegment": (MotionSegment, dict(kind="rise", span_deg=90.0, lift=10.0)),
    "SceneGear": (Gear, dict(name="sun", teeth=20, shift=0.1)),
    "Mesh": (Mesh, dict(first="sun", second="planet", angle_deg=30.0)),
    "Motion": (Motion, dict(fixed=("ring",), inputs={"sun": 1.0}, output="carrier")),
    "Scene": (Scene, dict(gears=(Gear("a", 20), Gear("b", 40)), meshes=(Mesh("a", "b"),), module=2.0)),
    "SynthesisLimits": (SynthesisLimits, dict(min_teeth=17, neighbour_margin=0.5)),
}

HOSTILE = (math.inf, -math.inf, math.nan, 1e300, -1e300, 1e-300, 0.0, -1.0, 5, "1", "", None, True, False,
           np.float64(2.5), np.int64(7), np.float32(0.3), np.bool_(True), [1, 2], ("a",), {"x": 1}, object())


def _plain(value) -> bool:
    """A value a spec may hold: no numpy scalar (JSON-ready, hashable as the number it is)."""
    if isinstance(value, (tuple, list)):
        return all(_plain(v) for v in value)
    return not isinstance(value, np.generic)


def test_the_valid_specs_are_valid():
    for make, kwargs in VALID.values():
        make(**kwargs)


def test_one_hostile_field_gives_a_spec_or_a_spec_error():
    """Every hostile value in every field of every spec (a few thousand constructions)."""
    bad = []
    for name, (make, kwargs) in sorted(VALID.items()):
        for key in (f.name for f in dataclasses.fields(make)):
            for value in HOSTILE:
                try:
                    spec = make(**{**kwargs, key: value})
                except SpecError as exc:
                    if not (exc.field and len(str(exc)) > len(exc.field) + 8):
                        bad.append(f"{name}.{key}={value!r}: terse {exc}")
                    continue
                except Exception as exc:  # noqa: BLE001 - collected: the assertion lists every one
                    bad.append(f"{name}.{key}={value!r}: {type(exc).__name__}: {exc}")
                    continue
                if not all(_plain(getattr(spec, f.name)) for f in dataclasses.fields(spec)):
                    bad.append(f"{name}.{key}={value!r} kept a numpy scalar: {spec!r}")
    assert bad == []


@pytest.mark.parametrize("build, field", [
    (lambda: Gear("sun", 20, shift="0.3"), "sun.shift"),
    (lambda: Gear("sun", np.float64(20)), "sun.teeth"),
    (lambda: Gear("sun", 20, internal=1), "sun.internal"),
    (lambda: Mesh("a", "b", center_distance="30"), "a-b.center_distance"),
    (lambda: Motion(inputs={"sun": "1"}), "input.sun"),
    (lambda: Motion(inputs={"sun": None}), "input.sun"),
    (lambda: Motion(fixed=None), "fixed"),
    (lambda: Scene((Gear("a", 20),), (), module="2"), "module"),
    (lambda: Scene((Gear("a", 20),), (), motion=None), "motion"),
    (lambda: SynthesisLimits(checks="yes"), "checks"),
    (lambda: gk.Deviations(pitch_deviations1=None), "pitch_deviations1"),
    (lambda: gk.Material(young="2e5"), "young"),
    (lambda: Allowances(gear1=("0", -0.1)), "gear1"),
    (lambda: MotionSegment("rise", "90", 10.0), "span_deg"),
    (lambda: CamSpec(40.0, MotionProgram.rise_dwell_return(10.0, 90.0, 30.0, 90.0), roller_radius=8.0,
                     groove="no"), "groove"),
])
def test_scene_and_other_specs_refuse_wrong_types_naming_the_field(build, field):
    with pytest.raises(SpecError) as exc:
        build()
    assert exc.value.field == field


def test_numpy_scalars_in_a_scene_are_numbers():
    gear = Gear("sun", np.int64(20), np.float64(0.25))
    assert (type(gear.teeth), type(gear.shift)) == (int, float) and gear == Gear("sun", 20, 0.25)
    assert Motion(inputs={"sun": np.float32(2.0)}).inputs == (("sun", 2.0),)
