"""Pictures of a cam (matplotlib, Agg, imported lazily): the s-v-a-j diagram, the pressure angle over
the cam angle with and without friction, and the profile with its pitch curve and follower.

:func:`save` writes a .png or .svg atomically (:func:`gearkit.export.atomic_write`).
"""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from gearkit.errors import SpecError

__all__ = ["figure", "save"]

_FORMATS = (".png", ".svg")


def _follower_outline(prof, phi0: float = 0.0):
    """The follower at cam angle ``phi0`` in the cam frame (roller circle, knife stem, face), for the picture."""
    spec = prof.spec
    if spec.contact == "roller":
        t = np.linspace(0.0, 2 * math.pi, 181)
        ring = prof.reference + spec.roller_radius * np.stack([np.cos(t), np.sin(t)], -1)
        return prof.motion.to_blank(ring, np.full(len(ring), phi0))
    u = np.linspace(0.0, 1.0, 2)
    seg = prof.tool.evaluate(u)[0]
    if spec.contact == "flat":
        half = 0.6 * (spec.prime_radius + spec.stroke)
        seg = np.array([[-half, 0.0], [half, 0.0]]) + ([0.0, 0.0] if spec.follower == "translating" else [half, 0.0])
    else:
        up = np.array([0.0, 0.3 * spec.prime_radius]) if spec.follower == "translating" else \
            np.array([-0.3 * spec.prime_radius, 0.0])
        seg = np.array([prof.reference, prof.reference + up])
    return prof.motion.to_blank(seg, np.full(len(seg), phi0))


def figure(prof, tol: float | None = None):
    """A matplotlib Figure of the generated cam ``prof`` (nothing is shown)."""
    import matplotlib
    matplotlib.use("Agg")
    from matplotlib.figure import Figure

    from gearkit.families.cam.follower import law_pressure_angle

    spec = prof.spec
    tol = 1e-4 * (spec.prime_radius + spec.stroke) if tol is None else tol
    fig = Figure(figsize=(11.0, 6.6), dpi=100, layout="constrained")
    outer = fig.add_gridspec(1, 2, width_ratios=(1.15, 1.0))
    left = outer[0].subgridspec(4, 1)
    right = outer[1].subgridspec(2, 1, height_ratios=(1.2, 1.0))
    deg = np.linspace(0.0, 360.0, 2881)
    phi = np.radians(deg)
    curves = spec.motion.evaluate(phi)
    motion_axes = []
    names = (("s", "mm"), ("s'", "mm/rad"), ("s''", "mm/rad²"), ("s'''", "mm/rad³"))
    colours = ("#1b4f72", "#117a65", "#b9770e", "#922b21")
    for k, (values, (label, unit), colour) in enumerate(zip(curves, names, colours)):
        ax = fig.add_subplot(left[k])
        motion_axes.append(ax)
        ax.plot(deg, values, color=colour, lw=1.4)
        ax.axhline(0.0, color="#999999", lw=0.6)
        ax.set_ylabel(f"{label}\n[{unit}]", fontsize=9)
        ax.set_xlim(0.0, 360.0)
        ax.set_xticks(np.arange(0, 361, 60))
        ax.grid(True, lw=0.3, alpha=0.6)
        ax.tick_params(labelsize=8)
        if k < 3:
            ax.tick_params(labelbottom=False)
        else:
            ax.set_xlabel("cam angle φ [deg]", fontsize=9)
        if k == 0:
            ax.set_title("follower motion: displacement, velocity, acceleration, jerk", fontsize=10)
    fig.align_ylabels(motion_axes)
    top = right[0].subgridspec(1, 2, width_ratios=(1.0, 0.45))
    ax = fig.add_subplot(top[0])
    out = prof.outline(tol)
    pitch = prof.pitch_outline(tol)[0] if spec.contact != "flat" else None
    ax.fill(out[:, 0], out[:, 1], color="#d6eaf8", ec="#1b4f72", lw=1.2, label="cam profile")
    if pitch is not None and spec.contact == "roller":
        ax.plot(*np.vstack([pitch, pitch[:1]]).T, color="#7f8c8d", lw=0.8, ls="--", label="pitch curve")
    foll = _follower_outline(prof)
    ax.plot(foll[:, 0], foll[:, 1], color="#922b21", lw=1.4, label=f"{spec.follower} {spec.contact}\nat φ = 0")
    ax.plot([0.0], [0.0], marker="+", color="black", ms=8, label="cam axis")
    ax.set_aspect("equal", adjustable="datalim")  # the box fills its cell, so the layout sees where it is
    ax.tick_params(labelsize=8)
    key = fig.add_subplot(top[1])
    key.axis("off")
    key.legend(*ax.get_legend_handles_labels(), fontsize=8, loc="upper left", borderaxespad=0.0, frameon=False)
    ax.set_title(f"cam, r0 = {spec.prime_radius:g} mm, stroke {spec.stroke:g} mm"
                 + ("\nundercut (loop cut away)" if prof.undercut else ""), fontsize=10)
    ax = fig.add_subplot(right[1])
    alpha = np.degrees(prof.pressure_angle(phi))
    if spec.contact == "flat" and spec.follower == "rocker":  # no pressure angle where the contact is behind the pivot
        behind = prof.face_contact(phi) <= 0.0
        alpha[behind] = np.nan
        edges = np.flatnonzero(np.diff(np.concatenate([[0], behind.astype(int), [0]])))
        for k, (a, b) in enumerate(zip(edges[::2], edges[1::2])):
            ax.axvspan(deg[a], deg[b - 1], color="#f5cba7", lw=0.0, label="contact behind the pivot" if k == 0 else None)
    ax.plot(deg, alpha, color="#1b4f72", lw=1.4, label="without friction")
    if spec.friction > 0 or spec.efficiency < 1:
        model = f"μ = {spec.friction:g}" if spec.friction > 0 else f"η = {spec.efficiency:g}"
        eta = 1.0 if spec.friction > 0 else spec.efficiency
        ax.plot(deg, np.degrees(law_pressure_angle(spec, phi, eta, spec.friction)), color="#922b21", lw=1.4, ls="--",
                label=f"with friction ({model})")
    lim = spec.limit_deg
    for sign in (1, -1):
        ax.axhline(sign * lim, color="#b9770e", lw=1.0, ls=":", label="limit ±%g°" % lim if sign > 0 else None)
    lo, hi = ax.get_ylim()  # the limit lines inside the frame, not on its edge
    ax.set_ylim(min(lo, -1.1 * lim), max(hi, 1.1 * lim))
    ax.set_xlim(0.0, 360.0)
    ax.set_xticks(np.arange(0, 361, 60))
    ax.set_xlabel("cam angle φ [deg]", fontsize=9)
    ax.set_ylabel("pressure angle [deg]", fontsize=9)
    ax.tick_params(labelsize=8)
    ax.grid(True, lw=0.3, alpha=0.6)
    ax.legend(fontsize=8, loc="lower left", bbox_to_anchor=(0.0, 1.01), borderaxespad=0.0, ncol=3, frameon=False)
    return fig


def save(prof, path, tol: float | None = None) -> Path:
    """Write the picture of ``prof`` to ``path`` (.png or .svg) atomically."""
    from gearkit.export import atomic_write

    ext = Path(path).suffix.lower()
    if ext not in _FORMATS:
        raise SpecError("--plot", f"{str(path)!r}: the file name must end in .png or .svg")
    fig = figure(prof, tol)
    return atomic_write(path, lambda tmp: fig.savefig(tmp, format=ext[1:]))
