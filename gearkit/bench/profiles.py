"""2D profiles: the accuracy ladder, scaling in z, and the kernel's overhead over the bare closed form.

The achieved deviation is measured **independently** of the sampler: every exact piece of
tooth 1's boundary (``ToothProfile.half.pieces``, mirrored for the left flank, rotated to
where tooth 1 sits) is evaluated at many parameters, and the largest distance from those
exact points to the gear's output outline is taken (:func:`gearkit.distances.distances_to_polyline`).
The sampler's own number is not used.
"""
from __future__ import annotations

import math

import numpy as np

from gearkit.bench.timing import median_time
from gearkit.distances import distances_to_polyline

#: kernel overhead target: the z = 40 outline at tol 1e-6 m over numpy's closed form for as many points
OVERHEAD_TARGET = 3.0

#: requested tolerances of the ladder, in modules
LADDER_TOLS = (1e-1, 1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7)
#: tooth counts of the scaling run
SCALING_TEETH = (10, 100, 1000, 10000)
#: the exact pieces are evaluated at this many times as many parameters as the half tooth has vertices
DENSITY = 24
#: geometric grading of the dense parameters towards each piece's ends (the sampler refines there most)
_ENDS = np.geomspace(1e-9, 1e-2, 60)


def _dense_parameters(n: int):
    w = np.concatenate([np.linspace(0.0, 1.0, n), _ENDS, 1.0 - _ENDS])
    return np.unique(w)


def exact_tooth_points(prof, n_half: int, tooth: int = 1):
    """Dense points on the exact boundary of tooth ``tooth`` (both halves), ``(k, 2)`` float64, mm."""
    pieces = prof.half.pieces
    per_piece = int(min(max(DENSITY * n_half // len(pieces), 400), 200_000))
    w = _dense_parameters(per_piece)
    right = np.concatenate([p(w) for p in pieces])
    pts = np.concatenate([right, right * np.array([-1.0, 1.0])])
    ang = 2.0 * math.pi * tooth / prof.teeth
    c, s = math.cos(ang), math.sin(ang)
    return np.stack([c * pts[:, 0] - s * pts[:, 1], s * pts[:, 0] + c * pts[:, 1]], -1)


def measured_deviation(prof, outline, n_half: int, tooth: int = 1) -> float:
    """Largest distance (mm) from the exact boundary of tooth ``tooth`` to the output ``outline``.

    Only the outline vertices of that tooth and its neighbours' halves are searched (the outline
    is ``teeth`` copies of one tooth polyline of ``len(outline) // teeth`` vertices).
    """
    z = prof.teeth
    n_t = len(outline) // z
    idx = np.arange(tooth * n_t - n_t // 2, (tooth + 1) * n_t + n_t // 2 + 1) % len(outline)
    window = outline[idx]
    exact = exact_tooth_points(prof, n_half, tooth)
    return float(distances_to_polyline(exact, window).max())


def _involute_cases(quick: bool):
    from gearkit.families.involute import GearSpec
    from gearkit.families.involute import ShaperCutter

    cases = [("spur z=40", GearSpec(40, 1.0))]
    if not quick:
        cases += [("helical z=20 beta=20", GearSpec(20, 1.0, 0.2, helix_angle_deg=20.0)),
                  ("undercut z=8", GearSpec(8, 1.0)),
                  ("internal z=60 z0=20", GearSpec(60, 1.0, internal=True, tool=ShaperCutter(20)))]
    return cases


def _generate_and_sample(spec, tol, generate=None):
    if generate is None:
        from gearkit.families.involute import tooth_profile

        generate = tooth_profile.__wrapped__  # bypass the cache: time the whole path
    prof = generate(spec)
    return prof, prof.outline(tol)


def profile_row(family, case, spec, tol_m, repeats, generate=None, unit=None):
    """One ladder rung: generate + sample at ``tol_m`` modules (or ``unit`` mm); time, count, measure."""
    tol = tol_m * (spec.module if unit is None else unit)
    seconds, (prof, outline) = median_time(lambda: _generate_and_sample(spec, tol, generate), repeats)
    n_half = len(prof.half_points(tol)[0])
    achieved = measured_deviation(prof, outline, n_half)
    return {"family": family, "product": "profile", "case": case, "tol": tol, "tol_m": tol_m,
            "achieved": achieved, "ratio": achieved / tol, "sampler_achieved": prof.achieved(tol),
            "vertices": int(len(outline)), "seconds": seconds}


def involute_ladder(quick: bool, repeats: int):
    rows = []
    for case, spec in _involute_cases(quick):
        for tol_m in LADDER_TOLS:
            rows.append(profile_row("involute", case, spec, tol_m, repeats))
    return rows


def novikov_ladder(quick: bool, repeats: int):
    """The Novikov pinion of the preset double-circular-arc rack system (z = 20, beta = 15 deg)."""
    try:
        from gearkit.families import novikov
        from gearkit.families.novikov.presets import rack_system
    except ImportError:
        return []
    spec = novikov.NovikovGearSpec(20, 1.0, rack_system("dca24").rack1, 15.0)
    generate = getattr(novikov.tooth_profile, "__wrapped__", novikov.tooth_profile)
    tols = LADDER_TOLS[::2] if quick else LADDER_TOLS
    return [profile_row("novikov", "dca24 z=20 beta=15", spec, t, repeats, generate) for t in tols]


def cycloidal_ladder(quick: bool, repeats: int):
    """The cycloid disc of a 12-pin drive (11 lobes, pin circle 90 mm, pin 7 mm, e = 4 mm);
    tolerances in units of the eccentricity (the disc's tooth height is 2e)."""
    try:
        from gearkit.families.cycloidal import DriveSpec, disc_profile
    except ImportError:
        return []
    spec = DriveSpec(12, 11, 90.0, 7.0, 4.0)
    generate = getattr(disc_profile, "__wrapped__", disc_profile)
    tols = LADDER_TOLS[::2] if quick else LADDER_TOLS
    return [profile_row("cycloidal", "disc 12 pins, 11 lobes, e=4", spec, t, repeats, generate,
                        unit=spec.eccentricity) for t in tols]


def involute_scaling(quick: bool, repeats: int):
    """Time and vertex count for z = 10 ... 10000 (tol 1e-3 m; also 1e-6 m unless quick)."""
    from gearkit.families.involute import GearSpec

    rows = []
    for tol_m in ((1e-3,) if quick else (1e-3, 1e-6)):
        for z in SCALING_TEETH:
            spec = GearSpec(z, 1.0)
            seconds, (prof, outline) = median_time(lambda: _generate_and_sample(spec, tol_m), repeats)
            n_half = len(prof.half_points(tol_m)[0])
            rows.append({"family": "involute", "product": "profile", "teeth": z, "tol": tol_m,
                         "achieved": measured_deviation(prof, outline, n_half), "vertices": int(len(outline)),
                         "seconds": seconds})
    rows += rack_scaling(quick, repeats)
    return rows


def rack_scaling(quick: bool, repeats: int):
    """The rack (z = infinity) row: one tooth of the rack a 20-tooth shaper cutter generates."""
    try:
        from gearkit.families.involute.rack import RackSpec, rack_profile
    except ImportError:
        return [{"family": "involute", "product": "profile", "teeth": "rack", "available": False,
                 "note": "the kernel has no rack (z = infinity) profile"}]
    from gearkit.families.involute import ShaperCutter

    spec = RackSpec(1.0, tool=ShaperCutter(20))
    rows = []
    for tol_m in ((1e-3,) if quick else (1e-3, 1e-6)):
        def run():
            prof = rack_profile.__wrapped__(spec)
            return prof, prof.outline(tol_m)

        seconds, (prof, outline) = median_time(run, repeats)
        pieces = prof.half.pieces
        w = _dense_parameters(int(min(max(DENSITY * len(prof.half_points(tol_m)[0]), 400), 200_000)))
        right = np.concatenate([p(w) for p in pieces])
        exact = np.concatenate([right, right * np.array([-1.0, 1.0])])
        achieved = float(distances_to_polyline(exact, outline).max())
        rows.append({"family": "involute", "product": "profile", "teeth": "rack", "tol": tol_m,
                     "achieved": achieved, "vertices": int(len(outline)), "seconds": seconds,
                     "note": "one tooth of a rack cut by a 20-tooth shaper cutter"})
    return rows


def _cpu_per_call(fn, calls: int) -> float:
    """CPU seconds per call of ``fn``, from batches of ``calls`` calls repeated until the CPU clock has
    advanced by at least half a batch's planned time (the batch was sized on the wall clock: on a loaded
    machine it can pass within one tick of a coarse CPU clock, which read 0 s)."""
    import time

    from gearkit.bench.timing import BATCH

    t0, done = time.process_time(), 0
    while True:
        for _ in range(calls):
            fn()
        done += calls
        spent = time.process_time() - t0
        if spent >= 0.5 * BATCH:
            return spent / done


def overhead(repeats: int = 21):
    """Kernel time for the z = 40 involute outline at tol 1e-6 m over numpy's time for the same
    number of closed-form involute points, both in CPU time (medians; the calls interleaved so a
    change of the machine's load hits both alike).

    Returns a dict with ``overhead_ratio`` (whole path: spec -> outline, uncached),
    ``overhead_ratio_sampling`` (outline of an already generated profile), the two times, the
    baseline time and the point count.
    """
    import time

    from gearkit.bench.timing import BATCH, batch_calls, closed_form_involute
    from gearkit.families.involute import GearSpec, tooth_profile

    spec = GearSpec(40, 1.0)
    tol = 1e-6 * spec.module
    gen = tooth_profile.__wrapped__(spec)
    n = len(gen.outline(tol))
    r_b, r_a = spec.base_diameter / 2.0, spec.blank_tip_diameter / 2.0
    roll_max = math.sqrt(max((r_a / r_b) ** 2 - 1.0, 1e-12))

    def sample_only():
        gen._cache.clear()
        return gen.outline(tol)

    runs = {"kernel": lambda: _generate_and_sample(spec, tol), "sampling": sample_only,
            "baseline": lambda: closed_form_involute(n, r_b, roll_max)}
    # a CPU clock may tick coarsely (every 4 ms while an interval timer runs, 15.6 ms on some systems): each
    # time is of batches of calls lasting about BATCH seconds, divided by the calls
    batch = {k: batch_calls(fn, BATCH) for k, fn in runs.items()}
    times = {k: [] for k in runs}
    start = time.perf_counter()
    for i in range(max(3, repeats)):
        for key, fn in runs.items():
            times[key].append(_cpu_per_call(fn, batch[key]))
        if i >= 2 and time.perf_counter() - start > 6.0:
            break
    kernel, sampling, base = (float(np.median(times[k])) for k in ("kernel", "sampling", "baseline"))
    return {"overhead_ratio": kernel / base, "overhead_ratio_sampling": sampling / base, "kernel_seconds": kernel,
            "sampling_seconds": sampling, "baseline_seconds": base, "points": int(n), "teeth": 40,
            "tol": tol, "target": OVERHEAD_TARGET, "clock": "CPU"}


def cam_ladder(quick: bool, repeats: int):
    """The digest's cam (cycloidal rise 20 mm over 60 deg, dwell 60, return 60; translating roller
    R_p = 10 mm, r0 = 56.7702 mm): generate + sample at each tol (mm), the achieved deviation measured
    by dense re-evaluation of the exact envelope pieces against the outline. Tols below a roller's floor,
    2e-7 (r0 + stroke) = 1.5e-5 mm here, are refused by the cam and left out."""
    try:
        from gearkit.families.cam import CamSpec, MotionProgram, cam_profile
        from gearkit.families.cam.profile import ROLLER_FLOOR
    except ImportError:
        return []
    spec = CamSpec(56.7702, MotionProgram.rise_dwell_return(20.0, 60.0, 60.0, 60.0), roller_radius=10.0)
    generate = getattr(cam_profile, "__wrapped__", cam_profile)
    rows = []
    for tol in (LADDER_TOLS[::2] if quick else LADDER_TOLS):
        if tol < ROLLER_FLOOR * (spec.prime_radius + spec.stroke):
            continue
        def run():
            prof = generate(spec)
            return prof, prof.outline(tol)

        seconds, (prof, outline) = median_time(run, repeats)
        w = _dense_parameters(int(min(max(DENSITY * len(outline) // len(prof.pieces), 400), 200_000)))
        exact = np.concatenate([pc(w) for pc in prof.pieces])
        achieved = float(distances_to_polyline(exact, outline, closed=True).max())
        rows.append({"family": "cam", "product": "profile", "case": "roller r0=56.77 cycloidal", "tol": tol,
                     "tol_m": tol, "achieved": achieved, "ratio": achieved / tol,
                     "sampler_achieved": prof.achieved(tol),
                     "vertices": int(len(outline)), "seconds": seconds})
    return rows
