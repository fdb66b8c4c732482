"""One shift pair of a :class:`~gearkit.blocking.field.PairField`, evaluated lazily with the scalar pair formulas.

:class:`FieldPoint` computes the pair geometry (:func:`~gearkit.pair.pair_geometry`, with the form
circles the field reads) and the margins on first use, then keeps them. It is the reference the
array margins (:mod:`gearkit.blocking.arrays`) are held against, and what point queries use.

A pair exists where the check finds one: the pair formulas give one, and each generated gear has a
tooth. Below the shift where its cutter leaves an undercut gear no involute flank (and above the one
where its tip reaches its base circle) the formulas still give a pair, but the check raises: no
margin exists there, not even one that reads no form circle.
"""
from __future__ import annotations

import math

from gearkit.checks.involute import fail_margins
from gearkit.errors import SpecError
from gearkit.pair.geometry import pair_geometry

__all__ = ["FieldPoint"]

NAN = float("nan")
_pair_geometry = getattr(pair_geometry, "__wrapped__", pair_geometry)


class FieldPoint:
    """Lazy evaluation of one shift pair: geometry and margins computed on first use, then kept."""

    __slots__ = ("field", "x1", "x2", "exact", "_geo", "_m", "_invalid")

    def __init__(self, field: PairField, x1: float, x2: float, exact: bool = True):
        self.field, self.x1, self.x2, self.exact = field, x1, x2, exact
        self._geo, self._m, self._invalid = {}, {}, None

    @property
    def valid(self) -> bool:
        """False where no pair exists at these shifts (the check raises a SpecError there)."""
        if self._invalid is None:
            try:
                self.geometry()
                self._invalid = ""
            except SpecError as exc:
                self._invalid = str(exc)
        return not self._invalid

    @property
    def why(self) -> str:
        """Why no pair exists at these shifts ("" where one does)."""
        return "" if self.valid else self._invalid

    def geometry(self, needs=(False, False)):
        """The pair geometry, with the generated form circles of the gears flagged in ``needs``."""
        needs = (bool(needs[0]), bool(needs[1]))
        g = self._geo.get(needs)
        if g is not None:
            return g
        f = self.field
        teeth = self._teeth()
        forms = tuple(d if need else None for need, d in zip(needs, teeth))
        key = forms if any(d is not None for d in forms) else None
        g = self._geo.get(key)
        if g is None:
            # the function itself, not its cache: a point keeps its own geometries (and thousands of
            # traced points would only evict the check's entries)
            g = self._geo[key] = _pair_geometry(f.spec(self.x1, self.x2), key)
        self._geo[needs] = g
        return g

    def _teeth(self) -> tuple:
        """The generated form diameters of the gears (None where the closed form is exact, always for a
        ring), whatever margin is asked for: the check generates both gears and raises where one has no
        involute flank left, so no pair exists there, even for a margin that reads no form circle (a SpecError)."""
        out = self._geo.get("teeth")
        if out is None:
            f = self.field
            out = tuple(None if (f.internal and i == 2) else f.form_diameter(i, x, exact=self.exact)
                        for i, x in ((1, self.x1), (2, self.x2)))
            self._geo["teeth"] = out
        if any(d is not None and math.isnan(d) for d in out):
            raise SpecError("shift", "the generated gear has no tooth at this shift")
        return out

    def _fail(self, g) -> dict:
        """:func:`~gearkit.checks.involute.fail_margins` of ``g``, kept per geometry."""
        key = ("fail", id(g))
        out = self._geo.get(key)
        if out is None:
            out = self._geo[key] = fail_margins(g)
        return out

    def margin(self, name: str) -> float:
        m = self._m.get(name)
        if m is None:
            try:
                m = self._compute(name)
            except SpecError:
                m = NAN
            self._m[name] = m
        return m

    def _compute(self, name: str) -> float:
        f = self.field
        mn = f.module
        base, _, level = name.partition("=")
        if base.startswith("undercut."):
            i = int(base[-1])
            return (self.x1, self.x2)[i - 1] - f.x_min[i - 1]
        d = f.by_name.get(name)
        g = self.geometry(d.needs if d is not None else (False, False))
        if base in ("interference.1", "interference.2", "pointing.1", "pointing.2", "tip_clearance.1",
                    "tip_clearance.2"):
            return self._fail(g)[base] / mn
        if name == "contact_ratio=1":
            return self._fail(g)["contact_ratio"]
        if base == "contact_ratio":
            return g.contact_ratio - float(level)
        if base == "contact_ratio_tip":
            return g.contact_ratio_nominal - float(level)
        if base.startswith("tip_thickness."):
            return g.gears[int(base[-1]) - 1].tip_thickness_normal / mn - float(level)
        if base == "sliding":
            z1 = g.specific_sliding["start"][0]
            z2 = g.specific_sliding["end"][1]
            return abs(z1) - abs(z2)
        if base == "exit_jamming":
            from gearkit.pair.internal import exit_jamming_margin
            return exit_jamming_margin(g)
        if base == "trimming.plunge":
            from gearkit.pair.internal import plunge_trimming
            gap = plunge_trimming(g)[0]
            return gap / mn if gap > 0 else min(gap / mn, -5e-324)
        if base == "tip_interference":
            from gearkit.pair.internal import SWEEP_RESOLUTION, tip_sweep_depth
            from gearkit.pair.sweep import SWEEP_ENOUGH
            return SWEEP_RESOLUTION - tip_sweep_depth(g, enough=(SWEEP_RESOLUTION + SWEEP_ENOUGH) * mn)[0] / mn
        if base == "trimming.nu":
            from gearkit.pair.internal import nu_radius
            return (g.gears[1].tip_diameter / 2 - nu_radius(g)) / mn
        if base == "center_distance":
            return (g.center_distance - float(level)) / mn
        raise KeyError(name)

    def hard_margins(self) -> dict:
        """Every hard margin (module units / ratio / rad), NaN where no pair exists."""
        return {n: self.margin(n) for n in self.field.hard}
