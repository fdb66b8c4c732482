"""Pages to look at: one self-contained HTML file per pair, drive, cam, scene or blocking contour.

:func:`pair_view`, :func:`drive_view`, :func:`cam_view` and :func:`blocking_view` build the page's data (the 2D
mesh animated from the contact simulation, the transmission error trace, the solids, the
design check's findings, the blocking map); :func:`write_page` writes it with the viewer
script inlined (no network at view time). The data format (:mod:`gearkit.view.page`) is
generic: any producer of bodies with poses, contact points and meshes gets the same page.

This package sits with ``solids`` and ``blocking``: it may import the pair, checks, contact,
solids and blocking layers; only the command line imports it.
"""
from gearkit.view.blocking import blocking_view, contour_map
from gearkit.view.cam import cam_view
from gearkit.view.mesh import drive_view, mesh_animation, pair_view
from gearkit.view.page import mesh_part, render, write_page
from gearkit.view.scene import scene_view

__all__ = ["blocking_view", "cam_view", "contour_map", "drive_view", "mesh_animation", "mesh_part", "pair_view", "render",
           "scene_view", "write_page"]
