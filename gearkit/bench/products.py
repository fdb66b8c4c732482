"""Products beyond the 2D profile: pair check, and the families and products that may not exist yet.

Each product is measured when its module imports; otherwise the bench lists it as not
available (so the table says what was measured, never silently skips).
"""
from __future__ import annotations

import importlib

import numpy as np

from gearkit.bench.timing import median_time

#: product -> module that provides it (checked by import)
PRODUCT_MODULES = {
    ("involute", "mesh"): "gearkit.solids",
    ("involute", "blocking contour"): "gearkit.blocking.contour",
    ("involute", "contact simulation"): "gearkit.contact",
    ("cycloidal", "profile"): "gearkit.families.cycloidal.disc",
    ("cycloidal", "contact simulation"): "gearkit.families.cycloidal.mesh",
    ("novikov", "profile"): "gearkit.families.novikov",
    ("novikov", "contact simulation"): "gearkit.families.novikov.mesh",
    ("cam", "profile"): "gearkit.families.cam",
}


def available(module: str) -> bool:
    try:
        importlib.import_module(module)
    except ImportError:
        return False
    return True


def pair_check_rows(quick: bool, repeats: int):
    """Time of the pair design check (generated and formula geometry), external and internal."""
    from gearkit.checks import check_pair
    from gearkit.pair import PairSpec
    from gearkit.families.involute import tooth_profile
    from gearkit.families.involute import ShaperCutter

    cases = [("external z=20/40 m=2", PairSpec(20, 40, 2.0))]
    if not quick:
        cases.append(("internal z=20/60 m=1", PairSpec(20, 60, 1.0, kind="internal", tool2=ShaperCutter(20))))
    rows = []
    for case, spec in cases:
        for geometry in ("formula", "generated"):
            def run():
                tooth_profile.cache_clear()  # time the generation, not the cache
                return check_pair(spec, geometry=geometry)

            seconds, report = median_time(run, repeats)
            rows.append({"family": "involute", "product": "pair check", "case": f"{case} ({geometry})",
                         "seconds": seconds, "findings": len(report.report.findings)
                         if hasattr(report, "report") else None})
    return rows


def unmeasured_products(measured=()):
    """Rows for the products this run did not measure: their module does not exist yet, or it
    exists but the bench has no measurement for it yet."""
    rows = []
    for (fam, prod), mod in PRODUCT_MODULES.items():
        if (fam, prod) in measured:
            continue
        note = "exists; not measured by the bench yet" if available(mod) else "not in gearkit yet"
        rows.append({"family": fam, "product": prod, "available": False, "module": mod, "note": note})
    return rows


def cycloidal_mesh_rows(quick: bool, repeats: int):
    """Time of the cycloid drive's simulated pin mesh (one mesh period, ``samples`` disc positions)."""
    try:
        from gearkit.families.cycloidal import DriveSpec, simulate_mesh
    except ImportError:
        return []
    spec = DriveSpec(12, 11, 90.0, 7.0, 4.0)
    rows = []
    for samples in ((400,) if quick else (400, 4000)):
        seconds, stats = median_time(lambda: simulate_mesh(spec, samples), repeats)
        rows.append({"family": "cycloidal", "product": "contact simulation",
                     "case": f"12-pin drive, {samples} positions", "seconds": seconds})
    return rows


def _contact_ratio_closed_form(z1, z2, m=1.0, alpha_deg=20.0):
    """eps_alpha of a standard external pair (x = 0, h_a* = 1, tight mesh), textbook closed form."""
    import math

    a = math.radians(alpha_deg)
    r1, r2 = z1 * m / 2, z2 * m / 2
    rb1, rb2 = r1 * math.cos(a), r2 * math.cos(a)
    ga = math.sqrt((r1 + m) ** 2 - rb1 ** 2) + math.sqrt((r2 + m) ** 2 - rb2 ** 2) - (r1 + r2) * math.sin(a)
    return ga / (math.pi * m * math.cos(a))


def involute_contact_rows(quick: bool, repeats: int):
    """Simulated meshing of the standard 20/40 pair (m = 1) against the number of driver angles:
    time, the contact ratio's error against the closed form, and the largest transmission error
    (exact involutes at the tight centre distance: 0)."""
    try:
        from gearkit.contact import Mesh, simulate
    except ImportError:
        return []
    from gearkit.families.involute import GearSpec, tooth_profile

    p1, p2 = tooth_profile(GearSpec(20, 1.0)), tooth_profile(GearSpec(40, 1.0))
    eps = _contact_ratio_closed_form(20, 40)
    rows = []
    for steps in ((64,) if quick else (64, 512)):
        seconds, res = median_time(lambda: simulate(Mesh(p1, p2, 30.0), steps=steps), 1 if steps > 1000 else repeats)
        rows.append({"family": "involute", "product": "contact simulation", "case": f"20/40 m=1, {steps} angles",
                     "seconds": seconds, "contact_ratio": res.contact_ratio,
                     "contact_ratio_error": abs(res.contact_ratio - eps),
                     "transmission_error_max_rad": res.transmission_error_max})
    return rows


def novikov_contact_rows(quick: bool, repeats: int):
    """Time of the Novikov pair's transverse contact solve (with and without the interference scan)."""
    try:
        from gearkit.families.novikov import NovikovPairSpec, tooth_profile
        from gearkit.families.novikov.mesh import mesh_contact
    except ImportError:
        return []
    spec = NovikovPairSpec(20, 40, 2.0, 15.0, 30.0)
    rows = []
    for scan in ((False,) if quick else (False, True)):
        def run():
            tooth_profile.cache_clear() if hasattr(tooth_profile, "cache_clear") else None
            return mesh_contact(spec, interference=scan)

        seconds, _ = median_time(run, repeats)
        rows.append({"family": "novikov", "product": "contact simulation",
                     "case": "dca24 20/40 m=2 beta=15" + (", interference scan" if scan else ", contact only"),
                     "seconds": seconds})
    return rows
