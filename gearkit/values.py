"""Frozen value classes: :func:`frozen` makes the class ``dataclasses.dataclass(frozen=True)`` makes,
without compiling its methods.

Every spec and record of gearkit is a frozen dataclass (inputs only, validated in
``__post_init__``). The standard library writes each dataclass's ``__init__``, ``__repr__``,
``__eq__``, ``__hash__``, ``__setattr__`` and ``__delattr__`` as source text and compiles it when
the class is made: about half a millisecond a class, so the thirty classes a command like
``gearkit check`` loads cost more than its own arithmetic. :func:`frozen` lets
:mod:`dataclasses` collect the fields (so ``dataclasses.fields``, ``replace``, ``asdict`` and
``is_dataclass`` read the class as theirs) and gives it the same methods as closures over the
field names, made without compiling anything:

* ``__init__(self, <fields>)`` in field order, defaults and ``default_factory`` as declared, then
  ``__post_init__`` if the class has one; the call's signature (``inspect.signature``) is the one
  the standard library writes;
* ``__repr__`` of the fields with ``repr=True``; ``__eq__`` (same class only) and ``__hash__`` over
  the fields with ``compare=True`` (``hash`` when given), as tuples;
* assigning or deleting a field raises :class:`dataclasses.FrozenInstanceError`.

A method the class body defines itself is kept, as :mod:`dataclasses` keeps it. A class without a
docstring gets the one the standard library writes (its name and signature), made when first read. One difference
shows: ``__dataclass_params__`` records the options the fields were collected with
(``init``, ``repr``, ``eq`` and ``frozen`` all False), not the ones the methods behave by.

Examples
--------
>>> import dataclasses
>>> @frozen
... class Pin:
...     radius: float
...     name: str = dataclasses.field(default="pin", compare=False)
...     def __post_init__(self):
...         object.__setattr__(self, "radius", float(self.radius))
>>> p = Pin(3)
>>> p, p == Pin(3.0, "other"), hash(p) == hash(Pin(3.0))
(Pin(radius=3.0, name='pin'), True, True)
>>> dataclasses.replace(p, radius=4), [f.name for f in dataclasses.fields(p)]
(Pin(radius=4.0, name='pin'), ['radius', 'name'])
>>> def bare(decorate):  # a class without a docstring gets the standard library's (written when read)
...     class Bare:
...         size: int = 1
...     return decorate(Bare)
>>> bare(frozen).__doc__ == bare(dataclasses.dataclass(frozen=True)).__doc__, bare(frozen)(2).__doc__
(True, "Bare(size: 'int' = 1)")
>>> p.radius = 5.0
Traceback (most recent call last):
...
dataclasses.FrozenInstanceError: cannot assign to field 'radius'
"""
from __future__ import annotations

import dataclasses
import inspect

__all__ = ["frozen", "FACTORY"]


class _Factory:
    def __repr__(self):
        return "<factory>"


#: the default a signature shows for a field made by its ``default_factory`` (as the standard library shows it)
FACTORY = _Factory()


def frozen(cls: type) -> type:
    """Class decorator: ``cls`` as ``@dataclass(frozen=True)`` makes it (see the module's notes)."""
    documented = bool(cls.__dict__.get("__doc__"))
    if not documented:  # a stand-in, so the standard library does not write the signature text itself
        cls.__doc__ = cls.__name__
    dataclasses.dataclass(cls, init=False, repr=False, eq=False)  # collects the fields, writes no method
    fields = dataclasses.fields(cls)
    if any(f.kw_only for f in fields):
        raise TypeError(f"{cls.__qualname__}: keyword-only fields are not supported")
    names = tuple(f.name for f in fields if f.init)
    own = cls.__dict__
    methods = {"__init__": _init(cls, names, fields), "__repr__": _repr(tuple(f.name for f in fields if f.repr)),
               "__eq__": _eq(tuple(f.name for f in fields if f.compare)),
               "__hash__": _hash(tuple(f.name for f in fields if (f.compare if f.hash is None else f.hash))),
               "__setattr__": _guard(cls, frozenset(f.name for f in fields), "assign to"),
               "__delattr__": _guard(cls, frozenset(f.name for f in fields), "delete")}
    for name, method in methods.items():
        if name not in own or (name == "__hash__" and own[name] is None):  # a body's __eq__ alone sets it None
            method.__qualname__ = f"{cls.__qualname__}.{name}"
            setattr(cls, name, method)
    cls.__signature__ = _SIGNATURE
    if not documented:
        cls.__doc__ = _SIGNATURE_DOC
    return cls


class _Signature:
    """``__signature__`` of a frozen class (what ``inspect.signature`` and ``help`` show), made when asked
    for: the fields' names, annotations and defaults, as the standard library's ``__init__`` has them."""

    def __get__(self, instance, owner):
        return inspect.Signature([
            inspect.Parameter(f.name, inspect.Parameter.POSITIONAL_OR_KEYWORD, annotation=f.type,
                              **({"default": f.default} if f.default is not dataclasses.MISSING else
                                 {"default": FACTORY} if f.default_factory is not dataclasses.MISSING else {}))
            for f in dataclasses.fields(owner) if f.init], return_annotation=None)


_SIGNATURE = _Signature()


class _SignatureDoc:
    """``__doc__`` of a frozen class without a docstring: its name and signature, as the standard library
    writes it (``Pin(radius: float, name: str = 'pin')``), made when read (``help``, doctest), not when
    the class is made."""

    def __get__(self, instance, owner):
        return owner.__name__ + str(inspect.signature(owner)).replace(" -> None", "")


_SIGNATURE_DOC = _SignatureDoc()


def _init(cls, names, fields):
    """``__init__`` over the init fields ``names``: positional or keyword, declared defaults, then
    ``__post_init__``; the standard library's errors for a wrong call."""
    defaults = {f.name: f.default for f in fields if f.default is not dataclasses.MISSING}
    factories = {f.name: f.default_factory for f in fields if f.default_factory is not dataclasses.MISSING}
    fixed = [f for f in fields if not f.init]  # not arguments: their default or factory, always
    post_init = hasattr(cls, "__post_init__")
    count = len(names)
    where = f"{cls.__qualname__}.__init__()"
    required = sum(1 for n in names if n not in defaults and n not in factories)
    takes = f"{count + 1}" if required == count else f"from {required + 1} to {count + 1}"  # self counted

    def __init__(self, *args, **kwargs):
        given = len(args)
        if given == count and not kwargs:
            values = dict(zip(names, args))
        else:
            for name in kwargs:
                if name not in names:
                    raise TypeError(f"{where} got an unexpected keyword argument {name!r}")
                if names.index(name) < given:
                    raise TypeError(f"{where} got multiple values for argument {name!r}")
            if given > count:
                raise TypeError(f"{where} takes {takes} positional arguments but {given + 1} were given")
            values, missing = {}, []
            for i, name in enumerate(names):  # in field order, as the standard library stores them
                if i < given:
                    values[name] = args[i]
                elif name in kwargs:
                    values[name] = kwargs[name]
                elif name in defaults:
                    values[name] = defaults[name]
                elif name in factories:
                    values[name] = factories[name]()
                else:
                    missing.append(repr(name))
            if missing:
                listed = missing[0] if len(missing) == 1 else (", ".join(missing[:-1]) + ("," if len(missing) > 2
                                                                                         else "") + " and " + missing[-1])
                raise TypeError(f"{where} missing {len(missing)} required positional argument"
                                f"{'s' if len(missing) > 1 else ''}: {listed}")
        for f in fixed:
            if f.default is not dataclasses.MISSING:
                values[f.name] = f.default
            elif f.default_factory is not dataclasses.MISSING:
                values[f.name] = f.default_factory()
        self.__dict__.update(values)  # past the frozen __setattr__, as the standard library's __init__ goes
        if post_init:
            self.__post_init__()

    return __init__


def _repr(names):
    def __repr__(self):
        return f"{type(self).__qualname__}({', '.join(f'{n}={getattr(self, n)!r}' for n in names)})"

    return __repr__


def _eq(names):
    def __eq__(self, other):
        if other.__class__ is not self.__class__:
            return NotImplemented
        return tuple(getattr(self, n) for n in names) == tuple(getattr(other, n) for n in names)

    return __eq__


def _hash(names):
    def __hash__(self):
        return hash(tuple(getattr(self, n) for n in names))

    return __hash__


def _guard(cls, names, verb):
    """``__setattr__`` / ``__delattr__``: a field (or any attribute of an instance of ``cls`` itself)
    is frozen; a subclass's own attributes pass, as the standard library has it."""
    if verb == "assign to":
        def __setattr__(self, name, value):
            if type(self) is cls or name in names:
                raise dataclasses.FrozenInstanceError(f"cannot assign to field {name!r}")
            super(cls, self).__setattr__(name, value)

        return __setattr__

    def __delattr__(self, name):
        if type(self) is cls or name in names:
            raise dataclasses.FrozenInstanceError(f"cannot delete field {name!r}")
        super(cls, self).__delattr__(name)

    return __delattr__
