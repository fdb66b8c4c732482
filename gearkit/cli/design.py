"""Design files for every command that describes a gear or a pair: one reader, and the flags override it.

A command takes its design file as its first argument (``gearkit check design.toml``); a flag given on
the command line overrides the file's value (``gearkit check design.toml --x1 0.4``). The file is read
by :func:`gearkit.export.read_toml` (a file problem is one line, exit 2) and has one of two shapes:

* an involute pair's design file (``kind``, ``module``, ``[gear1]``, ``[gear2]``, ``[limits]``; see
  :mod:`gearkit.checks.design_file`) for ``gear`` (``--gear 1|2`` picks the gear), ``check``, ``pair``,
  ``contact``, ``view pair``, ``blocking`` and ``atlas``;
* a cam design file (``[cam]`` and ``[[motion]]`` tables, :mod:`gearkit.families.cam.design`) for
  ``cam``: a flag typed sets its field, and any motion flag typed replaces the file's motion program;
* for the other families (``novikov``, ``cycloid``, ``cycloidal-drive``, ``rack``, ``view drive``) a
  table of the command's own flags: each key is a long flag's name (``z1 = 20``, ``helix_angle_deg = 15``,
  ``rack = "single-arc"``, ``pin-radius = 7``), each value what the flag takes, checked as the flag is.

Which flags were typed is known exactly (``args.given_flags``, see :func:`given`), so a flag given
with its default value still overrides the file.
"""
from __future__ import annotations

from gearkit.errors import SpecError

__all__ = ["add_design_argument", "apply_flag_design", "given", "require_flags"]


def add_design_argument(p, shape: str) -> None:
    """The optional first argument ``design`` (a TOML file of ``shape``: 'pair' or 'flags')."""
    what = {"pair": "an involute pair's design file (see 'gearkit check --help')",
            "cam": "a cam design file ([cam] and [[motion]] tables, see 'gearkit cam --help')",
            }.get(shape, "a TOML table of this command's flags (keys: the long flag names)")
    p.add_argument("design", nargs="?", help=f"TOML design file: {what}; flags given override its values")


def given(args, dest: str) -> bool:
    """True when the flag of ``dest`` was typed on the command line."""
    return dest in getattr(args, "given_flags", ())


def require_flags(args, *flags) -> None:
    """Each ``(dest, flag)`` must have a value (from the command line or the design file)."""
    for dest, flag in flags:
        if getattr(args, dest) is None:
            raise SpecError(flag, "is required (or give a design file)")


def apply_flag_design(args) -> None:
    """Fill ``args`` from a design file of the command's flags (``args.design``), each value checked as
    its flag checks it; flags typed on the command line keep their values."""
    if getattr(args, "design", None) is None:
        return
    from gearkit.export import read_toml

    data = read_toml(args.design, "design")
    actions = args.flag_actions
    for key, value in data.items():
        dest = key.replace("-", "_")
        action = actions.get(dest)
        if action is None or dest in ("design", "output", "json", "tol"):
            allowed = sorted(d for d in actions if d not in ("output", "json", "tol"))
            raise SpecError(f"design: {key}", f"unknown key; allowed: {', '.join(allowed)}")
        if not given(args, dest):
            setattr(args, dest, _checked(action, key, value))


def _checked(action, key: str, value):
    """``value`` as the flag of ``action`` would take it; SpecError naming the key otherwise."""
    if action.nargs == 0:  # a switch
        if not isinstance(value, bool):
            raise SpecError(f"design: {key}", f"{value!r} must be true or false")
        return value
    values = value if isinstance(value, list) and action.nargs in ("+", "*") else [value]
    out = []
    for v in values:
        if isinstance(v, (dict, list)) or isinstance(v, bool):
            raise SpecError(f"design: {key}", f"{v!r} must be a {'number' if action.type else 'string'}")
        if action.type is not None:
            if getattr(action.type, "kind", action.type) is int and isinstance(v, float) and not v.is_integer():
                raise SpecError(f"design: {key}", f"{v!r} must be a whole number")
            import argparse

            try:
                v = action.type(v)
            except (argparse.ArgumentTypeError, ValueError, TypeError) as exc:
                raise SpecError(f"design: {key}", str(exc) or f"{v!r} is not valid") from None
        if action.choices is not None and v not in action.choices:
            raise SpecError(f"design: {key}", f"{v!r} is not one of {', '.join(map(str, action.choices))}")
        out.append(v)
    return out if action.nargs in ("+", "*") else out[0]
