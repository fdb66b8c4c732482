"""Blocking contours: the map of admissible profile shifts (x1, x2) of a pair.

A blocking contour is the set of lines in the (x1, x2) plane that bound the shifts a pair may use
(reference digest 2): hard lines where :func:`~gearkit.checks.check_pair` starts to fail (B1/B2
tip-fillet interference, B3 eps_alpha = 1, B4/B5 pointed tips, B6 internal-pair jamming and
trimming) and quality lines inside (undercut onset, tip thickness levels, eps_alpha = 1.2, equal
specific sliding, constant centre distance). Every line is traced by root finding to a stated
tolerance from the same pair formulas and check functions as ``gearkit check``, evaluated as
arrays (:mod:`gearkit.blocking.arrays`); the region is the map of the check.

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
