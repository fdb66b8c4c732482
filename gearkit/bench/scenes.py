"""Scene rows of the bench: what each query costs at each fidelity, and planetary synthesis time.

Two scenes: the README's 3-planet set (``examples/planetary.toml``, 3 distinct gears, 5 parts)
and seed 003's four-speed box (7 distinct gears, 16 parts, state ``first``). Every row starts
from a fresh :class:`~gearkit.scene.SceneModel` with the kernel's caches cleared, so a row is
the cold cost of that query alone; ``built`` says what it built.
"""
from __future__ import annotations

from gearkit.bench.timing import median_time

__all__ = ["scene_rows", "synthesis_rows", "format_rows", "markdown_rows", "SCENES"]

PLANETARY = """\
module = 1.75
[gears]
sun    = { teeth = 21, shift = 0.438 }
planet = { teeth = 43, shift = 0.0426, count = 3, carrier = "carrier" }
ring   = { teeth = 108, internal = true }
[meshes]
sun-planet  = ["sun", "planet"]
planet-ring = ["planet", "ring"]
[motion]
fixed  = ["ring"]
input  = "sun"
output = "carrier"
"""

FOUR_SPEED = """\
module = 2.0
[gears]
s1    = { teeth = 120 }
s3    = { teeth = 144, shift = -0.1 }
s5    = { teeth = 80 }
ring4 = { teeth = 240, internal = true }
p2    = { teeth = 40, shaft = "block", carrier = "H", count = 4 }
p2b   = { teeth = 16, shaft = "block", carrier = "H", count = 4, shift = 0.1 }
p2c   = { teeth = 80, shaft = "block", carrier = "H", count = 4 }
[meshes]
s1-p2     = ["s1", "p2"]
s3-p2b    = ["s3", "p2b"]
s5-p2c    = ["s5", "p2c"]
p2c-ring4 = ["p2c", "ring4"]
[motion]
input  = "s1"
output = "s5"
[states.first]
fixed = ["s3"]
"""

#: (case, scene text, state)
SCENES = (("3-planet set 21/43/108", PLANETARY, None), ("four-speed box (state first)", FOUR_SPEED, "first"))


def _cold():
    """Clear the kernel's caches so the next query builds from scratch."""
    from gearkit.families.involute import tooth_profile
    from gearkit.pair import pair_geometry
    from gearkit.scene import scene_layout

    tooth_profile.cache_clear()
    pair_geometry.cache_clear()
    scene_layout.cache_clear()


def scene_rows(quick: bool, repeats: int) -> list:
    """One row per (scene, query): seconds (median of cold runs), what was built, the ratio."""
    from gearkit.scene import SceneModel, scene_from_text

    steps = 300 if quick else 2000
    rows = []
    for case, text, state in SCENES:
        scene = scene_from_text(text)
        queries = (("ratio", None, lambda m: m.ratio(state)),
                   ("check", "formula", lambda m: m.check("formula")),
                   ("check", "generated", lambda m: m.check("generated")),
                   ("check", "simulated", lambda m: m.check("simulated")),
                   ("check", "solid", lambda m: m.check("solid")),
                   ("solids (all parts)", "solid", lambda m: m.parts()))
        for query, fidelity, run in queries:
            expensive = fidelity in ("simulated", "solid")
            holder = {}

            def once(run=run):
                _cold()
                model = SceneModel(scene, steps=steps, state=state)
                holder["result"] = run(model)
                holder["model"] = model

            once()  # untimed: loads the modules the query needs, so the rows time the work alone
            seconds, _ = median_time(once, 1 if expensive or quick else repeats, budget=5.0)
            model = holder["model"]
            result = holder["result"]
            row = {"case": case, "query": query, "fidelity": fidelity, "seconds": seconds,
                   "built": dict(model.built), "ratio": float(model.ratio(state))}
            if query == "check":
                row["status"] = sorted({c.status for c in result})
            if query.startswith("solids"):
                row["parts"] = len(result)
            rows.append(row)
    return rows


def synthesis_rows(quick: bool, repeats: int) -> list:
    """Planetary synthesis: exact and 1 % ratio, 3 planets, every gear up to 200 teeth."""
    from gearkit.scene import SynthesisLimits, synthesize
    from gearkit.scene.synthesis import TEXTBOOK_LIMITS

    cases = (("i = 43/7 exact, K = 3, z <= 200, checks", 43 / 7, 0.0, SynthesisLimits(max_teeth=200), "simple"),
             ("i = 6.14 +- 1 %, K = 3, z <= 200, checks", 6.14, 0.01, SynthesisLimits(max_teeth=200), "simple"),
             ("i = 18/5 textbook limits (Ex.6)", 3.6, 0.0, TEXTBOOK_LIMITS, "simple"),
             ("i = 10 compound, textbook (Ex.9)", 10.0, 0.0, TEXTBOOK_LIMITS, "compound"))
    rows = []
    for case, ratio, tol, limits, scheme in cases:
        def run(ratio=ratio, tol=tol, limits=limits, scheme=scheme):
            _cold()
            return synthesize(ratio, 3, 1.75, scheme=scheme, ratio_tol=tol, limits=limits, count=5)

        run()  # untimed warm-up (module imports)
        seconds, sets = median_time(run, repeats, budget=10.0)
        rows.append({"case": case, "scheme": scheme, "seconds": seconds, "found": len(sets),
                     "best": list(sets[0].teeth) if sets else None, "target_seconds": 1.0})
    return rows


def format_rows(res: dict) -> list:
    """Text lines of the scene block of ``gearkit bench``."""
    lines = ["scenes (cold: fresh scene, kernel caches cleared; built = profiles/simulations/solids/interference)"]
    for r in res.get("scenes", []):
        b = r["built"]
        built = f"{b['profiles']}/{b['simulations']}/{b['solids']}/{b['interference']}"
        what = r["query"] + (f" {r['fidelity']}" if r["fidelity"] else "")
        extra = f"  status {','.join(r['status'])}" if "status" in r else ""
        extra += f"  {r['parts']} parts" if "parts" in r else ""
        lines.append(f"  {r['case']:30} {what:22} {_fmt(r['seconds']):>11}  built {built:>9}{extra}")
    lines.append("planetary synthesis (target: K = 3 up to 200 teeth under 1 s)")
    for r in res.get("synthesis", []):
        lines.append(f"  {r['case']:44} {_fmt(r['seconds']):>11}  {r['found']} sets, best {r['best']}")
    return lines


def _fmt(s):
    return f"{s * 1e3:8.2f} ms" if s < 1.0 else f"{s:8.3f} s "


def markdown_rows(res: dict) -> list:
    """Markdown lines of the scene block (README)."""
    out = ["**Scenes** (cold: a fresh scene with the kernel's caches cleared; built = profiles / simulations / "
           "solids / 3D interference runs)", "", "| scene | query | time | built |", "|---|---|---:|---:|"]
    for r in res.get("scenes", []):
        b = r["built"]
        what = r["query"] + (f" {r['fidelity']}" if r["fidelity"] and r["query"] == "check" else "")
        out.append(f"| {r['case']} | {what} | {_fmt(r['seconds']).strip()} | {b['profiles']} / {b['simulations']} / "
                   f"{b['solids']} / {b['interference']} |")
    out += ["", "| planetary synthesis (3 planets) | time | best |", "|---|---:|---|"]
    for r in res.get("synthesis", []):
        out.append(f"| {r['case']} | {_fmt(r['seconds']).strip()} | {r['best']} |")
    out.append("")
    return out
