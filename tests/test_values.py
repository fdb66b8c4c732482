"""``gearkit.values.frozen`` against the standard library's ``dataclass(frozen=True)`` (the oracle): the same
class body made both ways behaves the same way in every respect gearkit relies on."""
import copy
import dataclasses
import inspect
import pickle

import pytest

from gearkit.values import frozen


def body():
    """A fresh class body: required and defaulted fields, a factory, a field left out of compare
    and repr, a validating and normalising ``__post_init__``, a property."""

    class Spec:
        """A spec."""

        teeth: int
        module: float
        name: str = dataclasses.field(default="gear", compare=False)
        shift: float = 0.0
        notes: tuple = dataclasses.field(default_factory=tuple, repr=False)

        def __post_init__(self):
            if self.teeth < 1:
                raise ValueError("teeth")
            object.__setattr__(self, "module", float(self.module))

        @property
        def pitch(self):
            return 3.0 * self.module

    return Spec


Std = dataclasses.dataclass(frozen=True)(body())
Ours = frozen(body())
Std.__qualname__, Ours.__qualname__ = "Std", "Ours"  # module-level names (pickle finds the classes by them)
CALLS = [((12, 2),), ((12,), {"module": 2}), ((), {"teeth": 5, "module": 1, "shift": 0.25, "notes": (1,)}),
         ((7, 3, "pinion", -0.5, ("a",)),)]


def _call(cls, call):
    args = call[0]
    kwargs = call[1] if len(call) > 1 else {}
    return cls(*args, **kwargs)


@pytest.mark.parametrize("call", CALLS)
def test_instances_match_the_standard_library(call):
    a, b = _call(Std, call), _call(Ours, call)
    assert repr(a).replace("Std(", "Ours(") == repr(b)
    assert vars(a) == vars(b) and list(vars(a)) == list(vars(b))  # same values, stored in field order
    assert dataclasses.asdict(a) == dataclasses.asdict(b) and dataclasses.astuple(a) == dataclasses.astuple(b)
    assert hash(a) == hash(b)
    assert b == _call(Ours, call) and b != a  # equal to its own kind only, as the standard library's
    assert a.pitch == b.pitch
    assert dataclasses.replace(b, shift=1.0) == _call(Ours, ((b.teeth, b.module, b.name, 1.0, b.notes),))
    assert pickle.loads(pickle.dumps(b)) == b and copy.deepcopy(b) == b


def test_compare_false_fields_stay_out_of_eq_and_hash():
    assert Ours(12, 2, "a") == Ours(12, 2, "b") and hash(Ours(12, 2, "a")) == hash(Ours(12, 2, "b"))
    assert Ours(12, 2) != Ours(12, 2, shift=0.1)


def test_fields_signature_and_doc_match_the_standard_library():
    assert [(f.name, f.type, f.default, f.compare, f.repr) for f in dataclasses.fields(Ours)] == \
           [(f.name, f.type, f.default, f.compare, f.repr) for f in dataclasses.fields(Std)]
    assert dataclasses.is_dataclass(Ours) and dataclasses.is_dataclass(Ours(1, 1))
    assert str(inspect.signature(Ours)) == str(inspect.signature(Std))
    assert Ours.__match_args__ == Std.__match_args__
    assert Ours.__doc__ == Std.__doc__ == "A spec."


@pytest.mark.parametrize("args, kwargs", [((1, 2, "x", 0.0, (), 9), {}), ((1,), {}), ((), {}), ((1, 2), {"colour": 3}),
                                          ((1, 2), {"teeth": 3}), ((), {"module": 3})])
def test_a_wrong_call_raises_the_standard_librarys_type_error(args, kwargs):
    with pytest.raises(TypeError) as std:
        Std(*args, **kwargs)
    with pytest.raises(TypeError) as ours:
        Ours(*args, **kwargs)
    assert str(ours.value) == str(std.value).replace("Std.", "Ours.")


def test_post_init_validates_and_fields_are_frozen():
    with pytest.raises(ValueError, match="teeth"):
        Ours(0, 1)
    spec = Ours(3, 1)
    for action in (lambda: setattr(spec, "teeth", 4), lambda: setattr(spec, "other", 1),
                   lambda: delattr(spec, "module")):
        with pytest.raises(dataclasses.FrozenInstanceError):
            action()
    assert spec.teeth == 3 and spec.module == 1.0


def test_a_subclass_adds_fields_after_its_base_s():
    @frozen
    class Base:
        a: int
        b: float = 1.0

    @frozen
    class Child(Base):
        c: str = "c"

    child = Child(1, 2.0, "x")
    assert [f.name for f in dataclasses.fields(Child)] == ["a", "b", "c"]
    assert repr(child) == "test_a_subclass_adds_fields_after_its_base_s.<locals>.Child(a=1, b=2.0, c='x')"
    assert child != Base(1, 2.0) and child == Child(1, 2.0, "x")
    with pytest.raises(dataclasses.FrozenInstanceError):
        child.c = "y"


def test_methods_the_body_defines_are_kept():
    @frozen
    class Named:
        name: str

        def __repr__(self):
            return f"<{self.name}>"

        def __eq__(self, other):
            return isinstance(other, Named) and other.name.lower() == self.name.lower()

        def __hash__(self):
            return hash(self.name.lower())

    assert repr(Named("A")) == "<A>" and Named("A") == Named("a") and hash(Named("A")) == hash(Named("a"))
