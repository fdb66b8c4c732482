"""STEP round trips: every part re-reads as one valid solid (or the bodies it is made of), with its
name, a volume and bounding box that agree with the mesh and with the exact section area
(Cavalieri), and B-spline flanks within tol of the exact tooth surface; 3MF packages re-read
with the standard library; the missing kernel is one clear error.

Without the optional kernel (``pip install 'gearkit[step]'``) the STEP tests skip locally; under
CI (``CI`` set) a missing kernel fails them.
"""
import math
import os
import sys
import xml.etree.ElementTree as ET
import zipfile

import numpy as np
import pytest

from gearkit.cli import main
from gearkit.distances import distances_to_polyline
from gearkit.errors import SpecError
from gearkit.families.involute import GearSpec, tooth_profile
from gearkit.solids import SolidSpec, gear_solid, write_mesh

try:
    import OCP  # noqa: F401
    HAVE_OCP = True
except ImportError:  # pragma: no cover - the kernel is an optional extra
    HAVE_OCP = False
    if os.environ.get("CI"):
        raise RuntimeError("CI must install gearkit[step] (the B-rep kernel)") from None

needs_ocp = pytest.mark.skipif(not HAVE_OCP, reason="the optional B-rep kernel is absent: pip install 'gearkit[step]'")

TOL = 0.01  # mm, requested deviation of the solids under test
REF = TOL / 100  # mm, chord tolerance of the dense exact reference outline


def _shoelace(p):
    return 0.5 * float(np.dot(p[:, 0], np.roll(p[:, 1], -1)) - np.dot(p[:, 1], np.roll(p[:, 0], -1)))


def _read(path):
    from gearkit.solids.step import read_step

    return read_step(path)


def _agree(shape, solid, tol=TOL, solids=1):
    """One valid solid (or ``solids``), volume within 2 tol x area of the mesh's, bounding box within tol."""
    from OCP.BRepCheck import BRepCheck_Analyzer

    from gearkit.solids import brep

    assert brep.count_solids(shape) == solids
    assert BRepCheck_Analyzer(shape).IsValid()
    # both surfaces lie within tol of the exact one: the volumes differ by at most 2 tol x area
    assert abs(brep.volume(shape) - solid.volume) <= 2.0 * tol * solid.area
    lo, hi = brep.bounds(shape)
    mlo, mhi = solid.bounds
    assert np.allclose(lo, mlo, atol=tol) and np.allclose(hi, mhi, atol=tol)


def _flank_points(shape, n=9):
    """Points on every B-spline face of a shape, sampled on an n x n grid of its parameters."""
    from OCP.BRep import BRep_Tool
    from OCP.BRepAdaptor import BRepAdaptor_Surface
    from OCP.GeomAbs import GeomAbs_BSplineSurface
    from OCP.TopAbs import TopAbs_FACE
    from OCP.TopExp import TopExp_Explorer
    from OCP.TopoDS import TopoDS

    pts, faces = [], 0
    exp = TopExp_Explorer(shape, TopAbs_FACE)
    while exp.More():
        face = TopoDS.Face(exp.Current())
        ad = BRepAdaptor_Surface(face)
        if ad.GetType() == GeomAbs_BSplineSurface:
            faces += 1
            surf = BRep_Tool.Surface_s(face)
            u0, u1, v0, v1 = surf.Bounds()
            for u in np.linspace(u0, u1, n):
                for v in np.linspace(v0, v1, n):
                    p = surf.Value(float(u), float(v))
                    pts.append((p.X(), p.Y(), p.Z()))
        exp.Next()
    return np.array(pts), faces


def _flank_deviation(shape, prof, k):
    """Largest distance of the shape's B-spline faces from the exact helical tooth surface, mm:
    each point turned back by theta(z) = k z and measured against the dense exact outline."""
    pts, faces = _flank_points(shape)
    th = -k * pts[:, 2]
    c, s = np.cos(th), np.sin(th)
    q = np.stack([c * pts[:, 0] - s * pts[:, 1], s * pts[:, 0] + c * pts[:, 1]], -1)
    return float(distances_to_polyline(q, prof.outline(REF), closed=True).max()), faces


@needs_ocp
def test_readme_helical_gear_round_trip(tmp_path):
    """The README's helical gear: one solid named 'gear', volume within 0.1 % of the mesh's, flanks
    within tol of the exact surface, the CLI reporting the achieved deviation."""
    path = tmp_path / "gear.step"
    assert main(["gear", "-z", "20", "-m", "2", "--width", "10", "--helix-angle-deg", "20", "--bore", "8",
                 "--keyway", "3x1.4", "--tol", str(TOL), "-o", str(path), "--json"]) == 0
    prof = tooth_profile(GearSpec(20, 2.0, helix_angle_deg=20))
    mesh = gear_solid(prof, SolidSpec(10.0, bore=8.0, keyway=(3.0, 1.4)), TOL)
    parts = _read(path)
    assert [name for name, _ in parts] == ["gear"]
    shape = parts[0][1]
    _agree(shape, mesh)
    from gearkit.solids import brep

    assert abs(brep.volume(shape) - mesh.volume) <= 1e-3 * mesh.volume
    k = math.tan(math.radians(20)) / (prof.reference_diameter / 2)
    dev, faces = _flank_deviation(shape, prof, k)
    assert faces >= 20 * 8  # every tooth has its own flank, fillet, tip and root faces
    assert dev <= TOL + REF


@needs_ocp
def test_volume_is_section_area_times_width(tmp_path):
    """Cavalieri: a twisted prism's volume is its section area times its width (exact, no mesh)."""
    from gearkit.solids import brep
    from gearkit.solids.step import gear_shape

    prof = tooth_profile(GearSpec(11, 1.5, helix_angle_deg=-25))
    shape, achieved = gear_shape(prof, SolidSpec(7.0), TOL)
    outline = prof.outline(REF)
    area = _shoelace(outline)
    perimeter = float(np.linalg.norm(outline - np.roll(outline, -1, axis=0), axis=1).sum())
    assert achieved <= TOL
    assert abs(brep.volume(shape) - 7.0 * area) <= 7.0 * perimeter * (achieved + REF)


@needs_ocp
@pytest.mark.parametrize("body", [
    SolidSpec(8.0, helix_angle_deg=15.0, herringbone=True),
    SolidSpec(9.0, helix_angle_deg=15.0, herringbone=True, gap=2.0, bore=6.0),
])
def test_herringbone_and_double_helical(tmp_path, body):
    prof = tooth_profile(GearSpec(14, 1.5, helix_angle_deg=15))
    solid = gear_solid(prof, body, TOL)
    write_mesh(tmp_path / "g.step", [solid])
    (name, shape), = _read(tmp_path / "g.step")
    assert name == "gear"
    _agree(shape, solid)


@needs_ocp
@pytest.mark.parametrize("herringbone", [False, True])
def test_ring_gear(tmp_path, herringbone):
    from gearkit.families.involute import ShaperCutter

    prof = tooth_profile(GearSpec(24, 1.0, helix_angle_deg=10, internal=True, tool=ShaperCutter(12)))
    solid = gear_solid(prof, SolidSpec(6.0, herringbone=herringbone, gap=2.0 if herringbone else 0.0), TOL)
    write_mesh(tmp_path / "ring.stp", [solid])
    (_, shape), = _read(tmp_path / "ring.stp")
    _agree(shape, solid)


@needs_ocp
def test_pair_assembly_names_and_placement(tmp_path):
    """A pair's STEP is an assembly of the placed, named parts (the mesh export's placement)."""
    path = tmp_path / "pair.step"
    assert main(["pair", "--z1", "9", "--z2", "14", "-m", "1.5", "--width", "5", "--helix-angle-deg", "12",
                 "--tol", str(TOL), "--angle-deg", "7", "-o", str(path)]) in (0, 1)
    from gearkit.pair import PairSpec
    from gearkit.solids import pair_assembly

    asm = pair_assembly(PairSpec(9, 14, 1.5, helix_angle_deg=12, face_width=5.0), tol=TOL)
    placed = asm.placed(math.radians(7))
    parts = _read(path)
    assert [n for n, _ in parts] == ["pinion", "wheel"]
    for (_, shape), solid in zip(parts, placed):
        _agree(shape, solid)


@needs_ocp
def test_rack_pair_and_helical_rack(tmp_path):
    path = tmp_path / "rp.step"
    assert main(["pair", "--z1", "10", "-m", "2", "--rack-pair", "--width", "6", "--helix-angle-deg", "10",
                 "--tol", str(TOL), "-o", str(path)]) in (0, 1)
    assert [n for n, _ in _read(path)] == ["pinion", "rack"]
    from gearkit.families.involute import RackSpec, rack_profile
    from gearkit.solids import rack_solid

    bar = rack_solid(rack_profile(RackSpec(2.0, helix_angle_deg=10.0)), 30.0, 8.0, 6.0, TOL, start=-3.0)
    write_mesh(tmp_path / "rack.step", [bar])
    (_, shape), = _read(tmp_path / "rack.step")
    _agree(shape, bar)


@needs_ocp
def test_cycloid_drive_parts(tmp_path):
    """Disc with its bore and output holes, pins (one body each), housing, output pins: named and valid."""
    from gearkit.families.cycloidal import DriveSpec
    from gearkit.solids.drive import drive_parts

    spec = DriveSpec(8, 7, 40.0, 3.0, 1.5)
    parts = drive_parts(spec, 6.0, TOL)
    write_mesh(tmp_path / "drive.step", parts)
    read = dict(_read(tmp_path / "drive.step"))
    assert list(read) == [p.name for p in parts]
    for part in parts:
        _agree(read[part.name], part, solids=len(part.manifold.decompose()))
    assert len(parts[1].manifold.decompose()) == 8  # the pins


@needs_ocp
def test_novikov_pair(tmp_path):
    path = tmp_path / "nov.step"
    assert main(["novikov", "--z1", "12", "--z2", "18", "-m", "2", "--helix-angle-deg", "20", "--width", "16",
                 "--no-mesh", "--tol", str(TOL), "-o", str(path)]) in (0, 1)
    assert [n for n, _ in _read(path)] == ["gear1", "gear2"]


def _cam_outline():
    """An exact closed outline of two pieces: a base-circle arc and a rise, as a cam would give it."""
    def base(w):
        a = np.pi * (1.0 + np.asarray(w, float))  # the lower half, radius 20
        return 20.0 * np.stack([np.cos(a), np.sin(a)], -1)

    def lobe(w):  # the upper half, radius growing to 26 at the top and back (smooth at the ends)
        a = np.pi * np.asarray(w, float)
        r = 20.0 + 6.0 * np.sin(a) ** 2
        return np.stack([r * np.cos(a), r * np.sin(a)], -1)
    return [base, lobe]


@needs_ocp
def test_generic_prism_plugs_in(tmp_path):
    """A family's own exact outline: mesh, 3MF and STEP from prism_solid; the STEP volume is the exact
    section area (polar integral, less the bore and keyway) times the width."""
    from gearkit.solids import brep, prism_solid

    cam = prism_solid(_cam_outline(), SolidSpec(8.0, bore=10.0, keyway=(3.0, 1.2)), TOL, name="cam")
    write_mesh(tmp_path / "cam.3mf", [cam])
    write_mesh(tmp_path / "cam.step", [cam])
    (name, shape), = _read(tmp_path / "cam.step")
    assert name == "cam"
    _agree(shape, cam)
    r, h = 5.0, 1.5  # bore radius, keyway half width: the keyway adds w (r + depth) less the circle under it
    hole = math.pi * r ** 2 + 3.0 * (r + 1.2) - (h * math.sqrt(r ** 2 - h ** 2) + r ** 2 * math.asin(h / r))
    a = np.linspace(0.0, np.pi, 200001)
    r2 = (20.0 + 6.0 * np.sin(a) ** 2) ** 2
    area = 0.5 * np.pi * 20.0 ** 2 + 0.5 * float(((r2[1:] + r2[:-1]) / 2 * np.diff(a)).sum())
    perimeter = 2 * np.pi * 23.0  # more than the outline's length
    assert abs(brep.volume(shape) - 8.0 * (area - hole)) <= 8.0 * perimeter * TOL


@needs_ocp
def test_clockwise_outline_makes_the_same_prism(tmp_path):
    """A loop given clockwise (as a cam turning the other way lists it) gives the same solid."""
    from gearkit.solids import brep, prism_solid
    from gearkit.solids.step import shape

    ccw = prism_solid(_cam_outline(), SolidSpec(4.0), TOL)
    cw = prism_solid([lambda w, c=c: c(1.0 - np.asarray(w)) for c in _cam_outline()[::-1]], SolidSpec(4.0), TOL)
    assert cw.volume == pytest.approx(ccw.volume, rel=1e-9)
    solid, _ = shape(cw.recipe)
    _agree(solid, ccw)


@needs_ocp
def test_cam_step_round_trip(tmp_path):
    """A generated cam with its bore and keyway: one valid solid named 'cam', agreeing with the mesh."""
    from gearkit.cli.common import keyway_from_arg
    from gearkit.families.cam import CamSpec, MotionProgram, cam_profile
    from gearkit.solids.cam import cam_solid

    path = tmp_path / "cam.step"
    flags = ["--prime-radius", "40", "--roller-radius", "8", "--rise", "10", "--rise-deg", "90", "--return-deg", "90",
             "--width", "10", "--bore", "12", "--keyway", "4x1.5", "--tol", str(TOL)]
    assert main(["cam", *flags, "-o", str(path)]) == 0
    spec = CamSpec(40.0, MotionProgram.rise_dwell_return(10.0, 90.0, 0.0, 90.0), roller_radius=8.0)
    mesh = cam_solid(cam_profile(spec), SolidSpec(10.0, bore=12.0, keyway=keyway_from_arg("4x1.5")), TOL)
    (name, shape), = _read(path)
    assert name == "cam"
    _agree(shape, mesh)


@needs_ocp
def test_part_without_recipe_writes_nothing(tmp_path):
    from gearkit.solids import Solid

    g = gear_solid(tooth_profile(GearSpec(10, 1.0)), SolidSpec(3.0), TOL)
    bare = Solid(g.manifold, "bare", g.info)
    with pytest.raises(SpecError, match="bare"):
        write_mesh(tmp_path / "x.step", [bare])
    assert list(tmp_path.iterdir()) == []


def test_missing_kernel_names_the_extra(tmp_path, monkeypatch, capsys):
    monkeypatch.setitem(sys.modules, "OCP", None)
    monkeypatch.setitem(sys.modules, "OCP.BRepBuilderAPI", None)
    rc = main(["gear", "-z", "10", "-m", "1", "--width", "3", "-o", str(tmp_path / "g.step")])
    err = capsys.readouterr().err.strip().splitlines()
    assert rc == 2 and len(err) == 1 and "pip install 'gearkit[step]'" in err[0]
    assert list(tmp_path.iterdir()) == []


def test_3mf_package_round_trip(tmp_path):
    """A real 3MF package (content types, relationships, model in mm), named objects, the exact mesh."""
    from gearkit.solids import pair_assembly
    from gearkit.pair import PairSpec

    asm = pair_assembly(PairSpec(9, 14, 1.5, face_width=4.0), tol=TOL)
    parts = asm.placed(0.0)
    path = tmp_path / "pair.3mf"
    assert main(["pair", "--z1", "9", "--z2", "14", "-m", "1.5", "--width", "4", "--tol", str(TOL),
                 "-o", str(path)]) in (0, 1)
    with zipfile.ZipFile(path) as zf:
        assert {"[Content_Types].xml", "_rels/.rels", "3D/3dmodel.model"} <= set(zf.namelist())
        rels = ET.fromstring(zf.read("_rels/.rels"))
        model = ET.fromstring(zf.read("3D/3dmodel.model"))
    assert rels[0].get("Target") == "/3D/3dmodel.model"
    ns = {"m": "http://schemas.microsoft.com/3dmanufacturing/core/2015/02"}
    assert model.get("unit") == "millimeter"
    objects = model.findall("m:resources/m:object", ns)
    assert [o.get("name") for o in objects] == ["pinion", "wheel"]
    assert len(model.findall("m:build/m:item", ns)) == 2
    for obj, solid in zip(objects, parts):
        v = np.array([[float(e.get(a)) for a in "xyz"] for e in obj.findall("m:mesh/m:vertices/m:vertex", ns)])
        f = np.array([[int(e.get(a)) for a in ("v1", "v2", "v3")]
                      for e in obj.findall("m:mesh/m:triangles/m:triangle", ns)])
        t = v[f]
        volume = float(np.einsum("ij,ij->i", t[:, 0], np.cross(t[:, 1], t[:, 2])).sum()) / 6.0
        assert len(f) == solid.faces
        # 9 significant digits per coordinate: the volume agrees to ~1e-8 relative
        assert volume == pytest.approx(solid.volume, rel=1e-6)
