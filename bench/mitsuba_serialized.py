#!/usr/bin/env python3
"""Write the serialized-mesh fixtures of tests/data/mitsuba/ (and the textured quad of
scenes/mitsuba/mesh_textures.xml) and check that Mitsuba 3 reads them as meant: each mesh's positions, triangles, normals and texture coordinates as Mitsuba's
`serialized` plugin loads them, against the values written. grinlight's reader is tested on
the same files (tests/ply.rs).

    python3 bench/mitsuba_serialized.py [--write]

Two files, each of two meshes: `meshes_v4.serialized` (format version 4: named meshes, u64
offsets) and `meshes_v3.serialized` (version 3: no names, u32 offsets). Mesh 0 is a
tetrahedron in f32 with normals and texture coordinates, mesh 1 a quad of two triangles in f64
with vertex colours (which readers skip) and no normals. `scenes/mitsuba/textured_quad.serialized`
is textured_quad.obj's quad and (u, v) as stored in its file, one mesh in f32.
"""
import os
import struct
import sys
import zlib

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
OUT = os.path.join(ROOT, "tests", "data", "mitsuba")

TETRA = dict(
    positions=np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], float) * 0.5 + [0.25, -0.5, 1.0],
    normals=np.array([[-1, -1, -1], [1, 0, 0], [0, 1, 0], [0, 0, 1]], float),
    uv=np.array([[0, 0], [1, 0], [0, 1], [0.5, 0.5]], float),
    triangles=np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]]),
)
TEXTURED_QUAD = dict(
    positions=np.array([[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]], float),
    uv=np.array([[0, 0], [1, 0], [1, 1], [0, 1]], float),
    triangles=np.array([[0, 1, 2], [0, 2, 3]]),
)
QUAD = dict(
    positions=np.array([[-1, 0, -1], [1, 0, -1], [1, 0, 1], [-1, 0, 1]], float) * 1.5,
    colors=np.array([[1, 0, 0], [0, 1, 0], [0, 0, 1], [1, 1, 1]], float),
    triangles=np.array([[0, 2, 1], [0, 3, 2]]),
)


def mesh_bytes(version, name, mesh, double):
    normals, uv, colors = mesh.get("normals"), mesh.get("uv"), mesh.get("colors")
    flags = (0x0001 if normals is not None else 0) | (0x0002 if uv is not None else 0)
    flags |= (0x0008 if colors is not None else 0) | (0x2000 if double else 0x1000)
    kind = "<f8" if double else "<f4"
    body = struct.pack("<I", flags)
    if version == 4:
        body += name.encode() + b"\0"
    body += struct.pack("<QQ", len(mesh["positions"]), len(mesh["triangles"]))
    for a in (mesh["positions"], normals, uv, colors):
        if a is not None:
            body += np.ascontiguousarray(a, dtype=kind).tobytes()
    body += np.ascontiguousarray(mesh["triangles"], dtype="<u4").tobytes()
    return struct.pack("<HH", 0x041C, version) + zlib.compress(body)


def file_bytes(version, meshes):
    parts = [mesh_bytes(version, name, mesh, double) for name, mesh, double in meshes]
    offsets = np.cumsum([0] + [len(p) for p in parts[:-1]])
    table = b"".join(struct.pack("<Q" if version == 4 else "<I", int(o)) for o in offsets)
    return b"".join(parts) + table + struct.pack("<I", len(parts))


def check(path, meshes):
    import mitsuba as mi

    mi.set_variant("scalar_rgb")
    worst = 0.0
    for index, (_, mesh, _) in enumerate(meshes):
        shape = mi.load_dict({"type": "serialized", "filename": path, "shape_index": index})
        params = mi.traverse(shape)
        p = np.array(params["vertex_positions"]).reshape(-1, 3)
        f = np.array(params["faces"]).reshape(-1, 3)
        worst = max(worst, np.abs(p - mesh["positions"]).max())
        assert (f == mesh["triangles"]).all(), (path, index, f)
        if "uv" in mesh:
            t = np.array(params["vertex_texcoords"]).reshape(-1, 2)
            worst = max(worst, np.abs(t - mesh["uv"]).max())
        if "normals" in mesh:
            n = np.array(params["vertex_normals"]).reshape(-1, 3)
            want = mesh["normals"] / np.linalg.norm(mesh["normals"], axis=1, keepdims=True)
            worst = max(worst, np.abs(n - want).max())
    print(f"{os.path.basename(path)}: Mitsuba {mi.__version__} reads its {len(meshes)} mesh(es) as written (largest difference {worst:.1e})")
    return worst


def main():
    write = "--write" in sys.argv
    files = [(os.path.join(OUT, f"meshes_v{version}.serialized"), version,
              [("tetra", TETRA, False), ("quad", QUAD, True)]) for version in (4, 3)]
    files.append((os.path.join(ROOT, "scenes", "mitsuba", "textured_quad.serialized"), 4,
                  [("textured_quad", TEXTURED_QUAD, False)]))
    for path, version, meshes in files:
        path = path if write else os.path.join("/tmp", os.path.basename(path))
        with open(path, "wb") as f:
            f.write(file_bytes(version, meshes))
        assert check(path, meshes) < 1e-6


if __name__ == "__main__":
    main()
