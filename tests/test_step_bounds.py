"""Issue 13, bounded STEP: the size of a STEP file's work is estimated before any of it (B-rep faces from
the recipes) and refused above the limit unless ``--max-points`` raises it; a bar follows the work; a gear
of many teeth has its end caps cut into sectors (a valid solid, the same volume and box) so that the
kernel's checks grow about linearly with the teeth.

The sectored caps are tested on small gears with the threshold lowered (the code path is the same as a
2000-tooth gear's, in a fraction of a second).
"""
import json

import pytest

from gearkit.cli import main
from gearkit.families.involute import GearSpec, ShaperCutter, tooth_profile
from gearkit.progress import Progress
from gearkit.solids import SolidSpec, gear_solid, rack_solid, write_mesh

OCP = pytest.importorskip("OCP", reason="the optional B-rep kernel is absent: pip install 'gearkit[step]'")

TOL = 0.01  # mm, requested deviation of the solids under test


def _faces(shape, plane_at=None):
    """Number of faces of a shape; with ``plane_at`` (z, mm), only the planar faces lying at that height."""
    from OCP.BRepAdaptor import BRepAdaptor_Surface
    from OCP.GeomAbs import GeomAbs_Plane
    from OCP.TopAbs import TopAbs_FACE
    from OCP.TopExp import TopExp_Explorer
    from OCP.TopoDS import TopoDS

    from gearkit.solids import brep

    exp, n = TopExp_Explorer(shape, TopAbs_FACE), 0
    while exp.More():
        face = TopoDS.Face(exp.Current())
        if plane_at is None:
            n += 1
        elif BRepAdaptor_Surface(face).GetType() == GeomAbs_Plane:
            (_, _, z0), (_, _, z1) = brep.bounds(face)
            n += abs(z0 - plane_at) < 1e-6 and abs(z1 - plane_at) < 1e-6
        exp.Next()
    return n


BODIES = [
    ("spur, bore and keyway", GearSpec(40, 1.0), SolidSpec(4.0, bore=12.0, keyway=(3.0, 1.4))),
    ("double helical, gap", GearSpec(40, 1.0, helix_angle_deg=15.0),
     SolidSpec(9.0, helix_angle_deg=15.0, herringbone=True, gap=2.0, bore=10.0)),
    ("helical ring", GearSpec(48, 1.0, helix_angle_deg=10.0, internal=True, tool=ShaperCutter(12)), SolidSpec(5.0)),
    ("herringbone ring, gap", GearSpec(48, 1.0, helix_angle_deg=10.0, internal=True, tool=ShaperCutter(12)),
     SolidSpec(6.0, herringbone=True, gap=2.0)),
]


@pytest.mark.parametrize("what, gear, body", BODIES, ids=[b[0] for b in BODIES])
def test_sectored_end_caps_make_the_same_valid_solid(tmp_path, monkeypatch, what, gear, body):
    from OCP.BRepCheck import BRepCheck_Analyzer

    from gearkit.solids import brep, shapes
    from gearkit.solids.step import read_step

    monkeypatch.setattr(shapes, "SECTOR_ABOVE", 100)  # a 40-tooth gear's 320 cap edges are cut into sectors
    solid = gear_solid(tooth_profile(gear), body, TOL)
    write_mesh(tmp_path / "g.step", [solid])
    (_, shape), = read_step(tmp_path / "g.step")
    assert brep.count_solids(shape) == 1 and BRepCheck_Analyzer(shape).IsValid()
    # the mesh and the B-rep both lie within tol of the exact surface: volumes within 2 tol x area
    assert abs(brep.volume(shape) - solid.volume) <= 2.0 * TOL * solid.area
    lo, hi = brep.bounds(shape)
    assert all(abs(a - b) <= TOL for a, b in zip(tuple(lo) + tuple(hi), tuple(solid.bounds[0]) + tuple(solid.bounds[1])))
    # the cap at z = 0 is several faces: sqrt(teeth / faces per tooth) teeth a sector, and the core; the
    # halves of a double-helical gear are fused to their core or groove, and the fuse unifies coplanar faces
    teeth, per_tooth = gear.teeth, 2 * len(tooth_profile(gear).half.pieces)
    sectors = -(-teeth // max(1, round((teeth / per_tooth) ** 0.5)))
    assert _faces(shape, plane_at=0.0) == (1 if body.gap else sectors + 1)


@pytest.mark.parametrize("make", [
    lambda: gear_solid(tooth_profile(GearSpec(30, 1.0)), SolidSpec(4.0), TOL),
    lambda: gear_solid(tooth_profile(GearSpec(40, 1.0, helix_angle_deg=12.0)),
                       SolidSpec(6.0, helix_angle_deg=12.0, herringbone=True), TOL),
    lambda: gear_solid(tooth_profile(GearSpec(60, 1.0)), SolidSpec(4.0, bore=20.0), TOL),
    lambda: rack_solid(_rack(), length=30.0,
                       height=5.0, width=4.0, tol=TOL),
], ids=["spur", "herringbone", "sectored spur with bore", "rack bar"])
def test_the_face_estimate_is_the_built_count(make):
    """The estimate the command line bounds (from the recipe, before any face is made) is within 20 % of
    the faces the B-rep really has (above it, never far below)."""
    from gearkit.solids.step import estimate_faces, shape

    part = make()
    built = _faces(shape(part.recipe)[0])
    estimate = estimate_faces([part])
    assert 0.95 * built <= estimate <= 1.2 * built + 10


def _rack():
    from gearkit.families.involute import RackSpec, rack_profile

    return rack_profile(RackSpec(module=1.0))


def test_a_big_step_file_is_refused_before_any_work(tmp_path, capsys):
    out = tmp_path / "g.step"
    assert main(["gear", "-z", "2000", "-m", "1", "--width", "5", "-o", str(out)]) == 2
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0 and "B-rep faces" in err and "--max-points" in err and "1.6e+04" in err
    assert not out.exists() and list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("argv", [
    ["gear", "-z", "20", "-m", "1", "--width", "3"],
    ["pair", "--z1", "12", "--z2", "20", "-m", "1", "--width", "3"],
])
def test_max_points_raises_the_step_limit(tmp_path, capsys, argv):
    out = str(tmp_path / "p.step")
    assert main(["--max-points", "100", *argv, "-o", out]) == 2  # 20 teeth x 8 faces and more
    assert "--max-points" in capsys.readouterr().err and list(tmp_path.iterdir()) == []
    assert main(["--max-points", "5000", *argv, "-o", out, "--json"]) == 0
    json.loads(capsys.readouterr().out)
    from gearkit.solids.step import read_step

    assert len(read_step(out)) >= 1


def test_a_step_export_draws_the_bar(tmp_path, capsys, monkeypatch):
    monkeypatch.setattr(Progress, "delay", 0.0)
    argv = ["gear", "-z", "20", "-m", "1", "--width", "3", "-o", str(tmp_path / "g.step"), "--json"]
    assert main(["--progress", *argv]) == 0
    out, err = capsys.readouterr()
    assert "STEP [##############################] 100%" in err and "writing the file\n" in err
    json.loads(out)
    assert main(argv) == 0  # no terminal, no --progress: no bar
    assert "STEP [" not in capsys.readouterr().err
