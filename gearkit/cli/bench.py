"""``gearkit bench``: measure the speed-accuracy trade on this machine."""
from __future__ import annotations

import sys

from gearkit.cli.common import add_json_flag, add_output_flag


def register(subparsers) -> None:
    p = subparsers.add_parser(
        "bench", help="measure accuracy vs time: tolerance ladder, scaling in z, oracle, overhead",
        description="Measure the speed-accuracy trade: for each family and product, the requested tolerance "
                    "(1e-1 m ... 1e-7 m) against the achieved deviation (measured independently by dense "
                    "re-evaluation of the exact curve), vertex count and wall time; scaling in z; the swept-tool "
                    "oracle's convergence; the kernel's overhead over numpy's closed-form involute; whole-process "
                    "times of 'gearkit gear'. Lengths in mm.")
    p.add_argument("--quick", action="store_true", help="fewer cases and repeats (under a minute)")
    add_output_flag(p, "also write the results as JSON to FILE (checked before the bench runs)", metavar="FILE")
    add_json_flag(p, "print the results as one JSON object instead of the table")
    p.add_argument("--no-process", action="store_true", help="skip the whole-process (subprocess) timings")
    p.set_defaults(run=run)


def run(args) -> int:
    import json

    from gearkit.bench import format_table, run_bench

    res = run_bench(quick=args.quick, process=not args.no_process)  # its bar: gearkit.progress
    text = json.dumps(res, indent=1, allow_nan=False) + "\n"
    print(text if args.json else format_table(res), end="" if args.json else "\n")
    if args.output:
        from gearkit.export import atomic_write

        def write(tmp):
            with open(tmp, "w", encoding="utf-8") as fh:
                fh.write(text)

        atomic_write(args.output, write)
        print(f"gearkit bench: wrote {args.output}", file=sys.stderr)
    return 0
