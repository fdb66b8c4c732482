"""Scenes: several placed gears modelled lazily (kinematics, planetary synthesis, queries at a fidelity).

A :class:`Scene` is a frozen value (gears with identity, shafts, carriers, meshes, motion and
states), built in Python or read from TOML (:func:`load_scene`); :func:`scene_speeds` solves its
kinematics without geometry; :func:`scene_layout` places it from pair formulas (one spec per
gear); :class:`SceneModel` answers queries at a fidelity (``formula``, ``generated``, ``simulated``,
``solid``), building only what each needs and counting it; :func:`synthesize` ranks planetary
tooth numbers for a ratio.
"""
from gearkit.scene.files import load_scene, scene_from_dict, scene_from_text
from gearkit.scene.kinematics import Relation, Speeds, Train, scene_speeds, scene_train
from gearkit.scene.layout import Layout, MeshLayout, scene_layout
from gearkit.scene.model import MESH_KINDS, Gear, Mesh, Motion, Scene
from gearkit.scene.query import FIDELITIES, MeshCheck, SceneModel
from gearkit.scene.phasing import PlanetMesh, Phasing, assembly_positions, planet_phasing, textbook_assembly
from gearkit.scene.synthesis import (SCHEMES, TEXTBOOK_LIMITS, PlanetarySet, SynthesisLimits, planetary_scene,
                                     synthesize)

__all__ = ["FIDELITIES", "MESH_KINDS", "MeshCheck", "SceneModel", "SCHEMES", "TEXTBOOK_LIMITS", "Gear", "Layout", "Mesh", "MeshLayout", "Motion", "Phasing",
           "PlanetMesh", "PlanetarySet", "Relation", "Scene", "Speeds", "SynthesisLimits", "Train",
           "assembly_positions", "load_scene", "planet_phasing", "planetary_scene", "scene_from_dict",
           "scene_from_text", "scene_layout", "scene_speeds", "scene_train", "synthesize", "textbook_assembly"]
