"""``gearkit atlas``: blocking contours of every pair of a grid of tooth numbers, as a dataset.

Usage::

    gearkit atlas --z1 10:100:10 --z2 10:100:10 [--criterion balanced] [--tol 1e-4] [-o DIR]
                  [--workers 2 | --scheduler tcp://host:8786] [--internal --cutter-teeth 20] [--json]

Writes ``DIR/cells/z1-010_z2-020.json`` (one contour and recommendation per cell),
``DIR/index.json`` (a summary row per cell) and the contact sheet ``DIR/atlas.png``. Cells already in
``DIR`` are kept (an interrupted run resumes); the same input writes identical files.

Exit status: 0 ok, 2 bad input or I/O, 130 interrupted.
"""
from __future__ import annotations

import sys

from gearkit.cli.common import add_json_flag, add_output_flag, add_tol_flag, print_json
from gearkit.cli.design import add_design_argument
from gearkit.errors import SpecError

RANGE_MAX = 400  #: largest tooth number of an atlas axis


def register(subparsers) -> None:
    from gearkit.cli.blocking import add_template_arguments

    p = subparsers.add_parser(
        "atlas", help="blocking contours of a grid of tooth numbers: a dataset, an index and a contact sheet",
        description="Compute the blocking contour and the recommended shifts of every pair (z1, z2) of a grid "
                    "and write them as a dataset: one JSON file per cell, index.json, and the contact sheet "
                    "atlas.png. Resumable (cells on disk are kept) and deterministic. Runs on a local process "
                    "pool, or on a Dask cluster with --scheduler (needs gearkit[dask]).",
        epilog="Exit status: 0 ok, 2 bad input or I/O, 130 interrupted.")
    g = p.add_argument_group("pairs")
    add_design_argument(p, "pair")
    g.add_argument("--z1", help="pinion teeth: START:STOP:STEP (STOP included) or a,b,c (default: the design file's)")
    g.add_argument("--z2", help="wheel (ring) teeth: START:STOP:STEP or a,b,c (default: the design file's)")
    add_template_arguments(p, g)
    c = p.add_argument_group("contours")
    add_tol_flag(c, "accuracy of every traced line, shift units (default 1e-4)")
    c.add_argument("--criterion", choices=("balanced", "strength"), default="balanced",
                   help="recommendation criterion of every cell (default balanced)")
    r = p.add_argument_group("running")
    r.add_argument("--workers", type=int, default=2, help="local worker processes (default 2)")
    r.add_argument("--scheduler", help="address of a Dask scheduler (tcp://host:8786): run the cells there")
    r.add_argument("--no-progress", action="store_true", help="no progress bar on stderr, even with --progress")
    o = p.add_argument_group("output")
    add_output_flag(o, "directory of the dataset (default ./atlas; an existing one is resumed)", default="atlas")
    add_json_flag(o, "print the index as one JSON object")
    p.set_defaults(run=run, output_is_folder=True)  # -o names the dataset's folder (checked as one)


def parse_teeth(text: str, flag: str) -> list:
    """``10:100:10`` (stop included) or ``13,16,20`` -> sorted tooth numbers; SpecError naming ``flag``."""
    try:
        parts = [int(v) for v in text.split(":" if ":" in text else ",")]
    except ValueError:
        raise SpecError(flag, f"{text!r} is not START:STOP:STEP or comma-separated tooth numbers") from None
    if ":" in text:
        if len(parts) not in (2, 3):
            raise SpecError(flag, f"{text!r} is not START:STOP:STEP or comma-separated tooth numbers")
        start, stop = parts[0], parts[1]
        step = parts[2] if len(parts) == 3 else 1
        if step <= 0:
            raise SpecError(flag, f"{text!r}: the step must be a positive integer")
        if stop < start:
            raise SpecError(flag, f"{text!r} is empty: STOP must be at least START (STOP is included)")
        values = list(range(start, stop + 1, step))
    else:
        values = parts
    if min(values) < 3 or max(values) > RANGE_MAX:
        raise SpecError(flag, f"{text!r}: tooth numbers must lie in [3, {RANGE_MAX}]")
    return sorted(set(values))


def run(args) -> int:
    from gearkit.blocking.atlas import write_atlas
    from gearkit.cli.blocking import design_template, template_spec

    base = design_template(args)
    for name in ("z1", "z2"):
        if getattr(args, name) is None:
            if base is None or getattr(base, f"teeth{name[1]}") is None:
                raise SpecError(f"--{name}", "is required (or give a design file)")
            setattr(args, name, str(getattr(base, f"teeth{name[1]}")))
    z1s = parse_teeth(args.z1, "--z1")
    z2s = parse_teeth(args.z2, "--z2")
    if args.workers < 1:
        raise SpecError("--workers", f"{args.workers} must be a positive integer")
    template = template_spec(args, z1s[0], max(z2s[-1], z1s[0] + 8) if args.internal else z2s[0])
    options = {} if args.tol is None else {"tol": args.tol}
    try:
        index = write_atlas(z1s, z2s, args.output, template, workers=args.workers, scheduler=args.scheduler,
                            criterion=args.criterion, progress=False if args.no_progress else None, **options)
    except KeyboardInterrupt:  # the pool is stopped; the cells done are on disk, whole
        from pathlib import Path

        from gearkit.blocking.atlas import cell_name
        from gearkit.progress import line_break

        cells = Path(args.output) / "cells"
        done = sum((cells / cell_name(z1, z2)).exists() for z1 in z1s for z2 in z2s)
        print(f"{line_break()}gearkit atlas: interrupted; {done} of {len(z1s) * len(z2s)} cells are in "
              f"{cells}/ (the same command resumes)", file=sys.stderr)
        return 130
    if args.json:
        print_json(index, indent=None)
    else:
        cells = index["cells"]
        ok = sum(1 for c in cells if c["status"] == "ok")
        empty = sum(1 for c in cells if c.get("empty"))
        print(f"gearkit atlas: {len(cells)} cells ({ok} pairs, {empty} with an empty region, "
              f"{len(cells) - ok} not a pair) in {args.output}/ (index.json, cells/, atlas.png)")
    return 0


if __name__ == "__main__":  # pragma: no cover
    from gearkit.cli import main
    sys.exit(main(["atlas", *sys.argv[1:]]))
