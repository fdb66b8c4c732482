"""Novikov (circular-arc) pairs from Python: generate, check, mesh, and see what a centre-distance
error does to the contact.

Run: python examples/novikov_pair.py [OUTPUT_DIR]

The preset racks ("dca24", "single-arc") are NOT verified against the standards: verify against the
standard before production. A rack of your own is a TOML file (see gearkit.families.novikov.presets).
"""
import math
import sys
import tempfile
from pathlib import Path

from gearkit.checks.novikov import check_novikov
from gearkit.cli.novikov import format_report
from gearkit.export import write_profile
from gearkit.families.novikov import NovikovPairSpec, novikov_pair_geometry
from gearkit.families.novikov.mesh import mesh_contact, meshed_outlines
from gearkit.families.novikov.presets import rack_system


def main(out_dir: Path) -> None:
    # The worked helical pair of the reference digest: m_n = 4, z = 20/60, beta = 15 deg, b = 60 mm,
    # double circular-arc rack (alpha_k = 24 deg), one hob for both gears.
    spec = NovikovPairSpec(20, 60, 4.0, 15.0, 60.0, "dca24")
    result = check_novikov(spec)
    print(format_report(result))
    g = result.geometry
    assert abs(g.center_distance - 165.6442) < 1e-4 and abs(g.overlap_ratio - 1.23577) < 1e-5

    # Too narrow a face: eps_beta < 1 fails, and the finding says what to change.
    narrow = check_novikov(NovikovPairSpec(20, 60, 4.0, 15.0, 40.0, "dca24"), simulate=False)
    print("\nb = 40 mm:", narrow.report["overlap_ratio"].status, "-", narrow.report["overlap_ratio"].message)
    assert not narrow.ok

    # A centre-distance error moves the contact along the arcs: simulated mesh vs the rack formula
    # sin a_k' = sin a_k - da / (rho_f - rho_a).
    single = NovikovPairSpec(20, 60, 4.0, 15.0, 60.0, "single-arc")
    zone = single.racks.zones[0]
    print("\nsingle-arc pair, centre-distance error (m_n) -> contact angle alpha_k (deg)")
    for da in (-0.02, -0.01, 0.0, 0.01, 0.02):
        c = mesh_contact(single, 0, single.reference_center_distance + da * single.module, interference=False)
        predicted = math.degrees(math.asin(math.sin(single.racks.rack1.alpha) - da / zone.rho_diff))
        print(f"  {da:+.3f}   simulated {math.degrees(c.contact_angle):8.4f}   rack formula {predicted:8.4f}   "
              f"contact radius on the pinion {c.radii[0]:.4f} mm")

    # The racks' provenance travels with them.
    for name in ("dca24", "single-arc"):
        system = rack_system(name)
        print(f"\n{name}: {system.title}\n  verified: {system.verified}")

    # Both gears in mesh as a 2D drawing (atomic write).
    path = write_profile(out_dir / "novikov_pair.svg", meshed_outlines(spec),
                         novikov_pair_geometry(spec).to_dict())
    print(f"\nwrote {path}")


if __name__ == "__main__":
    out = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(tempfile.mkdtemp(prefix="gearkit-novikov-"))
    main(out)
