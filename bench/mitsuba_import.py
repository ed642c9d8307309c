#!/usr/bin/env python3
"""Render the Mitsuba 3 scenes of scenes/mitsuba/ with Mitsuba itself: the references that
tests/import.rs holds grinlight's renders of the same XML files against.

    python3 bench/mitsuba_import.py [CASE ...] [--runs K] [--spp N] [--write] [--grinlight]
                                    [--stored] [--integrator NAME] [-- GRINLIGHT OPTIONS]

For each case (a scene of scenes/mitsuba/ and the values of its parameters: CASES below), K independent Mitsuba renders (seeds 0..K-1, N samples a pixel each, the
scene's own resolution) are averaged over blocks of 8 × 8 pixels; with --write, the block means
and their standard errors (from the spread of the K runs) are written to
tests/data/mitsuba/<case>.csv (the references were written with --runs 16 --spp 1024). With --grinlight, grinlight renders the same XML as many times
(`grinlight render`, its release build) and the script prints a table: image means, their ratio,
and the largest block z-score |Δ|/√(se₁² + se₂²). With --stored the Mitsuba side is read from
tests/data/mitsuba/<case>.csv instead of rendered (no Mitsuba needed, --spp and --runs then set
grinlight's side alone); --integrator photon_map (or path) and options after `--` go to grinlight,
so that its photon mapper is held against the same references, e.g.

    python3 bench/mitsuba_import.py --grinlight --stored --runs 16 --spp 256 --integrator photon_map

Needs `pip install mitsuba` (3.9.1 wrote the files here), the fast `llvm_ad_rgb` variant:
`apt-get install libllvm19` and DRJIT_LIBLLVM_PATH set to the `libLLVM-19.so` it installs.
"""
import argparse
import os
import subprocess
import sys
import tempfile

import numpy as np

BLOCK = 8
ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

# Case name -> (scene in scenes/mitsuba/, its $parameters).
CASES = {
    "cornell_box": ("cornell_box.xml", {}),
    # Paths of two segments: direct light alone (grinlight's max_depth 1).
    "cornell_box_direct": ("cornell_box.xml", {"max_depth": "2"}),
    # Fog, a spot light in it, a glass ball of denser fog (volpath).
    "cornell_fog": ("cornell_fog.xml", {}),
    # A mirror ball, a diffuse ball, an environment map turned about +y, a directional light.
    "spheres_envmap": ("spheres_envmap.xml", {}),
    # An image texture on a rectangle and on an OBJ quad.
    "textures": ("textures.xml", {}),
    # The texture and a checkerboard on a sphere, a cylinder, a disk and a cube: their frames.
    "round_textures": ("round_textures.xml", {}),
    # The twin of scenes/pbrt/textured_shapes.pbrt: textures on a sphere, a cylinder, a rectangle.
    "textured_shapes": ("textured_shapes.xml", {}),
    # The texture on serialized, PLY and OBJ meshes, their v flipped or not, with and without
    # texture coordinates.
    "mesh_textures": ("mesh_textures.xml", {}),
    # Smoke whose density is a grid (a gridvolume) in a box, over a floor, under a sky and a
    # point light (volpath).
    "smoke_box": ("smoke_box.xml", {}),
    # Two emitting spheres over two diffuse balls and a floor.
    "sphere_lights": ("sphere_lights.xml", {}),
    # Two emitting meshes (an OBJ icosphere with vertex normals, a PLY ribbon with its normals
    # flipped) over a ball, a floor and a wall.
    "mesh_lights": ("mesh_lights.xml", {}),
    # A thin pane (thindielectric) across the view of two balls, under a sky and a lamp.
    "window": ("window.xml", {}),
    # An orthographic view, tilted and scaled, of a checkerboard, a ball and a box.
    "orthographic": ("orthographic.xml", {}),
    # Rough metal balls with Beckmann normals (Mitsuba's default distribution), α 0.05–0.2.
    "beckmann": ("beckmann.xml", {}),
    # Mitsuba's Gaussian pixel filter on edges at the blocks' boundaries and at the image's.
    "pixel_filter": ("pixel_filter.xml", {}),
    # Its crop window of 24 × 16 pixels from (8, 8): its left and top edges on the square's.
    "pixel_filter_crop": ("pixel_filter.xml", {"crop_x": "8", "crop_y": "8", "crop_w": "24", "crop_h": "16"}),
    # The Cornell box through the Gaussian pixel filter.
    "cornell_box_gaussian": ("cornell_box.xml", {"filter": "gaussian"}),
    # hide_emitters: the sky seen directly left out, seen in the mirror ball kept; emitting
    # spheres left out where seen, their light kept.
    "spheres_envmap_hidden": ("spheres_envmap.xml", {"hide": "true"}),
    "sphere_lights_hidden": ("sphere_lights.xml", {"hide": "true"}),
    # A shapegroup of three shapes placed by three instances.
    "instancing": ("instancing.xml", {}),
}


def blocks(image):
    """Block means of an (h, w, 3) image, as (h/B, w/B, 3)."""
    h, w, _ = image.shape
    return image[: h - h % BLOCK, : w - w % BLOCK].reshape(h // BLOCK, BLOCK, w // BLOCK, BLOCK, 3).mean(axis=(1, 3))


def mitsuba_runs(path, defines, runs, spp):
    import mitsuba as mi

    mi.set_variant("llvm_ad_rgb")
    scene = mi.load_file(path, spp=spp, **defines)
    out = []
    for k in range(runs):
        image = np.array(mi.render(scene, seed=k, spp=spp))[:, :, :3].astype(np.float64)
        out.append(blocks(image))
    return np.array(out)


def grinlight_runs(path, defines, runs, spp, options=()):
    """grinlight's renders of `path` (seeds 0..runs-1, `spp` samples a pixel, with its `defines`
    and further command-line `options`): block means per run, as (runs, h/B, w/B, 3)."""
    return grinlight_layer_runs(path, defines, runs, spp, ("beauty",), options)[:, 0]


def grinlight_layer_runs(path, defines, runs, spp, layers, options=()):
    """grinlight_runs for each of the EXR's `layers`: (runs, len(layers), h/B, w/B, 3)."""
    import OpenEXR

    exe = os.path.join(ROOT, "target", "release", "grinlight")
    out = []
    with tempfile.TemporaryDirectory() as tmp:
        for k in range(runs):
            exr = os.path.join(tmp, f"run{k}.exr")
            define = [arg for k_v in defines.items() for arg in ("-D", "=".join(k_v))]
            subprocess.run([exe, "render", path, "-o", exr, "--seed", str(k), "--spp", str(spp)] + define + list(options),
                           check=True, capture_output=True)
            per_layer = []
            with OpenEXR.File(exr, separate_channels=True) as f:
                for name in layers:
                    part = next(p for p in f.parts if p.name() == name)
                    image = np.stack([part.channels[c].pixels for c in "RGB"], axis=-1).astype(np.float64)
                    per_layer.append(blocks(image))
            out.append(per_layer)
    return np.array(out)


def read_blocks(path):
    """Block means and standard errors from a CSV `write_blocks` wrote, as (h/B, w/B, 3) each."""
    rows = np.loadtxt(path, delimiter=",", comments="#", skiprows=2)
    h, w = int(rows[:, 1].max()) + 1, int(rows[:, 0].max()) + 1
    mean, se = np.zeros((h, w, 3)), np.zeros((h, w, 3))
    for r in rows:
        bx, by = int(r[0]), int(r[1])
        mean[by, bx], se[by, bx] = r[2:5], r[5:8]
    return mean, se


def write_blocks(path, comment, mean, se):
    """Block means and their standard errors as a CSV of tests/data/mitsuba/ under `comment`."""
    with open(path, "w") as f:
        f.write(f"# {comment}\n")
        f.write("bx,by,r,g,b,se_r,se_g,se_b\n")
        for by in range(mean.shape[0]):
            for bx in range(mean.shape[1]):
                m, s = mean[by, bx], se[by, bx]
                f.write(f"{bx},{by},{m[0]:.9g},{m[1]:.9g},{m[2]:.9g},{s[0]:.6g},{s[1]:.6g},{s[2]:.6g}\n")


def block_z(ours, ours_se, theirs, theirs_se):
    """|Δ|/σ per block as tests/import.rs takes it: σ = √(se₁² + se₂²) plus 1e-5 of the value,
    the resolution of Mitsuba's f32 sums (a block of sky has no spread in either renderer)."""
    sigma = np.sqrt(ours_se ** 2 + theirs_se ** 2) + 1e-5 * np.abs(theirs)
    # Blocks both renderers find exactly zero (an unpolarized sky's S1) agree.
    return np.divide(np.abs(ours - theirs), sigma, out=np.zeros_like(sigma), where=sigma > 0)


def stats(runs):
    mean = runs.mean(axis=0)
    se = runs.std(axis=0, ddof=1) / np.sqrt(len(runs))
    return mean, se


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("cases", nargs="*", choices=[[]] + list(CASES))
    ap.add_argument("--runs", type=int, default=16)
    ap.add_argument("--spp", type=int, default=1024)
    ap.add_argument("--write", action="store_true")
    ap.add_argument("--grinlight", action="store_true")
    ap.add_argument("--stored", action="store_true")
    ap.add_argument("--integrator", choices=["path", "photon_map"])
    argv = sys.argv[1:]
    cut = argv.index("--") if "--" in argv else len(argv)
    a = ap.parse_args(argv[:cut])
    options = argv[cut + 1 :]
    if a.integrator:
        options += ["--integrator", a.integrator]

    rows = []
    for name in a.cases or list(CASES):
        scene, defines = CASES[name]
        path = os.path.join(ROOT, "scenes", "mitsuba", scene)
        if a.stored:
            mean, se = read_blocks(os.path.join(ROOT, "tests", "data", "mitsuba", name + ".csv"))
        else:
            import mitsuba as mi

            mean, se = stats(mitsuba_runs(path, defines, a.runs, a.spp))
        if a.write and not a.stored:
            given = "".join(f" -D {k}={v}" for k, v in defines.items())
            write_blocks(os.path.join(ROOT, "tests", "data", "mitsuba", name + ".csv"),
                         f"Mitsuba {mi.__version__} llvm_ad_rgb, scenes/mitsuba/{scene}{given}: {a.runs} runs of "
                         f"{a.spp} spp, means over blocks of {BLOCK}x{BLOCK} pixels and their standard errors "
                         f"(bench/mitsuba_import.py)", mean, se)
        if a.grinlight:
            spp = a.spp if a.stored else a.spp // 4
            gm, gs = stats(grinlight_runs(path, defines, a.runs, spp, options))
            z = block_z(gm, gs, mean, se)
            rel = np.abs(gm - mean) / np.maximum(mean, 1e-300)
            rows.append((name, mean.mean(), gm.mean(), gm.mean() / mean.mean(), z.max(), rel.max()))
    if rows:
        print(f"{'scene':28} {'Mitsuba mean':>13} {'grinlight':>10} {'ratio':>7} {'max |z|':>8} {'max rel':>8}")
        for r in rows:
            print(f"{r[0]:28} {r[1]:13.5f} {r[2]:10.5f} {r[3]:7.4f} {r[4]:8.2f} {r[5]:8.4f}")


if __name__ == "__main__":
    main()
