#!/usr/bin/env python3
"""Write the emitting meshes of scenes/mitsuba/mesh_lights.xml: an icosphere lamp (an
icosahedron subdivided once, 80 triangles wound outward, with outward vertex normals) as OBJ,
and a wavy ribbon of 16 triangles wound to face up (the scene flips its normals so that it
emits down) as ASCII PLY without normals.

    python3 bench/mitsuba_mesh_lights.py [DIR]   (default scenes/mitsuba)
"""
import math
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def icosphere():
    t = (1.0 + math.sqrt(5.0)) / 2.0
    v = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t),
         (0, -1, -t), (0, 1, -t), (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    v = [tuple(c / math.sqrt(sum(x * x for x in p)) for c in p) for p in v]
    f = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4),
         (11, 10, 2), (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8),
         (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    mids = {}

    def mid(a, b):
        key = (min(a, b), max(a, b))
        if key not in mids:
            p = [(v[a][k] + v[b][k]) / 2 for k in range(3)]
            n = math.sqrt(sum(x * x for x in p))
            v.append(tuple(x / n for x in p))
            mids[key] = len(v) - 1
        return mids[key]

    faces = []
    for a, b, c in f:
        ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
        faces += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
    # Every face wound outward.
    for a, b, c in faces:
        pa, pb, pc = v[a], v[b], v[c]
        e1 = [pb[k] - pa[k] for k in range(3)]
        e2 = [pc[k] - pa[k] for k in range(3)]
        n = (e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0])
        assert sum(n[k] * (pa[k] + pb[k] + pc[k]) for k in range(3)) > 0
    return v, faces


def ribbon(n=8):
    """A strip along x in [-1, 1], its height waving, wound to face +y."""
    v = []
    for i in range(n + 1):
        x = -1.0 + 2.0 * i / n
        y = 0.12 * math.sin(math.pi * x)
        v += [(x, y, -0.15), (x, y, 0.15)]
    faces = []
    for i in range(n):
        a, b, c, d = 2 * i, 2 * i + 1, 2 * i + 2, 2 * i + 3
        # (b - a) = +z, (c - a) ≈ +x: z × x = +y.
        faces += [(a, b, c), (c, b, d)]
    return v, faces


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "scenes", "mitsuba")
    v, f = icosphere()
    with open(os.path.join(out, "icosphere.obj"), "w") as fh:
        fh.write("# An icosahedron subdivided once: 80 triangles wound outward, unit radius\n")
        fh.write("# (bench/mitsuba_mesh_lights.py).\n")
        for p in v:
            fh.write("v %.9f %.9f %.9f\n" % p)
        for p in v:
            fh.write("vn %.9f %.9f %.9f\n" % p)
        for a, b, c in f:
            fh.write("f %d//%d %d//%d %d//%d\n" % (a + 1, a + 1, b + 1, b + 1, c + 1, c + 1))
    v, f = ribbon()
    with open(os.path.join(out, "ribbon.ply"), "w") as fh:
        fh.write("ply\nformat ascii 1.0\ncomment a wavy ribbon wound to face +y (bench/mitsuba_mesh_lights.py)\n")
        fh.write("element vertex %d\nproperty float x\nproperty float y\nproperty float z\n" % len(v))
        fh.write("element face %d\nproperty list uchar int vertex_indices\nend_header\n" % len(f))
        for p in v:
            fh.write("%.9f %.9f %.9f\n" % p)
        for a, b, c in f:
            fh.write("3 %d %d %d\n" % (a, b, c))


if __name__ == "__main__":
    main()
