"""Scenes: several placed gears modelled lazily (kinematics, planetary synthesis, queries at a fidelity).

A :class:`Scene` is a frozen value (gears with identity, shafts, carriers, meshes, motion and
states); :func:`scene_speeds` solves its kinematics without geometry; :func:`synthesize`
ranks planetary tooth numbers for a ratio.
"""
from gearkit.scene.kinematics import Relation, Speeds, Train, scene_speeds, scene_train
from gearkit.scene.model import MESH_KINDS, Gear, Mesh, Motion, Scene

__all__ = ["MESH_KINDS", "Gear", "Mesh", "Motion", "Relation", "Scene", "Speeds", "Train", "scene_speeds",
           "scene_train"]
