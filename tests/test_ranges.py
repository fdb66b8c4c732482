"""One allowed range per quantity (issue 13): the command line's :data:`gearkit.cli.vocabulary.QUANTITIES`
and every spec that holds the quantity accept exactly the same values.

For every (spec, field) of :data:`SPECS`, the field at each end of the quantity's range (the end itself
when closed, the next float inside when open) is not refused *for that field*, and the next value
outside is refused naming it. A spec may still refuse another field (a cycloid pinion of 3 teeth needs
smaller generating circles): the rule is about the range of the quantity itself. Every public spec with
a field of a quantity is in the table (or in :data:`NOT_THE_QUANTITY`, saying why), so a new spec is
walked too; ``tests/test_cli_vocabulary.py`` walks the commands' flags the same way.
"""
import dataclasses
import math

import pytest

import gearkit as gk
from gearkit.cli.vocabulary import QUANTITIES
from gearkit.errors import SpecError
from gearkit.scene.model import Gear, Mesh, Scene

RACK = gk.rack_system("dca24").racks[0]


def _scene(**kw):
    gear_kw = {k[5:]: v for k, v in kw.items() if k.startswith("gear_")}
    return Scene((Gear("a", **{"teeth": 20, **gear_kw}), Gear("b", 40)), (Mesh("a", "b"),),
                 **{k: v for k, v in kw.items() if not k.startswith("gear_")})


#: (name, build(**{field: value}), field, quantity)
SPECS = [
    ("GearSpec", lambda **kw: gk.GearSpec(**{"teeth": 20, "module": 2.0, **kw}), f, q)
    for f, q in (("teeth", "teeth"), ("module", "module"), ("shift", "shift"), ("helix_angle_deg", "helix_angle_deg"))
] + [
    ("RackSpec", lambda **kw: gk.RackSpec(**{"module": 2.0, **kw}), f, q)
    for f, q in (("module", "module"), ("helix_angle_deg", "helix_angle_deg"))
] + [
    ("BasicRack", lambda **kw: gk.BasicRack(**kw), "pressure_angle_deg", "pressure_angle_deg"),
    ("ShaperCutter", lambda **kw: gk.ShaperCutter(20, **kw), "pressure_angle_deg", "pressure_angle_deg"),
] + [
    ("PairSpec", lambda **kw: gk.PairSpec(**{"teeth1": 20, "teeth2": 40, "module": 2.0, **kw}), f, q)
    for f, q in (("teeth1", "teeth"), ("teeth2", "teeth"), ("module", "module"), ("shift1", "shift"),
                 ("shift2", "shift"), ("helix_angle_deg", "helix_angle_deg"),
                 ("pressure_angle_deg", "pressure_angle_deg"), ("face_width", "width"))
] + [
    ("NovikovGearSpec", lambda **kw: gk.NovikovGearSpec(**{"teeth": 20, "module": 2.0, "rack": RACK, "helix_angle_deg": 15.0,
                                                           **kw}), f, q)
    for f, q in (("teeth", "teeth"), ("module", "module"), ("helix_angle_deg", "helix_angle_deg"))
] + [
    ("NovikovPairSpec", lambda **kw: gk.NovikovPairSpec(**{"teeth1": 20, "teeth2": 40, "module": 2.0,
                                                           "helix_angle_deg": 15.0, "face_width": 30.0, **kw}), f, q)
    for f, q in (("teeth1", "teeth"), ("teeth2", "teeth"), ("module", "module"),
                 ("helix_angle_deg", "helix_angle_deg"), ("face_width", "width"))
] + [
    # the wheel has at least the pinion's teeth: the wheel's range is walked over a pinion of 3
    ("CycloidPairSpec", lambda **kw: gk.CycloidPairSpec(**{"module": 2.0, "pinion_teeth": 3, "wheel_teeth": 40,
                                                           **kw}), f, q)
    for f, q in (("module", "module"), ("pinion_teeth", "teeth"), ("wheel_teeth", "teeth"))
] + [
    ("PinGearSpec", lambda **kw: gk.PinGearSpec(**{"module": 2.0, "pins": 10, "wheel_teeth": 30, "pin_radius": 0.5,
                                                   **kw}), f, q)
    for f, q in (("module", "module"), ("pins", "teeth"), ("wheel_teeth", "teeth"))
] + [
    ("SolidSpec", lambda **kw: gk.SolidSpec(**{"width": 5.0, **kw}), f, q)
    for f, q in (("width", "width"), ("helix_angle_deg", "helix_angle_deg"))
] + [
    ("Scene", _scene, f, q)
    for f, q in (("module", "module"), ("pressure_angle_deg", "pressure_angle_deg"),
                 ("helix_angle_deg", "helix_angle_deg"), ("face_width", "width"), ("gear_teeth", "teeth"),
                 ("gear_shift", "shift"), ("gear_module", "module"), ("gear_helix_angle_deg", "helix_angle_deg"))
]

#: public spec fields named like a quantity that are another quantity, with the reason
NOT_THE_QUANTITY = {
    ("ShaperCutter", "teeth"): "a tool's teeth z0, [6, 1000]",
    ("ShaperCutter", "shift"): "the cutter's own shift x0, [-1, 1.5]",
    ("DriveSpec", "pins"): "a cycloidal drive's pin count, [3, 1000] (its disc is built whole)",
}
QUANTITY_FIELDS = {"teeth", "teeth1", "teeth2", "pinion_teeth", "wheel_teeth", "pins", "module", "shift", "shift1",
                   "shift2", "helix_angle_deg", "pressure_angle_deg", "face_width", "width"}


def _ends(q):
    """``[(value inside, value outside)]`` at each end of the quantity's range."""
    if q.kind is int:
        return [(int(q.lo), int(q.lo) - 1), (int(q.hi), int(q.hi) + 1)]
    lo_in = math.nextafter(q.lo, math.inf) if q.open_lo else q.lo
    hi_in = math.nextafter(q.hi, -math.inf) if q.open_hi else q.hi
    lo_out = q.lo if q.open_lo else math.nextafter(q.lo, -math.inf)
    hi_out = q.hi if q.open_hi else math.nextafter(q.hi, math.inf)
    return [(lo_in, lo_out), (hi_in, hi_out)]


def _refused_for(build, field, value):
    """The message if building with ``field = value`` is refused naming that field, else None."""
    try:
        build(**{field: value})
    except SpecError as exc:
        named = exc.field.split(".")[-1] in (field, field[5:] if field.startswith("gear_") else field)
        return str(exc) if named else None
    return None


@pytest.mark.parametrize("name, build, field, quantity", SPECS, ids=[f"{s[0]}.{s[2]}" for s in SPECS])
def test_a_spec_accepts_exactly_the_range_of_its_quantity(name, build, field, quantity):
    q = QUANTITIES[quantity]
    for inside, outside in _ends(q):
        assert _refused_for(build, field, inside) is None, f"{name}.{field} = {inside!r} is in {q.range_text}"
        message = _refused_for(build, field, outside)
        assert message is not None, f"{name}.{field} = {outside!r} is outside {q.range_text} but accepted"


def test_every_public_spec_with_a_quantity_is_walked():
    walked = {(name, field[5:] if field.startswith("gear_") else field) for name, _, field, _ in SPECS}
    missing = []
    for name in gk.__all__:
        obj = getattr(gk, name)
        if isinstance(obj, type) and dataclasses.is_dataclass(obj) and name.endswith("Spec") or name in (
                "BasicRack", "ShaperCutter", "Scene"):
            for f in dataclasses.fields(obj):
                if f.name in QUANTITY_FIELDS and (name, f.name) not in walked | set(NOT_THE_QUANTITY):
                    missing.append(f"{name}.{f.name}")
    assert missing == []
