"""Blocking contours: the map of admissible profile shifts (x1, x2) of a pair.

A blocking contour is the set of lines in the (x1, x2) plane that bound the shifts a pair may use
(reference digest 2): hard lines where :func:`~gearkit.checks.check_pair` starts to fail (B1/B2
tip-fillet interference, B3 eps_alpha = 1, B4/B5 pointed tips, B6 internal-pair jamming and
trimming) and quality lines inside (undercut onset, tip thickness levels, eps_alpha = 1.2, equal
specific sliding, constant centre distance). Every line is traced by root finding to a stated
tolerance from the same pair formulas and check functions as ``gearkit check``, evaluated as
arrays (:mod:`gearkit.blocking.arrays`); the region is the map of the check.

Modules, in the order a contour is made:

* margins: :mod:`~gearkit.blocking.field` (the check as functions of the shifts; lazily per point in
  :mod:`~gearkit.blocking.point`; the generated gears' form circles in :mod:`~gearkit.blocking.forms`)
  and the same on arrays, :mod:`~gearkit.blocking.arrays` over the pair geometry of
  :mod:`~gearkit.blocking.pair_arrays`, with the per-gear :mod:`~gearkit.blocking.gear_arrays` and the
  internal pair's :mod:`~gearkit.blocking.ring_arrays`;
* lines: :mod:`~gearkit.blocking.tracing` drives :mod:`~gearkit.blocking.level` (marching squares on
  the grids of :mod:`~gearkit.blocking.grid`, chords refined until they keep the tolerance in
  :mod:`~gearkit.blocking.refinement`, a chord's zero searched beyond its normal's ends in
  :mod:`~gearkit.blocking.wide`, roots and strips in :mod:`~gearkit.blocking.brackets`, kinked
  corners in :mod:`~gearkit.blocking.corners`); beside the no-pair area, :mod:`~gearkit.blocking.band`
  on the lattice of :mod:`~gearkit.blocking.lattice`, its edge in :mod:`~gearkit.blocking.edges`, its
  pieces joined to the grid's lines by :mod:`~gearkit.blocking.joins`; lines
  the grid cut short carried on by :mod:`~gearkit.blocking.ends` (continued as the fronts of
  :mod:`~gearkit.blocking.fronts`), undercut onsets made exact by :mod:`~gearkit.blocking.onsets`;
* region: :mod:`~gearkit.blocking.region` (polygons where the check passes; what its function does between two
  cuts of its outline in :mod:`~gearkit.blocking.between`), its thin wedges traced to
  their tips by :mod:`~gearkit.blocking.tips` (each tip solved in the plane by :mod:`~gearkit.blocking.apex`, the
  region's parts and which binds where in :mod:`~gearkit.blocking.parts`, a part beyond a saddle's neck walked round
  by :mod:`~gearkit.blocking.walk`), a flat strip's last cut carried down to the strip's end by
  :mod:`~gearkit.blocking.flats`;
* use: :mod:`~gearkit.blocking.contour` (the result and point queries), :mod:`~gearkit.blocking.recommend`,
  :mod:`~gearkit.blocking.plot` (pictures, JSON; the zoom about a star the region is thinner than in
  :mod:`~gearkit.blocking.inset`), :mod:`~gearkit.blocking.atlas` (many pairs in parallel).

>>> from gearkit.pair import PairSpec
>>> c = blocking_contour(PairSpec(13, 16, 1.0), tol=1e-6, lines=["undercut.1"])
>>> round(float(c.line("undercut.1").points[0, 0]), 6), c.contains(0.5, 0.3)
(0.239644, True)
"""
from gearkit.blocking.atlas import BlockingAtlas, blocking_atlas, write_atlas
from gearkit.blocking.contour import BlockingContour, Line, blocking_contour, default_window
from gearkit.blocking.field import LineDef, PairField
from gearkit.blocking.recommend import CRITERIA, Recommendation, recommend

__all__ = ["CRITERIA", "BlockingAtlas", "BlockingContour", "Line", "LineDef", "PairField", "Recommendation",
           "blocking_atlas", "blocking_contour", "default_window", "recommend", "write_atlas"]
