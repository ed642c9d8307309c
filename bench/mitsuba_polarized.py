#!/usr/bin/env python3
"""Render tests/data/mitsuba/polarized_spheres.toml (or --scene NAME: tests/data/mitsuba/NAME.toml,
polarized_rough for rough metal balls) with Mitsuba 3's polarized path tracer: the references
that tests/polarization.rs holds grinlight's Stokes images and views through a camera polarizer
against.

    python3 bench/mitsuba_polarized.py [--scene NAME] [--runs K] [--spp N] [--write]
                                       [--grinlight [--integrator I]]

Mitsuba renders the scene (converted by bench/mitsuba_reference.py) K times (seeds 0..K-1, N
samples a pixel) with its `stokes` integrator over `path` in the `llvm_ad_mono_polarized`
variant (the scene is grey, so its monochrome render is each of grinlight's RGB channels). What
a camera records through an ideal linear polarizer at angle φ in Mitsuba's Stokes basis is
I = ½(S0 + S1 cos 2φ + S2 sin 2φ); grinlight's camera polarizer at θ = 0°, 45°, 90° and 135°
(`polarizer_deg`, from the image's right toward its up) is at φ(θ) at each pixel's centre
(analyzer_angles: θ itself on the image's axes, up to 5.3° from it at this image's corners, at θ = 90°).
I's means over blocks of
8 × 8 pixels and their standard errors (from the spread of the K runs) are written with --write
to tests/data/mitsuba/NAME_<θ>.csv, and S0–S3's to NAME_S<k>.csv (the references were written with --runs 16
--spp 1024). With --grinlight, grinlight renders the scene through a camera polarizer at each θ
as many times (`grinlight render --integrator I`, `path` unless given; its release build, N/4
samples a pixel)
and the script prints a table: image means, their ratio, the largest block z-score
|Δ|/(√(se₁² + se₂²) + 10⁻⁵ of the value); and the mean |S3|/S0 Mitsuba finds (a linear polarizer cannot see it).

Needs `pip install mitsuba` (3.9.1 wrote the files here) and its LLVM variants' library:
`apt-get install libllvm19` and DRJIT_LIBLLVM_PATH set to the `libLLVM-19.so` it installs.
"""
import argparse
import os
import sys
import tempfile
import tomllib

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from mitsuba_import import (ROOT, BLOCK, block_z, blocks, grinlight_layer_runs, grinlight_runs,  # noqa: E402
                            stats, write_blocks)
from mitsuba_reference import mitsuba_scene  # noqa: E402

DATA = os.path.join(ROOT, "tests", "data", "mitsuba")
ANGLES = (0, 45, 90, 135)


def analyzer_angles(camera, degrees):
    """Per pixel (h, w): the angle (radians) of grinlight's camera polarizer at `degrees` in
    Mitsuba's Stokes basis of the ray d through the pixel's centre. Mitsuba's first axis is
    d × u (u the sensor's up), its second turned from it toward the light's direction −d's
    right hand; grinlight's polarizer is a sheet square to the view whose transmission axis is
    t = cos θ r + sin θ u (r the image's right): it absorbs along f × t (f the view's
    forward axis), so light along d leaves it polarized along d × (f × t) (Korger et al.
    2013's tilted polarizer, as Mitsuba's own `polarizer`). At the image's centre that is t."""
    position = np.array(camera["position"], float)
    f = np.array(camera["look_at"], float) - position
    f /= np.linalg.norm(f)
    r = np.cross(f, camera.get("up", [0.0, 1.0, 0.0]))
    r /= np.linalg.norm(r)
    u = np.cross(r, f)
    w, h = camera["width"], camera["height"]
    t = np.tan(np.radians(camera["fov_y_deg"]) / 2)
    x = (2 * (np.arange(w) + 0.5) / w - 1) * t * w / h
    y = (1 - 2 * (np.arange(h) + 0.5) / h) * t
    d = f + x[None, :, None] * r + y[:, None, None] * u
    d /= np.linalg.norm(d, axis=-1, keepdims=True)
    first = np.cross(d, u)
    first /= np.linalg.norm(first, axis=-1, keepdims=True)
    second = np.cross(-d, first)
    theta = np.radians(degrees)
    axis = np.cos(theta) * r + np.sin(theta) * u
    across = np.cross(d, np.cross(f, axis))
    return np.arctan2(np.sum(across * second, axis=-1), np.sum(across * first, axis=-1))


def mitsuba_runs(scene_path, runs, spp):
    """Per run, per angle: I(θ)'s block means, as (runs, angles, h/B, w/B, 3); per run, S0–S3's
    block means, as (runs, 4, h/B, w/B, 3); and the mean |S3|/S0 over the image."""
    import mitsuba as mi

    mi.set_variant("llvm_ad_mono_polarized")
    with open(scene_path, "rb") as f:
        table = tomllib.load(f)
    d = mitsuba_scene(mi, table, spp)
    angles = [analyzer_angles(table["camera"], a) for a in ANGLES]
    d["integrator"] = {"type": "stokes", "integrator": d["integrator"]}
    scene = mi.load_dict(d)
    out, stokes, circular = [], [], []
    rgb = lambda i: blocks(np.repeat(i[:, :, None], 3, axis=2))  # noqa: E731
    for k in range(runs):
        # Channels: Y, then S0–S3 each as R, G, B (equal in monochrome).
        image = np.array(mi.render(scene, seed=k, spp=spp)).astype(np.float64)
        s0, s1, s2, s3 = (image[:, :, 1 + 3 * i] for i in range(4))
        seen = [0.5 * (s0 + s1 * np.cos(2 * t) + s2 * np.sin(2 * t)) for t in angles]
        out.append([rgb(i) for i in seen])
        stokes.append([rgb(i) for i in (s0, s1, s2, s3)])
        circular.append(np.abs(s3).mean() / s0.mean())
    return np.array(out), np.array(stokes), float(np.mean(circular))


def write_reference(name, what, a, mean, se):
    """tests/data/mitsuba/<a.scene>_<name>.csv: the scene's `what`, Mitsuba's block means and
    their standard errors over a.runs runs of a.spp spp."""
    import mitsuba as mi

    write_blocks(os.path.join(DATA, f"{a.scene}_{name}.csv"),
                 f"Mitsuba {mi.__version__} llvm_ad_mono_polarized (stokes over path), "
                 f"tests/data/mitsuba/{a.scene}.toml {what}: {a.runs} runs of {a.spp} spp, "
                 f"means over blocks of {BLOCK}x{BLOCK} pixels and their standard errors "
                 f"(bench/mitsuba_polarized.py)", mean, se)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--scene", default="polarized_spheres")
    ap.add_argument("--runs", type=int, default=16)
    ap.add_argument("--spp", type=int, default=1024)
    ap.add_argument("--write", action="store_true")
    ap.add_argument("--grinlight", action="store_true")
    ap.add_argument("--integrator", default="path", choices=["path", "photon_map"])
    a = ap.parse_args()
    import mitsuba as mi

    scene = os.path.join(DATA, f"{a.scene}.toml")
    runs, stokes, circular = mitsuba_runs(scene, a.runs, a.spp)
    print(f"Mitsuba: mean |S3|/S0 {circular:.5f}")
    rows = []
    # The Stokes vector itself, grinlight's S0–S3 layers (`--stokes true`) against Mitsuba's.
    ours = None
    if a.grinlight:
        layers = [f"S{k}" for k in range(4)]
        ours = grinlight_layer_runs(scene, {}, a.runs, a.spp // 4, layers,
                                    ["--integrator", a.integrator, "--stokes", "true"])
    for k in range(4):
        mean, se = stats(stokes[:, k])
        if a.write:
            write_reference(f"S{k}", f"S{k} in Mitsuba's basis (first axis d x up)", a, mean, se)
        if ours is not None:
            gm, gs = stats(ours[:, k])
            z = block_z(gm, gs, mean, se)
            rows.append((f"S{k}", mean.mean(), gm.mean(), gm.mean() / mean.mean(), z.max()))
    for i, angle in enumerate(ANGLES):
        mean, se = stats(runs[:, i])
        if a.write:
            write_reference(angle, f"seen through a linear polarizer at {angle} deg "
                            "(½(S0 + S1 cos 2φ + S2 sin 2φ), φ its angle in Mitsuba's basis)", a, mean, se)
        if a.grinlight:
            with tempfile.TemporaryDirectory() as tmp:
                path = os.path.join(tmp, f"polarizer_{angle}.toml")
                with open(scene) as f:
                    text = f.read().replace("[camera]\n", f"[camera]\npolarizer_deg = {angle}\n", 1)
                with open(path, "w") as f:
                    f.write(text)
                gm, gs = stats(grinlight_runs(path, {}, a.runs, a.spp // 4, ["--integrator", a.integrator]))
            z = block_z(gm, gs, mean, se)
            rows.append((f"{angle}° pol.", mean.mean(), gm.mean(), gm.mean() / mean.mean(), z.max()))
    if rows:
        print(f"{'image':10} {'Mitsuba mean':>13} {'grinlight':>10} {'ratio':>7} {'max |z|':>8}")
        for r in rows:
            print(f"{r[0]:10} {r[1]:13.5f} {r[2]:10.5f} {r[3]:7.4f} {r[4]:8.2f}")


if __name__ == "__main__":
    main()
