"""Tip relief design: the long relief of a pair and the map of loaded TE over load and relief.

:func:`long_tip_relief` puts a tip relief on both gears from their highest point of single tooth
contact to the tip (the "long" relief: over the last ``(eps_alpha - 1) p_bt`` of each gear's roll).
:func:`harris_map` meshes the pair for each relief amount once (the rigid gaps) and solves it at
each load: the peak-to-peak loaded transmission error over loads and reliefs, and the relief
that minimises it at a design load. Unmodified teeth deflect into the next pair's path; a relief
equal to the deflection at the design load lets the load pass smoothly from pair to pair there.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from gearkit.errors import is_real, require
from gearkit.families.involute.modification import Modification
from gearkit.progress import Progress

__all__ = ["HarrisMap", "harris_map", "long_tip_relief"]


def long_tip_relief(spec, amount: float, shape: str = "linear"):
    """``(Modification, Modification)``: tip relief ``amount`` (mm) on pinion and wheel from their highest
    point of single tooth contact (roll lengths from the pair's path of contact) to the tip."""
    from gearkit.pair import pair_geometry

    require(is_real(amount) and 0 <= amount <= 1, "tip_relief", f"{amount!r} must be in [0, 1] mm")
    if amount == 0:
        return None, None
    g = pair_geometry(spec)
    p = g.path
    roll1 = p["E"] - p["D"]  # pinion: from D (its highest single contact) to its tip at E
    roll2 = p["B"] - p["A"]  # wheel: from B to its tip at A
    return (Modification(tip_relief=amount, tip_relief_roll=roll1, relief_shape=shape),
            Modification(tip_relief=amount, tip_relief_roll=roll2, relief_shape=shape))


@dataclass(frozen=True)
class HarrisMap:
    """Peak-to-peak loaded TE (mate rad) ``pp[i, j]`` at relief ``reliefs[i]`` (mm) and torque ``torques[j]``
    (N m); ``best_relief`` minimises it at ``design_torque``."""

    reliefs: np.ndarray = field(repr=False)
    torques: np.ndarray = field(repr=False)
    pp: np.ndarray = field(repr=False)
    design_torque: float = 0.0
    best_relief: float = 0.0
    steps: int = 0

    def to_dict(self) -> dict:
        return {"reliefs": [float(v) for v in self.reliefs], "torques": [float(v) for v in self.torques],
                "transmission_error_pp": [[float(v) * 1e6 for v in row] for row in self.pp],
                "design_torque": self.design_torque, "best_relief": self.best_relief, "steps": self.steps}


def harris_map(spec, torques, reliefs, *, design_torque: float | None = None, steps: int = 400,
               material=None, tol: float | None = None) -> HarrisMap:
    """Peak-to-peak loaded TE of ``spec`` over ``torques`` (N m) for long tip reliefs ``reliefs`` (mm).

    The best relief is the one of ``reliefs`` with the least p-p TE at ``design_torque`` (default: the
    largest torque), so its accuracy is the spacing of ``reliefs``.
    """
    from gearkit.contact.pair import analyse_loaded

    torques = np.asarray(torques, dtype=float)
    reliefs = np.asarray(reliefs, dtype=float)
    require(torques.ndim == 1 and torques.size >= 1 and np.all(torques >= 0), "torques", "must be >= 0 N m")
    require(reliefs.ndim == 1 and reliefs.size >= 1 and np.all(reliefs >= 0), "reliefs", "must be >= 0 mm")
    design = float(torques.max() if design_torque is None else design_torque)
    all_t = np.unique(np.concatenate([torques, [design]]))
    pp = np.zeros((len(reliefs), len(all_t)))
    with Progress("harris map", len(reliefs), unit="reliefs") as bar:
        for i, c in enumerate(reliefs):
            mods = long_tip_relief(spec, float(c))
            res = analyse_loaded(spec, [float(t) for t in all_t], modifications=mods, steps=steps,
                                 material=material, tol=tol)
            pp[i] = [r.transmission_error_pp for r in res]
            bar.update(i + 1)
    j_design = int(np.searchsorted(all_t, design))
    best = float(reliefs[int(np.argmin(pp[:, j_design]))])
    keep = np.isin(all_t, torques)
    return HarrisMap(reliefs, all_t[keep], pp[:, keep], design, best, int(steps))
