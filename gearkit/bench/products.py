"""Products beyond the 2D profile: pair check, and the families and products that may not exist yet.

Each product is measured when its module imports; otherwise the bench lists it as not
available (so the table says what was measured, never silently skips).
"""
from __future__ import annotations

import importlib

from gearkit.bench.timing import median_time

#: product -> module that provides it (checked by import)
PRODUCT_MODULES = {
    ("involute", "mesh"): "gearkit.solids",
    ("involute", "blocking contour"): "gearkit.blocking",
    ("involute", "contact simulation"): "gearkit.contact",
    ("cycloid", "profile"): "gearkit.families.cycloid",
    ("pinwheel", "profile"): "gearkit.families.pinwheel",
    ("novikov", "profile"): "gearkit.families.novikov",
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
    from gearkit.tools import ShaperCutter

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
