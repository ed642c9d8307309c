#!/usr/bin/env python3
"""The Cornell caustic's error against run time: grinlight against LuxCoreRender's PhotonGI.

    python3 bench/luxcore_caustic.py [--budgets 20 40 120] [--seeds 1 2] [--out DIR]
                                     [--grinlight PATH[,OPTION,...] ...] [--reference-spp N]
                                     [--luxcore "PROPERTY = VALUE" ...]

Each grinlight build given (by default `target/release/grinlight`; give an earlier build's
binary too to compare versions in the same run, and after a build's path, separated by
commas, options that replace the settings below for it, e.g.
`/tmp/gl_053,--caustic-photons,200000`) and LuxCore render `scenes/cornell_caustic.toml`
(256 × 256) for the same budget of wall time, one after another: grinlight with
`render --time-budget`, which starts no pass after the budget (so a run ends up to a pass
later: the table prints every run's measured seconds, process start to image written);
LuxCore stopped at the budget, its PhotonGI cache's construction included.
Each image is compared with an independent reference — Mitsuba 3's path tracer on the crop
alone (`bench/mitsuba_reference.py --crop`, 2 × 65 536 samples a pixel, about 5 minutes),
rendered as two halves of different seeds so that the reference's own noise (half the halves'
RMSE) can be taken out of each RMSE in quadrature. The error is the RMSE of linear radiance
over the crop's pixels and channels.

The crop, [144, 196) × [212, 240) from the top left, holds the glass ball's caustic on the
floor (much of it seen through the ball) and the floor around it.

LuxCore: path tracing (PATHCPU, Sobol) with the PhotonGI caustic cache, at BlendLuxCore's
default settings (100 000 cache entries, normal angle 10°, METROPOLIS photon sampler, the
cache re-traced every 8 samples a pixel with its radius × 0.96, down to 0.003) except the
lookup radius: 0.01 (in this 2-unit room; at 20 s, seed 1, the radii 0.075, 0.02, 0.01 and
0.005 gave RMSE 0.155, 0.064, 0.058 and 0.060; re-tracing every 4 samples or never, and
LuxCore's light tracing for caustics, were no better); no variance clamping, 64 path
segments. The scene is built as the reference's conventions say (refs/README.md): two-sided
Lambertian walls, a one-sided light of radiance 15 that reflects nothing, a smooth glass ball
of index 1.5 — a 256 × 512 UV sphere with smooth normals, as LuxCore has no analytic sphere
—, a box pixel filter of one pixel.

grinlight: the scene as shipped, with the per-pass settings in GRINLIGHT_SETTINGS (32 samples
a pixel, one gather ray, 10⁶ caustic photons a pass: tracing them and building the maps take
about a fifth of a render, and at 120 s 2 × 10⁵ or 2 × 10⁶ gave more error, 16 samples a pixel
too), as many passes as the budget starts.

Needs `pip install mitsuba pyluxcore openexr numpy` (mitsuba 3.9.1 and pyluxcore 2.11.2 were
used for the figures in docs/performance.md) and a release build of grinlight.
"""
import argparse
import math
import os
import statistics
import subprocess
import sys
import time

import numpy as np

SCENE = "scenes/cornell_caustic.toml"
CROP = (144, 212, 196, 240)
GRINLIGHT_SETTINGS = ["--spp", "32", "--gather", "1", "--caustic-photons", "1000000"]


def read_exr(path):
    """The first layer (grinlight: `beauty`) of an EXR as an H × W × 3 float64 array."""
    import OpenEXR
    with OpenEXR.File(path, separate_channels=False) as f:
        part = f.parts[0]
        return np.asarray(part.channels["RGB"].pixels, dtype=np.float64)[..., :3]


def crop(image):
    x0, y0, x1, y1 = CROP
    return image[y0:y1, x0:x1]


def reference(out, spp):
    """The two halves of the crop's reference, rendered if missing."""
    halves = []
    for seed in (0, 10**6):
        path = os.path.join(out, "reference-%d-%d.exr" % (spp, seed))
        if not os.path.exists(path):
            subprocess.run([sys.executable, "bench/mitsuba_reference.py", SCENE, path,
                            "--spp", str(spp), "--seed", str(seed),
                            "--crop", *map(str, CROP)], check=True)
        halves.append(read_exr(path))
    return halves


def rmse(a, b):
    return math.sqrt(float(np.mean((a - b) ** 2)))


def settings(build):
    """A build's binary and its options: GRINLIGHT_SETTINGS with those given after its path
    in place of theirs."""
    binary, *given = build.split(",")
    options = dict(zip(GRINLIGHT_SETTINGS[::2], GRINLIGHT_SETTINGS[1::2]))
    options.update(zip(given[::2], given[1::2]))
    return binary, [x for pair in options.items() for x in pair]


def run_grinlight(build, budget, seed, path):
    binary, options = settings(build)
    start = time.monotonic()
    subprocess.run([binary, "render", SCENE, "-o", path, "--seed", str(seed),
                    "--time-budget", str(budget), *options],
                   check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return time.monotonic() - start, crop(read_exr(path))


def uv_sphere(center, radius, rings=256, segments=512):
    """Vertices, smooth normals and triangles (wound counter-clockwise seen from outside) of
    a UV sphere."""
    vertices, normals, faces = [], [], []
    for i in range(rings + 1):
        theta = math.pi * i / rings
        for j in range(segments + 1):
            phi = 2.0 * math.pi * j / segments
            n = (math.sin(theta) * math.cos(phi), math.cos(theta),
                 math.sin(theta) * math.sin(phi))
            normals.append(n)
            vertices.append(tuple(c + radius * x for c, x in zip(center, n)))
    row = segments + 1
    for i in range(rings):
        for j in range(segments):
            a, b = i * row + j, i * row + j + 1
            c, d = a + row, b + row
            if i > 0:
                faces.append((a, b, c))
            if i < rings - 1:
                faces.append((b, d, c))
    return vertices, normals, faces


def write_ply(path, vertices, faces, normals=None):
    with open(path, "w") as f:
        f.write("ply\nformat ascii 1.0\nelement vertex %d\n" % len(vertices))
        f.write("property float x\nproperty float y\nproperty float z\n")
        if normals:
            f.write("property float nx\nproperty float ny\nproperty float nz\n")
        f.write("element face %d\nproperty list uchar int vertex_indices\nend_header\n"
                % len(faces))
        for i, v in enumerate(vertices):
            f.write("%r %r %r" % tuple(v))
            f.write(" %r %r %r\n" % tuple(normals[i]) if normals else "\n")
        for t in faces:
            f.write("%d %d %d %d\n" % (len(t), *t))


def luxcore_scene(out):
    """The scene's LuxCore description: the quads and the light as PLY triangles, the ball a
    UV sphere with smooth normals."""
    import tomllib
    with open(SCENE, "rb") as f:
        scene = tomllib.load(f)
    cam = scene["camera"]
    lines = [
        'scene.camera.type = "perspective"',
        "scene.camera.lookat.orig = %r %r %r" % tuple(cam["position"]),
        "scene.camera.lookat.target = %r %r %r" % tuple(cam["look_at"]),
        "scene.camera.up = %r %r %r" % tuple(cam.get("up", [0, 1, 0])),
        "scene.camera.fieldofview = %r" % cam["fov_y_deg"],
    ]
    for m in scene["material"]:
        name = m["name"]
        if m["type"] == "diffuse":
            lines += ['scene.materials.%s.type = "matte"' % name,
                      "scene.materials.%s.kd = %r %r %r" % (name, *m["albedo"])]
        elif m["type"] == "dielectric":
            lines += ['scene.materials.%s.type = "glass"' % name,
                      "scene.materials.%s.kr = 1 1 1" % name,
                      "scene.materials.%s.kt = 1 1 1" % name,
                      "scene.materials.%s.interiorior = %r" % (name, m["ior"]),
                      "scene.materials.%s.exteriorior = 1.0" % name]
        else:
            raise SystemExit("material type %r is not converted" % m["type"])
    for i, s in enumerate(scene["shape"]):
        path = os.path.join(out, "shape%d.ply" % i)
        if s["type"] == "quad":
            write_ply(path, s["vertices"], [(0, 1, 2), (0, 2, 3)])
        elif s["type"] == "sphere":
            v, n, f = uv_sphere(s["center"], s["radius"])
            write_ply(path, v, f, n)
        else:
            raise SystemExit("shape type %r is not converted" % s["type"])
        lines += ['scene.shapes.shape%d.type = "mesh"' % i,
                  'scene.shapes.shape%d.ply = "%s"' % (i, path),
                  'scene.objects.shape%d.shape = "shape%d"' % (i, i),
                  'scene.objects.shape%d.material = "%s"' % (i, s["material"])]
    for i, light in enumerate(scene["light"]):
        if light["type"] != "quad":
            raise SystemExit("light type %r is not converted" % light["type"])
        name = "light%d" % i
        path = os.path.join(out, name + ".ply")
        write_ply(path, light["vertices"], [(0, 1, 2), (0, 2, 3)])
        radiance = light["radiance"]
        lines += ['scene.materials.%s.type = "matte"' % name,
                  "scene.materials.%s.kd = 0 0 0" % name,
                  "scene.materials.%s.emission = %r %r %r" % (name, *radiance),
                  'scene.shapes.%s.type = "mesh"' % name,
                  'scene.shapes.%s.ply = "%s"' % (name, path),
                  'scene.objects.%s.shape = "%s"' % (name, name),
                  'scene.objects.%s.material = "%s"' % (name, name)]
    return "\n".join(lines) + "\n", cam["width"], cam["height"]


LUXCORE_SETTINGS = """
renderengine.type = "PATHCPU"
sampler.type = "SOBOL"
film.filter.type = "BOX"
film.filter.width = 0.5
path.pathdepth.total = 64
path.pathdepth.diffuse = 64
path.pathdepth.glossy = 64
path.pathdepth.specular = 64
path.clamping.variance.maxvalue = 0
path.photongi.sampler.type = "METROPOLIS"
path.photongi.photon.maxcount = 20000000
path.photongi.photon.maxdepth = 64
path.photongi.indirect.enabled = 0
path.photongi.caustic.enabled = 1
path.photongi.caustic.maxsize = 100000
path.photongi.caustic.lookup.radius = 0.01
path.photongi.caustic.lookup.normalangle = 10
path.photongi.caustic.updatespp = 8
path.photongi.caustic.updatespp.radiusreduction = 0.96
path.photongi.caustic.updatespp.minradius = 0.003
"""


def render_luxcore(out, budget, seed, path, extra):
    """A LuxCore render of `budget` seconds into `path` (.npy, rows from the top), run in a
    process of its own: pyluxcore and the OpenEXR module carry OpenEXR libraries of their own,
    which abort when both are loaded."""
    import pyluxcore
    pyluxcore.Init()
    text, width, height = luxcore_scene(out)
    scene = pyluxcore.Scene()
    props = pyluxcore.Properties()
    props.SetFromString(text)
    scene.Parse(props)
    config = pyluxcore.Properties()
    config.SetFromString(LUXCORE_SETTINGS + "renderengine.seed = %d\nfilm.width = %d\n"
                         "film.height = %d\n" % (seed, width, height) + "\n".join(extra))
    render = pyluxcore.RenderSession(pyluxcore.RenderConfig(config, scene))
    start = time.monotonic()
    render.Start()
    while time.monotonic() - start < budget:
        time.sleep(0.05)
    render.Stop()
    rgb = np.zeros((height, width, 3), dtype=np.float32)
    render.GetFilm().GetOutputFloat(pyluxcore.FilmOutputType.RGB, rgb)
    # LuxCore's film rows run from the bottom of the image up, and its image lies one row
    # below the camera convention's (refs/README.md): moved up by one row, its difference
    # from grinlight's image of the same scene falls 37-fold, against 0 or 2 rows or a column.
    np.save(path, np.roll(np.flipud(rgb), -1, axis=0))


def run_luxcore(out, budget, seed, path, extra):
    start = time.monotonic()
    # LuxCore logs every step to both streams: shown only when the render fails.
    run = subprocess.run([sys.executable, __file__, "--out", out, "--luxcore-render",
                          str(budget), str(seed), path, *extra], capture_output=True, text=True)
    if run.returncode != 0:
        raise SystemExit("LuxCore failed:\n" + run.stdout[-2000:] + run.stderr[-2000:])
    return time.monotonic() - start, crop(np.load(path).astype(np.float64))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--budgets", type=float, nargs="+", default=[20, 40, 120])
    ap.add_argument("--seeds", type=int, nargs="+", default=[1, 2])
    ap.add_argument("--out", default="out/luxcore_caustic")
    ap.add_argument("--grinlight", nargs="+", default=["target/release/grinlight"])
    ap.add_argument("--reference-spp", type=int, default=65536)
    ap.add_argument("--luxcore", nargs="*", default=[], metavar="PROPERTY",
                    help='LuxCore properties over the defaults, e.g. '
                    '"path.photongi.caustic.lookup.radius = 0.02"')
    ap.add_argument("--luxcore-render", nargs="+", help=argparse.SUPPRESS)
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    if a.luxcore_render:
        budget, seed, path, *extra = a.luxcore_render
        return render_luxcore(a.out, float(budget), int(seed), path, extra)
    half_a, half_b = reference(a.out, a.reference_spp)
    truth = 0.5 * (half_a + half_b)
    # The halves' difference has twice a half's variance; their mean half of a half's.
    own = 0.5 * rmse(half_a, half_b)
    print("reference: %d × 2 spp, its own RMSE %.5f over the crop (mean radiance %.4f)"
          % (a.reference_spp, own, truth.mean()))

    def error(image):
        return math.sqrt(max(rmse(image, truth) ** 2 - own ** 2, 0.0))

    print("%7s %4s  %-32s %8s %9s %7s %8s" % (
        "budget", "seed", "renderer", "seconds", "RMSE", "mean", "/LuxCore"))
    ratios = {}
    for budget in a.budgets:
        for seed in a.seeds:
            l_s, lux = run_luxcore(a.out, budget, seed,
                                   os.path.join(a.out, "luxcore-%g-%d.npy" % (budget, seed)),
                                   a.luxcore)
            le = error(lux)
            row = "%7g %4d  %-32s %8.1f %9.5f %7.4f %8s"
            print(row % (budget, seed, "LuxCore 2.11 PhotonGI", l_s, le,
                         lux.mean() / truth.mean(), ""), flush=True)
            for k, build in enumerate(a.grinlight):
                g_s, g = run_grinlight(build, budget, seed, os.path.join(
                    a.out, "grinlight%d-%g-%d.exr" % (k, budget, seed)))
                ge = error(g)
                ratios.setdefault((build, budget), []).append(ge / le)
                print(row % (budget, seed, build[-32:], g_s, ge, g.mean() / truth.mean(),
                             "%.3f" % (ge / le)), flush=True)
    for (build, budget), r in ratios.items():
        print("%s, %g s: median RMSE / LuxCore's %.3f" % (build, budget, statistics.median(r)))

if __name__ == "__main__":
    main()
