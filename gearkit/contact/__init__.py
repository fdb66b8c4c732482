"""Tooth contact analysis: a rigid, unloaded meshing simulation of any two generated profiles.

For every driver angle over a mesh cycle the mate is placed where it first touches the driver
(on the working flanks, and on the reverse flanks for backlash), from the exact pieces of both
profiles: transmission error, path of contact, pairs in contact and the simulated contact ratio,
backlash, and interference (depth, area, where). Helical gears as transverse slices.

* :class:`Mesh` — two profiles (gear, ring or rack) placed at a centre distance
  (:mod:`gearkit.contact.mesh`).
* :func:`simulate` — one mesh cycle → :class:`ContactAnalysis` (:mod:`gearkit.contact.analysis`);
  :func:`limits` — just where the mate stops either way at given driver angles.
* :func:`analyse_pair` / :func:`pair_mesh` — the same for a :class:`~gearkit.pair.PairSpec`.
* :func:`analyse_loaded` — the pair under load (:mod:`gearkit.contact.loaded`): loaded TE, load
  sharing, contact pattern, Hertzian pressure, mesh stiffness (:mod:`gearkit.contact.stiffness`);
  :func:`harris_map` — p-p TE over loads and tip reliefs (:mod:`gearkit.contact.harris`).
* :func:`pin_ring` — pins as teeth (cycloid–pin-wheel drives, lantern gearing).
* :func:`plot_transmission_error`, :func:`plot_path_of_contact` — PNG/SVG plots (matplotlib).

How it works (:mod:`gearkit.contact.solver`): the mate's tooth is a function of its radius, so a
driver point at radius ``rho`` bounds the mate's turn by the half width of its space there; the
bound is minimised over each driver flank — first on a polyline, then by Newton's method on the
derivatives of tables of both teeth (:mod:`gearkit.contact.table`: every piece fitted once, since
all teeth are turned copies of one, within 1e-12 of the outer radius; at most driver angles Newton starts from the
neighbouring angles' minima, :mod:`gearkit.contact.continuation`), and each half's best contact is evaluated on the
exact pieces (the mate's radius matched by the secant method), so the values reported are exact.
Only the driver halves that reach the mate's tip circle are searched, so the work per driver angle
does not grow with the tooth counts. ``Mesh(..., tables=False)`` works on the exact pieces
throughout (the reference the tables are tested against).

Examples
--------
>>> from gearkit.families.involute import GearSpec, tooth_profile
>>> mesh = Mesh(tooth_profile(GearSpec(20, 1.0)), tooth_profile(GearSpec(40, 1.0)), 30.0)
>>> res = simulate(mesh, steps=64)
>>> round(res.contact_ratio, 3), res.interference.found
(1.635, False)
"""
from gearkit.contact.analysis import ContactAnalysis, Interference, limits, simulate
from gearkit.contact.mesh import KINDS, Mesh
from gearkit.contact.harris import HarrisMap, harris_map, long_tip_relief
from gearkit.contact.loaded import Deviations, LoadedAnalysis
from gearkit.contact.pair import analyse_loaded, analyse_pair, pair_mesh
from gearkit.contact.stiffness import Material, iso_mesh_stiffness
from gearkit.contact.pins import pin_ring
from gearkit.contact.plot import plot_path_of_contact, plot_transmission_error, save_plot

__all__ = ["KINDS", "ContactAnalysis", "Deviations", "HarrisMap", "Interference", "LoadedAnalysis", "Material", "Mesh",
           "analyse_loaded", "analyse_pair", "harris_map", "iso_mesh_stiffness", "limits", "long_tip_relief",
           "pair_mesh", "pin_ring", "plot_path_of_contact", "plot_transmission_error", "save_plot", "simulate"]
