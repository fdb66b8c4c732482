"""Planetary tooth-number synthesis: ranked sets for a target ratio ``i_1B`` (sun 1 driving, gear 4
fixed, carrier B driven) with K planets.

Schemes (textbook Fig. 3.115; gear 1 the input, 4 fixed, planet gears 2 and 3 on one shaft):

============  ================================  ====================  ======================
scheme        layout                            ``i_1B``              coaxial (zero gears)
============  ================================  ====================  ======================
``simple``    sun 1 - planet 2 - ring 4         ``1 + z4/z1``         ``z1 + 2 z2 = z4``
``compound``  sun 1 - 2 | 3 - ring 4            ``1 + z2 z4/(z1 z3)`` ``z1 + z2 = z4 - z3``
``external``  sun 1 - 2 | 3 - external 4        ``1 - z2 z4/(z1 z3)`` ``z1 + z2 = z3 + z4``
``internal``  ring 1 - 2 | 3 - ring 4           ``1 - z2 z4/(z1 z3)`` ``z1 - z2 = z4 - z3``
============  ================================  ====================  ======================

Every set within the ratio tolerance and the tooth limits is ranked by size (the largest ring's
teeth; ``external``: the outer tip circle in modules), then ratio error. The best are then
built as scenes and kept only if they pass, in order: coaxiality (exact, or through profile
shifts when the tooth sums differ by up to ``max_sum_difference`` teeth: planets unshifted, each
central gear shifted to the larger reference centre distance), assembly (equal spacing, else the
unequal angles nearest to it that assemble), neighbour clearance (real tip circles, a margin in
modules) and gearkit's own pair checks on every mesh (``formula`` fidelity).

Examples
--------
>>> best = synthesize(3.6, 3, 2.0, limits=TEXTBOOK_LIMITS)[0]
>>> best.teeth, best.phasing.kind
((35, 28, 91), 'sequential')
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction

from gearkit.errors import SpecError, check_fields, is_int, is_real, require
from gearkit.progress import Progress

__all__ = ["SCHEMES", "SynthesisLimits", "TEXTBOOK_LIMITS", "PlanetarySet", "synthesize", "candidate_sets",
           "set_ratio", "planetary_scene", "factorised_teeth"]

SCHEMES = ("simple", "compound", "external", "internal")


@dataclass(frozen=True)
class SynthesisLimits:
    """Tooth limits and acceptance rules of :func:`synthesize`.

    ``min_teeth``: external gears; ``min_planet_ring``: planet gears meshing a ring;
    ``min_ring``; ``min_difference``: ring minus its planet gear; ``max_teeth``: every gear;
    ``max_sum_difference``: tooth-sum mismatch profile shift may absorb; ``neighbour_margin``:
    gap between planet tips, module units; ``checks``: run gearkit's pair checks on each mesh;
    ``equal_spacing``: keep only sets whose planets assemble equally spaced.
    """

    min_teeth: int = 17
    min_planet_ring: int = 17
    min_ring: int = 0
    min_difference: int = 0
    max_teeth: int = 200
    max_sum_difference: int = 2
    neighbour_margin: float = 0.5
    checks: bool = True
    equal_spacing: bool = False

    def __post_init__(self):
        check_fields(self)
        for name in ("min_teeth", "min_planet_ring", "min_ring", "min_difference", "max_teeth",
                     "max_sum_difference"):
            v = getattr(self, name)
            require(is_int(v) and 0 <= v <= 100000, name, f"{v!r} must be an integer in [0, 100000]")
        require(self.max_teeth >= max(self.min_teeth, 3), "max_teeth", f"{self.max_teeth} must be >= min_teeth")
        require(is_real(self.neighbour_margin) and self.neighbour_margin >= 0, "neighbour_margin", "must be >= 0")


#: the textbook's limits for zero spur gears (alpha 20 deg, h_a* = 1; digest §5.2): exact coaxiality,
#: equally spaced planets, tips merely clear
TEXTBOOK_LIMITS = SynthesisLimits(17, 20, 85, 8, 200, 0, 0.0, False, True)


def set_ratio(scheme: str, teeth: tuple) -> Fraction:
    """``i_1B`` of a tooth set (exact)."""
    if scheme == "simple":
        z1, _, z4 = teeth
        return 1 + Fraction(z4, z1)
    z1, z2, z3, z4 = teeth
    sign = 1 if scheme == "compound" else -1
    return 1 + sign * Fraction(z2 * z4, z1 * z3)


def factorised_teeth(scheme: str, a: int, b: int, c: int, d: int, gamma) -> tuple:
    """The textbook's factorisation (3.238) for compound planets: with ``bd/ac`` the ratio's factor
    (``|1 - i_1B|``, or ``i_1B - 1`` for ``compound``), teeth proportional to (a, b, c, d) that are
    coaxial by construction, scaled by ``gamma``.

    >>> factorised_teeth("external", 6, 5, 4, 5, 1)
    (54, 45, 44, 55)
    """
    g = Fraction(gamma)
    if scheme == "external":
        t = (a * (c + d), b * (c + d), c * (a + b), d * (a + b))
    elif scheme == "internal":
        t = (a * (d - c), b * (d - c), c * (a - b), d * (a - b))
    elif scheme == "compound":
        t = (a * (d - c), b * (d - c), c * (a + b), d * (a + b))
    else:
        raise SpecError("scheme", f"{scheme!r}: the factorisation is for compound planets (external, internal, "
                        "compound)")
    out = tuple(v * g for v in t)
    require(all(v.denominator == 1 and v > 0 for v in out), "gamma", f"{gamma} does not make every tooth number a "
            f"positive integer ({', '.join(str(v) for v in out)})")
    return tuple(int(v) for v in out)


def _mismatch(scheme: str, t: tuple) -> int:
    if scheme == "simple":
        return t[2] - t[0] - 2 * t[1]
    z1, z2, z3, z4 = t
    return {"compound": z4 - z3 - z1 - z2, "external": z3 + z4 - z1 - z2, "internal": z4 - z3 - z1 + z2}[scheme]


def _envelope(scheme: str, t: tuple) -> int:
    if scheme == "simple":
        return t[2]
    if scheme == "internal":
        return max(t[0], t[3])
    if scheme == "external":
        return max(t[0] + t[1] + max(t[1], t[2]) + 2, t[0] + 2, t[3] + 2)
    return t[3]


def _int_range(lo: float, hi: float, floor: int, ceil: int) -> range:
    a = max(math.ceil(lo - 1e-9), floor)
    b = min(math.floor(hi + 1e-9), ceil)
    return range(a, b + 1)


def _ok_teeth(scheme: str, t: tuple, lim: SynthesisLimits) -> bool:
    if scheme == "simple":
        z1, z2, z4 = t
        return (z1 >= lim.min_teeth and z2 >= max(lim.min_teeth, lim.min_planet_ring) and z4 >= lim.min_ring
                and z4 - z2 >= lim.min_difference and z4 <= lim.max_teeth)
    z1, z2, z3, z4 = t
    if min(t) < 3 or max(t) > lim.max_teeth:
        return False
    if scheme == "compound":
        return (min(z1, z2) >= lim.min_teeth and z3 >= lim.min_planet_ring and z4 >= lim.min_ring
                and z4 - z3 >= lim.min_difference)
    if scheme == "external":
        return min(t) >= lim.min_teeth
    return (min(z2, z3) >= lim.min_planet_ring and min(z1, z4) >= lim.min_ring and z1 - z2 >= lim.min_difference
            and z4 - z3 >= lim.min_difference)


def candidate_sets(scheme: str, ratio: float, tol: float, lim: SynthesisLimits) -> list:
    """Every tooth set of ``scheme`` within ``tol`` (relative) of ``ratio`` and the tooth limits,
    ranked by size, then ratio error, then tooth-sum mismatch (no geometry yet)."""
    require(scheme in SCHEMES, "scheme", f"{scheme!r} is not one of {', '.join(SCHEMES)}")
    lo, hi = sorted((ratio * (1 - tol), ratio * (1 + tol)))
    slack = 1e-12 * max(abs(ratio), 1.0)
    zmax = lim.max_teeth
    found = []
    deltas = range(-lim.max_sum_difference, lim.max_sum_difference + 1)
    outer = range(max(lim.min_teeth, 3), zmax + 1) if scheme == "simple" else range(3, zmax + 1)
    out = []
    with Progress("planetary search", 2 * max(len(outer), 1)) as bar:  # the sets made, then their ratios
        for k, z in enumerate(outer):
            if scheme == "simple":
                for z4 in _int_range((lo - 1) * z, (hi - 1) * z, max(lim.min_ring, z + 2), zmax):
                    for d in deltas:
                        if (z4 - z - d) % 2 == 0 and (z4 - z - d) > 0:
                            found.append((z, (z4 - z - d) // 2, z4))
            else:
                for z3 in range(3, zmax + 1):
                    for d in deltas:
                        found += _compound_z1(scheme, z, z3, d, lo, hi, zmax)
            bar.update(k + 1)
        for k, t in enumerate(found):
            r = set_ratio(scheme, t)
            if lo - slack <= r <= hi + slack and _ok_teeth(scheme, t, lim):
                out.append((_envelope(scheme, t), abs(float(r) - ratio), abs(_mismatch(scheme, t)), t))
            if not k & 0x3FF:
                bar.update(len(outer) + len(outer) * k // len(found))
    out.sort()
    return [(t, set_ratio(scheme, t)) for *_, t in out]


def _compound_z1(scheme, z2, z3, d, lo, hi, zmax) -> list:
    """z1 of compound sets (z1, z2, z3, z4) whose ratio lies in [lo, hi] (z1 is linear in i)."""
    # i_1B = 1 + s z2 z4 / (z1 z3) with z4 = z1 + c: z1 (k z3 - z2) = z2 c, k = s (i - 1)
    c = {"compound": z2 + z3 + d, "external": z2 - z3 + d, "internal": z3 - z2 + d}[scheme]
    s = 1 if scheme == "compound" else -1
    dens = [s * (i - 1) * z3 - z2 for i in (lo, hi)]
    if min(abs(v) for v in dens) < 1e-12 or (dens[0] > 0) != (dens[1] > 0):
        span = range(3, zmax + 1)  # the ratio band crosses the pole: any z1
    else:
        ends = [z2 * c / v for v in dens]
        span = _int_range(min(ends), max(ends), 3, zmax)
    out = []
    for z1 in span:
        z4 = z1 + c
        if 3 <= z4 <= zmax:
            out.append((z1, z2, z3, z4))
    return out


@dataclass(frozen=True)
class PlanetarySet:
    """One accepted tooth set: teeth (scheme order), its ratio, the scene it builds, and how its
    planets sit (``phasing``: angles, mesh phases, class), the assembly positions per turn, the
    textbook assembly number (C, p, carrier turn) or None, and the neighbour clearance (mm)."""

    scheme: str
    teeth: tuple
    planets: int
    ratio: Fraction
    module: float
    shifts: dict
    center_distance: float
    phasing: object
    positions: int
    textbook: tuple | None
    neighbour_clearance: float
    checks: str
    scene: object

    def to_dict(self) -> dict:
        """The JSON object of one ``gearkit planetary --json`` candidate."""
        t = self.teeth
        planet = t[1] if self.scheme == "simple" else [t[1], t[2]]
        ph = self.phasing
        return {
            "scheme": self.scheme, "sun": t[0], "planet": planet, "ring": t[-1], "planets": self.planets,
            "ratio": float(self.ratio), "ratio_exact": f"{self.ratio.numerator}/{self.ratio.denominator}",
            "module": self.module, "shifts": self.shifts, "center_distance": self.center_distance,
            "planet_angles_deg": list(ph.angles_deg), "planet_rotation_deg": list(ph.rotations),
            "sun_phase_deg": [360.0 * g for g in ph.phases[0]], "ring_phase_deg": [360.0 * g for g in ph.phases[-1]],
            "phasing": ph.kind, "cancels": ph.cancels(),
            "assembly": {"positions_per_turn": self.positions, "equal_spacing": self.positions % self.planets == 0,
                         "textbook": None if self.textbook is None else
                         {"C": self.textbook[0], "p": self.textbook[1], "carrier_turn_deg": self.textbook[2]}},
            "neighbour_clearance": self.neighbour_clearance, "checks": self.checks,
        }


def _names(scheme):
    if scheme == "simple":
        return ("sun", "planet", "ring")
    return ("sun", "planet", "planet2", "ring")


def planetary_scene(scheme: str, teeth: tuple, planets: int, module: float, shifts: dict | None = None,
                    angles_deg: tuple | None = None):
    """The :class:`~gearkit.scene.Scene` of a tooth set: gear 1 ``sun`` driven, gear 4 ``ring``
    fixed, the ``carrier`` the output (``internal`` scheme: ``sun`` is a ring too)."""
    from gearkit.scene.model import Gear, Mesh, Motion, Scene

    shifts = shifts or {}
    names = _names(scheme)
    x = {n: shifts.get(n, 0.0) for n in names}
    kw = {"count": planets, "carrier": "carrier", "angles_deg": angles_deg}
    if scheme == "simple":
        gears = (Gear("sun", teeth[0], x["sun"]), Gear("planet", teeth[1], x["planet"], **kw),
                 Gear("ring", teeth[2], x["ring"], internal=True))
        meshes = (Mesh("sun", "planet"), Mesh("planet", "ring"))
    else:
        gears = (Gear("sun", teeth[0], x["sun"], internal=scheme == "internal"),
                 Gear("planet", teeth[1], x["planet"], shaft="planets", **kw),
                 Gear("planet2", teeth[2], x["planet2"], shaft="planets", **kw),
                 Gear("ring", teeth[3], x["ring"], internal=scheme != "external"))
        meshes = (Mesh("sun", "planet"), Mesh("planet2", "ring"))
    return Scene(gears, meshes, module=module, motion=Motion(fixed=("ring",), inputs=(("sun", 1.0),),
                                                             output="carrier"))


def _coaxial_shifts(scheme, teeth, module) -> tuple:
    """Shifts that bring both stages to one centre distance (planets unshifted), and that a_w."""
    from gearkit.pair import PairSpec, shifts_for_center_distance
    from gearkit.families.involute import ShaperCutter
    from gearkit.scene.layout import cutter_teeth
    from gearkit.scene.model import Gear

    names = _names(scheme)
    if scheme == "simple":
        stages = [("sun", teeth[0], teeth[1], False), ("ring", teeth[2], teeth[1], True)]
    else:
        stages = [("sun", teeth[0], teeth[1], scheme == "internal"), ("ring", teeth[3], teeth[2], scheme != "external")]
    refs = [module * (zc - zp if internal else zc + zp) / 2 for _, zc, zp, internal in stages]
    a_w = max(refs)
    shifts = {n: 0.0 for n in names}
    for (name, zc, zp, internal), ref in zip(stages, refs):
        if abs(ref - a_w) < 1e-12 * a_w:
            continue
        tool2 = ShaperCutter(cutter_teeth(Gear("ring", zc, internal=True))) if internal else None
        spec = PairSpec(zp, zc, module, kind="internal" if internal else "external", tool2=tool2)
        shifts[name] = shifts_for_center_distance(spec, a_w, split="x1").shift2
    return shifts, a_w


def synthesize(ratio: float, planets: int, module: float, *, scheme: str = "simple", ratio_tol: float = 0.0,
               limits: SynthesisLimits = SynthesisLimits(), count: int = 10) -> list:
    """Ranked :class:`PlanetarySet` s for ``i_1B = ratio`` with ``planets`` planets (see the notes).

    Parameters
    ----------
    ratio : float
        Target ``i_1B`` (sun speed / carrier speed, gear 4 fixed).
    planets : int, >= 1
    module : float, mm
    scheme : {"simple", "compound", "external", "internal"}
    ratio_tol : float
        Relative tolerance on the ratio (0: exact).
    limits : SynthesisLimits
    count : int
        How many accepted sets to return (best first).
    """
    require(is_real(ratio) and ratio != 0, "ratio", f"{ratio!r} must be a non-zero number")
    require(is_int(planets) and 1 <= planets <= 64, "planets", f"{planets!r} must be an integer in [1, 64]")
    require(is_real(module) and 1e-4 <= module <= 1e4, "module", f"{module!r} must be a length in [0.0001, 10000] mm")
    require(is_real(ratio_tol) and 0 <= ratio_tol < 0.5, "ratio_tol", f"{ratio_tol!r} must be in [0, 0.5)")
    require(is_int(count) and count >= 1, "count", f"{count!r} must be >= 1")
    if scheme == "simple":
        require(ratio * (1 + ratio_tol) > 2, "ratio", f"a simple planetary set gives i_1B > 2 (asked {ratio:g}): "
                "use a compound scheme")
    out = []
    candidates = candidate_sets(scheme, float(ratio), float(ratio_tol), limits)
    with Progress("planetary checks", len(candidates), unit="sets") as bar:
        for k, (teeth, r) in enumerate(candidates):
            bar.update(k)
            if _accepted(out, scheme, teeth, r, planets, module, limits) and len(out) == count:
                break
    return out


def _accepted(out: list, scheme: str, teeth: tuple, r, planets: int, module: float, limits) -> bool:
    """Append the set ``teeth`` (ratio ``r``) to ``out`` if it assembles, is coaxial, clears its
    neighbours and passes the pair checks; True if it did."""
    from gearkit.scene.layout import scene_layout
    from gearkit.scene.phasing import PlanetMesh, assembly_positions, planet_phasing, textbook_assembly

    if scheme == "simple":
        meshes = [PlanetMesh(teeth[0], teeth[1], False), PlanetMesh(teeth[2], teeth[1], True)]
    else:
        meshes = [PlanetMesh(teeth[0], teeth[1], scheme == "internal"),
                  PlanetMesh(teeth[3], teeth[2], scheme != "external")]
    positions = assembly_positions(meshes)
    if not positions or positions < planets or limits.equal_spacing and positions % planets:
        return False
    try:
        phasing = planet_phasing(planets, meshes)
        shifts, a_w = _coaxial_shifts(scheme, teeth, module)
        scene = planetary_scene(scheme, teeth, planets, module, shifts, tuple(phasing.angles_deg))
        layout = scene_layout(scene)
    except SpecError:  # overlapping planets, shifts out of range, a loop that does not close
        return False
    gap = layout.neighbour_clearance["carrier"]
    if gap < limits.neighbour_margin * module:
        return False
    status = "unchecked"
    if limits.checks:
        from gearkit.checks.involute import check_pair

        reports = [check_pair(m.spec, geometry="formula").report for m in layout.meshes]
        if any(not rep.ok for rep in reports):
            return False
        status = "warn" if any(rep.status == "warn" for rep in reports) else "ok"
    a_w = layout.radii["planets" if scheme != "simple" else "planet"]
    out.append(PlanetarySet(scheme, teeth, planets, r, float(module), shifts, a_w, phasing, positions,
                            textbook_assembly(teeth[0], r, planets, max_p=1000), gap, status, scene))
    return True
