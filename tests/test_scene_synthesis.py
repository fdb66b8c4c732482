"""Planetary synthesis, assembly and phasing against the textbook digest's worked examples
(seed_textbook_other_gears_trains.md §5, §7) and independent closed forms."""
import math
from fractions import Fraction

import pytest

from gearkit.errors import SpecError
from gearkit.scene import scene_speeds
from gearkit.scene.layout import scene_layout
from gearkit.scene.phasing import (PlanetMesh, assembly_positions, neighbour_ratio, planet_phasing,
                                   textbook_assembly)
from gearkit.scene.synthesis import (TEXTBOOK_LIMITS, factorised_teeth, planetary_scene, set_ratio,
                                     synthesize)


def test_example_6_simple_scheme_ranks_first():
    """Ex.6 (L17566): i_1B = 18/5, K = 3: (35, 28, 91), C = 42 at p = 0 (carrier turn 120 deg)."""
    best = synthesize(3.6, 3, 2.0, limits=TEXTBOOK_LIMITS)[0]
    assert best.teeth == (35, 28, 91) and best.ratio == Fraction(18, 5)
    assert best.textbook == (42, 0, 120.0)
    # zero gears: the tip gap is m [(z1 + z2) sin(pi/K) - (z2 + 2)] (h_a* = 1), here 2(63 sin 60 - 30)
    assert best.neighbour_clearance == pytest.approx(2 * (63 * math.sin(math.pi / 3) - 30), abs=1e-9)


def test_example_7_scheme_a_needs_p_1():
    """Ex.7 (L17676): i_1B = -1/24, K = 3: (54, 45, 44, 55), C = -3 at p = 1 (carrier 480 deg)."""
    best = synthesize(-1 / 24, 3, 2.0, scheme="external", limits=TEXTBOOK_LIMITS)[0]
    assert best.teeth == (54, 45, 44, 55) and best.ratio == Fraction(-1, 24)
    assert best.textbook == (-3, 1, 480.0)
    assert factorised_teeth("external", 6, 5, 4, 5, 1) == (54, 45, 44, 55)  # 25/24 = 5*5/(6*4)
    assert factorised_teeth("external", 8, 5, 3, 5, 1) == (64, 40, 39, 65)  # 5*5/(8*3), variant II


def test_example_8_scheme_b_variants():
    """Ex.8 (L17789): i_1B = 1/40: I (90, 27, 28, 91) ranks first with C = 3 at p = 1; variants II and
    III (gamma 8 and 2) have neighbour numbers 82/24 and 66/40 > 1: one planet only."""
    best = synthesize(1 / 40, 3, 2.0, scheme="internal", limits=TEXTBOOK_LIMITS)[0]
    assert best.teeth == (90, 27, 28, 91) and best.textbook == (3, 1, 480.0)
    assert factorised_teeth("internal", 10, 3, 4, 13, 1) == (90, 27, 28, 91)
    two = factorised_teeth("internal", 4, 3, 10, 13, 8)
    three = factorised_teeth("internal", 10, 6, 8, 13, 2)
    assert two == (96, 72, 80, 104) and three == (100, 60, 64, 104)
    for t, number in ((two, 82 / 24), (three, 66 / 40)):
        assert set_ratio("internal", t) == Fraction(1, 40)
        assert neighbour_ratio(max(t[1], t[2]), t[0], t[1], internal=True) == pytest.approx(number, rel=1e-12)
        assert number > 1  # sin(180/K) <= 1 < number for every K > 1


def test_example_9_textbook_set_valid_but_not_most_compact():
    """Ex.9 (L17916): i_1B = 10, K = 3: the textbook's (18, 54, 36, 108) (gamma = 4.5, C = 60) is
    valid, but (24, 54, 26, 104), (21, 54, 30, 105) and (30, 54, 21, 105) are smaller."""
    sets = synthesize(10, 3, 2.0, scheme="compound", limits=TEXTBOOK_LIMITS, count=6)
    teeth = [s.teeth for s in sets]
    assert teeth[:4] == [(24, 54, 26, 104), (21, 54, 30, 105), (30, 54, 21, 105), (18, 54, 36, 108)]
    assert sets[3].textbook == (60, 0, 120.0)
    assert factorised_teeth("compound", 1, 3, 2, 6, Fraction(9, 2)) == (18, 54, 36, 108)


@pytest.mark.parametrize("teeth, k, scheme, number", [
    ((35, 28, 28, 91), 3, "simple", 30 / 63), ((54, 45, 44, 55), 3, "external", 47 / 99),
    ((90, 27, 28, 91), 3, "internal", 30 / 63), ((18, 54, 36, 108), 3, "compound", 56 / 72)])
def test_neighbour_numbers(teeth, k, scheme, number):
    """§8 item 21: Ex.6 0.476, Ex.7 0.475, Ex.8 0.476, Ex.9 0.778, all below sin 60 deg."""
    z1, z2, z3, _ = teeth
    value = neighbour_ratio(max(z2, z3), z1, z2, internal=scheme == "internal")
    assert value == pytest.approx(number, rel=1e-12) and value < math.sin(math.pi / k)


def test_seed_003_box_takes_at_most_five_planets():
    """§6.4: the largest planet gear z2'' = 80 on 2a/m = 160: (80 + 2)/160 < sin(180/K) iff K <= 5."""
    number = neighbour_ratio(80, 80, 80)
    assert [k for k in range(2, 9) if number < math.sin(math.pi / k)] == [2, 3, 4, 5]


def test_general_assembly_condition_beyond_the_textbook():
    """§5.5: scheme (compound) (112, 38, 24, 74), K = 2 assembles (N/(K gcd) = 5500/4 integer) though
    the textbook's C = 1375 (1 + 2p)/12 is never an integer."""
    meshes = [PlanetMesh(112, 38, False), PlanetMesh(74, 24, True)]
    n = 112 * 24 + 38 * 74
    assert assembly_positions(meshes) == n // math.gcd(38, 24)
    assert assembly_positions(meshes) % 2 == 0
    assert textbook_assembly(112, set_ratio("compound", (112, 38, 24, 74)), 2) is None


def test_simple_planets_both_conditions_agree():
    """For simple planets both conditions reduce to (z1 + z4)/K integer."""
    for z1 in range(12, 40):
        for z2 in range(12, 30):
            z4 = z1 + 2 * z2
            meshes = [PlanetMesh(z1, z2, False), PlanetMesh(z4, z2, True)]
            assert assembly_positions(meshes) == z1 + z4
            for k in (2, 3, 4, 5):
                equal = (z1 + z4) % k == 0
                assert equal == (textbook_assembly(z1, set_ratio("simple", (z1, z2, z4)), k) is not None)


def test_unequal_angles_assemble_and_phasing_classes():
    # (22 + 108)/3 is not an integer: the planets sit on the 130-position grid nearest 120 deg
    p = planet_phasing(3, [PlanetMesh(22, 43, False), PlanetMesh(108, 43, True)])
    assert p.kind == "unequal"
    for a in p.angles_deg:
        assert (a / 360 * 130) == pytest.approx(round(a / 360 * 130), abs=1e-9)
    # equal spacing: the mesh harmonics l whose torque ripple survives are l z_s = 0 (mod K), those
    # whose net force survives l z_s = +-1 (mod K) (the classic phasing rule)
    for z_sun, z_ring, k, kind in ((21, 108, 3, "in_phase"), (20, 106, 3, "sequential"), (21, 107, 2, "counter_phase"),
                                   (19, 105, 4, "sequential")):
        zp = (z_ring - z_sun) // 2
        ph = planet_phasing(k, [PlanetMesh(z_sun, zp, False), PlanetMesh(z_ring, zp, True)])
        assert ph.kind == kind
        cancels = ph.cancels()
        for l in range(1, k + 1):
            assert (l in cancels["torque_ripple"]) == ((l * z_sun) % k != 0)
            assert (l in cancels["net_force"]) == ((l * z_sun) % k not in (1, k - 1))
        assert cancels["steady_net_force"] if k > 1 else True


def test_issue_set_found_with_its_shift_and_ratio_agrees_with_the_kinematics():
    """The issue's 21/43/108 set: i_1B = 1 + 108/21 exactly; 21 + 2*43 = 107 != 108, so profile shift
    closes the loop; the synthesis ratio equals the scene's linear-system ratio."""
    sets = synthesize(1 + 108 / 21, 3, 1.75, count=3)
    best = sets[0]
    assert best.teeth == (21, 43, 108) and best.ratio == Fraction(43, 7)
    assert best.shifts["sun"] > 0 and best.shifts["planet"] == 0 and best.phasing.kind == "in_phase"
    layout = scene_layout(best.scene)
    tight = [m.spec.center_distance for m in layout.meshes]
    assert tight[0] == pytest.approx(tight[1], abs=1e-9) == pytest.approx(best.center_distance, abs=1e-9)
    for s in sets:
        assert scene_speeds(s.scene).ratio("sun", "carrier") == s.ratio
    assert best.to_dict()["planet_angles_deg"] == pytest.approx([0, 120, 240])


def test_loop_that_does_not_close_names_the_meshes():
    """L16240's z1 = z3 = 100, z2 = 99, z4 = 101: 199 != 201 with zero gears, the loop cannot close."""
    scene = planetary_scene("external", (100, 99, 100, 101), 1, 1.0)
    with pytest.raises(SpecError, match="loop through sun-planet and planet2-ring does not close: .* 99.5 mm and 100.5 mm"):
        scene_layout(scene)


def test_overlapping_planets_and_bad_angles_are_errors():
    with pytest.raises(SpecError, match="tips of planet planet#1 and planet#2 overlap"):
        scene_layout(planetary_scene("simple", (20, 40, 100), 5, 1.0))
    with pytest.raises(SpecError, match="cannot be assembled"):
        scene_layout(planetary_scene("simple", (22, 43, 108), 3, 1.0))


def test_synthesis_rejects_bad_input():
    with pytest.raises(SpecError, match="ratio"):
        synthesize(1.5, 3, 1.0)
    with pytest.raises(SpecError, match="planets"):
        synthesize(5.0, 0, 1.0)
