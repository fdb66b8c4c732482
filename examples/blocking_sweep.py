"""Measure blocking contours against their contract (achieved deviation <= 2 tol).

Each contour is measured as ``gearkit bench`` measures its contract rows: the exact deviation of every
traced line and of the region from the zero sets of their margins, and the scan gap (exact zeros on
scan lines across the window that no traced line comes near), both divided by tol.

Pairs are named ``Z1/Z2`` (external) or ``Z1/Z2/Z0`` (internal, Z0 the shaper's teeth), or drawn at
random (``--seed``: eight pairs a seed, the generator of the blocking contract tests)::

    python examples/blocking_sweep.py 46/49/20 12/30 --tol 1e-3
    python examples/blocking_sweep.py --seed 1 2 --internal --tol 1e-3 1e-5

One line a contour: the pair, tol, exact / tol, scan / tol, CPU seconds, and ``OFF`` where either
ratio exceeds 2; then how many of them keep the contract.
"""
from __future__ import annotations

import argparse
import time

import numpy as np

from gearkit.bench.exact import deviation
from gearkit.bench.topology import scan_gap
from gearkit.blocking import blocking_contour
from gearkit.errors import SpecError
from gearkit.families.involute import ShaperCutter
from gearkit.pair import PairSpec

PAIRS_PER_SEED = 8


def pair_of(name: str) -> PairSpec:
    """``"Z1/Z2"`` -> external pair, ``"Z1/Z2/Z0"`` -> internal pair cut by a Z0-tooth shaper."""
    parts = name.split("/")
    if len(parts) not in (2, 3) or not all(v.isdigit() for v in parts):
        raise SpecError("pair", f"{name!r} must be Z1/Z2 or Z1/Z2/Z0 (whole numbers of teeth)")
    z = [int(v) for v in parts]
    if len(z) == 2:
        return PairSpec(z[0], z[1], 1.0)
    return PairSpec(z[0], z[1], 1.0, kind="internal", tool2=ShaperCutter(z[2]))


def random_names(seed: int, internal: bool) -> list:
    """The eight pairs of ``seed`` (z1 12..49, z2 z1+6..z1+65, shaper 12..min(39, z2-6) internal;
    z1 10..59, z2 z1..119 external)."""
    rng = np.random.default_rng(seed)
    names = []
    for _ in range(PAIRS_PER_SEED):
        if internal:
            z1 = int(rng.integers(12, 50))
            z2 = z1 + int(rng.integers(6, 60))
            names.append(f"{z1}/{z2}/{int(rng.integers(12, min(40, z2 - 5)))}")
        else:
            z1 = int(rng.integers(10, 60))
            names.append(f"{z1}/{int(rng.integers(z1, 120))}")
    return names


def measure(name: str, tol: float) -> dict:
    c0 = time.process_time()
    contour = blocking_contour(pair_of(name), tol=tol)
    seconds = time.process_time() - c0
    exact, scan = deviation(contour) / tol, scan_gap(contour)[0] / tol
    return {"pair": name, "tol": tol, "exact": exact, "scan": scan, "seconds": seconds,
            "ok": max(exact, scan) <= 2.0}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("pairs", nargs="*", help="Z1/Z2 or Z1/Z2/Z0")
    ap.add_argument("--seed", type=int, nargs="*", default=[], help="random pairs of these seeds")
    ap.add_argument("--internal", action="store_true", help="random pairs are internal")
    ap.add_argument("--tol", type=float, nargs="+", default=[1e-3])
    args = ap.parse_args(argv)
    names = list(args.pairs) + [n for s in args.seed for n in random_names(s, args.internal)]
    kept = total = 0
    try:
        for name in names:  # every name read before the first (long) contour
            pair_of(name)
    except SpecError as e:
        ap.exit(2, f"blocking_sweep: {e}\n")
    for tol in args.tol:
        for name in names:
            try:
                r = measure(name, tol)
            except SpecError as e:
                ap.exit(2, f"blocking_sweep: {e}\n")
            kept, total = kept + r["ok"], total + 1
            print(f"{name:>10} tol {tol:.0e}  exact {r['exact']:7.3g}  scan {r['scan']:7.3g}  "
                  f"{r['seconds']:6.1f} s{'' if r['ok'] else '  OFF'}", flush=True)
    print(f"{kept} of {total} within 2 tol")
    return 0 if kept == total else 1


if __name__ == "__main__":
    try:
        raise SystemExit(main())
    except KeyboardInterrupt:
        raise SystemExit("blocking_sweep: interrupted")
