"""The cycloidal family from Python: a cycloid–pin-wheel drive, its disc cut by its pins, the mesh
simulated on the generated disc, a backlash modification, and clock gearing.

Run: python examples/cycloidal_drive.py [OUTPUT_DIR]

Writes disc.dxf (outline, bore, output holes), disc.stl and drive.obj (disc, pins, housing,
output pins) into OUTPUT_DIR (default: a temporary directory).
"""
import math
import sys
import tempfile
from pathlib import Path

from gearkit.checks.cycloidal import check_cycloid_pair, check_drive
from gearkit.export import write_profile
from gearkit.families.cycloidal import (CycloidPairSpec, DriveSpec, backlash, disc_curve, disc_profile, psi_max,
                                        simulate_mesh)
from gearkit.families.cycloidal.assembly import drive_loops
from gearkit.solids import write_mesh
from gearkit.solids.drive import disc_solid, drive_parts


def main(out_dir: Path) -> None:
    out_dir.mkdir(parents=True, exist_ok=True)
    # The reference digest's worked drive: 12 pins on R_Z = 90 mm, pins r_Z = 7, e = 4, 11 lobes (dz = +1).
    spec = DriveSpec(pins=12, lobes=11, pin_circle_radius=90.0, pin_radius=7.0, eccentricity=4.0)
    disc = disc_profile(spec)  # the envelope of a pin under the rolling of the disc's centrode in the ring's
    print(f"disc: tip r = {disc.tip_diameter / 2:.6f} mm, root r = {disc.root_diameter / 2:.6f} mm, "
          f"K1 = {spec.k1:.6f}, psi_max = {math.degrees(psi_max(spec)):.4f} deg")
    assert abs(disc.tip_diameter / 2 - 87.0) < 1e-9 and abs(disc.root_diameter / 2 - 79.0) < 1e-9
    crest = disc_curve(spec, [-math.pi / 11])[0]  # the closed form's crest, for comparison
    assert abs(math.hypot(*crest) - 87.0) < 1e-9

    result = check_drive(spec)
    v = result.values
    print(f"contact ratio {v['contact_ratio']:.4f}; simulated: pins in contact {v['pins_in_contact']:.4f}, "
          f"load-carrying {v['load_carrying_pins']:.4f}; |rho_0|min {v['min_curvature_radius']:.4f} mm")
    print("findings:", ", ".join(f"{f.id} {f.status}" for f in result.report))

    # A two-tooth difference: pointed teeth, eps = 6.4199 (the paper printed 6.43).
    two = DriveSpec(24, 22, 90.0, 7.0, 4.0)
    stats = simulate_mesh(two)
    print(f"dz = 2: eps = {check_drive(two, samples=200).values['contact_ratio']:.4f}, simulated mean "
          f"{stats.loaded[0]:.4f} pins loaded ({stats.loaded[1]}..{stats.loaded[2]})")

    # Grinding with pins 0.02 mm larger opens backlash: one pin touches at zero load.
    modified = DriveSpec(12, 11, 90.0, 7.0, 4.0, equidistant_mod=0.02)
    angle, state = backlash(modified)
    print(f"dr = 0.02 mm: backlash {angle * 1e3:.5f} mrad (continuous formula "
          f"{0.02 / modified.disc_pitch_radius * 1e3:.5f}), pins touching {int(state.touching.sum())}")

    write_profile(out_dir / "disc.dxf", drive_loops(spec, 1e-3))
    write_mesh(out_dir / "disc.stl", [disc_solid(spec, 14.0, 0.02)])
    write_mesh(out_dir / "drive.obj", drive_parts(spec, 14.0, 0.02))

    # Clock gearing in the BS 978-2 style: radial pinion flanks, wheel addendum 0.95 A.
    clock = check_cycloid_pair(CycloidPairSpec(1.0, 8, 64, clock=True)).values
    print(f"clock 8/64: A = {clock['theoretical_addendum']:.4f}, addendum factor {clock['wheel_addendum_factor']:.4f}, "
          f"tip-radius factor {clock['wheel_addendum_radius_factor']:.4f}, eps {clock['contact_ratio']:.4f}")
    print(f"wrote {out_dir / 'disc.dxf'}, {out_dir / 'disc.stl'}, {out_dir / 'drive.obj'}")


if __name__ == "__main__":
    main(Path(sys.argv[1]) if len(sys.argv) > 1 else Path(tempfile.mkdtemp(prefix="gearkit-cycloid-")))
