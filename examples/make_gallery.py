"""Write gearkit's reference mesh gallery: small meshes with their invariants (JSON) beside them.

Usage::

    python examples/make_gallery.py [OUT_DIR]      # default: the repository's meshes/

Each item is written as a mesh (STL, or OBJ with named parts for an assembly) and a JSON file of
the same stem holding what was built and, per part, its invariants: volume (mm^3), surface area
(mm^2), bounding box (mm), face count, requested and achieved tolerance (mm). The tests rebuild
every item and compare these invariants (never bytes), and measure the stored files against them.
"""
from __future__ import annotations

import json
import sys
from pathlib import Path

from gearkit.families.involute import GearSpec, tooth_profile
from gearkit.families.novikov import NovikovGearSpec
from gearkit.families.novikov import tooth_profile as novikov_profile
from gearkit.families.novikov.presets import rack_system
from gearkit.families.involute.rack import RackSpec, rack_profile
from gearkit.pair import PairSpec
from gearkit.solids import SolidSpec, gear_solid, pair_assembly, rack_solid, write_mesh
from gearkit.families.involute import ShaperCutter

MESHES = Path(__file__).resolve().parents[1] / "meshes"


def _spur():
    prof = tooth_profile(GearSpec(12, 2.0))
    return [gear_solid(prof, SolidSpec(5.0, bore=6.0, keyway=(2.0, 1.0)), 0.01, "spur")]


def _helical():
    prof = tooth_profile(GearSpec(20, 2.0, helix_angle_deg=20.0))
    return [gear_solid(prof, SolidSpec(10.0), 0.01, "helical")]


def _double_helical():
    prof = tooth_profile(GearSpec(24, 1.5, helix_angle_deg=30.0))
    return [gear_solid(prof, SolidSpec(12.0, herringbone=True, gap=3.0, bore=8.0), 0.01, "double_helical")]


def _ring():
    prof = tooth_profile(GearSpec(48, 1.0, internal=True, tool=ShaperCutter(18)))
    return [gear_solid(prof, SolidSpec(8.0, rim=3.0), 0.01, "ring")]


def _rack():
    prof = rack_profile(RackSpec(2.0, helix_angle_deg=20.0))
    return [rack_solid(prof, 60.0, 10.0, 12.0, 0.01, name="rack")]


def _novikov():
    prof = novikov_profile(NovikovGearSpec(18, 2.0, rack_system("dca24").rack1, helix_angle_deg=15.0))
    return [gear_solid(prof, SolidSpec(16.0), 0.01, "novikov")]


def _pair():
    spec = PairSpec(13, 40, 2.0, 0.3, 0.0, thinning1=0.1, thinning2=0.1)
    return list(pair_assembly(spec, width=8.0, tol=0.02).placed(0.0))


#: stem -> (file extension, builder, what it shows)
ITEMS = {
    "spur_z12_m2_bore_keyway": ("stl", _spur, "spur gear z = 12, m = 2 mm, b = 5 mm, bore 6 mm, keyway 2 x 1 mm"),
    "helical_z20_m2_b10_beta20": ("stl", _helical, "helical gear z = 20, m_n = 2 mm, beta = 20 deg right hand"),
    "double_helical_z24_gap3": ("stl", _double_helical, "double-helical z = 24, m_n = 1.5 mm, beta = 30 deg, "
                                                        "b = 12 mm with a 3 mm gap, bore 8 mm"),
    "ring_z48_m1_rim3": ("stl", _ring, "ring gear z = 48, m = 1 mm, cut by an 18-tooth shaper, rim 3 mm"),
    "rack_m2_beta20": ("stl", _rack, "helical rack m_n = 2 mm, beta = 20 deg, 60 x 10 x 12 mm"),
    "novikov_z18_dca24": ("stl", _novikov, "Novikov gear z = 18, m_n = 2 mm, beta = 15 deg, rack dca24"),
    "pair_13_40_m2": ("obj", _pair, "pinion and wheel 13/40, m = 2 mm, x1 = 0.3, placed and phased"),
}


def invariants(solid) -> dict:
    return solid.invariants()


def build(stem: str):
    """The parts of gallery item ``stem`` and its JSON record."""
    ext, builder, what = ITEMS[stem]
    parts = builder()
    record = {"file": f"{stem}.{ext}", "description": what, "parts": {p.name: invariants(p) for p in parts}}
    return parts, record


def main(out_dir=MESHES) -> list:
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    written = []
    for stem in ITEMS:
        parts, record = build(stem)
        path = write_mesh(out / record["file"], parts)
        (out / f"{stem}.json").write_text(json.dumps(record, indent=2) + "\n")
        size = path.stat().st_size
        if size >= 1 << 20:
            raise SystemExit(f"{path.name} is {size} bytes: gallery meshes must stay under 1 MB")
        written.append(path)
        print(f"{path.name:<36} {size / 1024:8.1f} kB  " + ", ".join(
            f"{name}: {inv['faces']} faces, achieved {inv['achieved']:.3g} mm" for name, inv in record["parts"].items()))
    return written


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else MESHES)
