"""Parts of a cycloidal drive (and of cycloid and pin gear pairs) as 2D loops.

The drive in its own frame (mm): the pin ring's centre at the origin, the disc's centre at
``e`` along the crank, the disc placed at relative angle 0 (the mesh frame of
:mod:`gearkit.families.cycloidal.mesh` moved to the ring centre). Output mechanism: ``n`` pins
of radius ``r_w`` on the circle ``R_w`` about the ring's axis run in holes of radius
``r_w + e`` on the same circle about the disc's centre (each pin touches its hole). The pin
ring's housing holds the pins from outside (inner radius ``R_Z + r_Z``).

The same parts as solids (the disc with its bore and output holes, pins, housing, output pins) are
:mod:`gearkit.solids.drive`.
"""
from __future__ import annotations

import math

import numpy as np

from gearkit.errors import require
from gearkit.families.cycloidal.disc import disc_profile
from gearkit.families.cycloidal.drive import DriveSpec, frame_phase
from gearkit.values import frozen

__all__ = ["OutputMechanism", "circle", "disc_offset", "drive_loops", "pin_centres", "output_pin_centres"]


def circle(centre, radius: float, tol: float, clockwise: bool = False):
    """Closed polygon of a circle (every chord within ``tol``), ``(n, 2)`` mm, counter-clockwise."""
    n = max(12, int(math.ceil(math.pi / math.acos(max(-1.0, 1.0 - tol / radius)))))
    t = np.linspace(0.0, 2.0 * math.pi, n, endpoint=False)
    if clockwise:
        t = -t
    return np.asarray(centre, dtype=float) + radius * np.stack([np.cos(t), np.sin(t)], -1)


@frozen
class OutputMechanism:
    """Output pins and the disc's bore, mm (None: derived from the disc's root radius r_f).

    Defaults: ``count`` 6, pin circle ``0.6 r_f``, pin radius ``0.08 r_f``, bore ``0.25 r_f``.
    """

    count: int = 6
    pin_circle_radius: float | None = None
    pin_radius: float | None = None
    bore_radius: float | None = None

    def resolve(self, spec: DriveSpec):
        """(count, R_w, r_w, hole radius r_w + e, bore radius), checked to fit inside the disc."""
        require(isinstance(self.count, int) and 0 <= self.count <= 64, "output_pins",
                f"{self.count!r} must be an integer in [0, 64]")
        rf = spec.pin_circle_radius - spec.eccentricity - spec.pin_radius
        rw_c = 0.6 * rf if self.pin_circle_radius is None else float(self.pin_circle_radius)
        rw = 0.08 * rf if self.pin_radius is None else float(self.pin_radius)
        bore = 0.25 * rf if self.bore_radius is None else float(self.bore_radius)
        hole = rw + spec.eccentricity
        for name, v in (("output_pin_circle_radius", rw_c), ("output_pin_radius", rw), ("bore", bore)):
            require(math.isfinite(v) and v > 0, name, f"{v!r} must be a positive length in mm")
        if spec.sign > 0 and self.count:
            wall = 0.02 * rf
            require(rw_c + hole + wall < rf, "output_pin_circle_radius",
                    f"the output holes (radius {hole:.6g} mm on {rw_c:.6g} mm) must stay inside the disc's root "
                    f"circle r_f = {rf:.6g} mm")
            require(rw_c - hole - wall > bore, "bore", f"the bore (radius {bore:.6g} mm) runs into the output holes")
            if self.count > 1:
                require(2.0 * rw_c * math.sin(math.pi / self.count) > 2.0 * hole + wall, "output_pins",
                        f"{self.count} holes of radius {hole:.6g} mm do not fit on the circle {rw_c:.6g} mm")
        return self.count, rw_c, rw, hole, bore


def disc_offset(spec: DriveSpec):
    """The disc centre in the drive frame (ring centre at the origin), mm, ``(2,)``.

    Examples
    --------
    >>> spec = DriveSpec(12, 11, 90.0, 7.0, 4.0)
    >>> bool(np.isclose(np.hypot(*disc_offset(spec)), spec.eccentricity))
    True
    """
    ph = frame_phase(spec)
    return spec.eccentricity * np.array([math.sin(ph), math.cos(ph)])


def pin_centres(spec: DriveSpec):
    """Centres of the ring's pins in the drive frame, ``(pins, 2)`` mm, on the pin circle R_Z.

    Examples
    --------
    >>> spec = DriveSpec(12, 11, 90.0, 7.0, 4.0)
    >>> np.allclose(np.hypot(*pin_centres(spec).T), 90.0)
    True
    """
    beta = frame_phase(spec) - 2.0 * math.pi * np.arange(spec.pins) / spec.pins
    return spec.pin_circle_radius * np.stack([np.sin(beta), np.cos(beta)], -1)


def output_pin_centres(count: int, radius: float):
    """Centres of ``count`` output pins (or holes) on the circle ``radius`` about the origin, pin 0 on +y,
    ``(count, 2)`` mm."""
    a = 2.0 * math.pi * np.arange(count) / max(count, 1)
    return radius * np.stack([np.sin(a), np.cos(a)], -1)


def drive_loops(spec: DriveSpec, tol: float, output: OutputMechanism = OutputMechanism(), placed: bool = False):
    """The disc as closed 2D loops: its outline, then its bore and output holes (disc frame, or the
    drive frame with ``placed``). For a ring (dz < 0): its tooth outline only."""
    disc = disc_profile(spec)
    loops = [disc.outline(tol)]
    if spec.sign > 0:
        count, rw_c, _, hole, bore = output.resolve(spec)
        loops.append(circle((0.0, 0.0), bore, tol, clockwise=True))
        loops += [circle(c, hole, tol, clockwise=True) for c in output_pin_centres(count, rw_c)]
    if placed:
        loops = [lp + disc_offset(spec) for lp in loops]
    return loops
