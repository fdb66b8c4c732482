"""Mesh files, written atomically: STL (binary, or ASCII on request), OBJ and GLB.

STL is written with numpy straight from the solid's arrays (single precision, as the format
stores it), so a plain export never imports trimesh. OBJ (one named object per part) and GLB
(one named node per part) go through trimesh. Every writer goes through
:func:`gearkit.export.atomic_write`: a failed export leaves no file behind.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from gearkit.errors import SpecError
from gearkit.export import atomic_write

MESH_FORMATS = ("stl", "obj", "glb")

_STL_RECORD = np.dtype([("normal", "<f4", (3,)), ("vertices", "<f4", (3, 3)), ("attr", "<u2")])


def mesh_format(path) -> str | None:
    """The mesh format named by ``path``'s extension, or None for any other extension."""
    ext = Path(path).suffix.lower().lstrip(".")
    return ext if ext in MESH_FORMATS else None


def _triangles(parts):
    """(m, 3, 3) float32 triangles of all parts and their (m, 3) float32 unit normals."""
    tris = []
    for part in parts:
        v, f = part.arrays()
        tris.append(v[f])
    tri = np.concatenate(tris).astype(np.float32)
    t64 = tri.astype(np.float64)
    n = np.cross(t64[:, 1] - t64[:, 0], t64[:, 2] - t64[:, 0])
    length = np.linalg.norm(n, axis=1, keepdims=True)
    n = np.divide(n, length, out=np.zeros_like(n), where=length > 0)
    return tri, n.astype(np.float32)


def _stl_binary(parts, tmp):
    tri, normals = _triangles(parts)
    rec = np.zeros(len(tri), dtype=_STL_RECORD)
    rec["normal"] = normals
    rec["vertices"] = tri
    names = ", ".join(p.name for p in parts)
    header = f"gearkit binary STL: {names}; mm".encode("ascii", "replace")[:80].ljust(80, b" ")
    with open(tmp, "wb") as fh:
        fh.write(header)
        fh.write(np.uint32(len(rec)).tobytes())
        fh.write(rec.tobytes())


_FACET = ("facet normal %.9g %.9g %.9g\n outer loop\n  vertex %.9g %.9g %.9g\n  vertex %.9g %.9g %.9g\n"
          "  vertex %.9g %.9g %.9g\n endloop\nendfacet\n")


def _stl_ascii(parts, tmp):
    with open(tmp, "w") as fh:
        for part in parts:
            tri, normals = _triangles([part])
            data = np.concatenate([normals, tri.reshape(-1, 9)], axis=1).astype(np.float64)
            name = "".join(ch if ch.isalnum() or ch in "-_" else "_" for ch in part.name) or "gear"
            fh.write(f"solid {name}\n")
            fh.write((_FACET * len(data)) % tuple(data.ravel()))
            fh.write(f"endsolid {name}\n")


def _scene(parts):
    import trimesh

    scene = trimesh.Scene()
    for part in parts:
        scene.add_geometry(part.to_trimesh(), geom_name=part.name, node_name=part.name)
    return scene


def _obj(parts, tmp):
    from trimesh.exchange.obj import export_obj

    text = export_obj(_scene(parts), include_normals=False, include_color=False, include_texture=False, digits=9)
    Path(tmp).write_text(text)


def _glb(parts, tmp):
    Path(tmp).write_bytes(_scene(parts).export(file_type="glb"))


def write_mesh(path, parts, ascii: bool = False) -> Path:
    """Write solids to a mesh file; the format comes from the extension.

    Parameters
    ----------
    path : str or Path, ending in .stl, .obj or .glb
    parts : sequence of Solid
        Named parts: OBJ objects and GLB nodes carry their names; STL holds them all.
    ascii : bool, ASCII STL instead of binary

    Returns
    -------
    Path
    """
    fmt = mesh_format(path)
    if fmt is None:
        raise SpecError("output", f"unknown mesh format {Path(path).suffix!r} for {str(path)!r}; allowed: "
                        + ", ".join("." + f for f in MESH_FORMATS))
    parts = list(parts)
    if not parts:
        raise SpecError("output", "nothing to write")
    names = [p.name for p in parts]
    if len(set(names)) != len(names):
        raise SpecError("output", f"part names must differ: {names}")
    if ascii and fmt != "stl":
        raise SpecError("ascii", "applies to STL only")
    writer = {"stl": _stl_ascii if ascii else _stl_binary, "obj": _obj, "glb": _glb}[fmt]
    return atomic_write(path, lambda tmp: writer(parts, tmp))
