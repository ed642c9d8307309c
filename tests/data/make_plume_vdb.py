#!/usr/bin/python3
"""Writes tests/data/plume.vdb, the OpenVDB fixture of tests/vdb.rs (run once; the file is
shipped). Needs Debian's python3-openvdb (OpenVDB 10.0.1): `apt-get install python3-openvdb`.

Grids (index space (i, j, k) → world (0.3, 0.1, -0.2) + 0.05·(i, j, k)):
- "temperature" (float, background 300 K): T = 300 + 40·exp(−q/16), q = i² + (j − 4)² + (k − 3)²,
  over i in −3..=8, j in 0..=9, k in 0..=7 (a box that straddles i = 0, so two root nodes);
  voxels with T < 300.5 K are left inactive (they read as the background).
- "density" (float, background 1.2): ρ = 1.2 − 0.001·(i + 2j + 3k) over the same box, all
  active.
- "velocity" (vec3s): one voxel, to be refused (not a scalar grid).
"""
import math
import pyopenvdb as vdb

RANGE = [(i, j, k) for i in range(-3, 9) for j in range(0, 10) for k in range(0, 8)]


def transform():
    t = vdb.createLinearTransform(voxelSize=0.05)
    t.translate((0.3, 0.1, -0.2))
    return t


temperature = vdb.FloatGrid(300.0)
temperature.name = "temperature"
temperature.transform = transform()
acc = temperature.getAccessor()
for i, j, k in RANGE:
    t = 300.0 + 40.0 * math.exp(-(i * i + (j - 4) ** 2 + (k - 3) ** 2) / 16.0)
    acc.setValueOnly((i, j, k), t)
    acc.setActiveState((i, j, k), t >= 300.5)

density = vdb.FloatGrid(1.2)
density.name = "density"
density.transform = transform()
acc = density.getAccessor()
for i, j, k in RANGE:
    acc.setValueOn((i, j, k), 1.2 - 0.001 * (i + 2 * j + 3 * k))

velocity = vdb.Vec3SGrid()
velocity.name = "velocity"
velocity.transform = transform()
velocity.getAccessor().setValueOn((0, 0, 0), (1.0, 0.0, 0.0))

vdb.write("tests/data/plume.vdb", grids=[temperature, density, velocity])
