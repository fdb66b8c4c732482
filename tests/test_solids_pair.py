"""Pairs as solids: phasing, 3D interference (manifold3d booleans) and the pair geometry's backlash."""
import math

import numpy as np
import pytest

from gearkit.errors import SpecError
from gearkit.pair import PairSpec, pair_geometry
from gearkit.solids import pair_assembly
from gearkit.families.involute import ShaperCutter

M = 2.0
TOL = 2e-3  # mesh tolerance, mm: far below the backlash (~0.2 mm) and the 0.2 m shifts
SAMPLES = 7  # rotations sampled over one pinion pitch

PAIRS = {
    "spur": PairSpec(20, 31, M, thinning1=0.1, thinning2=0.1),
    "helical": PairSpec(13, 40, M, 0.3, 0.0, helix_angle_deg=15.0, thinning1=0.1, thinning2=0.1),
    "rack": PairSpec(18, None, M, kind="rack", helix_angle_deg=-20.0, thinning1=0.1, thinning2=0.1),
    # the ring's tips cut back to d_a2 = 97.6 mm: with the default tips they dig into the pinion's fillet
    "internal": PairSpec(20, 50, M, 0.0, 0.15, kind="internal", tool2=ShaperCutter(20), thinning1=0.1,
                         tip_diameter2=97.6),
}
# moving the wheel 0.2 m towards the pinion's teeth: a smaller centre distance, except for a ring
TIGHTER = {"spur": -1, "helical": -1, "rack": -1, "internal": +1}


@pytest.fixture(scope="module")
def assemblies():
    return {name: pair_assembly(spec, width=8.0, tol=TOL) for name, spec in PAIRS.items()}


def angles(spec):
    pitch = 2 * math.pi / spec.teeth1
    return pitch * np.arange(SAMPLES) / SAMPLES


@pytest.mark.parametrize("name", list(PAIRS))
def test_pair_with_backlash_runs_free_and_jams_when_moved_in(assemblies, name):
    spec, asm = PAIRS[name], assemblies[name]
    g = pair_geometry(spec)
    assert g.backlash > 0.1
    assert asm.center_distance == pytest.approx(g.center_distance)
    free = asm.sweep(angles(spec))
    assert (free == 0.0).all()
    tight = asm.moved(asm.center_distance + TIGHTER[name] * 0.2 * M).sweep(angles(spec))
    assert (tight > 0.0).all()


@pytest.mark.parametrize("name", ["spur", "helical", "internal"])
def test_phasing_puts_a_tooth_in_the_middle_of_a_space(assemblies, name):
    """Turning the pinion alone by the backlash (transverse, on the working circle) closes one flank."""
    spec, asm = PAIRS[name], assemblies[name]
    g = pair_geometry(spec)
    play = g.backlash / 2 / (g.gears[0].working_diameter / 2)  # half the angular play, rad
    wheel = asm.placed(0.0)[1]
    for sign in (+1, -1):
        inside = asm.placed(sign * 0.8 * play)[0]
        beyond = asm.placed(sign * 1.25 * play)[0]
        assert (inside.manifold ^ wheel.manifold).volume() == 0.0
        assert (beyond.manifold ^ wheel.manifold).volume() > 0.0
    half_pitch = asm.placed(math.pi / spec.teeth1)[0]
    assert (half_pitch.manifold ^ wheel.manifold).volume() > 1.0  # out of phase: teeth collide


def test_a_failing_interference_check_shows_up_in_3d():
    """With its default tips the ring's tip meets the pinion's fillet (the design check fails
    ``interference.1``): the pinion then cannot turn through its backlash."""
    from dataclasses import replace

    from gearkit.checks import check_pair

    # the backlash comes from a centre distance 0.13 mm inside the tight mesh: a thinning allowance would
    # feed the pinion's cutter in (ISO 21771 x_E), deepening its fillet clear of the ring's tip
    nominal = replace(PAIRS["internal"], tip_diameter2=None, thinning1=0.0)
    spec = replace(nominal, center_distance=pair_geometry(nominal).tight_center_distance - 0.13)
    assert "interference.1" in {f.id for f in check_pair(spec).report.failures}
    g = pair_geometry(spec)
    asm = pair_assembly(spec, width=4.0, tol=TOL)
    play = g.backlash / 2 / (g.gears[0].working_diameter / 2)
    pinion, ring = asm.placed(0.8 * play)[0], asm.placed(0.0)[1]
    assert asm.interference(0.0) == 0.0
    assert (pinion.manifold ^ ring.manifold).volume() > 0.0


def test_rack_moves_with_the_pinion_reference_circle(assemblies):
    spec, asm = PAIRS["rack"], assemblies["rack"]
    pinion, rack = asm.placed(0.3)
    _, rack0 = asm.placed(0.0)
    shift = rack.bounds[0][1] - rack0.bounds[0][1]
    assert shift == pytest.approx(asm.pinion_radius * 0.3, abs=1e-9)
    assert asm.pinion_radius == pytest.approx(spec.teeth1 * M / math.cos(math.radians(20.0)) / 2)


def test_assembly_summary_and_bad_input(assemblies):
    info = assemblies["spur"].summary()
    assert [p["name"] for p in info["parts"]] == ["pinion", "wheel"]
    assert info["achieved"] <= info["tol"] == TOL
    with pytest.raises(SpecError, match="width"):
        pair_assembly(PairSpec(20, 31, M))
    with pytest.raises(SpecError, match="center_distance"):
        assemblies["spur"].moved(-1.0)
    with pytest.raises(SpecError, match="herringbone"):
        pair_assembly(PAIRS["rack"], width=5.0, herringbone=True)
