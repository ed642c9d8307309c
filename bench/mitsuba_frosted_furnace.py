#!/usr/bin/env python3
"""A frosted glass ball in a white furnace, by grinlight and by Mitsuba 3: a rough dielectric
sphere (GGX α, n = 1.5) under a uniform sky of radiance 1, nothing else. Glass absorbs nothing,
so every pixel must read exactly 1. Prints the mean over the ball's disc and over rings of it
(the rim is where light inside the ball meets its surface most often and at grazing angles),
for each renderer.

    python3 bench/mitsuba_frosted_furnace.py [ALPHA ...]   (0.15 0.5)

A single-scattering microfacet model (Walter et al. 2007, Mitsuba's `roughdielectric`) loses
the light its masking and shadowing stop: each meeting of the surface keeps only G₂/G₁ of it,
and inside a ball light meets the surface again and again. grinlight walks the microsurface
(Heitz et al. 2016) and loses nothing. Needs `pip install mitsuba numpy OpenEXR` and a built
grinlight (`cargo build --release`); Mitsuba renders with bench/mitsuba_reference.py.
"""
import os
import subprocess
import sys
import tempfile

import numpy as np
import OpenEXR

SCENE = """
[camera]
position = [0, 0, 3]
look_at = [0, 0, 0]
fov_y_deg = 24
width = 64
height = 64

[render]
spp = {spp}
passes = 1
max_depth = 256

[[material]]
name = "frosted"
type = "dielectric"
ior = 1.5
roughness = {alpha}

[[shape]]
type = "sphere"
center = [0, 0, 0]
radius = 0.6
material = "frosted"

[[light]]
type = "environment"
sky = "uniform"
"""


def beauty(path):
    parts = OpenEXR.File(path).parts
    part = next((p for p in parts if p.name() == "beauty"), parts[0])
    return np.asarray(next(iter(part.channels.values())).pixels, dtype=np.float64).mean(axis=-1)


def rings(image):
    h, w = image.shape
    y, x = np.mgrid[0:h, 0:w] + 0.5
    # The ball's disc: radius 0.6 at distance 3 in a 24° field.
    r = np.hypot(x - w / 2, y - h / 2) / (w / 2) * np.tan(np.radians(12)) * 3 / (0.6 * 3 / np.sqrt(9 - 0.36))
    return [image[(r >= lo) & (r < hi)].mean() for lo, hi in [(0, 0.5), (0.5, 0.8), (0.8, 0.95), (0, 0.95)]]


def main():
    alphas = [float(a) for a in sys.argv[1:]] or [0.15, 0.5]
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    out = tempfile.mkdtemp()
    print("α     renderer   centre  middle  rim     disc   (exact: 1)")
    for alpha in alphas:
        scene = os.path.join(out, "furnace.toml")
        with open(scene, "w") as f:
            f.write(SCENE.format(alpha=alpha, spp=4096))
        subprocess.run([sys.executable, os.path.join(root, "bench", "mitsuba_reference.py"),
                        scene, os.path.join(out, "m.exr"), "--spp", "4096"],
                       check=True, capture_output=True)
        subprocess.run([os.path.join(root, "target", "release", "grinlight"), "render", scene,
                        "--integrator", "path", "-o", os.path.join(out, "g.exr")],
                       check=True, capture_output=True)
        for name, path in [("grinlight", "g.exr"), ("Mitsuba", "m.exr")]:
            values = rings(beauty(os.path.join(out, path)))
            print("%-5g %-10s %s" % (alpha, name, "  ".join("%.4f" % v for v in values)))


if __name__ == "__main__":
    main()
