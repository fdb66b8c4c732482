"""Blocking contour of the textbook's z1 = 13, z2 = 16 pair: lines, region, recommendation, picture.

Run: python examples/blocking_contour.py [output.png|.svg|.json]
"""
import sys

from gearkit.blocking import blocking_contour
from gearkit.pair import PairSpec

contour = blocking_contour(PairSpec(13, 16, module=1.0))
rec = contour.recommend("balanced")
mark = contour.mark(0.5, 0.3)
print(f"{len(contour.lines)} lines, region of {len(contour.region)} polygon(s), {contour.seconds:.2f} s")
print(f"recommended x1 = {rec.x1:.4f}, x2 = {rec.x2:.4f}: {rec.reason}")
print(f"design point (0.5, 0.3): {'inside' if mark['inside'] else 'outside'} {mark['binding']}")
out = sys.argv[1] if len(sys.argv) > 1 else "blocking_13_16.png"
contour.save(out, rec, mark)
print(f"wrote {out}")
