"""`gearkit gear` with a mesh output and `gearkit pair`, in process; the plain STL path's imports."""
import json
import math
import re
import subprocess
import sys
from pathlib import Path

import pytest
import trimesh

from gearkit.cli import main

ROOT = Path(__file__).resolve().parents[1]


def _json(capsys, argv, code=0):
    assert main(argv) == code
    return json.loads(capsys.readouterr().out)


def test_helical_stl_with_bore_and_keyway(tmp_path, capsys):
    out = tmp_path / "gear.stl"
    info = _json(capsys, ["gear", "-z", "20", "-m", "2", "--helix-angle-deg", "20", "--width", "10", "--bore", "8",
                          "--keyway", "3x1.4", "--tol", "0.01", "-o", str(out), "--json"])
    solid = info["solid"]
    assert solid["kind"] == "helical" and solid["hand"] == "right" and solid["layers"] >= 2
    assert solid["achieved"] <= solid["tol"] == 0.01
    mesh = trimesh.load(out)
    assert mesh.is_watertight and len(mesh.faces) == solid["faces"]
    assert mesh.volume == pytest.approx(solid["volume"], rel=1e-6)
    assert info["reference_diameter"] == pytest.approx(40 / math.cos(math.radians(20)))


def test_herringbone_ring_obj_and_table(tmp_path, capsys):
    out = tmp_path / "ring.obj"
    assert main(["gear", "-z", "60", "-m", "1", "--internal", "--cutter-teeth", "24", "--helix-angle-deg", "-15",
                 "--width", "12", "--herringbone", "--gap", "2", "--outer-diameter", "72", "--tol", "0.01",
                 "-o", str(out)]) == 0
    text = capsys.readouterr().out
    assert "double-helical ring" in text and "accuracy                 requested 0.01 mm" in text
    mesh = trimesh.load(out, force="mesh")
    assert mesh.is_watertight
    assert mesh.bounds[1][0] == pytest.approx(36.0, abs=1e-6)


def test_solid_flags_need_a_mesh_output_and_a_width(tmp_path, capsys):
    assert main(["gear", "-z", "20", "-m", "2", "--width", "5", "-o", str(tmp_path / "g.svg")]) == 2
    assert "--width" in capsys.readouterr().err
    assert main(["gear", "-z", "20", "-m", "2", "-o", str(tmp_path / "g.stl")]) == 2
    assert "--width" in capsys.readouterr().err
    assert main(["gear", "-z", "20", "-m", "2", "--width", "5", "--bore", "4", "--keyway", "3-1",
                 "-o", str(tmp_path / "g.stl")]) == 2
    assert "WIDTHxDEPTH" in capsys.readouterr().err
    assert main(["gear", "-z", "20", "-m", "2", "--width", "5", "--bore", "60", "-o", str(tmp_path / "g.stl")]) == 2
    assert "bore" in capsys.readouterr().err
    assert not list(tmp_path.iterdir())


def test_pair_command_exports_named_parts_and_reports_interference(tmp_path, capsys):
    out = tmp_path / "pair.obj"
    flags = ["pair", "--z1", "18", "--z2", "31", "-m", "2", "--thinning1", "0.08", "--thinning2", "0.08",
             "--width", "6", "--tol", "0.01"]
    info = _json(capsys, flags + ["--sweep", "5", "-o", str(out), "--json"])
    assert [p["name"] for p in info["parts"]] == ["pinion", "wheel"]
    assert info["interference"] == 0.0 and max(info["sweep"]["interference"]) == 0.0
    assert info["achieved"] <= info["tol"] and info["faces"] == sum(p["faces"] for p in info["parts"])
    scene = trimesh.load(out, force="scene", split_objects=True, group_material=False)
    assert set(scene.geometry) == {"pinion", "wheel"}
    tight = _json(capsys, flags + ["--center-distance", "48.2", "--x1", "0", "--x2", "0", "--json"], code=1)
    assert tight["interference"] > 0.0


def test_pair_command_takes_a_design_file_and_writes_glb(tmp_path, capsys):
    out = tmp_path / "pair.glb"
    code = main(["pair", str(ROOT / "examples" / "design.toml"), "--width", "8", "--tol", "0.02", "-o", str(out)])
    text = capsys.readouterr().out
    assert code in (0, 1) and "interference at 0 deg" in text
    assert set(trimesh.load(out, force="scene").geometry) >= {"pinion"}
    assert main(["pair", "--z1", "18", "--z2", "31", "-m", "2", "--width", "5", "-o", str(tmp_path / "p.svg")]) == 2


def test_plain_stl_export_imports_neither_trimesh_nor_scipy(tmp_path):
    code = ("import sys; from gearkit.cli import main; "
            f"main(['gear', '-z', '12', '-m', '2', '--width', '5', '-o', {str(tmp_path / 'g.stl')!r}]); "
            "print(sorted(m for m in ('trimesh', 'scipy') if m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip().splitlines()[-1] == "[]"


def test_only_the_solids_and_the_oracle_import_the_mesh_libraries():
    pattern = re.compile(r"^\s*(import|from)\s+(manifold3d|trimesh)\b", re.M)
    offenders = []
    for path in (ROOT / "gearkit").rglob("*.py"):
        rel = path.relative_to(ROOT / "gearkit").as_posix()
        if rel.startswith("solids/") or rel.startswith("oracles/"):
            continue
        if pattern.search(path.read_text()):
            offenders.append(rel)
    assert offenders == []


def test_the_stl_command_samples_the_tooth_surface_once(tmp_path, capsys, monkeypatch):
    """``gearkit gear -o x.stl`` plans the tooth surface once: it sizes the solid from the plan and builds
    the solid from it (it sampled the tooth a second time for the size)."""
    import gearkit.solids.gear as gear_module
    from gearkit.families.involute import GearSpec, tooth_profile
    from gearkit.solids import SolidSpec

    calls = []
    sample = gear_module.tooth_polyline
    monkeypatch.setattr(gear_module, "tooth_polyline", lambda *a, **k: calls.append(a[1]) or sample(*a, **k))
    gear_module.gear_plan(tooth_profile(GearSpec(12, 2.0)), SolidSpec(5.0), 0.001)
    planned, calls[:] = list(calls), []
    assert main(["gear", "-z", "12", "-m", "2", "--width", "5", "--tol", "0.001", "-o", str(tmp_path / "z12.stl")]) == 0
    assert calls == planned and len(planned) >= 1
