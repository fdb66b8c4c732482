"""Straight solids checked and measured by their structure (``gearkit.solids.extrusion``), against the
mesh check that sorts every edge (``gearkit.solids.measures.mesh_measures``) and plain second methods.

Oracles: every directed edge of the mesh counted in a dictionary (each once, its reverse once); the
volume and area from ``np.cross`` over all facets at once (divergence theorem) and, for hand-made
sections, in closed form; the normals from ``np.cross`` of the single-precision vertices. Tolerances:
the volume and area sum the same products in another order, so they agree to ``REL = 1e-12``
relative; the normals are formed from the same exact differences, so to the bit.
"""
from collections import Counter

import numpy as np
import pytest

from gearkit.errors import GeometryError
from gearkit.families.involute import GearSpec, ShaperCutter, tooth_profile
from gearkit.solids import SolidSpec, gear_solid
from gearkit.solids import measures as measures_module
from gearkit.solids import solid as solid_module
from gearkit.solids.extrusion import Wall, extruded
from gearkit.solids.gear import bore_points, circle_points, gear_plan
from gearkit.solids.measures import mesh_measures
from gearkit.solids.section import Section

REL = 1e-12

RING = dict(internal=True, tool=ShaperCutter(20))
STRAIGHT = {
    "spur": (GearSpec(31, 1.0), SolidSpec(4.0), 2e-3),
    "few teeth, undercut": (GearSpec(6, 1.0), SolidSpec(2.0), 2e-3),
    "bore in the core": (GearSpec(40, 2.0), SolidSpec(10.0, bore=20.0), 1e-2),
    "keyway": (GearSpec(40, 2.0), SolidSpec(10.0, bore=20.0, keyway=(6.0, 2.5)), 1e-2),
    "bore into the cells": (GearSpec(20, 2.0), SolidSpec(10.0, bore=30.0), 1e-2),
    "ring": (GearSpec(60, 1.0, **RING), SolidSpec(6.0), 5e-3),
    "ring, outer diameter": (GearSpec(60, 1.0, **RING), SolidSpec(6.0, outer_diameter=80.0), 5e-3),
}


def assert_measures_agree(solid, v, f):
    """The solid's measures against np.cross over all facets and the edges counted one by one."""
    directed = Counter(zip(f.ravel().tolist(), f[:, (1, 2, 0)].ravel().tolist()))
    assert all(n == 1 and directed[(b, a)] == 1 for (a, b), n in directed.items())
    p = v[f]
    n = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])
    assert solid.volume == pytest.approx(np.einsum("ij,ij->", p[:, 0], n) / 6.0, rel=REL)
    assert solid.area == pytest.approx(0.5 * np.linalg.norm(n, axis=1).sum(), rel=REL)
    s = v.astype(np.float32).astype(np.float64)[f]
    ns = np.cross(s[:, 1] - s[:, 0], s[:, 2] - s[:, 0])
    assert np.array_equal(solid.normals(), (ns / np.linalg.norm(ns, axis=1)[:, None]).astype(np.float32))


@pytest.mark.parametrize("case", list(STRAIGHT))
def test_a_straight_gear_is_checked_by_its_structure_and_measures_as_the_full_check(case, monkeypatch):
    gear, spec, tol = STRAIGHT[case]
    monkeypatch.setattr(measures_module, "CHUNK", 256)  # several chunks of facets and of loop edges

    def refused(*args, **kwargs):
        raise AssertionError("a straight gear went through the full mesh check")

    monkeypatch.setattr(solid_module, "mesh_measures", refused)
    solid = gear_solid(tooth_profile(gear), spec, tol)
    monkeypatch.undo()
    v, f = solid.arrays()
    assert len(f) > 4 * 256
    assert_measures_agree(solid, v, f)
    full = mesh_measures(v, f)
    assert np.array_equal(full["normals"], solid.normals())
    assert solid.volume == pytest.approx(full["volume"], rel=REL)
    assert solid.area == pytest.approx(full["area"], rel=REL)


def test_the_cases_reach_every_kind_of_end_face():
    """The premise of the cases above: cells with a fan, cells with a band to the bore, a whole face."""
    kinds = set()
    for gear, spec, tol in STRAIGHT.values():
        prof = tooth_profile(gear)
        sec = Section(gear_plan(prof, spec, tol).polyline, prof.teeth, prof.internal)
        wall = None if spec.bore is None else bore_points(spec.bore, spec.keyway, tol)
        if prof.internal:
            wall = circle_points(prof.root_diameter / 2.0 + 2.0 * prof.module, tol)
        extra, _ = sec.end_face(0.0, wall)
        kinds.add("fan" if len(extra) == prof.teeth + 1 else "band" if len(extra) == prof.teeth else "whole")
    assert kinds == {"fan", "band", "whole"}


SQUARE = np.array([[0.0, 0.0], [4.0, 0.0], [4.0, 4.0], [0.0, 4.0]])
HOLE = np.array([[1.0, 1.0], [3.0, 1.0], [3.0, 2.0], [1.0, 2.0]])
# the square minus the hole: outer loop 0-3, hole loop 4-7 (both counter-clockwise)
FRAME = [[0, 1, 5], [0, 5, 4], [1, 2, 6], [1, 6, 5], [2, 3, 7], [2, 7, 6], [3, 0, 4], [3, 4, 7]]


def test_a_frame_with_a_hole_and_split_quads_measures_its_closed_form():
    diag = np.array([True, False, True, False])
    solid = extruded(np.concatenate([SQUARE, HOLE]), FRAME, [Wall(4, diagonals=diag), Wall(4, True, diag[::-1])],
                     -1.0, 2.0, "frame", {})
    height, area = 3.0, 16.0 - 2.0
    assert solid.volume == pytest.approx(area * height, rel=REL)
    assert solid.area == pytest.approx(2 * area + (16.0 + 6.0) * height, rel=REL)
    assert_measures_agree(solid, *solid.arrays())


@pytest.mark.parametrize("walls, triangles", [
    ([Wall(4), Wall(4, True)], FRAME[:-1]),  # a triangle missing: the section is open
    ([Wall(4), Wall(4)], FRAME),  # the hole's wall said to face outwards
    ([Wall(4), Wall(4, True)], [t[::-1] for t in FRAME]),  # the section turned over
], ids=["open", "hole facing out", "turned over"])
def test_a_section_its_walls_do_not_bound_goes_to_the_full_check_which_refuses_it(walls, triangles, monkeypatch):
    full = []
    monkeypatch.setattr(solid_module, "mesh_measures", lambda *a: full.append(a) or mesh_measures(*a))
    with pytest.raises(GeometryError):
        extruded(np.concatenate([SQUARE, HOLE]), triangles, walls, 0.0, 1.0, "frame", {})
    assert full


def test_a_facet_of_no_area_in_single_precision_is_left_to_the_full_check(monkeypatch):
    full = []
    monkeypatch.setattr(solid_module, "mesh_measures", lambda *a: full.append(a) or mesh_measures(*a))
    # a fifth corner a float32 step from the fourth: a wall quad and an end triangle of no area when written
    five = np.concatenate([SQUARE, [[0.0, 4.0 - 1e-9]]])
    with pytest.raises(GeometryError):
        extruded(five, [[0, 1, 2], [0, 2, 3], [0, 3, 4]], [Wall(5)], 0.0, 1.0, "sliver", {})
    assert full


def test_malformed_sections_raise():
    with pytest.raises(GeometryError, match="section"):
        extruded(SQUARE, [[0, 1, 9]], [Wall(4)], 0.0, 1.0, "bad", {})
    with pytest.raises(GeometryError, match="section"):
        extruded(SQUARE, [[0, 1, 2]], [Wall(2)], 0.0, 1.0, "bad", {})


def test_a_thin_extrusion_still_has_a_height_in_single_precision():
    """A width far below the radius (z = 1000 at 10 um) keeps every wall facet's area when written."""
    prof = tooth_profile(GearSpec(1000, 1.0))
    thin, thick = (gear_solid(prof, SolidSpec(width), 1e-3) for width in (0.01, 5.0))
    assert_measures_agree(thin, *thin.arrays())
    assert thin.volume / 0.01 == pytest.approx(thick.volume / 5.0, rel=REL)  # the same section


def test_the_structure_check_reports_its_progress_over_every_facet(capsys, monkeypatch):
    from gearkit.progress import Progress

    monkeypatch.setattr(Progress, "mode", "on")
    monkeypatch.setattr(Progress, "delay", 0.0)
    monkeypatch.setattr(measures_module, "CHUNK", 256)
    gear, spec, tol = STRAIGHT["keyway"]
    solid = gear_solid(tooth_profile(gear), spec, tol)
    assert f"mesh check [##############################] {solid.faces}/{solid.faces} facets" in capsys.readouterr().err
