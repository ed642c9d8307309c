#!/usr/bin/env python3
"""Rough plastic: grinlight's `plastic` and Mitsuba 3's `roughplastic` (nonlinear, GGX) against
the layer both stand for, simulated ray by ray (examples/plastic_layer.rs: a GGX dielectric
coat walked over every order of its microsurface, a Lambertian base under it).

    python3 bench/mitsuba_plastic.py [ALPHA] [ETA] [RHO] [RAYS]   (0.1 1.5 0.8 4e6)

Prints f at directions away from the coat's specular peak for light arriving at θo, each
model's ratio to the layer, and the medians of those ratios. Needs `pip install mitsuba`
(its scalar_rgb variant: a BSDF evaluated point by point).
"""
import math
import subprocess
import sys

import mitsuba as mi


def main():
    args = sys.argv[1:] or ["0.1", "1.5", "0.8", "4e6"]
    alpha, eta, rho = (float(a) for a in args[:3])
    out = subprocess.run(
        ["cargo", "run", "--release", "--quiet", "--example", "plastic_layer", "--", *args],
        check=True, capture_output=True, text=True).stdout
    mi.set_variant("scalar_rgb")
    bsdf = mi.load_dict({
        "type": "roughplastic", "distribution": "ggx", "alpha": alpha, "int_ior": eta,
        "ext_ior": 1.0, "nonlinear": True,
        "diffuse_reflectance": {"type": "rgb", "value": [rho] * 3}})
    ctx = mi.BSDFContext()
    print("θo   θi   φ     layer f             grinlight  Mitsuba    grinlight/layer  Mitsuba/layer")
    ratios = {"grinlight": [], "Mitsuba": []}
    for line in out.splitlines():
        parts = line.split()
        if len(parts) != 8 or parts[4] != "±":
            print(line)
            continue
        to, ti, phi = (float(p) for p in parts[:3])
        layer, se, ours = float(parts[3]), float(parts[5]), float(parts[6])
        si = mi.SurfaceInteraction3f()
        si.sh_frame = mi.Frame3f(mi.Vector3f(0, 0, 1))
        si.wi = mi.Vector3f(math.sin(math.radians(to)), 0, math.cos(math.radians(to)))
        a, p = math.radians(ti), math.radians(phi)
        wo = mi.Vector3f(math.sin(a) * math.cos(p), math.sin(a) * math.sin(p), math.cos(a))
        # Mitsuba's eval holds the cosine at the outgoing direction.
        theirs = bsdf.eval(ctx, si, wo)[0] / math.cos(a)
        ratios["grinlight"].append(ours / layer)
        ratios["Mitsuba"].append(theirs / layer)
        print("%-4g %-4g %-5g %.5f ± %.5f   %.5f    %.5f    %.4f           %.4f" % (
            to, ti, phi, layer, se, ours, theirs, ours / layer, theirs / layer))
    for name, r in ratios.items():
        r = sorted(r)
        print("%s / layer: median %.4f, range %.4f–%.4f over %d directions" % (
            name, r[len(r) // 2], r[0], r[-1], len(r)))


if __name__ == "__main__":
    main()
