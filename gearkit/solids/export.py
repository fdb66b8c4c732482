"""3D files, written atomically: STL (binary, or ASCII on request), OBJ, GLB, 3MF and STEP.

STL is written with numpy straight from the solid's arrays (single precision, as the format
stores it), so a plain export never imports trimesh. OBJ (one named object per part), GLB
(one named node per part) and 3MF (one named object per part, unit millimeter) go through
trimesh. STEP is not a mesh: :mod:`gearkit.solids.step` rebuilds every part as an exact B-rep
(the optional ``gearkit[step]`` kernel). Every writer goes through
:func:`gearkit.export.atomic_write`: a failed export leaves no file behind.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from gearkit.errors import SpecError
from gearkit.export import atomic_write

MESH_FORMATS = ("stl", "obj", "glb", "3mf", "step", "stp")

_STL_RECORD = np.dtype([("normal", "<f4", (3,)), ("vertices", "<f4", (3, 3)), ("attr", "<u2")])


def mesh_format(path) -> str | None:
    """The 3D format named by ``path``'s extension, or None for any other extension."""
    ext = Path(path).suffix.lower().lstrip(".")
    return ext if ext in MESH_FORMATS else None


def _triangle_chunks(parts, chunk: int = 1 << 15):
    """(k, 3, 3) float32 triangles of all parts, a chunk at a time, and their (k, 3) float32 unit
    normals (:meth:`~gearkit.solids.Solid.normals`: from the single-precision vertices the file stores)."""
    for part in parts:
        v, f = part.arrays()
        v32 = v.astype(np.float32)
        normals = part.normals()
        for s in range(0, len(f), chunk):
            yield v32[f[s:s + chunk]], normals[s:s + chunk]


def _stl_binary(parts, tmp):
    names = ", ".join(p.name for p in parts)
    header = f"gearkit binary STL: {names}; mm".encode("ascii", "replace")[:80].ljust(80, b" ")
    count = sum(len(p.arrays()[1]) for p in parts)
    with open(tmp, "wb") as fh:
        fh.write(header)
        fh.write(np.uint32(count).tobytes())
        for tri, normals in _triangle_chunks(parts):
            rec = np.zeros(len(tri), dtype=_STL_RECORD)
            rec["normal"] = normals
            rec["vertices"] = tri
            fh.write(memoryview(rec).cast("B"))


_FACET = ("facet normal %.9g %.9g %.9g\n outer loop\n  vertex %.9g %.9g %.9g\n  vertex %.9g %.9g %.9g\n"
          "  vertex %.9g %.9g %.9g\n endloop\nendfacet\n")


def _stl_ascii(parts, tmp):
    with open(tmp, "w") as fh:
        for part in parts:
            name = "".join(ch if ch.isalnum() or ch in "-_" else "_" for ch in part.name) or "gear"
            fh.write(f"solid {name}\n")
            for tri, normals in _triangle_chunks([part]):
                data = np.concatenate([normals, tri.reshape(-1, 9)], axis=1).astype(np.float64)
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


_3MF_TYPES = ('<?xml version="1.0" encoding="UTF-8"?>\n<Types xmlns="http://schemas.openxmlformats.org/package/2006/'
              'content-types"><Default Extension="rels" ContentType="application/vnd.openxmlformats-package.'
              'relationships+xml"/><Default Extension="model" ContentType="application/vnd.ms-package.3dmanufacturing'
              '-3dmodel+xml"/></Types>\n')
_3MF_RELS = ('<?xml version="1.0" encoding="UTF-8"?>\n<Relationships xmlns="http://schemas.openxmlformats.org/package/'
             '2006/relationships"><Relationship Target="/3D/3dmodel.model" Id="rel0" Type="http://schemas.microsoft.'
             'com/3dmanufacturing/2013/01/3dmodel"/></Relationships>\n')


def _3mf(parts, tmp):
    """3MF package: [Content_Types].xml, _rels/.rels and 3D/3dmodel.model (unit millimeter, one named
    object per part, each placed once in the build)."""
    import zipfile
    from xml.sax.saxutils import quoteattr

    body = ['<?xml version="1.0" encoding="UTF-8"?>\n<model unit="millimeter" xml:lang="en-US" '
            'xmlns="http://schemas.microsoft.com/3dmanufacturing/core/2015/02">\n<resources>\n']
    for k, part in enumerate(parts, start=1):
        v, f = part.arrays()
        body.append(f'<object id="{k}" name={quoteattr(part.name)} type="model"><mesh><vertices>\n')
        body.append(("<vertex x=\"%.9g\" y=\"%.9g\" z=\"%.9g\"/>\n" * len(v)) % tuple(v.ravel()))
        body.append("</vertices><triangles>\n")
        body.append(("<triangle v1=\"%d\" v2=\"%d\" v3=\"%d\"/>\n" * len(f)) % tuple(f.ravel()))
        body.append("</triangles></mesh></object>\n")
    body.append("</resources>\n<build>")
    body += [f'<item objectid="{k}"/>' for k in range(1, len(parts) + 1)]
    body.append("</build>\n</model>\n")
    with zipfile.ZipFile(tmp, "w", compression=zipfile.ZIP_DEFLATED) as zf:
        zf.writestr("[Content_Types].xml", _3MF_TYPES)
        zf.writestr("_rels/.rels", _3MF_RELS)
        zf.writestr("3D/3dmodel.model", "".join(body))


def write_mesh(path, parts, ascii: bool = False) -> Path:
    """Write solids to a 3D file; the format comes from the extension.

    Parameters
    ----------
    path : str or Path, ending in .stl, .obj, .glb, .3mf or .step (.stp)
    parts : sequence of Solid
        Named parts: OBJ objects, GLB nodes, 3MF objects and STEP products carry their names;
        STL holds them all. STEP rebuilds each part as an exact B-rep (``pip install 'gearkit[step]'``).
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
    if fmt in ("step", "stp"):
        from gearkit.solids.step import write_step

        write_step(path, parts)
        return Path(path)
    writer = {"stl": _stl_ascii if ascii else _stl_binary, "obj": _obj, "glb": _glb, "3mf": _3mf}[fmt]
    return atomic_write(path, lambda tmp: writer(parts, tmp))
