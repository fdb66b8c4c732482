"""The mesh gallery under meshes/: rebuilt items keep their recorded invariants, and the stored files
measure as recorded (so an altered gallery mesh fails the check)."""
import importlib.util
import json
import shutil
from pathlib import Path

import numpy as np
import pytest
import trimesh

ROOT = Path(__file__).resolve().parents[1]
MESHES = ROOT / "meshes"
REL = 1e-9  # rebuilt invariants: same code and inputs, only floating-point noise may differ
SINGLE = 1e-6  # stored files hold single-precision (STL) or 9-digit (OBJ) coordinates


def _gallery():
    spec = importlib.util.spec_from_file_location("make_gallery", ROOT / "examples" / "make_gallery.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


GALLERY = _gallery()


def _close(a, b, rel, what, problems):
    a, b = np.asarray(a, float), np.asarray(b, float)
    scale = max(float(np.abs(b).max(initial=0.0)), 1.0)
    if a.shape != b.shape or not np.allclose(a, b, rtol=rel, atol=rel * scale):
        problems.append(f"{what}: {a.tolist()} != recorded {b.tolist()}")


def measure_file(path: Path) -> dict:
    """Invariants of a stored mesh file, per part, as trimesh reads it."""
    if path.suffix == ".obj":
        scene = trimesh.load(path, force="scene", split_objects=True, group_material=False)
        meshes = dict(scene.geometry)
    else:
        meshes = {None: trimesh.load(path, force="mesh")}
    out = {}
    for name, mesh in meshes.items():
        out[name] = {"volume": mesh.volume, "area": mesh.area, "bbox": mesh.bounds.tolist(),
                     "faces": len(mesh.faces), "watertight": bool(mesh.is_watertight)}
    return out


def check_gallery(directory: Path, rebuild: bool = True) -> list:
    """Mismatches between the recorded invariants, the stored files and (optionally) a rebuild."""
    problems = []
    records = sorted(directory.glob("*.json"))
    if sorted(r.stem for r in records) != sorted(GALLERY.ITEMS):
        problems.append(f"gallery items {[r.stem for r in records]} != {sorted(GALLERY.ITEMS)}")
    for rec_path in records:
        record = json.loads(rec_path.read_text())
        mesh_path = directory / record["file"]
        if mesh_path.stat().st_size >= 1 << 20:
            problems.append(f"{mesh_path.name} is larger than 1 MB")
        stored = measure_file(mesh_path)
        if set(stored) != set(record["parts"]) and list(stored) != [None]:
            problems.append(f"{mesh_path.name}: parts {sorted(stored)} != {sorted(record['parts'])}")
            continue
        for name, inv in record["parts"].items():
            got = stored[name] if name in stored else stored[None]
            where = f"{mesh_path.name}[{name}]"
            if not got["watertight"]:
                problems.append(f"{where}: not watertight")
            if got["faces"] != inv["faces"]:
                problems.append(f"{where}: {got['faces']} faces != recorded {inv['faces']}")
            for key in ("volume", "area", "bbox"):
                _close(got[key], inv[key], SINGLE, f"{where} {key}", problems)
        if rebuild and rec_path.stem in GALLERY.ITEMS:
            _, fresh = GALLERY.build(rec_path.stem)
            for name, inv in record["parts"].items():
                new = fresh["parts"].get(name)
                if new is None:
                    problems.append(f"rebuilt {rec_path.stem} has no part {name}")
                    continue
                if new["faces"] != inv["faces"]:
                    problems.append(f"rebuilt {rec_path.stem}[{name}]: {new['faces']} faces != {inv['faces']}")
                for key in ("volume", "area", "bbox", "tol", "achieved"):
                    _close(new[key], inv[key], REL, f"rebuilt {rec_path.stem}[{name}] {key}", problems)
                if new["achieved"] > new["tol"]:
                    problems.append(f"rebuilt {rec_path.stem}[{name}]: achieved {new['achieved']} > tol")
    return problems


def test_gallery_matches_its_invariants():
    assert check_gallery(MESHES) == []


@pytest.mark.parametrize("alteration", ["move_vertex", "drop_facets"])
def test_an_altered_gallery_mesh_fails_the_check(tmp_path, alteration):
    shutil.copytree(MESHES, tmp_path / "meshes")
    target = tmp_path / "meshes" / "helical_z20_m2_b10_beta20.stl"
    mesh = trimesh.load(target, force="mesh")
    if alteration == "move_vertex":  # a 0.05 mm dent in one vertex: still watertight, different volume
        v = mesh.vertices.copy()
        i = int(np.argmax(np.hypot(v[:, 0], v[:, 1])))
        v[i, :2] *= 1.0 - 0.05 / np.hypot(*v[i, :2])
        mesh = trimesh.Trimesh(v, mesh.faces, process=False)
    else:
        mesh = trimesh.Trimesh(mesh.vertices, mesh.faces[:-2], process=False)
    mesh.export(target)
    problems = check_gallery(tmp_path / "meshes", rebuild=False)
    assert problems and all("helical_z20" in p for p in problems)
