#!/usr/bin/env python3
"""Write the density grid of scenes/mitsuba/smoke_box.xml (`scenes/mitsuba/smoke.vol`, Mitsuba's
`.vol` format: f32, one channel) and check how Mitsuba 3 looks a `gridvolume` up, the
convention grinlight's import converts exactly: a grid of resolution r over the unit cube that
`to_world` places, value i at (i + 1/2)/r, trilinear between those points and clamped beyond
the outer ones (the bounding box in the file not read). Mitsuba's lookups at random points,
inside and outside the cube, are compared with that formula.

    python3 bench/mitsuba_gridvolume.py [--write]
"""
import os
import struct
import sys

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
RES = (12, 10, 8)  # x, y, z


def smoke():
    """A lopsided blob over a thin haze that thickens toward +x: values by (z, y, x)."""
    x, y, z = [(np.arange(n) + 0.5) / n for n in RES]
    Z, Y, X = np.meshgrid(z, y, x, indexing="ij")
    blob = np.exp(-(((X - 0.62) / 0.22) ** 2 + ((Y - 0.4) / 0.3) ** 2 + ((Z - 0.5) / 0.25) ** 2))
    return 0.1 + 0.3 * X + 2.0 * blob


def vol_bytes(values):
    zr, yr, xr = values.shape
    header = b"VOL" + bytes([3]) + struct.pack("<iiiii", 1, xr, yr, zr, 1)
    header += struct.pack("<6f", 0, 0, 0, 1, 1, 1)
    return header + values.astype("<f4").tobytes()


def trilinear(values, p):
    """The convention: value (i, j, k) at ((i, j, k) + 1/2)/r, clamped."""
    zr, yr, xr = values.shape
    res = np.array([xr, yr, zr], float)
    q = np.clip(p * res - 0.5, 0, res - 1)
    i0 = np.minimum(np.floor(q).astype(int), (res - 2).astype(int))
    f = q - i0
    out = 0.0
    for dx in (0, 1):
        for dy in (0, 1):
            for dz in (0, 1):
                w = (f[0] if dx else 1 - f[0]) * (f[1] if dy else 1 - f[1]) * (f[2] if dz else 1 - f[2])
                out += w * values[i0[2] + dz, i0[1] + dy, i0[0] + dx]
    return out


def main():
    import mitsuba as mi

    mi.set_variant("scalar_rgb")
    values = smoke()
    path = os.path.join(ROOT, "scenes", "mitsuba", "smoke.vol") if "--write" in sys.argv else "/tmp/smoke.vol"
    with open(path, "wb") as f:
        f.write(vol_bytes(values))
    grid = mi.load_dict({"type": "gridvolume", "filename": path})
    rng = np.random.default_rng(1)
    worst = 0.0
    for p in rng.uniform(-0.2, 1.2, size=(2000, 3)):
        it = mi.Interaction3f()
        it.p = mi.Point3f(*p)
        worst = max(worst, abs(grid.eval_1(it) - trilinear(values, p)))
    print(f"{os.path.basename(path)}: {RES[0]} x {RES[1]} x {RES[2]}; Mitsuba {mi.__version__}'s lookups at 2000 points "
          f"against value i at (i + 1/2)/r, trilinear, clamped: largest difference {worst:.1e}")
    assert worst < 1e-5


if __name__ == "__main__":
    main()
