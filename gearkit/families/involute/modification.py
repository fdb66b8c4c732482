"""Micro-geometry of an involute flank: profile and lead modifications as normal deviations.

A :class:`Modification` is a value on the gear spec (``GearSpec(..., modification=...)``). Its
amounts are lengths in mm of material removed (positive) along the transverse line of action,
that is normal to the transverse involute, as a gear measuring machine reports them:

* **profile** (over the roll length ``L = sqrt(r^2 - r_b^2)`` of the flank, ``L_low .. L_tip``
  the generated flank's range): tip relief ``C_a`` from its start (a diameter ``d_Ca`` or a
  roll length ``L_Ca`` back from the tip) to the tip, root relief ``C_f`` likewise down to the
  flank's lowest point, each ``linear`` or ``arc`` (a circular arc tangent to the flank at the
  start); profile crowning ``C_alpha`` (parabolic, zero at mid roll, ``C_alpha`` at both ends);
  profile slope ``f_Halpha`` (linear, ``+f/2`` at the tip, ``-f/2`` at the lowest point).
* **lead** (over the face position ``zeta in [0, b]``): lead crowning ``C_beta`` (parabolic, zero
  mid face), end relief ``C_I`` over ``b_I`` from each face (linear), helix slope ``f_Hbeta``
  (linear, ``+f/2`` at ``zeta = b``).

The profile part is applied to the generated tooth (:func:`modify_half`): every point of the flank
turns about the gear centre by ``Delta(L) / r_b``, which moves an involute by exactly ``Delta``
along its normal; the tip arc closes up to the relieved flank and the fillet takes the deviation
of the flank's lowest point down to zero at the root circle, so outlines and meshes keep their
``tol`` contract. The lead part acts across the face width: contact analysis adds it per face
slice (:mod:`gearkit.contact.loaded`).

Examples
--------
>>> m = Modification(tip_relief=0.01, tip_relief_roll=2.0)
>>> float(m.profile_deviation(9.0, 5.0, 10.0)), float(m.profile_deviation(7.0, 5.0, 10.0))
(0.005, 0.0)
>>> float(Modification(lead_crowning=0.01).lead_deviation(0.0, 20.0))
0.01
"""
from __future__ import annotations

import dataclasses
import math

import numpy as np

from gearkit.boundary import CircleArc, Piece
from gearkit.errors import check_fields, is_real, require
from gearkit.values import frozen

__all__ = ["Modification", "modify_half"]

_SHAPES = ("linear", "arc")
_PROFILE = ("tip_relief", "root_relief", "profile_crowning", "profile_slope")
_LEAD = ("lead_crowning", "end_relief", "helix_slope")


@frozen
class Modification:
    """Profile and lead modifications of one gear (mm of material removed, see the module notes).

    Parameters
    ----------
    tip_relief, root_relief : float, mm, in [0, 1]
        ``C_a``, ``C_f`` at the tip / at the flank's lowest point.
    tip_relief_diameter, root_relief_diameter : float or None, mm
        Where the relief starts (``d_Ca``, ``d_Cf``); or give ``*_roll``.
    tip_relief_roll, root_relief_roll : float or None, mm, > 0
        Length of the relief along the roll (``L_Ca``, ``L_Cf``) from the tip / lowest point.
    relief_shape : {"linear", "arc"}
    profile_crowning, profile_slope : float, mm, |.| <= 1
    lead_crowning, end_relief, helix_slope : float, mm, |.| <= 1
    end_relief_length : float, mm, >= 0 (``b_I`` from each face)
    """

    tip_relief: float = 0.0
    tip_relief_diameter: float | None = None
    tip_relief_roll: float | None = None
    root_relief: float = 0.0
    root_relief_diameter: float | None = None
    root_relief_roll: float | None = None
    relief_shape: str = "linear"
    profile_crowning: float = 0.0
    profile_slope: float = 0.0
    lead_crowning: float = 0.0
    end_relief: float = 0.0
    end_relief_length: float = 0.0
    helix_slope: float = 0.0

    def __post_init__(self):
        check_fields(self)
        for name in _PROFILE + _LEAD:
            v = getattr(self, name)
            require(is_real(v) and abs(v) <= 1.0, name, f"{v!r} must be a length in [-1, 1] mm")
        for name in ("tip_relief", "root_relief", "end_relief"):
            require(getattr(self, name) >= 0, name, f"{getattr(self, name)!r} must be >= 0 mm (material removed)")
        require(self.relief_shape in _SHAPES, "relief_shape", f"{self.relief_shape!r} must be one of {_SHAPES}")
        require(is_real(self.end_relief_length) and self.end_relief_length >= 0, "end_relief_length",
                f"{self.end_relief_length!r} must be >= 0 mm")
        require(self.end_relief == 0 or self.end_relief_length > 0, "end_relief_length",
                "must be > 0 mm when end_relief is given")
        for side in ("tip", "root"):
            d, roll = getattr(self, f"{side}_relief_diameter"), getattr(self, f"{side}_relief_roll")
            require(d is None or roll is None, f"{side}_relief_roll",
                    f"give the {side} relief's start as a diameter or a roll length, not both")
            require(d is None or (is_real(d) and d > 0), f"{side}_relief_diameter", f"{d!r} must be > 0 mm")
            require(roll is None or (is_real(roll) and roll > 0), f"{side}_relief_roll", f"{roll!r} must be > 0 mm")
            require(getattr(self, f"{side}_relief") == 0 or d is not None or roll is not None,
                    f"{side}_relief_diameter", f"say where the {side} relief starts (a diameter or a roll length)")

    @property
    def has_profile(self) -> bool:
        """Any profile modification (applied to the generated tooth)."""
        return any(getattr(self, n) != 0 for n in _PROFILE)

    @property
    def has_lead(self) -> bool:
        """Any lead modification (applied across the face width)."""
        return any(getattr(self, n) != 0 for n in _LEAD)

    def _start(self, side, base_radius, l_end):
        d, roll = getattr(self, f"{side}_relief_diameter"), getattr(self, f"{side}_relief_roll")
        if d is not None:
            return math.sqrt(max((d / 2) ** 2 - base_radius ** 2, 0.0))
        return l_end - roll if side == "tip" else l_end + roll

    def _relief(self, amount, s, span):
        """Relief at the fraction ``s`` in [0, 1] of its length ``span`` (mm)."""
        if self.relief_shape == "linear":
            return amount * s
        radius = (span ** 2 + amount ** 2) / (2 * amount)  # the arc tangent at the start through the end
        x = s * span
        return radius - np.sqrt(np.maximum(radius ** 2 - x ** 2, 0.0))

    def profile_deviation(self, roll, l_low: float, l_tip: float, base_radius: float = 0.0):
        """Material removed (mm) at roll lengths ``roll`` (mm) of a flank spanning ``l_low .. l_tip``.

        ``base_radius`` (mm) converts the start diameters to roll lengths.
        """
        roll = np.asarray(roll, dtype=float)
        out = np.zeros(roll.shape)
        span = l_tip - l_low
        mid = 0.5 * (l_tip + l_low)
        if self.tip_relief:
            start = self._start("tip", base_radius, l_tip)
            length = max(l_tip - start, 1e-300)
            out += self._relief(self.tip_relief, np.clip((roll - start) / length, 0.0, 1.0), length)
        if self.root_relief:
            start = self._start("root", base_radius, l_low)
            length = max(start - l_low, 1e-300)
            out += self._relief(self.root_relief, np.clip((start - roll) / length, 0.0, 1.0), length)
        if span > 0:
            out += self.profile_crowning * (2 * (roll - mid) / span) ** 2
            out += self.profile_slope * (roll - mid) / span
        return out

    def lead_deviation(self, zeta, face_width: float):
        """Material removed (mm) at face positions ``zeta`` (mm, ``0 .. face_width``)."""
        zeta = np.asarray(zeta, dtype=float)
        b = float(face_width)
        if b <= 0:
            return np.zeros(zeta.shape)
        c = 2 * (zeta - b / 2) / b
        out = self.lead_crowning * c ** 2 + self.helix_slope * (zeta - b / 2) / b
        if self.end_relief:
            length = self.end_relief_length
            out = out + self.end_relief * np.clip((np.abs(zeta - b / 2) - (b / 2 - length)) / length, 0.0, 1.0)
        return out


class _Turned:
    """A boundary curve whose points turn about the blank centre by ``angle(points, w)`` (rad, towards the
    tooth centre line: material removed from a right half tooth)."""

    def __init__(self, curve, angle):
        self.curve, self.angle = curve, angle
        self.label = getattr(curve, "label", "")

    def __call__(self, w):
        w = np.asarray(w, dtype=float)
        q = self.curve(w)
        a = self.angle(q, w)
        c, s = np.cos(a), np.sin(a)
        return np.stack([c * q[..., 0] - s * q[..., 1], s * q[..., 0] + c * q[..., 1]], -1)


def modify_half(half, mod: Modification, base_radius: float, root_radius: float):
    """The half tooth ``half`` (right half of an external gear) with ``mod``'s profile part applied.

    The flank pieces (label ``flank``) span the roll range; pieces above them on the tip circle close up
    to the relieved flank; pieces below take the lowest flank point's turn, fading to zero at
    ``root_radius``.
    """
    if not mod.has_profile:
        return half
    rb = float(base_radius)
    flank_r = []
    for pc in half.pieces:
        if pc.label == "flank":
            q = pc(np.array([0.0, 1.0]))
            flank_r += list(np.hypot(q[:, 0], q[:, 1]))
    r_low, r_tip = min(flank_r), max(flank_r)

    def roll(r):
        return np.sqrt(np.maximum(r * r - rb * rb, 0.0))

    l_low, l_tip = float(roll(r_low)), float(roll(r_tip))

    def turn_r(r):
        on = mod.profile_deviation(roll(np.clip(r, r_low, r_tip)), l_low, l_tip, rb) / rb
        fade = np.clip((r - root_radius) / max(r_low - root_radius, 1e-300), 0.0, 1.0)
        return np.where(r >= r_low, on, on * fade)

    a_tip = float(turn_r(np.array(r_tip)))
    pieces = []
    for pc in half.pieces:
        if isinstance(pc.curve, CircleArc) and abs(pc.curve.radius - r_tip) <= 1e-9 * r_tip:
            arc = pc.curve
            end = max(abs(arc.psi0), abs(arc.psi1))
            scale = 1.0 - a_tip / end if end > 0 else 1.0
            pieces.append(Piece(pc.label, CircleArc(arc.radius, arc.psi0 * scale, arc.psi1 * scale, arc.label),
                                pc.w0, pc.w1))
        else:
            pieces.append(Piece(pc.label, _Turned(pc.curve, lambda q, w: turn_r(np.hypot(q[..., 0], q[..., 1]))),
                                pc.w0, pc.w1))
    return dataclasses.replace(half, pieces=tuple(pieces))
