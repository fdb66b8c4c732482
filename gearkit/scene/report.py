"""What ``gearkit scene`` reports: kinematics, layout, mesh checks at a fidelity, and what was built.

:func:`scene_report` returns the JSON object (keys read by tools: ``dof``, ``ratio`` = w_input /
w_output, ``speeds`` {member: speed with the input at 1}, ``meshes`` [{``gears``,
``center_distance``, ``status``}], ``built`` {counts}); :func:`format_report` the text a user
reads.
"""
from __future__ import annotations

import math

__all__ = ["scene_report", "format_report"]


def _float(v):
    return None if v is None else float(v)


def _kinematics(model, state) -> dict:
    scene = model.scene
    motion = scene.state(state)
    one = len(motion.inputs) == 1
    inputs = {motion.inputs[0][0]: 1} if one else None
    sp = model.speeds(state, inputs)
    out = {"dof": sp.dof, "inputs": {k: v for k, v in motion.inputs} if not one else {motion.inputs[0][0]: 1.0},
           "output": motion.output, "ratio": None, "ratio_exact": None,
           "speeds": {m: _float(v) for m, v in sp.speeds.items()},
           "relative_speeds": {m: _float(sp.relative(m)) for m in scene.members
                               if scene.carrier_of(m) and sp.speeds[m] is not None
                               and sp.speeds[scene.carrier_of(m)] is not None},
           "mesh_frequencies": {k: _float(v) for k, v in sp.mesh_frequencies().items()}}
    if one and motion.output is not None:
        r = model.ratio(state)
        out["ratio"], out["ratio_exact"] = float(r), f"{r.numerator}/{r.denominator}"
    return out


def scene_report(model, fidelity: str = "formula", angle_deg: float = 0.0, state: str | None = None,
                 output: str | None = None) -> dict:
    """The report of a :class:`~gearkit.scene.SceneModel` at ``fidelity`` (see the module notes);
    ``output``: also export the placed scene there (.obj, .glb, .stl, .png, .svg)."""
    scene = model.scene
    out = {"fidelity": fidelity, "state": state}
    out.update(_kinematics(model, state))
    out["states"] = {}
    for name, _ in scene.states:
        k = _kinematics(model, name)
        out["states"][name] = {key: k[key] for key in ("dof", "ratio", "ratio_exact", "speeds")}
    layout = model.layout()
    out["gears"] = {g.name: {"teeth": g.teeth, "shift": g.shift, "module": scene.module_of(g),
                             "internal": g.internal, "member": g.member, "copies": g.count,
                             "helix_angle_deg": layout.helix[g.name], "tip_diameter": layout.tips.get(g.name)}
                    for g in scene.gears}
    out["planets"] = {}
    for carrier in scene.carriers:
        shafts = [m for m in scene.members if scene.carrier_of(m) == carrier]
        out["planets"][carrier] = {
            "shafts": {m: {"radius": layout.radii[m],
                           "angles_deg": [math.degrees(a) for a in scene.member_gears(m)[0].angles()]} for m in shafts},
            "neighbour_clearance": layout.neighbour_clearance[carrier]}
    checks = model.check(fidelity, angle_deg=angle_deg)
    out["meshes"] = [c.to_dict() for c in checks]
    out["ok"] = all(c.status != "fail" for c in checks)
    if output is not None:
        out["file"] = str(model.export(output, angle_deg))
        out["angle_deg"] = angle_deg
    out["built"] = dict(model.built)
    return out


def format_report(rep: dict, name: str = "scene") -> str:
    """The text of ``gearkit scene``."""
    rows = [f"{name}: {len(rep['gears'])} gears, {len(rep['meshes'])} meshes, DOF {rep['dof']}"]
    if rep["ratio"] is not None:
        (inp,) = rep["inputs"]
        rows.append(f"  ratio {inp}/{rep['output']} = {rep['ratio']:.10g} ({rep['ratio_exact']})")
    rows.append("  speeds (input at 1): " + ", ".join(
        f"{m} {v:+.6g}" if v is not None else f"{m} free" for m, v in rep["speeds"].items()))
    if rep["relative_speeds"]:
        rows.append("  relative to the carrier: " + ", ".join(f"{m} {v:+.6g}" for m, v in rep["relative_speeds"].items()))
    rows.append("  mesh frequencies (teeth per input turn): " + ", ".join(
        f"{k} {v:.6g}" for k, v in rep["mesh_frequencies"].items() if v is not None))
    for state, k in rep["states"].items():
        ratio = "-" if k["ratio"] is None else f"{k['ratio']:.10g} ({k['ratio_exact']})"
        rows.append(f"  state {state:<12} DOF {k['dof']}  ratio {ratio}")
    rows.append("  gears:")
    for g, info in rep["gears"].items():
        tip = "-" if info["tip_diameter"] is None else f"{info['tip_diameter']:.4f}"
        rows.append(f"    {g:<12} z {info['teeth']:>4}  x {info['shift']:+.4f}  d_a {tip} mm"
                    + (f"  x{info['copies']}" if info["copies"] > 1 else ""))
    for carrier, p in rep["planets"].items():
        for m, sh in p["shafts"].items():
            rows.append(f"  {carrier}: {m} at r = {sh['radius']:.6f} mm, angles "
                        + ", ".join(f"{a:.4g}" for a in sh["angles_deg"]) + " deg")
        rows.append(f"  {carrier}: neighbour tip clearance {p['neighbour_clearance']:.4f} mm")
    rows.append(f"  meshes ({rep['fidelity']}):")
    for m in rep["meshes"]:
        extra = ""
        if m["interference_volume"] is not None:
            extra = f"  3D interference {m['interference_volume']:.4g} mm^3 (bound {m['interference_bound']:.3g})"
        rows.append(f"    {m['mesh']:<16} a_w {m['center_distance']:.6f} mm  {m['status']}{extra}")
        for f in m["findings"]:
            rows.append(f"      {f['status']:<5} {f['id']}: {f['message']}")
    rows.append("  built: " + ", ".join(f"{k} {v}" for k, v in rep["built"].items()))
    if "file" in rep:
        rows.append(f"  wrote {rep['file']}")
    return "\n".join(rows)

