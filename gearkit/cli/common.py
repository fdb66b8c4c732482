"""The command line's shared vocabulary: the flags every command spells the same way, parsed once.

A command module holds only what is particular to it; everything two commands share is here:

* one gear: ``-z/--teeth``, ``-m/--module``, ``-x/--shift`` and the tool flags (:func:`add_tool_flags`,
  :func:`tool_from_args`);
* a pair: the design file (``gearkit check design.toml``) or the pair, tool and limit flags
  (:func:`add_pair_arguments`, :func:`pair_spec_from_args`);
* progress: ``--progress`` (a bar on stderr for long work even when it is not a terminal;
  :class:`gearkit.progress.Progress`);
* output: ``--tol`` (a max deviation in mm, validated by :func:`tol_from`), ``--json`` (one JSON object
  on stdout, :func:`print_json`), ``-o/--output FILE``, ``--keyway WxD`` (:func:`keyway_from_arg`).

Bad input raises :class:`~gearkit.errors.SpecError` naming the flag; :func:`gearkit.cli.main` prints it
on one line and exits 2.
"""
from __future__ import annotations

import math

from gearkit.cli.vocabulary import QUANTITIES, add_renamed_flag
from gearkit.errors import SpecError

Q = QUANTITIES

__all__ = ["QUANTITIES", "RACKS", "RACK_HELP", "SIGN_NOTE", "TIP_RULES", "add_gear_flags",
           "add_json_flag", "add_keyway_flag", "add_module_flag", "add_output_flag", "add_pair_arguments",
           "add_progress_flag", "add_rack_flag", "add_renamed_flag", "add_tol_flag", "add_tool_flags",
           "keyway_from_arg", "output_kind", "pair_spec_from_args", "print_json", "rack_from_args",
           "refuse_unused_cutter_flags", "shaper_from_args", "tol_from", "tool_from_args"]

#: how a pair's (or a gear's) tip diameters follow (``--tip-rule``)
TIP_RULES = ("shortened", "standard")
#: the basic racks a ``--rack`` flag names, the same in every command and design file
RACKS = ("standard", "iso53a", "iso53b", "iso53c", "iso53d")
RACK_HELP = ("generating basic rack: 'standard' (h_aP* 1, h_fP* 1.25, the largest tip rounding 0.38 m; the default) "
             "or an ISO 53 profile iso53a..iso53d (20 degrees)")


def add_rack_flag(p, help: str = RACK_HELP) -> None:
    """``--rack NAME``: the involute basic rack, one of :data:`RACKS` (default ``standard``)."""
    p.add_argument("--rack", choices=RACKS, default="standard", help=help)


def rack_from_args(args):
    """The :class:`~gearkit.families.involute.BasicRack` of ``--rack`` and ``--pressure-angle-deg``."""
    from gearkit.families.involute import named_rack

    return named_rack(getattr(args, "rack", None) or "standard", args.pressure_angle_deg, "--rack",
                      "--pressure-angle-deg")


def add_tool_flags(p) -> None:
    """Tool flags shared by commands that build one involute gear."""
    p.add_argument("--pressure-angle-deg", type=Q["pressure_angle_deg"], default=None,
                   help="normal pressure angle of the rack/cutter, degrees (default 20)")
    add_rack_flag(p)
    p.add_argument("--cutter-teeth", type=int, default=None,
                   help="cut with a shaper cutter of this many teeth (required with --internal; default 20 then)")
    p.add_argument("--cutter-shift", type=float, default=0.0, help="shaper cutter's own shift coefficient x0")
    p.add_argument("--cutter-addendum", type=float, default=1.25, help="shaper cutter addendum h_a0* (module units)")


def add_gear_flags(p, required: bool = True) -> None:
    """``-z/--teeth``, ``-m/--module`` and ``-x/--shift`` of one involute gear."""
    p.add_argument("-z", "--teeth", type=Q["teeth"], required=required, help="number of teeth")
    add_module_flag(p, "normal module, mm", required=required)
    p.add_argument("-x", "--shift", type=Q["shift"], default=0.0, help="normal profile shift coefficient x_n")


def add_module_flag(p, help: str, **kwargs) -> None:
    """``-m/--module``: the (normal) module in mm."""
    p.add_argument("-m", "--module", type=Q["module"], help=help, **kwargs)


def add_keyway_flag(p, flag: str = "--keyway", help: str = "keyway width x depth in the bore, mm") -> None:
    """``--keyway WxD`` (or ``flag``): a keyway in a bore, read by :func:`keyway_from_arg`."""
    p.add_argument(flag, default=None, metavar="WxD", help=help)


def add_tol_flag(p, help: str) -> None:
    """``--tol``: the max deviation (mm) of the command's output; None when not given."""
    p.add_argument("--tol", type=float, default=None, help=help)


def add_json_flag(p, help: str = "print one JSON object") -> None:
    """``--json``: print one JSON object instead of the table."""
    p.add_argument("--json", action="store_true", help=help)


def add_output_flag(p, help: str, **kwargs) -> None:
    """``-o/--output FILE``: what the command writes (its formats go in ``help``)."""
    kwargs.setdefault("default", None)
    p.add_argument("-o", "--output", help=help, **kwargs)


def add_progress_flag(p) -> None:
    """``--progress``: draw progress bars on stderr even when it is not a terminal (the command line
    takes it anywhere on the line, before or after the command)."""
    p.add_argument("--progress", action="store_true",
                   help="draw progress bars on stderr even when it is not a terminal (on a terminal they are "
                        "drawn anyway; also after the command)")


def tol_from(value, default: float | None) -> float | None:
    """The ``--tol`` value (``default`` when not given), checked to be a positive finite length; None
    when neither is given (the command's own default applies downstream).

    Examples
    --------
    >>> tol_from(None, 0.002), tol_from(0.01, 0.002), tol_from(None, None)
    (0.002, 0.01, None)
    """
    tol = default if value is None else value
    if tol is None:
        return None
    if not (isinstance(tol, (int, float)) and math.isfinite(tol) and tol > 0):
        raise SpecError("--tol", f"{tol!r} must be a positive length in mm")
    return float(tol)


def output_kind(path) -> str | None:
    """``"2d"`` (a profile file), ``"mesh"`` (a solid file) or None (no ``-o``) for an output path; an
    unknown extension is rejected (SpecError) before any work."""
    if not path:
        return None
    from gearkit.solids.export import mesh_format

    if mesh_format(path) is not None:
        return "mesh"
    from gearkit.export import profile_format

    profile_format(path)
    return "2d"


def print_json(obj, indent: int | None = 2, **kwargs) -> None:
    """Print ``obj`` as one JSON object (non-finite numbers are an error: use ``gearkit.export.json_number``)."""
    import json

    kwargs.setdefault("allow_nan", False)
    print(json.dumps(obj, indent=indent, **kwargs))


def keyway_from_arg(text):
    """``"3x1.4"`` -> (3.0, 1.4); None stays None."""
    if text is None:
        return None
    try:
        w, d = (float(v) for v in text.lower().split("x"))
    except ValueError:
        raise SpecError("--keyway", f"{text!r} must be WIDTHxDEPTH in mm, e.g. 3x1.4") from None
    return (w, d)


#: a shaper cutter's field -> the flag that sets it (the teeth flag is the caller's)
_SHAPER_FLAGS = {"cutter.shift": "--cutter-shift", "cutter.addendum": "--cutter-addendum",
                 "cutter.pressure_angle_deg": "--pressure-angle-deg"}


def shaper_from_args(teeth, alpha, shift, addendum, teeth_flag: str = "--cutter-teeth"):
    """The :class:`~gearkit.families.involute.ShaperCutter` of the cutter flags; a refused value names its flag.

    >>> shaper_from_args(4, 20.0, 0.0, 1.25)
    Traceback (most recent call last):
    gearkit.errors.SpecError: --cutter-teeth: 4 must be an integer in [6, 1000]
    """
    from gearkit.families.involute import ShaperCutter

    try:
        return ShaperCutter(teeth, alpha, shift, addendum)
    except SpecError as exc:
        flag = teeth_flag if exc.field == "cutter.teeth" else _SHAPER_FLAGS.get(exc.field)
        if flag is None:  # a derived limit (dedendum, tip radius): the API's own name says what it is
            raise
        raise exc.renamed(flag) from None


def refuse_unused_cutter_flags(args) -> None:
    """``--cutter-shift``/``--cutter-addendum`` typed where no shaper cuts: say so rather than ignore them."""
    from gearkit.cli.design import given

    shapers = ("--pinion-cutter-teeth or --internal with --cutter-teeth" if hasattr(args, "pinion_cutter_teeth")
               else "--cutter-teeth or --internal")
    for dest, flag in (("cutter_shift", "--cutter-shift"), ("cutter_addendum", "--cutter-addendum")):
        if given(args, dest):
            raise SpecError(flag, f"applies to a shaper cutter, and none cuts these gears (give {shapers})")


def tool_from_args(args, internal: bool):
    alpha = 20.0 if args.pressure_angle_deg is None else args.pressure_angle_deg
    if args.cutter_teeth is not None or internal:
        return shaper_from_args(20 if args.cutter_teeth is None else args.cutter_teeth, alpha, args.cutter_shift,
                                args.cutter_addendum)
    refuse_unused_cutter_flags(args)
    return rack_from_args(args)


SIGN_NOTE = ("Shifts are normal coefficients x_n. A ring's --x2 is read as ISO 21771 says (--ring-shift iso, the "
             "default: by its tooth thickness, as if rack-cut; the shaper setting that cuts it is derived) or as "
             "the shaper's radial setting (--ring-shift cutter); positive --x2 makes the ring's teeth thinner and "
             "its tip (inner) diameter larger. An external shaper-cut gear's shift is the cutter's radial setting.")


def add_pair_arguments(p, limits: bool = True) -> None:
    """The design-file argument and the pair, tool (and limit) flags every pair command shares."""
    p.add_argument("design", nargs="?", help="TOML design file of the pair (see 'gearkit check --help'); the "
                   "flags given override its values")
    g = p.add_argument_group("pair")
    g.add_argument("--z1", type=Q["teeth"], help="pinion teeth")
    g.add_argument("--z2", type=Q["teeth"], help="wheel (or ring) teeth")
    add_module_flag(g, "normal module m_n, mm")
    g.add_argument("--x1", type=Q["shift"], help="pinion normal shift coefficient x_n1 (default 0)")
    g.add_argument("--x2", type=Q["shift"], help="wheel/ring normal shift coefficient x_n2 (default 0; ring: see above)")
    g.add_argument("--center-distance", type=float, help="operating centre distance a_w, mm (rack pair: pinion "
                   "axis to rack datum). Alone: the shifts are solved and split by --split; with --x1: x2 "
                   "follows; with --x1 and --x2: the pair runs at a_w (backlash)")
    g.add_argument("--split", choices=("x1", "equal", "balanced"), help="shift split for --center-distance "
                   "(default balanced: equal specific sliding at the roots)")
    g.add_argument("--pressure-angle-deg", type=Q["pressure_angle_deg"],
                   help="normal pressure angle alpha_n, degrees (default 20)")
    g.add_argument("--helix-angle-deg", type=Q["helix_angle_deg"], default=0.0, help="helix angle beta, degrees")
    g.add_argument("--width", type=Q["width"], help="face width b, mm (for the overlap ratio)")
    kind = g.add_mutually_exclusive_group()
    kind.add_argument("--internal", action="store_true", help="pinion inside a ring (needs --cutter-teeth)")
    kind.add_argument("--rack-pair", action="store_true", help="pinion and rack (no --z2)")
    g.add_argument("--addendum", type=float, default=1.0, help="addendum coefficient h_a* (default 1)")
    tip = g.add_mutually_exclusive_group()
    tip.add_argument("--tip-rule", choices=TIP_RULES, default="shortened",
                     help="tip diameters: 'shortened' keeps the standard clearance (default), 'standard' is "
                          "d_a = d + 2 m_n (h_a* + x)")
    add_renamed_flag(tip, "--tip", "--tip-rule", "tip_rule", choices=TIP_RULES)
    for n, whose in ((1, "pinion"), (2, "wheel/ring")):
        tip_n = g.add_mutually_exclusive_group()
        tip_n.add_argument(f"--tip-diameter{n}", dest=f"da{n}", type=float, help=f"given {whose} tip diameter d_a{n}, mm")
        add_renamed_flag(tip_n, f"--da{n}", f"--tip-diameter{n}", f"da{n}", type=float)
    g.add_argument("--thinning1", type=float, default=0.0, help="pinion normal tooth thinning for backlash, mm")
    g.add_argument("--thinning2", type=float, default=0.0, help="wheel normal tooth thinning for backlash, mm")
    t = p.add_argument_group("tools")
    add_rack_flag(t, RACK_HELP.replace("generating basic rack", "basic rack of the rack-cut gears"))
    t.add_argument("--cutter-teeth", type=int, help="teeth z0 of the shaper cutter that cuts the ring")
    t.add_argument("--ring-shift", choices=("iso", "cutter"), default="iso",
                   help="how the ring's --x2 is read: 'iso' (ISO 21771, by the tooth thickness; default) or "
                        "'cutter' (the shaper's radial setting)")
    t.add_argument("--cutter-shift", type=float, default=0.0, help="the shaper's own shift x0")
    t.add_argument("--cutter-addendum", type=float, default=1.25, help="the shaper's addendum h_a0* (default 1.25)")
    t.add_argument("--pinion-cutter-teeth", type=int, help="cut the pinion with a shaper of this many teeth")
    if not limits:
        p.set_defaults(min_tip_thickness=None, min_contact_ratio=None, min_tip_clearance=None)
        return
    lim = p.add_argument_group("limits")
    lim.add_argument("--min-tip-thickness", type=float, help="warn below this s_an / m_n (default 0.25)")
    lim.add_argument("--min-contact-ratio", type=float, help="warn below this eps_alpha (default 1.2)")
    lim.add_argument("--min-tip-clearance", type=float, help="warn below this c / m_n (default 0.1)")


def pair_spec_from_args(args):
    """``(PairSpec, CheckLimits)`` from the pair flags, or from a design file whose values the flags typed
    on the command line override (:func:`override_pair_spec`)."""
    if args.design is not None:
        from gearkit.checks import load_design

        spec, limits = load_design(args.design)
        return override_pair_spec(spec, args), _override_limits(limits, args)
    return _spec_from_flags(args)


#: pair flag destination -> the PairSpec field it sets
_PAIR_FIELDS = {"z1": "teeth1", "z2": "teeth2", "module": "module", "x1": "shift1", "x2": "shift2",
                "pressure_angle_deg": "pressure_angle_deg", "helix_angle_deg": "helix_angle_deg",
                "width": "face_width", "addendum": "addendum", "tip_rule": "tip_rule", "da1": "tip_diameter1",
                "da2": "tip_diameter2", "thinning1": "thinning1", "thinning2": "thinning2",
                "ring_shift": "shift_convention"}


def override_pair_spec(spec, args):
    """``spec`` (read from a design file) with every pair or tool flag typed on the command line applied;
    ``--center-distance`` solves the shifts again unless ``--x1``/``--x2`` are typed too."""
    from dataclasses import replace

    from gearkit.cli.design import given
    from gearkit.families.involute import BasicRack, ShaperCutter

    changes = {f: getattr(args, d) for d, f in _PAIR_FIELDS.items() if given(args, d)}
    if given(args, "internal") and args.internal:
        changes["kind"] = "internal"
    if given(args, "rack_pair") and args.rack_pair:
        changes.update(kind="rack", teeth2=None)
    alpha = changes.get("pressure_angle_deg", spec.pressure_angle_deg)
    tools = list(spec.tools)
    for k, tool in enumerate(tools):
        if isinstance(tool, BasicRack) and given(args, "rack"):
            tools[k] = rack_from_args(_namespace_with(args, pressure_angle_deg=alpha))
        elif isinstance(tool, BasicRack) and alpha is not None:
            tools[k] = replace(tool, pressure_angle_deg=alpha)
        elif isinstance(tool, ShaperCutter):
            cutter = {"shift": args.cutter_shift} if given(args, "cutter_shift") else {}
            cutter.update({"addendum": args.cutter_addendum} if given(args, "cutter_addendum") else {})
            tools[k] = replace(tool, **cutter, **({} if alpha is None else {"pressure_angle_deg": alpha}))
    a = 20.0 if alpha is None else alpha
    shaper = (getattr(args, "cutter_shift", 0.0), getattr(args, "cutter_addendum", 1.25))
    if given(args, "pinion_cutter_teeth"):
        tools[0] = shaper_from_args(args.pinion_cutter_teeth, a, *shaper, "--pinion-cutter-teeth")
    if given(args, "cutter_teeth"):
        tools[1] = shaper_from_args(args.cutter_teeth, a, *shaper)
    spec = replace(spec, tool1=tools[0], tool2=None if changes.get("kind") == "rack" else tools[1], **changes)
    if given(args, "center_distance"):
        x1 = args.x1 if given(args, "x1") else None
        x2 = args.x2 if given(args, "x2") else None
        return _apply_center_distance(replace(spec, center_distance=None), args.center_distance, x1, x2,
                                      args.split if given(args, "split") else None)
    if given(args, "split"):
        raise SpecError("--split", "applies only with a centre distance (--center-distance)")
    return spec


def _namespace_with(args, **values):
    """A copy of ``args`` with ``values`` set (the namespace is not changed)."""
    import argparse

    return argparse.Namespace(**{**vars(args), **values})


def _override_limits(limits, args):
    from dataclasses import replace

    from gearkit.cli.design import given

    names = ("min_tip_thickness", "min_contact_ratio", "min_tip_clearance")
    return replace(limits, **{k: getattr(args, k) for k in names if given(args, k) and getattr(args, k) is not None})


def _spec_from_flags(args):
    from gearkit.checks import CheckLimits
    from gearkit.pair import PairSpec

    kind = "internal" if args.internal else "rack" if args.rack_pair else "external"
    for name, flag in (("z1", "--z1"), ("module", "-m/--module")):
        if getattr(args, name) is None:
            raise SpecError(flag, "is required (or give a design file)")
    if kind == "rack":
        if args.z2 is not None:
            raise SpecError("--z2", "a rack pair has no z2")
    elif args.z2 is None:
        raise SpecError("--z2", "is required")
    alpha = args.pressure_angle_deg
    rack = rack_from_args(args)
    tool1 = rack
    if args.pinion_cutter_teeth is not None:
        tool1 = shaper_from_args(args.pinion_cutter_teeth, rack.pressure_angle_deg, args.cutter_shift,
                                 args.cutter_addendum, "--pinion-cutter-teeth")
    tool2 = rack
    if kind == "internal":
        if args.cutter_teeth is None:
            raise SpecError("--cutter-teeth", "an internal gear is cut by a shaper: give its tooth number z0")
        tool2 = shaper_from_args(args.cutter_teeth, rack.pressure_angle_deg, args.cutter_shift, args.cutter_addendum)
    elif args.cutter_teeth is not None:
        raise SpecError("--cutter-teeth", "applies to internal pairs (use --pinion-cutter-teeth, or a design file)")
    if tool1 is rack and tool2 is rack:
        refuse_unused_cutter_flags(args)
    spec = PairSpec(args.z1, args.z2, args.module, args.x1 or 0.0, args.x2 or 0.0, kind, alpha,
                    args.helix_angle_deg, args.width, tool1, tool2, args.addendum, args.tip_rule, args.da1, args.da2,
                    None, args.thinning1, args.thinning2, args.ring_shift)
    spec = _apply_center_distance(spec, args.center_distance, args.x1, args.x2, args.split)
    limits = CheckLimits(**{k: getattr(args, k) for k in ("min_tip_thickness", "min_contact_ratio",
                                                           "min_tip_clearance") if getattr(args, k) is not None})
    return spec, limits


def _apply_center_distance(spec, a_w, x1, x2, split):
    """Resolve the shifts/centre-distance combinations (see ``--center-distance``)."""
    from dataclasses import replace

    from gearkit.pair import shifts_for_center_distance

    if a_w is None:
        if split is not None:
            raise SpecError("--split", "applies only with a centre distance (--center-distance)")
        return spec
    if x1 is not None and x2 is not None:
        if split is not None:
            raise SpecError("--split", "both shifts are given: nothing to split")
        return replace(spec, center_distance=a_w)
    if x2 is not None:
        raise SpecError("--x2", "with a centre distance give --x1 (x2 follows), both shifts, or neither")
    if x1 is not None and split not in (None, "x1"):
        raise SpecError("--split", f"--x1 is given, so the split is 'x1', not {split!r}")
    rule = "x1" if x1 is not None else (split or "balanced")
    try:
        return shifts_for_center_distance(spec, a_w, rule)
    except SpecError as exc:  # the API names its argument; the command line names the flag
        flag = {"split": "--split", "center_distance": "--center-distance"}.get(exc.field)
        if flag is None:
            raise
        raise exc.renamed(flag) from None
