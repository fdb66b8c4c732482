"""Lazy queries on a scene at a named fidelity, with a record of what was built.

One vocabulary for fidelity: ``formula`` (pair formulas, no tooth), ``generated`` (the exact
generated teeth), ``simulated`` (the generated teeth meshed over a cycle), ``solid`` (meshes,
3D interference). What each query costs:

==========================  =====================================================================
query                       builds
==========================  =====================================================================
``speeds``, ``ratio``       nothing: a rational linear solve (:mod:`gearkit.scene.kinematics`)
``layout``                  pair formulas of every mesh (microseconds)
``check("formula")``        the formula layout, then the formula checks of each mesh
``check("generated")``      one generated profile per *distinct* gear (a planet is built once for
                            all its copies and meshes), then the checks read off them
``check("simulated")``      the above plus one meshing simulation per mesh (about a second each)
``check("solid")``          the above plus one solid per distinct gear and, for each mesh asked,
                            the 3D interference of its two placed solids
``parts``, ``export``       one solid per distinct gear, placed as copies
==========================  =====================================================================

Results are cached by (gear spec, fidelity, tol); :attr:`SceneModel.built` counts what the
scene asked the kernel to build (``profiles``, ``simulations``, ``solids``, ``interference``), so a
test can prove that a query built only what it needed.

Examples
--------
>>> from gearkit.scene.model import Gear, Mesh, Motion, Scene
>>> s = Scene((Gear("a", 15), Gear("idler", 30, 0.5), Gear("b", 40)), (Mesh("a", "idler"), Mesh("idler", "b")),
...           module=2.0, motion=Motion(inputs={"a": 1}, output="b"))
>>> model = SceneModel(s)
>>> model.ratio(), model.built["profiles"]
(Fraction(8, 3), 0)
>>> checks = model.check("generated")
>>> model.built["profiles"]
3
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from gearkit.errors import SpecError, require
from gearkit.progress import Progress

__all__ = ["FIDELITIES", "MeshCheck", "SceneModel"]

FIDELITIES = ("formula", "generated", "simulated", "solid")


@dataclass(frozen=True)
class MeshCheck:
    """One mesh checked at a fidelity: the pair check and, at ``solid``, the 3D interference volume
    (mm^3) of its placed solids with the volume the meshes' own tolerance can fake (None below
    ``solid``).

    Two solids within ``tol`` of their exact teeth may overlap where the exact teeth only touch: the
    mesh fails when the overlap exceeds a layer ``2 tol`` deep over the face width and one module of
    profile (``interference_bound``).
    """

    label: str
    names: tuple
    center_distance: float
    check: object
    interference: float | None = None
    interference_bound: float | None = None

    @property
    def status(self) -> str:
        if self.interference is not None and self.interference > self.interference_bound:
            return "fail"
        return self.check.report.status

    def to_dict(self) -> dict:
        return {"mesh": self.label, "gears": list(self.names), "center_distance": self.center_distance,
                "status": self.status, "interference_volume": self.interference,
                "interference_bound": self.interference_bound,
                "findings": [f.to_dict() for f in self.check.report.findings if f.status != "ok"]}


class SceneModel:
    """A scene and everything built for it so far (see the module notes).

    Parameters
    ----------
    scene : Scene
    tol : float or None, mm
        Largest deviation of outlines and solids from the exact teeth (default ``5e-3 m`` for
        solids, ``1e-3 m`` for outlines).
    width : float or None, mm
        Face width of the solids (default: the scene's, else 8 modules).
    steps : int
        Steps of each meshing simulation.
    state : str or None
        The state (brakes, clutches) whose motion turns the parts for an input angle.
    """

    def __init__(self, scene, tol: float | None = None, width: float | None = None, steps: int = 2000,
                 state: str | None = None):
        from gearkit.scene.model import Scene

        require(isinstance(scene, Scene), "scene", "give a Scene")
        if tol is not None:
            require(isinstance(tol, (int, float)) and math.isfinite(tol) and tol > 0, "tol",
                    f"{tol!r} must be a positive length in mm")
        if width is not None:
            require(isinstance(width, (int, float)) and math.isfinite(width) and width > 0, "width",
                    f"{width!r} must be a positive length in mm")
        self.scene = scene
        self.tol = tol
        self.width = width if width is not None else (scene.face_width or 8.0 * scene.module)
        self.steps = int(steps)
        scene.state(state)  # raises for an unknown state
        self.state = state
        self.built = {"profiles": 0, "simulations": 0, "solids": 0, "interference": 0}
        self._cache = {}

    # -- no geometry ----------------------------------------------------------------------
    def speeds(self, state: str | None = None, inputs: dict | None = None):
        """Speeds of every member (:func:`~gearkit.scene.scene_speeds`); builds nothing."""
        from gearkit.scene.kinematics import scene_speeds

        return scene_speeds(self.scene, state, inputs)

    def ratio(self, state: str | None = None):
        """``w_input / w_output`` of the motion (one input) in ``state``; builds nothing."""
        motion = self.scene.state(state)
        require(len(motion.inputs) == 1, "motion.input", "a ratio needs exactly one input")
        require(motion.output is not None, "motion.output", "give an output to ask for a ratio")
        name = motion.inputs[0][0]
        return self.speeds(state, {name: 1}).ratio(self.scene.member_of(name), self.scene.member_of(motion.output))

    # -- geometry, lazily -----------------------------------------------------------------
    def layout(self):
        """The formula layout (:func:`~gearkit.scene.scene_layout`)."""
        from gearkit.scene.layout import scene_layout

        return scene_layout(self.scene)

    def _cached(self, key, counter, build):
        if key not in self._cache:
            self._cache[key] = build()
            if counter:
                self.built[counter] += 1
        return self._cache[key]

    def profile(self, gear: str):
        """The generated tooth profile of ``gear`` (one per distinct gear spec)."""
        from gearkit.families.involute import tooth_profile

        spec = self.layout().gear_spec(gear)
        return self._cached((spec, "generated", None), "profiles", lambda: tooth_profile(spec))

    def _profiles(self, mesh_layout) -> tuple:
        names = mesh_layout.names[: 1 if mesh_layout.kind == "rack" else 2]
        return tuple(self.profile(n) for n in names)

    def simulation(self, label: str):
        """The meshing simulation of mesh ``label`` (:func:`~gearkit.contact.analyse_pair`)."""
        from gearkit.contact import analyse_pair

        m = self.layout().mesh(label)
        profiles = self._profiles(m)
        return self._cached((m.spec, "simulated", self.tol), "simulations",
                            lambda: analyse_pair(m.spec, self.steps, tol=self.tol, profiles=profiles))

    def solid(self, gear: str):
        """The solid of ``gear`` in its own frame (one per distinct gear spec and tol)."""
        from gearkit.solids import SolidSpec, gear_solid

        spec = self.layout().gear_spec(gear)
        key = (spec, "solid", self.tol, self.width)
        return self._cached(key, "solids", lambda: gear_solid(self.profile(gear), SolidSpec(width=self.width),
                                                              self.tol, name=gear))

    def poses(self, angle_deg: float = 0.0) -> list:
        """Every gear copy placed (:func:`~gearkit.scene.placement.poses`) with the input turned by
        ``angle_deg`` degrees."""
        from gearkit.scene.placement import poses

        speeds = None
        if angle_deg:
            motion = self.scene.state(self.state)
            require(len(motion.inputs) == 1, "angle", "turning the input needs exactly one input")
            speeds = self.speeds(self.state, {motion.inputs[0][0]: 1})
        return poses(self.scene, self.layout(), speeds, math.radians(angle_deg))

    def parts(self, angle_deg: float = 0.0) -> list:
        """Every gear copy as a placed :class:`~gearkit.solids.Solid` named ``gear`` or ``gear#k``."""
        return [self.solid(p.gear).placed(p.rotation, (p.x, p.y, 0.0), p.name) for p in self.poses(angle_deg)]

    def outlines(self, angle_deg: float = 0.0) -> list:
        """Every gear copy's closed outline placed in the scene: [(name, (n, 2) float64 mm)]."""
        import numpy as np

        out = []
        for p in self.poses(angle_deg):
            prof = self.profile(p.gear)
            tol = self.tol if self.tol is not None else 1e-3 * prof.module
            pts = self._cached((self.layout().gear_spec(p.gear), "outline", tol), None, lambda: prof.outline(tol))
            c, s = math.cos(p.rotation), math.sin(p.rotation)
            out.append((p.name, pts @ np.array([[c, s], [-s, c]]) + (p.x, p.y)))
        return out

    def interference(self, label: str, angle_deg: float = 0.0) -> float:
        """3D interference volume (mm^3) of mesh ``label``'s two placed solids (first copies)."""
        m = self.layout().mesh(label)
        placed = {p.name: p for p in self.poses(angle_deg)}
        parts = []
        for name in (m.mesh.first, m.mesh.second):
            p = placed[name]
            parts.append(self.solid(name).placed(p.rotation, (p.x, p.y, 0.0), p.name))
        key = (m.spec, "interference", self.tol, self.width, angle_deg)
        return self._cached(key, "interference",
                            lambda: float((parts[0].manifold ^ parts[1].manifold).volume()))

    def check(self, fidelity: str = "formula", meshes=None, angle_deg: float = 0.0) -> list:
        """Check every mesh (or those named in ``meshes``) at ``fidelity``: a list of :class:`MeshCheck`."""
        require(fidelity in FIDELITIES, "fidelity", f"{fidelity!r} is not one of {', '.join(FIDELITIES)}")
        layout = self.layout()
        wanted = [m.mesh.label for m in layout.meshes] if meshes is None else list(meshes)
        out = []
        with Progress("scene", len(wanted), unit="meshes") as bar:
            for k, label in enumerate(wanted):
                bar.note = f"mesh {label}"
                bar.update(k)
                out.append(self._check_mesh(layout.mesh(label), fidelity, angle_deg))
        return out

    def _check_mesh(self, m, fidelity: str, angle_deg: float):
        """The :class:`MeshCheck` of one mesh of the layout at ``fidelity``."""
        from gearkit.checks.involute import check_pair

        label = m.mesh.label
        if fidelity == "formula":
            chk = check_pair(m.spec, geometry="formula")
        elif fidelity == "simulated":
            chk = check_pair(m.spec, simulate=True, profiles=self._profiles(m), analysis=self.simulation(label))
        else:
            chk = check_pair(m.spec, profiles=self._profiles(m))
        inter = bound = None
        if fidelity == "solid":
            inter = self.interference(label, angle_deg)
            tol = max(self.solid(n).info["tol"] for n in (m.mesh.first, m.mesh.second))
            bound = 2.0 * tol * self.width * m.spec.module
        return MeshCheck(label, m.names, m.center_distance, chk, inter, bound)

    def export(self, path, angle_deg: float = 0.0):
        """Write the placed scene: ``.obj``/``.glb``/``.stl`` (solids, named parts) or ``.png``/``.svg``
        (the placed outlines); atomic. Returns the path."""
        from pathlib import Path

        suffix = Path(path).suffix.lower()
        if suffix in (".png", ".svg"):
            from gearkit.scene.picture import write_picture

            return write_picture(path, self, angle_deg)
        from gearkit.solids import write_mesh
        from gearkit.solids.export import mesh_format

        if mesh_format(path) is None:
            raise SpecError("output", f"unknown format {suffix!r} for {str(path)!r}; allowed: .obj, .glb, .stl, "
                            ".3mf, .step, .png, .svg")
        return write_mesh(path, self.parts(angle_deg))
