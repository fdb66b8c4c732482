"""Regenerate the README's "Speed and accuracy" section from a fresh ``gearkit bench`` run.

    python examples/bench_table.py            # full bench, rewrite README.md between the markers
    python examples/bench_table.py --quick    # the quick bench (under a minute)
    python examples/bench_table.py --print    # print the block, leave README.md alone
    python examples/bench_table.py --from-json bench.json   # render a saved `gearkit bench -o bench.json` run

The block lives between ``<!-- bench:start -->`` and ``<!-- bench:end -->``; nothing outside
the markers is touched. The numbers are measured, never typed.

The script runs the bench as ``gearkit bench`` runs it: :mod:`gearkit.cli` is imported before numpy
loads, so numpy's BLAS runs on one thread (unless the environment says otherwise) in the timed
in-process rows too, and the whole-process rows' children still start in the user's environment.
"""
from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

import gearkit.cli  # noqa: F401 - before numpy loads: its BLAS on one thread, as the command runs
from gearkit.bench import markdown_table, run_bench  # noqa: E402

START, END = "<!-- bench:start -->", "<!-- bench:end -->"
README = Path(__file__).resolve().parent.parent / "README.md"


def replace_block(text: str, block: str) -> str:
    """``text`` with everything between the markers replaced by ``block``."""
    i, j = text.find(START), text.find(END)
    if i < 0 or j < i:
        raise SystemExit(f"{README}: markers {START} ... {END} not found")
    return text[: i + len(START)] + "\n" + block.rstrip() + "\n" + text[j:]


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--print", dest="print_only", action="store_true")
    ap.add_argument("--from-json", default=None, help="render this saved bench run instead of running one")
    ap.add_argument("--readme", default=str(README))
    args = ap.parse_args(argv)
    if args.from_json:
        res = json.loads(Path(args.from_json).read_text(encoding="utf-8"))
    else:
        res = run_bench(quick=args.quick, progress=lambda m: print(f"bench: {m} ...", file=sys.stderr, flush=True))
    block = markdown_table(res)
    if args.print_only:
        print(block)
        return 0
    path = Path(args.readme)
    path.write_text(replace_block(path.read_text(encoding="utf-8"), block), encoding="utf-8")
    print(f"updated {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
