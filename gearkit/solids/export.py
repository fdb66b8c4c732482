"""3D files, written atomically: STL (binary, or ASCII on request), OBJ, GLB, 3MF and STEP.

Every mesh format is written with numpy straight from the solids' arrays, a chunk of facets at a
time behind a progress bar (:class:`~gearkit.progress.Progress`: a big export says how far it is):
STL (single precision, as the format stores it), OBJ (one named object per part), GLB (one named
node and mesh per part) and 3MF (one named object per part, unit millimeter). No export imports
trimesh. STEP is not a mesh: :mod:`gearkit.solids.step` rebuilds every part as an exact B-rep
(the optional ``gearkit[step]`` kernel). Every writer goes through
:func:`gearkit.export.atomic_write`: a failed export leaves no file behind.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from gearkit.errors import SpecError
from gearkit.export import atomic_write
from gearkit.progress import Progress

MESH_FORMATS = ("stl", "obj", "glb", "3mf", "step", "stp")

#: facets (and vertices) formatted or packed at once by the writers: bounds their temporaries (a binary
#: STL chunk's buffers stay in the allocator's heap, reused, not fresh pages each time) and paces their
#: progress bars
CHUNK = 1 << 13

_STL_RECORD = np.dtype([("normal", "<f4", (3,)), ("vertices", "<f4", (3, 3)), ("attr", "<u2")])


def mesh_format(path) -> str | None:
    """The 3D format named by ``path``'s extension, or None for any other extension."""
    ext = Path(path).suffix.lower().lstrip(".")
    return ext if ext in MESH_FORMATS else None


def _triangle_chunks(parts, chunk: int = CHUNK):
    """(k, 3, 3) float32 triangles of all parts, a chunk at a time, and their (k, 3) float32 unit
    normals (:meth:`~gearkit.solids.Solid.normals`: from the single-precision vertices the file stores)."""
    for part in parts:
        v, f = part.arrays()
        v32 = v.astype(np.float32)
        normals = part.normals()
        for s in range(0, len(f), chunk):
            yield v32.take(f[s:s + chunk], axis=0), normals[s:s + chunk]  # (take: a row gather's fast path)


def _facets(parts) -> int:
    return sum(len(p.arrays()[1]) for p in parts)


def _rows_of(parts) -> int:
    """Vertices and facets of all parts: the rows a text format writes."""
    return sum(len(p.arrays()[0]) + len(p.arrays()[1]) for p in parts)


def _stl_records(parts, chunk: int = CHUNK):
    """Binary STL records (``(k, 50)`` uint8: a facet's float32 normal and three corners, a zero
    attribute) of all parts, a chunk at a time in one reused buffer: the corners gathered as 12-byte
    points (a facet's three side by side are its 36 bytes), copied in with the normals a record at a time."""
    records = np.zeros((min(_facets(parts), chunk), _STL_RECORD.itemsize), dtype=np.uint8)  # attribute 0, kept
    for part in parts:
        v, f = part.arrays()
        points = np.ascontiguousarray(v, dtype="<f4").view("V12")[:, 0]
        normals = np.ascontiguousarray(part.normals(), dtype="<f4").view("V12")[:, 0]
        for s in range(0, len(f), chunk):
            corners = points.take(f[s:s + chunk])  # (k, 3) points: each row a facet's 36 bytes
            out = records[:len(corners)]
            out[:, :12].view("V12")[:, 0] = normals[s:s + chunk]
            out[:, 12:48].view("V36")[:, 0] = corners.view("V36")[:, 0]
            yield out


def _stl_binary(parts, tmp):
    names = ", ".join(p.name for p in parts)
    header = f"gearkit binary STL: {names}; mm".encode("ascii", "replace")[:80].ljust(80, b" ")
    count = _facets(parts)
    with open(tmp, "wb") as fh, Progress("STL", count, unit="facets") as bar:
        fh.write(header)
        fh.write(np.uint32(count).tobytes())
        for out in _stl_records(parts):
            fh.write(memoryview(out).cast("B"))
            bar.step(len(out))


_FACET = ("facet normal %.9g %.9g %.9g\n outer loop\n  vertex %.9g %.9g %.9g\n  vertex %.9g %.9g %.9g\n"
          "  vertex %.9g %.9g %.9g\n endloop\nendfacet\n")


def _stl_ascii(parts, tmp):
    with open(tmp, "w") as fh, Progress("STL", _facets(parts), unit="facets") as bar:
        for part in parts:
            name = "".join(ch if ch.isalnum() or ch in "-_" else "_" for ch in part.name) or "gear"
            fh.write(f"solid {name}\n")
            for tri, normals in _triangle_chunks([part]):
                data = np.concatenate([normals, tri.reshape(-1, 9)], axis=1).astype(np.float64)
                fh.write((_FACET * len(data)) % tuple(data.ravel()))
                bar.step(len(tri))
            fh.write(f"endsolid {name}\n")


def _rows(array, row: str, bar, chunk: int = CHUNK):
    """The text of ``row`` (a %-format of one row's values) for every row of ``array``, a chunk at a
    time; each chunk advances ``bar`` by its rows."""
    for s in range(0, len(array), chunk):
        block = array[s:s + chunk]
        yield (row * len(block)) % tuple(block.ravel().tolist())
        bar.step(len(block))


def _obj(parts, tmp):
    """Wavefront OBJ: one named object (``o NAME``) per part, vertices in mm, 1-based facets that
    count on across the parts."""
    with open(tmp, "w") as fh, Progress("OBJ", _rows_of(parts)) as bar:
        fh.write("# gearkit OBJ; mm\n")
        base = 1
        for part in parts:
            v, f = part.arrays()
            fh.write(f"o {part.name}\n")
            fh.writelines(_rows(v, "v %.9g %.9g %.9g\n", bar))
            fh.writelines(_rows(f + base, "f %d %d %d\n", bar))
            base += len(v)


def _glb(parts, tmp):
    """glTF 2.0 binary: one named node and mesh per part (positions float32, indices uint32, mm as
    given: a viewer's unit is the metre)."""
    import json

    nodes, meshes, accessors, views, chunks, offset = [], [], [], [], [], 0
    with Progress("GLB", _facets(parts), unit="facets") as bar:
        for k, part in enumerate(parts):
            v, f = part.arrays()
            if len(v) >= 2 ** 32 - 1:
                raise SpecError("output", f"{part.name}: a GLB mesh holds fewer than 2^32 vertices")
            pos = np.ascontiguousarray(v, dtype="<f4")
            idx = np.ascontiguousarray(f, dtype="<u4")
            for data, target in ((pos, 34962), (idx, 34963)):  # array buffer, element array buffer
                raw = data.tobytes()
                views.append({"buffer": 0, "byteOffset": offset, "byteLength": len(raw), "target": target})
                chunks.append(raw)
                offset += len(raw)  # both are multiples of 4 bytes
            accessors.append({"bufferView": 2 * k, "componentType": 5126, "count": len(pos), "type": "VEC3",
                              "min": pos.min(axis=0).tolist(), "max": pos.max(axis=0).tolist()})
            accessors.append({"bufferView": 2 * k + 1, "componentType": 5125, "count": idx.size, "type": "SCALAR"})
            meshes.append({"name": part.name, "primitives": [{"attributes": {"POSITION": 2 * k}, "indices": 2 * k + 1,
                                                              "mode": 4}]})
            nodes.append({"name": part.name, "mesh": k})
            bar.step(len(f))
        doc = {"asset": {"version": "2.0", "generator": "gearkit"}, "scene": 0,
               "scenes": [{"nodes": list(range(len(parts)))}], "nodes": nodes, "meshes": meshes,
               "accessors": accessors, "bufferViews": views, "buffers": [{"byteLength": offset}]}
        text = json.dumps(doc, separators=(",", ":")).encode()
        text += b" " * (-len(text) % 4)
        with open(tmp, "wb") as fh:
            fh.write(b"glTF" + np.array([2, 12 + 8 + len(text) + 8 + offset], dtype="<u4").tobytes())
            fh.write(np.array([len(text), 0x4E4F534A], dtype="<u4").tobytes() + text)  # "JSON"
            fh.write(np.array([offset, 0x004E4942], dtype="<u4").tobytes())  # "BIN\0"
            fh.writelines(chunks)


_3MF_TYPES = ('<?xml version="1.0" encoding="UTF-8"?>\n<Types xmlns="http://schemas.openxmlformats.org/package/2006/'
              'content-types"><Default Extension="rels" ContentType="application/vnd.openxmlformats-package.'
              'relationships+xml"/><Default Extension="model" ContentType="application/vnd.ms-package.3dmanufacturing'
              '-3dmodel+xml"/></Types>\n')
_3MF_RELS = ('<?xml version="1.0" encoding="UTF-8"?>\n<Relationships xmlns="http://schemas.openxmlformats.org/package/'
             '2006/relationships"><Relationship Target="/3D/3dmodel.model" Id="rel0" Type="http://schemas.microsoft.'
             'com/3dmanufacturing/2013/01/3dmodel"/></Relationships>\n')


def _3mf(parts, tmp):
    """3MF package: [Content_Types].xml, _rels/.rels and 3D/3dmodel.model (unit millimeter, one named
    object per part, each placed once in the build), the model streamed into the archive a chunk at a time."""
    import zipfile
    from xml.sax.saxutils import quoteattr

    with zipfile.ZipFile(tmp, "w", compression=zipfile.ZIP_DEFLATED) as zf, \
            Progress("3MF", _rows_of(parts)) as bar:
        zf.writestr("[Content_Types].xml", _3MF_TYPES)
        zf.writestr("_rels/.rels", _3MF_RELS)
        with zf.open("3D/3dmodel.model", "w") as raw:
            def put(text):
                raw.write(text.encode())
            put('<?xml version="1.0" encoding="UTF-8"?>\n<model unit="millimeter" xml:lang="en-US" '
                'xmlns="http://schemas.microsoft.com/3dmanufacturing/core/2015/02">\n<resources>\n')
            for k, part in enumerate(parts, start=1):
                v, f = part.arrays()
                put(f'<object id="{k}" name={quoteattr(part.name)} type="model"><mesh><vertices>\n')
                for text in _rows(v, '<vertex x="%.9g" y="%.9g" z="%.9g"/>\n', bar):
                    put(text)
                put("</vertices><triangles>\n")
                for text in _rows(f, '<triangle v1="%d" v2="%d" v3="%d"/>\n', bar):
                    put(text)
                put("</triangles></mesh></object>\n")
            put("</resources>\n<build>" + "".join(f'<item objectid="{k}"/>' for k in range(1, len(parts) + 1))
                + "</build>\n</model>\n")


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
