"""The numpy mesh check (``gearkit.solids.measures.mesh_measures``) against plain second methods.

Oracles: a unit cube's volume and area (closed form); for a gear mesh spanning several chunks of
facets, the edges counted one by one in a dictionary (every directed edge once, its reverse once),
the volume and area from ``np.cross`` over all facets at once (divergence theorem), and the
normals from ``np.cross`` of the single-precision vertices. Tolerances: the volume and area sum the
same products in another order, so they agree to ``REL = 1e-12`` relative; the normals are formed
from the same exact differences, so to the bit.
"""
from collections import Counter

import numpy as np
import pytest

from gearkit.errors import GeometryError
from gearkit.families.involute import GearSpec, tooth_profile
from gearkit.solids import SolidSpec, gear_solid
from gearkit.solids import measures as measures_module
from gearkit.solids.measures import mesh_measures

REL = 1e-12

CUBE_V = np.array([[x, y, z] for x in (0.0, 1.0) for y in (0.0, 1.0) for z in (0.0, 1.0)])
CUBE_F = np.array([[0, 1, 3], [0, 3, 2], [4, 6, 7], [4, 7, 5], [0, 4, 5], [0, 5, 1],
                   [2, 3, 7], [2, 7, 6], [0, 2, 6], [0, 6, 4], [1, 5, 7], [1, 7, 3]])


def test_a_cube_measures_its_closed_form():
    m = mesh_measures(CUBE_V, CUBE_F)
    assert m["volume"] == pytest.approx(1.0, rel=REL)
    assert m["area"] == pytest.approx(6.0, rel=REL)


@pytest.mark.parametrize("faces", [
    CUBE_F[:-1],  # an open box: an odd count of edges
    np.concatenate([CUBE_F[:-1], CUBE_F[-1:, ::-1]]),  # one facet turned over
    np.concatenate([CUBE_F, CUBE_F[:2]]),  # two facets twice
    np.concatenate([CUBE_F, CUBE_F[:2, ::-1]]),  # a flat double wall
], ids=["open", "turned", "repeated", "double wall"])
def test_a_mesh_that_is_not_closed_and_oriented_is_refused(faces):
    with pytest.raises(GeometryError):
        mesh_measures(CUBE_V, faces)


def test_a_gear_mesh_over_many_chunks_agrees_with_plain_numpy(monkeypatch):
    monkeypatch.setattr(measures_module, "CHUNK", 4096)  # chunks of facets, and of the sorted edge pairs
    solid = gear_solid(tooth_profile(GearSpec(200, 1.0)), SolidSpec(5.0), 1e-3)
    v, f = solid.arrays()
    assert len(f) > 2 * measures_module.CHUNK
    directed = Counter(zip(f.ravel().tolist(), f[:, (1, 2, 0)].ravel().tolist()))
    assert all(n == 1 and directed[(b, a)] == 1 for (a, b), n in directed.items())
    m = mesh_measures(v, f)
    p = v[f]
    n = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])
    assert m["volume"] == pytest.approx(np.einsum("ij,ij->", p[:, 0], n) / 6.0, rel=REL)
    assert m["area"] == pytest.approx(0.5 * np.linalg.norm(n, axis=1).sum(), rel=REL)
    s = v.astype(np.float32).astype(np.float64)[f]
    ns = np.cross(s[:, 1] - s[:, 0], s[:, 2] - s[:, 0])
    assert np.array_equal(m["normals"], (ns / np.linalg.norm(ns, axis=1)[:, None]).astype(np.float32))
