"""Novikov pairs: the pair spec and its geometry (contact zones, helices, overlap).

Pair geometry (no profile shift, as in Novikov practice; normal module m_n):
``a = m_n (z1 + z2) / (2 cos beta)``, transverse contact angle ``tan a_t = tan a_k / cos beta``,
contact point at ``h_k m_n`` from the pitch line and ``X = h_k m_n cot(a_k) cos(beta)`` from the pole,
contact-helix radius ``R_K = sqrt((r +- h_k m_n)^2 + X^2)``, lead ``pi m_n z / sin(beta)``; the two
contacts of a double-arc flank ``((x_Kf - x_Ka) + 2 h_k cot(a_k) cos^2(beta)) m_n / sin(beta)`` apart along
the axis (their normals cross the axis ``Delta m_n / sin(beta)`` apart, Delta the pierce-point distance); axial
overlap ``eps_beta = b sin(beta) / (pi m_n)`` (the transverse ratio is zero by design),
centre-distance sensitivity ``sin a_k' = sin a_k - da / (rho_f - rho_a)`` (rack approximation).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import lru_cache

from gearkit.errors import check_fields, is_int, is_real, require
from gearkit.export import json_number
from gearkit.families.novikov.gear import NovikovGearSpec
from gearkit.families.novikov.presets import RackSystem, rack_system

__all__ = ["NovikovPairSpec", "NovikovPairGeometry", "ContactGeometry", "novikov_pair_geometry", "gear_specs"]


@dataclass(frozen=True)
class NovikovPairSpec:
    """A Novikov pair, inputs only.

    Parameters
    ----------
    teeth1, teeth2 : int
        Pinion (gear 1) and wheel (gear 2) tooth numbers.
    module : float, mm (normal module m_n)
    helix_angle_deg : float, degrees, in (-60, 60): beta, its sign the pinion's hand (positive right, negative
        left; the wheel has the other hand). A left-hand pair is the mirror image of the right-hand one: its
        geometry, checks and contact are those of ``|beta|``. 0 is allowed, and fails the overlap check.
    face_width : float, mm, > 0
    racks : RackSystem or str
        A preset name (``"dca24"``, ``"single-arc"``), a ``.toml`` rack file, or a RackSystem.
    center_distance : float or None, mm
        Operating centre distance a_w (None: the reference a); within 0.5 m_n of a.
    """

    teeth1: int
    teeth2: int
    module: float
    helix_angle_deg: float
    face_width: float
    racks: RackSystem | str = "dca24"
    center_distance: float | None = None
    tip_diameter1: float | None = field(default=None)
    tip_diameter2: float | None = field(default=None)

    def __post_init__(self):
        check_fields(self)
        for k in (1, 2):
            z = getattr(self, f"teeth{k}")
            require(is_int(z) and 3 <= z <= 100000, f"teeth{k}", f"{z!r} must be an integer in [3, 100000]")
        require(is_real(self.module) and 1e-4 <= self.module <= 1e4, "module",
                f"{self.module!r} must be a length in [0.0001, 10000] mm")
        b = self.helix_angle_deg
        require(is_real(b) and -60.0 < b < 60.0, "helix_angle_deg", f"{b!r} must be in (-60, 60) degrees (the sign is "
                "the pinion's hand: positive right, negative left)")
        require(is_real(self.face_width) and 0 < self.face_width <= 1e5, "face_width",
                f"{self.face_width!r} must be a length in (0, 100000] mm")
        object.__setattr__(self, "racks", rack_system(self.racks))
        if self.center_distance is not None:
            a, m = self.reference_center_distance, self.module
            require(is_real(self.center_distance) and abs(self.center_distance - a) <= 0.5 * m, "center_distance",
                    f"{self.center_distance!r} mm must be within 0.5 m_n of the reference a = {a:.6g} mm "
                    "(Novikov pairs run at their reference centre distance)")
        self.gear(1), self.gear(2)  # validates the tip diameters

    @property
    def beta(self) -> float:
        """|beta|, rad: the pair's geometry is that of its right-hand twin (the mirror image)."""
        return math.radians(abs(self.helix_angle_deg))

    @property
    def hand(self) -> str:
        """The pinion's hand: ``"right"``, ``"left"`` or ``"none"`` (spur); the wheel's is the other."""
        b = self.helix_angle_deg
        return "right" if b > 0 else "left" if b < 0 else "none"

    @property
    def reference_center_distance(self) -> float:
        """a = m_n (z1 + z2) / (2 cos beta), mm."""
        return self.module * (self.teeth1 + self.teeth2) / (2.0 * math.cos(self.beta))

    def gear(self, k: int) -> NovikovGearSpec:
        """The spec of gear ``k`` (1 or 2)."""
        return NovikovGearSpec(getattr(self, f"teeth{k}"), self.module, self.racks.racks[k - 1],
                               self.helix_angle_deg if k == 1 else -self.helix_angle_deg,
                               getattr(self, f"tip_diameter{k}"))


def gear_specs(spec: NovikovPairSpec) -> tuple:
    return spec.gear(1), spec.gear(2)


@dataclass(frozen=True)
class ContactGeometry:
    """One contact zone of a Novikov pair (lengths mm, angles rad).

    ``convex_gear`` is the gear whose convex (addendum) arc works in this zone; ``radii`` and
    ``leads`` are the contact-helix radius and lead on gear 1 and gear 2; ``helix_angles`` the
    helix angle of each contact helix (tan beta_K = tan beta R_K / r).
    """

    zone: int
    convex_gear: int
    height: float
    pole_offset: float
    distance: float
    radii: tuple
    leads: tuple
    helix_angles: tuple


@dataclass(frozen=True)
class NovikovPairGeometry:
    """Derived geometry of a :class:`NovikovPairSpec` (lengths mm, angles rad).

    ``operating_contact_angle`` is the normal contact angle at the operating centre distance (rack
    formula), None when the contact has run off the working arcs; ``center_distance_window`` the
    range of a_w - a (mm) that keeps every contact on the racks' working arcs; ``contact_axial_distance``
    the axial distance between the convex and the concave contact point of one flank (double-arc
    only), ``pole_axial_distance`` the axial distance between the points where those two contacts'
    normals cross the instantaneous axis (Delta m_n / sin(beta), Delta the distance of the arcs'
    pierce points on the pitch line; the two differ by 2 h_k m_n cot(a_k) sin(beta)).
    """

    spec: NovikovPairSpec
    kind: str
    module: float
    transverse_module: float
    helix_angle: float
    reference_center_distance: float
    center_distance: float
    pitch_radii: tuple
    tip_diameters: tuple
    root_diameters: tuple
    axial_pitch: float
    overlap_ratio: float
    transverse_contact_ratio: float
    contact_angle: float
    contact_angle_transverse: float
    operating_contact_angle: float | None
    contacts: tuple
    contact_axial_distance: float | None
    pole_axial_distance: float | None
    sensitivity: float
    center_distance_window: tuple
    tip_clearances: tuple
    backlash: float

    @property
    def center_distance_error(self) -> float:
        """a_w - a, mm."""
        return self.center_distance - self.reference_center_distance

    @property
    def mean_contacts(self) -> float:
        """Mean number of simultaneous contact points: eps_beta per contact zone."""
        return self.overlap_ratio * len(self.contacts)

    def to_dict(self) -> dict:
        """JSON-ready values (lengths mm, angles degrees)."""
        deg = math.degrees
        return {
            "kind": self.kind, "racks": self.spec.racks.name, "verified_racks": self.spec.racks.verified,
            "teeth": [self.spec.teeth1, self.spec.teeth2], "module": self.module,
            "transverse_module": self.transverse_module, "helix_angle_deg": float(self.spec.helix_angle_deg),
            "hand": self.spec.hand,
            "face_width": self.spec.face_width, "reference_center_distance": self.reference_center_distance,
            "center_distance": self.center_distance, "pitch_diameters": [2 * r for r in self.pitch_radii],
            "tip_diameters": list(self.tip_diameters), "root_diameters": list(self.root_diameters),
            "axial_pitch": json_number(self.axial_pitch), "overlap_ratio": self.overlap_ratio,
            "transverse_contact_ratio": self.transverse_contact_ratio, "contact_angle_deg": deg(self.contact_angle),
            "contact_angle_transverse_deg": deg(self.contact_angle_transverse),
            "operating_contact_angle_deg": None if self.operating_contact_angle is None
            else deg(self.operating_contact_angle),
            "contact_radii": [list(c.radii) for c in self.contacts],
            "contacts": [{"zone": c.zone, "convex_gear": c.convex_gear, "height": c.height,
                          "pole_offset": c.pole_offset, "distance": c.distance, "radii": list(c.radii),
                          "leads": [json_number(v) for v in c.leads],
                          "helix_angles_deg": [deg(v) for v in c.helix_angles]} for c in self.contacts],
            "contact_axial_distance": json_number(self.contact_axial_distance),
            "pole_axial_distance": json_number(self.pole_axial_distance),
            "sensitivity_deg_per_0.01m": deg(self.sensitivity),
            "center_distance_window": list(self.center_distance_window),
            "tip_clearances": list(self.tip_clearances), "backlash": self.backlash,
            "mean_contacts": self.mean_contacts,
        }


def _window(spec: NovikovPairSpec) -> tuple:
    """a_w - a range (module units) keeping the contact angle inside every zone's working arcs."""
    lo, hi = -math.inf, math.inf
    a = spec.racks.rack1.alpha
    for zone in spec.racks.zones:
        cvx = spec.racks.racks[zone.convex_gear - 1]
        ccv = spec.racks.racks[2 - zone.convex_gear]
        c_lo, c_hi = cvx.geometry.convex_window
        f_lo, f_hi = ccv.geometry.concave_window
        a_lo, a_hi = max(c_lo, f_lo), min(c_hi, f_hi)
        lo = max(lo, (math.sin(a) - math.sin(a_hi)) * zone.rho_diff)
        hi = min(hi, (math.sin(a) - math.sin(a_lo)) * zone.rho_diff)
    return lo, hi


@lru_cache(maxsize=128)
def novikov_pair_geometry(spec: NovikovPairSpec) -> NovikovPairGeometry:
    """Pair geometry of a Novikov pair from closed forms (see the module docstring).

    Examples
    --------
    >>> g = novikov_pair_geometry(NovikovPairSpec(20, 60, 4.0, 15.0, 60.0, "dca24"))
    >>> round(g.center_distance, 4), round(g.overlap_ratio, 5)
    (165.6442, 1.23577)
    """
    m, beta = spec.module, spec.beta
    z = (spec.teeth1, spec.teeth2)
    a = spec.reference_center_distance
    a_w = a if spec.center_distance is None else spec.center_distance
    r = tuple(m * zi / (2 * math.cos(beta)) for zi in z)
    racks = spec.racks
    alpha = racks.rack1.alpha
    alpha_t = math.atan(math.tan(alpha) / math.cos(beta))
    sin_b = math.sin(beta)
    contacts = []
    for zone in racks.zones:
        h = zone.height * m
        x = h * math.cos(beta) / math.tan(alpha)
        sign = (1, -1) if zone.convex_gear == 1 else (-1, 1)
        radii = tuple(math.hypot(r[k] + sign[k] * h, x) for k in (0, 1))
        leads = tuple(math.pi * m * z[k] / sin_b if sin_b else math.inf for k in (0, 1))
        helix = tuple(math.atan(math.tan(beta) * radii[k] / r[k]) for k in (0, 1))
        contacts.append(ContactGeometry(zone.index, zone.convex_gear, h, x, h / math.sin(alpha_t), radii, leads,
                                        helix))
    q_k = q_p = None
    if racks.kind == "double-arc":
        # contact at the phase where the transverse normal meets the pole: a rack point at normal-section
        # x and height y touches in the section z = (x_P cos(b) + y cot(a_k) cos^2(b) - x) / sin(b) (x_P the
        # pole's transverse position), so the two contacts of one flank lie
        # ((x_Kf - x_Ka) + 2 h_k cot(a_k) cos^2(b)) / sin(b) apart; their normals cross the axis
        # h_k cot(a_k) sin(b) further out on each side
        rk = racks.rack1
        h = racks.zones[0].height
        d_x = float(rk.contact_point("concave")[0] - rk.contact_point("convex")[0])
        cot = 1.0 / math.tan(alpha)
        q_k = m * (d_x + 2 * h * cot * math.cos(beta) ** 2) / sin_b if sin_b else math.inf
        q_p = m * (d_x + 2 * h * cot) / sin_b if sin_b else math.inf
    lo, hi = _window(spec)
    d_rho = min(zn.rho_diff for zn in racks.zones)
    s = math.sin(alpha) - (a_w - a) / m / d_rho
    op = math.asin(s) if lo - 1e-12 <= (a_w - a) / m <= hi + 1e-12 else None
    tips = tuple(spec.gear(k).blank_tip_diameter for k in (1, 2))
    roots = tuple(2 * r[k] - 2 * racks.racks[k].dedendum * m for k in (0, 1))
    clear = (a_w - tips[0] / 2 - roots[1] / 2, a_w - tips[1] / 2 - roots[0] / 2)
    return NovikovPairGeometry(
        spec=spec, kind=racks.kind, module=m, transverse_module=m / math.cos(beta), helix_angle=beta,
        reference_center_distance=a, center_distance=a_w, pitch_radii=r, tip_diameters=tips, root_diameters=roots,
        axial_pitch=math.pi * m / sin_b if sin_b else math.inf,
        overlap_ratio=spec.face_width * sin_b / (math.pi * m), transverse_contact_ratio=0.0,
        contact_angle=alpha, contact_angle_transverse=alpha_t, operating_contact_angle=op,
        contacts=tuple(contacts), contact_axial_distance=q_k, pole_axial_distance=q_p,
        sensitivity=-0.01 / (d_rho * math.cos(alpha)), center_distance_window=(lo * m, hi * m),
        tip_clearances=clear, backlash=min(zn.backlash for zn in racks.zones) * m)
