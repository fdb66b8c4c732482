"""Mesh export: STL (binary and ASCII), OBJ and GLB round trips through trimesh; atomic writes."""
import numpy as np
import pytest
import trimesh

from gearkit.errors import SpecError
from gearkit.families.involute import GearSpec, tooth_profile
from gearkit.pair import PairSpec
from gearkit.solids import SolidSpec, gear_solid, pair_assembly, write_mesh
from gearkit.solids import export as mesh_export

SINGLE = 1e-6  # relative change of volume and area from storing coordinates in single precision


@pytest.fixture(scope="module")
def gear():
    prof = tooth_profile(GearSpec(17, 1.5, helix_angle_deg=12.0))
    return gear_solid(prof, SolidSpec(6.0, bore=5.0, keyway=(2.0, 0.8)), 5e-3, name="gear17")


@pytest.mark.parametrize("ext,ascii", [("stl", False), ("stl", True), ("obj", False), ("glb", False)])
def test_round_trip_is_watertight_with_the_same_volume(tmp_path, gear, ext, ascii):
    path = write_mesh(tmp_path / f"g.{ext}", [gear], ascii=ascii)
    mesh = trimesh.load(path, force="mesh")
    assert mesh.is_watertight and mesh.is_winding_consistent
    assert len(mesh.faces) == gear.faces
    assert mesh.volume == pytest.approx(gear.volume, rel=SINGLE)
    assert mesh.area == pytest.approx(gear.area, rel=SINGLE)
    lo, hi = gear.bounds
    assert np.allclose(mesh.bounds, [lo, hi], atol=1e-5)
    assert not list(tmp_path.glob("*.part"))


def test_binary_stl_layout(tmp_path, gear):
    data = write_mesh(tmp_path / "g.stl", [gear]).read_bytes()
    assert not data.startswith(b"solid")  # else some readers take it for ASCII
    count = int(np.frombuffer(data[80:84], "<u4")[0])
    assert count == gear.faces and len(data) == 84 + 50 * count
    text = write_mesh(tmp_path / "a.stl", [gear], ascii=True).read_text()
    assert text.startswith("solid gear17\n") and text.rstrip().endswith("endsolid gear17")


def test_binary_stl_records_are_each_facets_normal_and_corners_in_single_precision(tmp_path, gear):
    """Read back with numpy's own record type: every facet, over several chunks and two parts, is its
    float32 normal, its three float32 corners in order, and a zero attribute."""
    spur = gear_solid(tooth_profile(GearSpec(150, 1.0)), SolidSpec(3.0), 1e-3, name="spur150")
    assert spur.faces > 2 * mesh_export.CHUNK
    data = write_mesh(tmp_path / "two.stl", [gear, spur]).read_bytes()
    record = np.dtype([("normal", "<f4", (3,)), ("corners", "<f4", (3, 3)), ("attribute", "<u2")])
    read = np.frombuffer(data, dtype=record, offset=84)
    assert int(np.frombuffer(data[80:84], "<u4")[0]) == len(read) == gear.faces + spur.faces
    at = 0
    for part in (gear, spur):
        v, f = part.arrays()
        rows = read[at:at + len(f)]
        assert np.array_equal(rows["corners"], v.astype(np.float32)[f])
        assert np.array_equal(rows["normal"], part.normals())
        at += len(f)
    assert not read["attribute"].any()


def test_assembly_obj_and_glb_keep_named_parts(tmp_path):
    asm = pair_assembly(PairSpec(14, 25, 1.0, 0.3, 0.0, thinning1=0.05, thinning2=0.05), width=4.0, tol=0.01)
    for ext in ("obj", "glb"):
        path = asm.export(tmp_path / f"pair.{ext}")
        scene = trimesh.load(path, force="scene", split_objects=True, group_material=False)
        assert set(scene.geometry) == {"pinion", "wheel"}
        placed = dict(zip(("pinion", "wheel"), asm.placed()))
        for name, mesh in scene.geometry.items():  # the parts are placed in the vertices (identity nodes)
            assert mesh.is_watertight and len(mesh.faces) == placed[name].faces
            assert mesh.volume == pytest.approx(placed[name].volume, rel=SINGLE)
            assert np.allclose(mesh.bounds, np.array(placed[name].bounds), atol=1e-4)


def test_a_failed_export_leaves_no_file_and_keeps_the_old_one(tmp_path, gear, monkeypatch):
    target = tmp_path / "g.stl"
    target.write_bytes(b"old")

    real = mesh_export._stl_records

    def broken(parts, chunk=64):  # fails after the first chunk is written: a partial file exists then
        yield next(real(parts, chunk))
        raise RuntimeError("disk full")

    monkeypatch.setattr(mesh_export, "_stl_records", broken)
    with pytest.raises(RuntimeError):
        write_mesh(target, [gear])
    with pytest.raises(RuntimeError):
        write_mesh(tmp_path / "new.stl", [gear])
    assert target.read_bytes() == b"old"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["g.stl"]


def test_bad_export_requests(tmp_path, gear):
    with pytest.raises(SpecError, match="unknown mesh format"):
        write_mesh(tmp_path / "g.ply", [gear])
    with pytest.raises(SpecError, match="ascii"):
        write_mesh(tmp_path / "g.obj", [gear], ascii=True)
    with pytest.raises(SpecError, match="names"):
        write_mesh(tmp_path / "g.obj", [gear, gear])
    with pytest.raises(SpecError, match="directory"):
        write_mesh(tmp_path / "missing" / "g.stl", [gear])
    assert not list(tmp_path.iterdir())
