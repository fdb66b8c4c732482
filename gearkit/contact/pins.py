"""A ring (or wheel) of cylindrical pins as a tooth profile, for meshing pin gearing.

The pins of a cycloid–pin-wheel drive or of lantern gearing are the teeth: pin ``k`` of radius
``r`` centred at radius ``R`` on the tooth centre line. The half tooth is exact: half of the pin
circle, from its point nearest the mate (the tip) round to the point farthest from it, then the
carrier circle (labelled ``root``) to the space centre line. The carrier is by default the circle
through the pins' far points (``R + r`` for a ring, ``R - r`` for a wheel); a deeper one (a lantern's
hub, the mate's tips reaching between the pins) is joined to the pin by a radial stem of no width.

* ``internal=True``: a pin ring around its mate (a cycloid disc inside the pins): the tips are
  the pins' innermost points, at ``R - r``.
* ``internal=False``: a pin wheel inside or beside its mate (lantern gearing, a cycloid ring):
  the tips are the outermost points, at ``R + r``.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from gearkit.boundary import CircleArc, HalfTooth, Piece
from gearkit.profile import ToothProfile
from gearkit.errors import require

__all__ = ["PinArc", "pin_ring"]


@dataclass(frozen=True)
class PinArc:
    """Arc of the pin centred at ``(0, centre)``: ``c + r (sin g, -s cos g)``, ``g`` from ``g0`` to ``g1``
    (``s`` = +1: starts at the innermost point; -1: at the outermost)."""

    centre: float
    radius: float
    g0: float
    g1: float
    side: float
    label: str = "flank"

    def __call__(self, w):
        g = self.g0 + np.asarray(w, dtype=float) * (self.g1 - self.g0)
        return np.stack([self.radius * np.sin(g), self.centre - self.side * self.radius * np.cos(g)], -1)


@dataclass(frozen=True)
class _Stem:
    """The tooth centre line from radius ``r0`` to ``r1``."""

    r0: float
    r1: float

    def __call__(self, w):
        y = self.r0 + np.asarray(w, dtype=float) * (self.r1 - self.r0)
        return np.stack([np.zeros_like(y), y], -1)


def pin_ring(pins: int, pin_circle_radius: float, pin_radius: float, internal: bool = True,
             carrier_radius: float | None = None) -> ToothProfile:
    """Pins as teeth: ``pins`` pins of radius ``pin_radius`` on the circle ``pin_circle_radius`` (mm).

    ``carrier_radius`` (mm) is the root circle between the pins (default: through the pins' far
    points; for a ring at least ``R + r``, for a wheel at most ``R - r``).

    Examples
    --------
    >>> ring = pin_ring(12, 90.0, 7.0)
    >>> round(ring.tip_diameter / 2, 12), round(ring.root_diameter / 2, 12), ring.internal
    (83.0, 97.0, True)
    """
    require(isinstance(pins, (int, np.integer)) and 3 <= pins <= 100000, "pins",
            f"{pins!r} must be an integer in [3, 100000]")
    big_r, r = float(pin_circle_radius), float(pin_radius)
    require(math.isfinite(big_r) and big_r > 0, "pin_circle_radius", f"{big_r!r} must be > 0 mm")
    require(math.isfinite(r) and 0 < r < big_r * math.sin(math.pi / pins), "pin_radius",
            f"{r!r} must be in (0, {big_r * math.sin(math.pi / pins):.6g}) mm (neighbouring pins must not overlap)")
    side = 1.0 if internal else -1.0
    far = big_r + side * r
    rc = far if carrier_radius is None else float(carrier_radius)
    require(math.isfinite(rc) and rc > 0 and side * (rc - far) >= 0, "carrier_radius",
            f"{carrier_radius!r} must be {'>=' if internal else '<='} {far:g} mm (the pins' far side) and > 0")
    pieces = [Piece("flank", PinArc(big_r, r, 0.0, math.pi, side), 0.0, 1.0)]
    joins = []
    if rc != far:  # a radial stem on the tooth centre line down (or up) to the carrier
        pieces.append(Piece("root", _Stem(far, rc), 0.0, 1.0))
        joins.append("corner")
    pieces.append(Piece("root", CircleArc(rc, 0.0, math.pi / pins, "root"), 0.0, 1.0))
    joins.append("corner")
    half = HalfTooth(tuple(pieces), tuple(joins), False, math.pi / pins)
    return ToothProfile(half, pins, internal, 2 * big_r / pins, family="pins",
                        reference_diameter=2 * big_r)
