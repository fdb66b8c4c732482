"""Mesh stiffness: the ISO 6336-1 values and a compliance model of each tooth along its flank.

**ISO 6336-1 (method B)** — :func:`iso_mesh_stiffness`: the theoretical single stiffness
``c'_th = 1 / q'`` from the published polynomial in the virtual tooth numbers ``z_n`` and the
shifts, times the correction ``C_M`` (0.8), the gear blank factor ``C_R`` (1 for solid gears), the
basic rack factor ``C_B`` and ``cos beta``, gives the single stiffness ``c'``; the mesh stiffness
is ``c_gamma_alpha = c' (0.75 eps_alpha + 0.25)``, ``c_gamma_beta = 0.85 c_gamma_alpha``. Below a
line load of 100 N/mm, ``c'`` scales with the line load over 100 N/mm. Units N/(mm um).

**Compliance model** — :class:`ToothCompliance`: each generated tooth is a cantilever of its own
varying thickness (read off the generated outline) clamped at the root circle, loaded along the
flank normal at the contact point; per unit face width (plane strain, ``E' = E / (1 - nu^2)``):

* bending ``int (cos a_F (y_P - y) - sin a_F x_P)^2 / (E' I(y)) dy`` with ``I = (2 x)^3 / 12``,
* shear ``int 1.2 cos^2 a_F / (G 2 x) dy``, compression ``int sin^2 a_F / (E' 2 x) dy``,
* foundation: the root section (width ``S_f``) as a rigid strip on an elastic half-plane, turned
  by the root moment (``16 M / (pi E' S_f^2)``), which moves the load point by
  ``16 (M/F)^2 / (pi E' S_f^2)`` per unit load, and shifted by the section's forces by the
  half-plane's logarithmic law taken to the gear centre, ``2 ln(2 r_f / S_f) / (pi E')`` per unit
  load (``r_f`` the root radius),

``a_F`` the angle between the load and the tooth's cross-section, ``(x_P, y_P)`` the contact point
in the tooth frame (``y`` along the centre line). The **contact compliance** is the approach of two
elastic cylinders in line contact, measured to the teeth's centre lines:
``delta_H = 2 w (1 - nu^2) / (pi E) (ln(2 h_1 / b_H) + ln(2 h_2 / b_H) - nu / (1 - nu))``, ``w`` the
load per unit length, ``b_H = sqrt(4 w R / (pi E*))`` the Hertzian half width, ``R`` the relative
radius of curvature, ``h_i`` the distances from the contact to the centre lines along the load;
non-linear in ``w`` (:func:`hertz_approach`), as is the peak pressure ``p_H = sqrt(w E* / (pi R))``.

Examples
--------
>>> iso = iso_mesh_stiffness(20, 40, contact_ratio=1.635)
>>> round(iso.single, 2), round(iso.mesh, 2)
(12.69, 18.74)
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from gearkit.errors import check_fields, is_real, require

__all__ = ["IsoStiffness", "Material", "ToothCompliance", "hertz_approach", "hertz_pressure", "iso_mesh_stiffness"]

#: ISO 6336-1 method B coefficients C1..C9 of q' (mm um / N)
_ISO_C = (0.04723, 0.15551, 0.25791, -0.00635, -0.11654, -0.00193, -0.24188, 0.00529, 0.00182)


@dataclass(frozen=True)
class Material:
    """Elastic constants of both gears: Young's modulus ``young`` (MPa) and Poisson's ratio."""

    young: float = 206000.0
    poisson: float = 0.3

    def __post_init__(self):
        check_fields(self)
        require(is_real(self.young) and 1e3 <= self.young <= 1e7, "young", f"{self.young!r} must be in [1e3, 1e7] MPa")
        require(is_real(self.poisson) and 0 <= self.poisson < 0.5, "poisson", f"{self.poisson!r} must be in [0, 0.5)")

    @property
    def plane_strain(self) -> float:
        """``E' = E / (1 - nu^2)``, MPa."""
        return self.young / (1 - self.poisson ** 2)

    @property
    def contact_modulus(self) -> float:
        """``E*`` of two bodies of this material: ``1 / E* = 2 (1 - nu^2) / E``, MPa."""
        return self.plane_strain / 2


@dataclass(frozen=True)
class IsoStiffness:
    """ISO 6336-1 method B stiffness values, N/(mm um) per mm of face width."""

    theoretical: float
    single: float
    mesh: float
    mesh_beta: float
    basic_rack_factor: float


def iso_mesh_stiffness(z1: int, z2: int, shift1: float = 0.0, shift2: float = 0.0, *, contact_ratio: float,
                       helix_angle_deg: float = 0.0, pressure_angle_deg: float = 20.0, dedendum: float = 1.25,
                       blank_factor: float = 1.0, correction: float = 0.8,
                       line_load: float | None = None) -> IsoStiffness:
    """Single and mesh stiffness of an external steel pair by ISO 6336-1 method B.

    Parameters
    ----------
    z1, z2 : int; shift1, shift2 : float (x_n)
    contact_ratio : float, eps_alpha
    dedendum : float, h_fP / m_n of the basic rack
    blank_factor : float, C_R (1 for solid gears)
    correction : float, C_M (0.8)
    line_load : float or None, N/mm, F_t K_A / b; below 100 N/mm c' is reduced in proportion
    """
    beta = math.radians(abs(helix_angle_deg))
    alpha_n = math.radians(pressure_angle_deg)
    alpha_t = math.atan(math.tan(alpha_n) / math.cos(beta))
    beta_b = math.atan(math.tan(beta) * math.cos(alpha_t))
    zn1 = z1 / (math.cos(beta_b) ** 2 * math.cos(beta))
    zn2 = z2 / (math.cos(beta_b) ** 2 * math.cos(beta))
    c = _ISO_C
    q = (c[0] + c[1] / zn1 + c[2] / zn2 + c[3] * shift1 + c[4] * shift1 / zn1 + c[5] * shift2
         + c[6] * shift2 / zn2 + c[7] * shift1 ** 2 + c[8] * shift2 ** 2)
    c_th = 1.0 / q
    c_b = (1 + 0.5 * (1.2 - dedendum)) * (1 - 0.02 * (20.0 - pressure_angle_deg))
    single = c_th * correction * blank_factor * c_b * math.cos(beta)
    if line_load is not None and line_load < 100.0:
        single *= line_load / 100.0
    mesh = single * (0.75 * contact_ratio + 0.25)
    return IsoStiffness(c_th, single, mesh, 0.85 * mesh, c_b)


def hertz_pressure(w, radius, material: Material):
    """Peak Hertzian pressure (MPa) of a line contact: load ``w`` (N/mm), relative radius ``radius`` (mm)."""
    w = np.maximum(np.asarray(w, dtype=float), 0.0)
    return np.sqrt(w * material.contact_modulus / (math.pi * np.asarray(radius, dtype=float)))


def hertz_approach(w, radius, h1, h2, material: Material):
    """Approach (mm) of two teeth in line contact under ``w`` (N/mm), measured to their centre lines.

    ``radius`` the relative radius of curvature (mm), ``h1``, ``h2`` the distances (mm) from the contact
    to each tooth's centre line along the load. Zero at zero load.
    """
    w = np.maximum(np.asarray(w, dtype=float), 0.0)
    nu = material.poisson
    half = np.sqrt(4 * np.maximum(w, 1e-300) * radius / (math.pi * material.contact_modulus))
    logs = np.log(2 * h1 / half) + np.log(2 * h2 / half) - nu / (1 - nu)
    return np.where(w > 0, 2 * w * (1 - nu ** 2) / (math.pi * material.young) * logs, 0.0)


class ToothCompliance:
    """Bending, shear, compression and foundation compliance of one generated external tooth.

    Parameters
    ----------
    profile : ToothProfile of an external involute gear (``base_diameter``)
    material : Material
    samples : int, flank radii of the table (the compliance is interpolated between them)

    Attributes
    ----------
    radius : (samples,) float64, mm, flank radii of the table
    compliance : (samples,) float64, mm^2/N, deflection per unit load per unit face width
    """

    def __init__(self, profile, material: Material, samples: int = 48):
        self.material = material
        self.base_radius = profile.base_diameter / 2
        pts, _ = profile.half_points(1e-4 * profile.module)
        r = np.hypot(pts[:, 0], pts[:, 1])
        root = int(np.argmin(r))
        # the tooth from the tip down to the root circle: half thickness x over the height y
        tooth = pts[:root + 1]
        y, x = tooth[:, 1], np.abs(tooth[:, 0])
        keep = np.concatenate([[True], np.diff(y) < 0])
        self._y, self._x = y[keep][::-1], x[keep][::-1]  # increasing y
        self.root_radius = float(r[root])
        flank = np.concatenate([pc(np.linspace(0.0, 1.0, 257)) for pc in profile.half.pieces if pc.label == "flank"])
        self._flank_r = np.hypot(flank[:, 0], flank[:, 1])
        self._flank_x, self._flank_y = np.abs(flank[:, 0]), flank[:, 1]
        self.radius = np.linspace(self._flank_r.min(), self._flank_r.max(), samples)
        self.compliance = np.array([self._at(rc) for rc in self.radius])

    def point(self, radius):
        """Contact point ``(x_P, y_P)`` (mm, tooth frame) on the flank at ``radius`` and the load angle a_F."""
        order = np.argsort(self._flank_r)
        rr = self._flank_r[order]
        x = np.interp(radius, rr, self._flank_x[order])
        y = np.interp(radius, rr, self._flank_y[order])
        a_f = np.arccos(np.clip(self.base_radius / np.asarray(radius, dtype=float), -1, 1)) - np.arctan2(x, y)
        return x, y, a_f

    def _at(self, rc) -> float:
        e1 = self.material.plane_strain
        g = self.material.young / (2 * (1 + self.material.poisson))
        x_p, y_p, a_f = (float(v) for v in self.point(rc))
        y0 = self._y[0]
        yy = np.linspace(y0, y_p, 400)
        half = np.interp(yy, self._y, self._x)
        area = 2 * half
        inertia = area ** 3 / 12
        c, s = math.cos(a_f), math.sin(a_f)
        lever = c * (y_p - yy) - s * x_p
        bend = np.trapezoid(lever ** 2 / (e1 * inertia), yy)
        shear = np.trapezoid(1.2 * c * c / (g * area), yy)
        comp = np.trapezoid(s * s / (e1 * area), yy)
        s_f = area[0]
        turn = 16 * lever[0] ** 2 / (math.pi * e1 * s_f ** 2)  # the root section turned on the half-plane
        shift = 2 * math.log(2 * self.root_radius / s_f) / (math.pi * e1)  # and shifted, to the gear centre
        found = turn + shift
        return float(bend + shear + comp + found)

    def __call__(self, radius):
        """Compliance (mm^2/N) at contact radii ``radius`` (mm), interpolated; held at the table's ends."""
        return np.interp(radius, self.radius, self.compliance)

    def lever(self, radius):
        """Distance (mm) from the contact at ``radius`` to the tooth centre line along the load."""
        x, _, a_f = self.point(radius)
        return x / np.cos(a_f)
