"""Plots of a loaded contact analysis: loaded TE, load sharing, contact pattern, Harris map.

Same conventions as :mod:`gearkit.contact.plot` (matplotlib's object API, atomic writes, the format
from the suffix). :func:`save_loaded_plot` picks the plot from the file name.
"""
from __future__ import annotations

import os

import numpy as np

from gearkit.contact.plot import ROUND_OFF, new_figure, write_figure

__all__ = ["plot_harris_map", "plot_load_sharing", "plot_loaded_te", "plot_pattern", "save_loaded_plot"]


def _title(res) -> str:
    return (f"{res.torque:g} N m: p-p TE {res.transmission_error_pp * 1e6:.3f} µrad, loaded contact ratio "
            f"{res.contact_ratio_loaded:.3f}; {res.steps} steps, {res.slices} slice{'s' if res.slices > 1 else ''}")


def plot_loaded_te(res, path) -> str:
    """Loaded and rigid transmission error (µrad) and mesh stiffness over the cycle."""
    fig = new_figure()
    ax = fig.add_subplot(1, 1, 1)
    phi = np.degrees(res.driver_angle)
    rigid = res.rigid_transmission_error * 1e6
    if np.all(np.abs(rigid) <= ROUND_OFF * 1e6):
        rigid = np.zeros_like(rigid)  # conjugate flanks: zero to round-off
    ax.plot(phi, res.transmission_error * 1e6, color="tab:blue", lw=1.4, label="loaded TE")
    ax.plot(phi, rigid, color="tab:gray", lw=1.0, ls="--", label="rigid TE (no load)")
    lo = min(float(np.min(res.transmission_error)), float(np.min(res.rigid_transmission_error))) * 1e6
    hi = max(float(np.max(res.transmission_error)), float(np.max(res.rigid_transmission_error))) * 1e6
    pad = max(0.1 * (hi - lo), 0.5)
    ax.set_ylim(lo - pad, hi + pad)
    ax.set_xlabel("driver angle (deg)")
    ax.set_ylabel("transmission error (µrad, + mate lags)", color="tab:blue")
    twin = ax.twinx()
    twin.plot(phi, res.mesh_stiffness, color="tab:orange", lw=1.0, label="mesh stiffness")
    twin.set_ylabel("mesh stiffness (N/mm/µm)", color="tab:orange")
    twin.set_ylim(0, max(1.0, float(res.mesh_stiffness.max())) * 1.15)
    ax.legend(loc="lower left", fontsize=8)
    ax.set_title(_title(res), fontsize=9)
    ax.grid(True, alpha=0.3)
    return write_figure(fig, path)


def plot_load_sharing(res, path) -> str:
    """Fraction of the load carried by each tooth pair over the cycle."""
    fig = new_figure()
    ax = fig.add_subplot(1, 1, 1)
    phi = np.degrees(res.driver_angle)
    for j, t in enumerate(res.pair_teeth):
        share = res.sharing[:, j]
        ax.plot(phi, np.where(res.load[:, :, j].sum(1) > 0, share, np.nan), lw=1.3, label=f"driver tooth {int(t)}")
    ax.set_ylim(-0.05, 1.1)
    ax.set_xlabel("driver angle (deg)")
    ax.set_ylabel("load share")
    ax.legend(loc="center right", fontsize=8)
    ax.set_title(_title(res), fontsize=9)
    ax.grid(True, alpha=0.3)
    return write_figure(fig, path)


def plot_pattern(res, path) -> str:
    """Contact pattern: the largest load per unit length (N/mm) over the driver's roll angle and the face."""
    fig = new_figure(7.0, 4.8)
    ax = fig.add_subplot(1, 1, 1)
    roll = res.pattern_roll_deg
    dr = roll[1] - roll[0] if len(roll) > 1 else 1.0
    dz = res.face_width / res.slices
    extent = (0.0, res.face_width, roll[0] - dr / 2, roll[-1] + dr / 2)
    im = ax.imshow(res.pattern, origin="lower", aspect="auto", extent=extent, cmap="inferno",
                   vmin=0.0, vmax=max(float(res.pattern.max()), 1e-9), interpolation="nearest")
    cb = fig.colorbar(im, ax=ax)
    cb.set_label("load per unit length (N/mm)")
    ax.set_xlabel(f"face width (mm; {res.slices} slices of {dz:.3g} mm)")
    ax.set_ylabel("driver roll angle (deg; tip at the top)")
    ax.set_title(f"contact pattern, {_title(res)}\nmax Hertzian pressure {res.max_contact_pressure:.0f} MPa",
                 fontsize=9)
    return write_figure(fig, path)


def plot_harris_map(hmap, path) -> str:
    """Peak-to-peak loaded TE over torque, one line per tip relief; the best relief at the design load."""
    fig = new_figure()
    ax = fig.add_subplot(1, 1, 1)
    for i, c in enumerate(hmap.reliefs):
        best = c == hmap.best_relief
        ax.plot(hmap.torques, hmap.pp[i] * 1e6, marker="o", ms=3, lw=2.2 if best else 1.0,
                label=f"tip relief {c * 1e3:.1f} µm" + (" (best)" if best else ""))
    ax.axvline(hmap.design_torque, color="black", lw=0.8, ls=":")
    ax.set_xlabel("pinion torque (N m)")
    ax.set_ylabel("peak-to-peak loaded TE (µrad)")
    ax.set_ylim(bottom=0)
    ax.legend(fontsize=7, ncol=2)
    ax.set_title(f"Harris map: best relief {hmap.best_relief * 1e3:.1f} µm at {hmap.design_torque:g} N m "
                 f"({hmap.steps} steps)", fontsize=9)
    ax.grid(True, alpha=0.3)
    return write_figure(fig, path)


def save_loaded_plot(res, path) -> str:
    """``pattern`` in the file name: the contact pattern; ``load`` or ``shar``: the load sharing; else the TE."""
    name = os.path.basename(os.fspath(path)).lower()
    if "pattern" in name:
        return plot_pattern(res, path)
    if "load" in name or "shar" in name:
        return plot_load_sharing(res, path)
    return plot_loaded_te(res, path)
