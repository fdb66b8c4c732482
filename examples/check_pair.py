"""Check gear pairs from Python: the textbook's two worked examples and a standard pair that fails.

Run: python examples/check_pair.py
"""
import math

from gearkit.checks import check_pair
from gearkit.cli.check import format_report
from gearkit.pair import PairSpec, shifts_for_center_distance
from gearkit.families.involute import ShaperCutter


def main() -> None:
    # Helical external pair (m = 6, beta = 20 deg 30', z = 8/14). The textbook gives transverse shifts
    # xi = 0.45 and 0.03; gearkit takes normal shifts x_n = xi / cos(beta).
    beta = 20.5
    cos_b = math.cos(math.radians(beta))
    helical = PairSpec(8, 14, 6.0, 0.45 / cos_b, 0.03 / cos_b, helix_angle_deg=beta, face_width=54.0)
    res = check_pair(helical)
    g = res.geometry
    print(format_report(res))
    print(f"alpha_wt = {math.degrees(g.working_pressure_angle):.5f} deg, eps_alpha = {g.contact_ratio:.5f}, "
          f"eps_gamma = {g.total_contact_ratio:.5f}, s_a2 = {g.gears[1].tip_thickness:.5f} mm\n")

    # Internal pair cut by a medium-worn 20-tooth shaper (x_u + x_c = 1.3), z = 46/49, x2 = 0.52 as the
    # textbook gives it: the shaper's radial setting (gearkit reads a ring's shift by ISO 21771 by default).
    shaper = ShaperCutter(20, addendum=1.3)
    internal = PairSpec(46, 49, 8.0, 0.0, 0.52, kind="internal", tool1=shaper, tool2=shaper,
                        shift_convention="cutter")
    res = check_pair(internal)
    print(format_report(res))
    print(f"a_w = {res.geometry.center_distance:.4f} mm, eps (tip to tip) = {res.geometry.contact_ratio_nominal:.5f}\n")

    # The standard 12/24 pair: undercut pinion, the wheel's tip digs into its fillet.
    res = check_pair(PairSpec(12, 24, 1.0))
    print(format_report(res))
    assert not res.ok

    # Design from a centre distance: shifts solved and split for balanced sliding.
    spec = shifts_for_center_distance(PairSpec(12, 24, 1.0), 18.5, split="balanced")
    res = check_pair(spec)
    print(f"\nat a_w = 18.5 mm: x1 = {spec.shift1:.4f}, x2 = {spec.shift2:.4f} -> {res.report.status}")


if __name__ == "__main__":
    main()
