"""The rack itself (z = infinity): a straight row of teeth.

A rack cut by a shaper cutter is generated like any other gear: the cutter's pitch circle
rolls on the rack's straight pitch line (:class:`~gearkit.motion.RollingMotion` with a
straight blank centrode) and the tooth is the cutter's envelope, trimmed in the strip
``0 <= x <= p/2`` below the tip line. A rack defined by a basic rack (``BasicRack``) *is*
that profile: straight flanks at alpha, addendum h_aP*, dedendum h_fP*, root fillet rho_fP*;
its pieces are built exactly from those lines and arcs.

Frame: the rack's datum (reference) line is y = 0, teeth point to +y, tooth 0 centred on x = 0.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from gearkit.boundary import HalfTooth, Piece, linear_coords, trim_half_tooth
from gearkit.pieces import crossings
from gearkit.profile import HalfToothProfile
from gearkit.envelope import chain_branches
from gearkit.errors import GeometryError, SpecError, check_count, check_fields, require, require_cut_inputs
from gearkit.motion import RollingMotion
from gearkit.families.involute.tools import BasicRack, ShaperCutter
from gearkit.segments import arc, line, rotation_matrix, transform_chain


@dataclass(frozen=True)
class RackSpec:
    """A rack, inputs only.

    Parameters
    ----------
    module : float, mm (normal module)
    tool : BasicRack or ShaperCutter or None
        BasicRack: the rack's own profile. ShaperCutter: the cutter that generates it.
        None: the standard basic rack.
    helix_angle_deg : float, degrees in (-60, 60): teeth inclined to the rack's axis
    thinning : float, mm: tooth thinning for backlash (normal section, on the datum line)
    """

    module: float
    tool: BasicRack | ShaperCutter | None = None
    helix_angle_deg: float = 0.0
    thinning: float = 0.0

    def __post_init__(self):
        check_fields(self)
        require_cut_inputs(self.module, self.helix_angle_deg, self.thinning)
        if self.tool is None:
            object.__setattr__(self, "tool", BasicRack())
        require(isinstance(self.tool, (BasicRack, ShaperCutter)), "tool", "must be a BasicRack or a ShaperCutter")

    @property
    def beta(self) -> float:
        return abs(math.radians(self.helix_angle_deg))

    @property
    def transverse_pitch(self) -> float:
        return math.pi * self.module / math.cos(self.beta)


class RackProfile(HalfToothProfile):
    """A generated rack tooth; ``outline(tol, teeth)`` lays ``teeth`` of them along x."""

    def __init__(self, half: HalfTooth, spec: RackSpec):
        self.half = half
        self.spec = spec
        self.pitch = spec.transverse_pitch
        self.module = spec.module
        self._cache = {}

    @property
    def tip_height(self) -> float:
        return float(self._end("tip")[1])

    @property
    def root_height(self) -> float:
        return float(self._end("root")[1])

    def thickness_at(self, height: float) -> float:
        """Tooth thickness (mm, transverse) at ``height`` above the datum line."""
        hits = crossings(self.half.pieces, lambda p: linear_coords(p)[0], float(height))
        if not hits:
            raise ValueError(f"height {height} misses the tooth flank")
        k, w = hits[0]
        return 2.0 * float(self.half.pieces[k].curve(np.array([w]))[0, 0])

    @property
    def tooth_thickness(self) -> float:
        """Thickness on the datum line (transverse), mm."""
        return self.thickness_at(0.0)

    @property
    def tip_thickness(self) -> float:
        return 0.0 if self.pointed else 2.0 * float(self.half.pieces[0](np.array([1.0]))[0, 0])

    def tooth_points(self, tol: float):
        """One tooth from the left space centre (x = -p/2) to the right one (x = +p/2)."""
        half, _ = self.half_points(tol)
        return np.concatenate([half[::-1] * np.array([-1.0, 1.0]), half[1:]])

    def outline(self, tol: float | None = None, teeth: int = 1):
        """Open polyline of ``teeth`` teeth, left to right, starting at x = -p/2 (mm)."""
        teeth = check_count(teeth, "teeth", 1, 100000)
        tol = 1e-3 * self.module if tol is None else tol
        tooth = self.tooth_points(tol)
        body = tooth[:-1]
        reps = [body + np.array([k * self.pitch, 0.0]) for k in range(teeth)]
        last = tooth[-1:] + np.array([(teeth - 1) * self.pitch, 0.0])
        return np.concatenate(reps + [last])



def _segment_piece(seg, label):
    return Piece(label, seg, 0.0, 1.0)


def _basic_rack_half(spec: RackSpec) -> HalfTooth:
    """The basic rack's right half tooth, exact: tip line, flank, root fillet, root line."""
    rack, m = spec.tool, spec.module
    stretch = np.diag([1.0 / math.cos(spec.beta), 1.0])
    a = rack.alpha
    p = math.pi * m
    ha, hf, rho = rack.addendum * m, rack.dedendum * m, rack.fillet * m

    def x_flank(y):  # right flank, normal section
        return p / 4 - spec.thinning / 2 - y * math.tan(a)

    x_tip = x_flank(ha)
    require(x_tip > 0, "tool", "the rack tooth is pointed below its tip line")
    side_angle, side_x, flank_end = a, x_flank, []
    if rack.protuberance > 0:  # the space bottom is the cutter's tip: widened by the protuberance
        ap, pr = rack.alpha_protuberance, rack.protuberance * m
        y_x = -hf + rack.protuberance_top * m  # where the protuberance flank meets the main flank

        def side_x(y):
            return x_flank(-hf) - pr / math.cos(a) - (y + hf) * math.tan(ap)
        side_angle, flank_end = ap, [(x_flank(y_x), y_x)]
    yc = -hf + rho
    xc = side_x(yc) + rho / math.cos(side_angle)  # fillet centre, in the space
    touch = (xc - rho * math.cos(side_angle), yc - rho * math.sin(side_angle))
    ends = [(x_tip, ha)] + flank_end + [touch]
    chain = [line((0.0, ha), (x_tip, ha), "tip")]
    chain += [line(ends[k], ends[k + 1], "flank" if k == 0 else "fillet") for k in range(len(ends) - 1)]
    chain.append(arc((xc, yc), rho, math.pi + side_angle, 1.5 * math.pi, "fillet"))
    if p / 2 - xc > 1e-12 * p:  # the largest fillet meets its mirror at the space centre: no root line
        chain.append(line((xc, -hf), (p / 2, -hf), "root"))
    chain = transform_chain(chain, stretch)
    pieces = tuple(_segment_piece(s, s.label) for s in chain)
    joins = ("corner",) * len(ends) + ("smooth",) * (len(pieces) - 1 - len(ends))
    return HalfTooth(pieces, joins, False, spec.transverse_pitch / 2)


def _shaper_rack_half(spec: RackSpec) -> HalfTooth:
    cutter = spec.tool
    m_n = spec.module
    m_t = m_n / math.cos(spec.beta)
    alpha_t = math.atan(math.tan(math.radians(cutter.pressure_angle_deg)) / math.cos(spec.beta))
    r_w0 = m_t * cutter.teeth / 2
    chain = cutter.half_tooth(m_t, alpha_t, module_radial=m_n)
    chain = transform_chain(chain, rotation_matrix(-math.pi + math.pi / cutter.teeth), (0.0, r_w0))
    branches = chain_branches(chain, RollingMotion(blank_centre=None, tool_centre=r_w0))
    if spec.thinning:
        raise SpecError("thinning", "is supported for racks defined by a basic rack")
    return trim_half_tooth(branches, 0, 1.0 * m_n, False, 2e-4 * m_n, pitch=spec.transverse_pitch)


@lru_cache(maxsize=64)
def rack_profile(spec: RackSpec) -> RackProfile:
    """The rack's tooth: the basic rack's own profile, or generated by a shaper cutter.

    Examples
    --------
    >>> r = rack_profile(RackSpec(2.0))
    >>> round(r.tooth_thickness, 9), r.tip_height, r.root_height
    (3.141592654, 2.0, -2.5)
    """
    try:
        half = _basic_rack_half(spec) if isinstance(spec.tool, BasicRack) else _shaper_rack_half(spec)
    except GeometryError as exc:
        raise SpecError("tool", f"this cutter leaves no rack tooth ({exc})") from None
    return RackProfile(half, spec)
