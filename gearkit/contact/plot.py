"""Plots of a contact analysis: transmission error over the cycle, path of contact on the profiles.

matplotlib is imported here only (and only its object API with the Agg canvas: no pyplot, no
global state). Files are written atomically: to a temporary file beside the target, then
renamed over it. The format follows the suffix (``.png`` or ``.svg``).
"""
from __future__ import annotations

import math
import os

import numpy as np

from gearkit.errors import SpecError

__all__ = ["new_figure", "plot_path_of_contact", "plot_transmission_error", "save_plot", "write_figure"]

_FORMATS = ("png", "svg")
#: a rigid TE below this (rad; mm for a rack) is round-off of the exact solution, drawn as zero
ROUND_OFF = 1e-12


def new_figure(width=7.0, height=4.5):
    """A matplotlib Figure on the Agg canvas (no pyplot state)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    fig = Figure(figsize=(width, height), dpi=120)
    FigureCanvasAgg(fig)
    return fig


def write_figure(fig, path) -> str:
    """Write ``fig`` to ``path`` atomically in the format of its suffix (png, svg); returns the path."""
    path = os.fspath(path)
    fmt = os.path.splitext(path)[1].lower().lstrip(".")
    if fmt not in _FORMATS:
        raise SpecError("output", f"{path!r}: the plot format must be one of {', '.join(_FORMATS)} (from the suffix)")
    from gearkit.export import atomic_write

    atomic_write(path, lambda tmp: fig.savefig(tmp, format=fmt))
    return path


def plot_transmission_error(result, path) -> str:
    """Transmission error (µrad; µm for a rack) and pairs in contact over the mesh cycle."""
    fig = new_figure()
    ax = fig.add_subplot(1, 1, 1)
    phi = np.degrees(result.driver_angle)
    te = result.transmission_error * 1e6
    unit = "µm" if result.units == "mm" else "µrad"
    noise = ROUND_OFF * 1e6
    flat = bool(np.all(np.abs(te[np.isfinite(te)]) <= noise))
    if flat:  # conjugate flanks: zero to round-off, drawn as zero on a readable scale
        ax.set_ylim(-1.0, 1.0)
        ax.text(0.02, 0.92, f"TE = 0 to round-off (max |TE| {np.nanmax(np.abs(te)):.1e} {unit})",
                transform=ax.transAxes, fontsize=8)
        te = np.zeros_like(te)
    ax.plot(phi, np.where(np.isfinite(te), te, np.nan), color="tab:blue", lw=1.2, label="transmission error")
    ax.set_xlabel("driver angle (deg)")
    ax.set_ylabel(f"transmission error ({unit})", color="tab:blue")
    twin = ax.twinx()
    twin.step(phi, result.pairs_in_contact, where="mid", color="tab:orange", lw=1.0, label="pairs in contact")
    twin.set_ylabel("pairs in contact", color="tab:orange")
    twin.set_ylim(-0.2, max(2, int(result.pairs_in_contact.max())) + 0.5)
    title = (f"{result.mesh.kind} mesh: simulated contact ratio {result.contact_ratio:.4f}"
             + (f", total {result.total_contact_ratio:.4f}" if result.slices > 1 else ""))
    if result.interference.found:
        title += f"; interference {result.interference.max_depth:.3g} mm ({', '.join(result.interference.where)})"
    ax.set_title(title, fontsize=9)
    ax.grid(True, alpha=0.3)
    return write_figure(fig, path)


def _half_points(profile, tol):
    pts, _ = profile.half.sample(tol)
    return np.concatenate([pts[::-1] * np.array([-1.0, 1.0]), pts[1:]])


def _driver_teeth(mesh, phi, tol):
    tooth = _half_points(mesh.gear1, tol)
    _, theta = mesh.teeth(np.array([phi]))
    out = []
    for th in theta[0]:
        c, s = math.cos(th), math.sin(th)
        out.append(np.stack([c * tooth[:, 0] - s * tooth[:, 1], s * tooth[:, 0] + c * tooth[:, 1]], -1))
    return out


def _mate_teeth(mesh, phi, delta, tol, count):
    tooth = _half_points(mesh.gear2, tol)
    out = []
    if mesh.kind == "rack":
        centre = mesh.beta0 + mesh.ratio * phi + delta
        j0 = round(centre / mesh.pitch2)
        for j in range(j0 - count, j0 + count + 1):
            out.append(mesh.mate_to_fixed(tooth + np.array([-j * mesh.pitch2, 0.0]), phi, delta))
        return out
    toward = 0.0 if mesh.kind != "external" else math.pi
    frame = toward + mesh.beta0 + mesh.ratio * phi + delta  # mate-frame polar angle of the mesh
    j0 = round(-frame / mesh.pitch2)
    for j in range(j0 - count, j0 + count + 1):
        a = j * mesh.pitch2
        c, s = math.cos(a), math.sin(a)
        p = np.stack([c * tooth[:, 0] - s * tooth[:, 1], s * tooth[:, 0] + c * tooth[:, 1]], -1)
        out.append(mesh.mate_to_fixed(p, phi, delta))
    return out


def plot_path_of_contact(result, path, step: int | None = None) -> str:
    """Both profiles at one driver angle (default: the middle of the cycle) and the path of contact
    (every working contact over the cycle, in the fixed frame; slice 0 for a helical pair)."""
    mesh = result.mesh
    n = len(result.driver_angle)
    j = n // 2 if step is None else int(step)
    phi = float(result.driver_angle[j])
    delta = float(result.reference + result.transmission_error[j])
    tol = max(mesh.tol, 1e-3 * mesh.module)
    fig = new_figure(6.5, 6.5)
    ax = fig.add_subplot(1, 1, 1)
    for k, t in enumerate(_driver_teeth(mesh, phi, tol)):
        ax.plot(t[:, 0], t[:, 1], color="tab:blue", lw=1.0, label="driver" if k == 0 else None)
    for k, t in enumerate(_mate_teeth(mesh, phi, delta, tol, max(3, len(mesh.offsets) // 2 + 1))):
        ax.plot(t[:, 0], t[:, 1], color="tab:green", lw=1.0, label="mate" if k == 0 else None)
    c = result.contacts
    first = c["slice"] == 0
    pts = c["point"][first]
    ax.plot(pts[:, 0], pts[:, 1], ".", color="tab:red", ms=2.0, label="path of contact")
    now = first & (c["step"] == j)
    if now.any():
        ax.plot(c["point"][now, 0], c["point"][now, 1], "o", color="black", ms=4.0, label="contacts now")
    ax.plot(*mesh.pitch_point, "+", color="black", ms=8.0)
    lo = np.nanmin(pts, axis=0) if len(pts) else mesh.pitch_point
    hi = np.nanmax(pts, axis=0) if len(pts) else mesh.pitch_point
    span = max(float(np.max(hi - lo)), 4.0 * mesh.module) * 0.8
    centre = 0.5 * (lo + hi)
    ax.set_xlim(centre[0] - span, centre[0] + span)
    ax.set_ylim(centre[1] - span, centre[1] + span)
    ax.set_aspect("equal")
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("y (mm)")
    ax.legend(loc="upper right", fontsize=8)
    ax.set_title(f"path of contact, driver at {math.degrees(phi):.3f} deg", fontsize=9)
    ax.grid(True, alpha=0.3)
    return write_figure(fig, path)


def save_plot(result, path) -> str:
    """``plot_path_of_contact`` when the file name contains "path", else ``plot_transmission_error``."""
    name = os.path.basename(os.fspath(path)).lower()
    return (plot_path_of_contact if "path" in name else plot_transmission_error)(result, path)
