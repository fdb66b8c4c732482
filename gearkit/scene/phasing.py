"""Planet assembly and phasing: where identical planets fit, and how their meshes are phased.

A planet (or a compound planet block) at carrier angle ``theta`` meshes central gears ``i``
(``z_ci`` teeth; the planet gear meshing it has ``z_pi``). With the central gears held, the
tooth phases at each mesh must match for some rotation ``phi`` of the planet about its axis::

    (z_ci + s_i z_pi) theta - s_i z_pi phi  =  0   (mod 2 pi),   s_i = +1 external, -1 internal

relative to the first planet. Eliminating ``phi`` between two meshes gives the general
condition: ``theta`` is a multiple of ``2 pi g / N`` with ``N = |a1 b2 - a2 b1|`` (``a = z_c + s z_p``,
``b = s z_p``) and ``g = gcd(z_p1, z_p2)``; for a simple planet this is the familiar
``(z_sun + z_ring) theta / 2 pi`` integer, for compound planets the textbook digest's
``N / (K gcd(z2, z3))`` integer with ``N = z1 z3 -+ z2 z4`` (equal spacing). Further meshes (a
triple planet) keep the angles where every mesh fits. :func:`textbook_assembly` gives the
textbook's own (sufficient) rule for planets inserted in one orientation:
``C = z1 i_1B (1 + K p) / K`` integer.

Mesh phases: planet ``k`` at ``theta_k`` meets central gear ``i`` ``frac(z_ci theta_k / 2 pi)`` of a
mesh cycle after the first planet. The torque ripple of mesh harmonic ``l`` cancels when
``sum_k exp(2 pi i l gamma_k) = 0``; the net (translational) force of harmonic ``l`` cancels when
``sum_k exp(i (2 pi l gamma_k +- theta_k)) = 0``.

Examples
--------
>>> assembly_positions([PlanetMesh(21, 43, False), PlanetMesh(108, 43, True)])
129
>>> p = planet_phasing(3, [PlanetMesh(21, 43, False), PlanetMesh(108, 43, True)])
>>> p.kind, [round(a, 6) for a in p.angles_deg]
('in_phase', [0.0, 120.0, 240.0])
"""
from __future__ import annotations

import cmath
import math
from dataclasses import dataclass
from fractions import Fraction

from gearkit.errors import require

__all__ = ["PlanetMesh", "Phasing", "assembly_positions", "planet_phasing", "planet_rotation", "textbook_assembly",
           "neighbour_ratio"]

_CANCEL_TOL = 1e-9


@dataclass(frozen=True)
class PlanetMesh:
    """A planet gear (``planet_teeth``) meshing a central gear (``central_teeth``); ``internal``: a ring."""

    central_teeth: int
    planet_teeth: int
    internal: bool

    @property
    def a(self) -> int:
        return self.central_teeth + (-self.planet_teeth if self.internal else self.planet_teeth)

    @property
    def b(self) -> int:
        return -self.planet_teeth if self.internal else self.planet_teeth


def planet_rotation(meshes, turns: Fraction) -> Fraction | None:
    """A planet rotation (turns) that fits every mesh at carrier position ``turns``, or None."""
    m0 = meshes[0]
    for k in range(abs(m0.b)):
        f = (m0.a * turns - k) / m0.b
        if all((m.a * turns - m.b * f).denominator == 1 for m in meshes[1:]):
            return f % 1
    return None


def _divisors(n: int) -> list:
    small = [d for d in range(1, math.isqrt(n) + 1) if n % d == 0]
    return sorted(set(small + [n // d for d in small]))


def assembly_positions(meshes) -> int | None:
    """How many carrier positions per turn an identical planet fits in (its angles are the
    multiples of 360 deg / that number); None when one mesh leaves the angle free, 0 when the
    meshes never fit together (a degenerate block)."""
    meshes = list(meshes)
    if len(meshes) < 2:
        return None
    m1, m2 = meshes[0], meshes[1]
    d = abs(m1.a * m2.b - m2.a * m1.b)
    if d == 0:
        return 0
    g = math.gcd(m1.b, m2.b)
    base = d // g if d % g == 0 else d
    if len(meshes) == 2:
        return base
    for step in _divisors(base):  # the fitting positions are a subgroup: find its generator
        if planet_rotation(meshes, Fraction(step, base)) is not None:
            return base // step
    return 1


def textbook_assembly(sun_teeth: int, ratio, planets: int, max_p: int = 10000):
    """The textbook condition ``C = z1 i_1B (1 + K p)/K`` integer: (C, p, carrier turn in degrees)
    for the smallest ``p >= 0``, or None when no ``p <= max_p`` works.

    >>> textbook_assembly(35, Fraction(18, 5), 3)
    (42, 0, 120.0)
    >>> textbook_assembly(54, Fraction(-1, 24), 3)
    (-3, 1, 480.0)
    """
    c0 = Fraction(sun_teeth) * Fraction(ratio) / planets
    q = c0.denominator  # C is an integer iff q divides 1 + K p
    if math.gcd(planets, q) != 1:
        return None if q > 1 else (int(c0), 0, 360.0 / planets)
    p = (-pow(planets, -1, q)) % q if q > 1 else 0
    if p > max_p:
        return None
    return int(c0 * (1 + planets * p)), p, 360.0 * (1 + planets * p) / planets


def neighbour_ratio(largest_planet: int, central: int, planet: int, internal: bool = False) -> float:
    """The textbook neighbour number ``(z_c + 2)/(z1 +- z2)`` (zero gears, h_a* = 1): planets clear
    when it is below ``sin(180 deg / K)``.

    >>> round(neighbour_ratio(28, 35, 28), 4), round(neighbour_ratio(28, 90, 27, internal=True), 4)
    (0.4762, 0.4762)
    """
    return (largest_planet + 2) / (central - planet if internal else central + planet)


@dataclass(frozen=True)
class Phasing:
    """Planet angles and mesh phases of a planet set, and what the phasing cancels.

    ``angles_deg``: planet positions; ``phases``: {central teeth index: per-planet phase in mesh
    cycles}; ``kind``: ``in_phase`` | ``sequential`` | ``counter_phase`` | ``unequal``;
    ``torque_ripple`` and ``net_force``: per mesh harmonic 1..K, the residual amplitude as a
    fraction of one planet's (0: cancelled); ``steady_net_force``: residual of the steady mesh
    forces (0 for balanced spacing).
    """

    angles_deg: tuple
    rotations: tuple
    phases: tuple
    kind: str
    torque_ripple: tuple
    net_force: tuple
    steady_net_force: float

    def cancels(self) -> dict:
        """The harmonics whose torque ripple / net force cancel (1-based), and the steady force."""
        return {"torque_ripple": [l + 1 for l, v in enumerate(self.torque_ripple) if v < _CANCEL_TOL],
                "net_force": [l + 1 for l, v in enumerate(self.net_force) if v < _CANCEL_TOL],
                "steady_net_force": self.steady_net_force < _CANCEL_TOL}


def _fit_angles(positions: int | None, planets: int) -> list:
    """Planet positions (turns, exact) nearest to equal spacing on the ``positions`` grid."""
    if positions is None:
        return [Fraction(k, planets) for k in range(planets)]
    steps = sorted({round(Fraction(k * positions, planets)) % positions for k in range(planets)})
    require(len(steps) == planets, "planets",
            f"only {positions} assembly position(s) per turn: {planets} planets do not fit")
    return [Fraction(s, positions) for s in steps]


def planet_phasing(planets: int, meshes, reference: int = 0, turns=None) -> Phasing:
    """Angles, planet rotations, mesh phases and phasing class of ``planets`` identical planets.

    Parameters
    ----------
    planets : int
    meshes : sequence of PlanetMesh
        The planet block's meshes with the central gears.
    reference : int
        The mesh whose phases classify the set (0: the first, usually the sun).
    turns : sequence of Fraction or None
        Planet positions in turns; None places them on the assembly grid nearest to equal spacing.
    """
    meshes = list(meshes)
    require(planets >= 1, "planets", f"{planets!r} must be >= 1")
    if turns is None:
        positions = assembly_positions(meshes)
        require(positions != 0, "planets", "the planet block's meshes never fit together")
        turns = _fit_angles(positions, planets)
    turns = [Fraction(t) for t in turns]
    rotations = []
    for t in turns:
        f = planet_rotation(meshes, t - turns[0]) if len(meshes) > 1 else Fraction(0)
        require(f is not None, "planets", f"no planet fits at {float(t) * 360:.6g} deg")
        rotations.append(float(f) * 360.0)
    phases = tuple(tuple(float((m.central_teeth * (t - turns[0])) % 1) for t in turns) for m in meshes)
    gam = phases[reference]
    theta = [2 * math.pi * float(t) for t in turns]
    torque, force = [], []
    for harmonic in range(1, planets + 1):
        terms = [cmath.exp(2j * math.pi * harmonic * g) for g in gam]
        torque.append(abs(sum(terms)) / planets)
        force.append(max(abs(sum(e * cmath.exp(s * 1j * th) for e, th in zip(terms, theta))) / planets
                         for s in (1, -1)))
    steady = abs(sum(cmath.exp(1j * th) for th in theta)) / planets
    return Phasing(tuple(float(t) * 360.0 for t in turns), tuple(rotations), phases, _kind(gam, turns, planets),
                   tuple(torque), tuple(force), steady)


def _kind(gam, turns, planets) -> str:
    if all(abs(g) < _CANCEL_TOL or abs(g - 1) < _CANCEL_TOL for g in gam):
        return "in_phase"
    equal = all(t == Fraction(k, planets) for k, t in enumerate(turns))
    if not equal:
        return "unequal"
    if planets % 2 == 0 and all(abs(g - (k % 2) / 2) < _CANCEL_TOL for k, g in enumerate(gam)):
        return "counter_phase"
    return "sequential"
