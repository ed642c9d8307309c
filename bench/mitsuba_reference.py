#!/usr/bin/env python3
"""Render a grinlight scene with Mitsuba 3 as an independent reference.

    python3 bench/mitsuba_reference.py SCENE.toml OUT.exr [--spp N] [--seed S] [--rgb-metals OUT.toml]
                                        [--crop X0 Y0 X1 Y1]

Reads the subset of grinlight's scene format that Cornell-box-like scenes use -- quads, boxes,
spheres and open cylinders; diffuse, conductor, dielectric and plastic materials; quad lights
and a uniform sky -- and builds
the same scene for Mitsuba's path tracer (box pixel filter, max_depth + 1 path segments; the fast
`llvm_ad_rgb` variant, or `--variant scalar_rgb`), with the conventions of refs/README.md:
two-sided Lambertian quads, a one-sided
emitter that reflects nothing, exact Fresnel, GGX with visible-normal sampling; plastic as
`roughplastic` with `nonlinear = true` (light scattered among the base and the coat's inner
side, ρ/(1 − ρ F̄ᵢ), as grinlight's plastic has it).

A measured metal (`metal = "Au"`) is colour-converted differently by the two renderers; to
compare the BSDFs themselves, --rgb-metals writes a copy of the scene whose metals are given
by the RGB eta and k below, which both renderers then use as they are.

--crop renders only the pixels [X0, X1) × [Y0, Y1) (from the top left) of the camera's image,
into an EXR of that size.

Needs `pip install mitsuba` (3.9.1 was used for the figures in docs/validation.md); the LLVM
variants need LLVM's shared library: `apt-get install libllvm19` and DRJIT_LIBLLVM_PATH set to
the `libLLVM-19.so` it installs (`dpkg -L libllvm19`; LLVM 14 and 15 abort with "Cannot select:
fminimum").
"""
import argparse
import os
import tempfile
import time
import tomllib

# RGB complex indices used for the comparison (the values common in RGB renderers for
# these metals); both renderers read the same numbers.
RGB_METALS = {
    "Au": ([0.143, 0.374, 1.442], [3.983, 2.385, 1.603]),
    "Ag": ([0.155, 0.117, 0.138], [4.828, 3.122, 2.147]),
    "Cu": ([0.200, 0.924, 1.102], [3.912, 2.452, 2.142]),
    "Al": ([1.657, 0.880, 0.521], [9.224, 6.270, 4.837]),
}


def rgb(v):
    return v if isinstance(v, list) else [v, v, v]


def write_obj(directory, name, quads):
    """An OBJ of quads (each four corners v0..v3, normal (v1-v0)x(v3-v0)) as triangles."""
    path = os.path.join(directory, name + ".obj")
    with open(path, "w") as f:
        for q in quads:
            for v in q:
                f.write("v %r %r %r\n" % tuple(v))
        for i in range(len(quads)):
            b = 4 * i + 1
            f.write("f %d %d %d\nf %d %d %d\n" % (b, b + 1, b + 2, b, b + 2, b + 3))
    return path


def box_quads(lo, hi):
    (x0, y0, z0), (x1, y1, z1) = lo, hi
    return [
        [[x0, y0, z0], [x0, y0, z1], [x0, y1, z1], [x0, y1, z0]],  # -x
        [[x1, y0, z0], [x1, y1, z0], [x1, y1, z1], [x1, y0, z1]],  # +x
        [[x0, y0, z0], [x1, y0, z0], [x1, y0, z1], [x0, y0, z1]],  # -y
        [[x0, y1, z0], [x0, y1, z1], [x1, y1, z1], [x1, y1, z0]],  # +y
        [[x0, y0, z0], [x0, y1, z0], [x1, y1, z0], [x1, y0, z0]],  # -z
        [[x0, y0, z1], [x1, y0, z1], [x1, y1, z1], [x0, y1, z1]],  # +z
    ]


def bsdf(m):
    kind = m["type"]
    alpha = m.get("roughness", 0.0)
    if kind == "diffuse":
        return {"type": "twosided", "b": {"type": "diffuse",
                "reflectance": {"type": "rgb", "value": rgb(m["albedo"])}}}
    if kind == "conductor":
        if "metal" in m:
            eta, k = RGB_METALS[m["metal"]]
        else:
            eta, k = rgb(m["eta"]), rgb(m["k"])
        b = {"type": "roughconductor" if alpha > 0 else "conductor",
             "eta": {"type": "rgb", "value": eta}, "k": {"type": "rgb", "value": k}}
        if alpha > 0:
            b.update(distribution="ggx", alpha=alpha)
        return {"type": "twosided", "b": b}
    if kind == "dielectric":
        b = {"type": "roughdielectric" if alpha > 0 else "dielectric",
             "int_ior": float(m["ior"]), "ext_ior": 1.0}
        if alpha > 0:
            b.update(distribution="ggx", alpha=alpha)
        return b
    if kind == "plastic":
        return {"type": "twosided", "b": {"type": "roughplastic", "distribution": "ggx",
                "alpha": m.get("roughness", 0.1), "int_ior": float(m.get("ior", 1.5)),
                "ext_ior": 1.0, "nonlinear": True,
                "diffuse_reflectance": {"type": "rgb", "value": rgb(m["albedo"])}}}
    raise SystemExit("material type %r is not converted" % kind)


def mitsuba_scene(mi, scene, spp, crop=None):
    """Mitsuba's scene dictionary for the grinlight scene table `scene` (read by tomllib), its
    sensor drawing `spp` samples a pixel over the pixels `crop` (X0, Y0, X1, Y1) if given;
    files its meshes need are written to a temporary directory."""
    materials = {m["name"]: m for m in scene["material"]}
    tmp = tempfile.mkdtemp()
    cam = scene["camera"]
    # An ambient uniform medium of index 1 that scatters (fog): Mitsuba's homogeneous medium,
    # the sensor's and every shape's exterior, rendered by volpath.
    fog = None
    if "ambient" in scene:
        m = next(m for m in scene["medium"] if m["name"] == scene["ambient"])
        if m["profile"] != "uniform" or m.get("n", 1.0) != 1.0:
            raise SystemExit("only an ambient uniform medium of n = 1 is converted")
        sigma_s = rgb(m.get("scattering", 0.0))
        sigma_a = m.get("absorption", 0.0)
        sigma_t = [s_ + sigma_a for s_ in sigma_s]
        phase = m.get("phase", "isotropic")
        fog = {
            "type": "homogeneous",
            "sigma_t": {"type": "rgb", "value": sigma_t},
            "albedo": {"type": "rgb", "value": [s_ / t if t > 0 else 0.0
                                                for s_, t in zip(sigma_s, sigma_t)]},
            "phase": ({"type": "hg", "g": phase["hg"]} if isinstance(phase, dict)
                      else {"type": "rayleigh"} if phase == "rayleigh"
                      else {"type": "isotropic"}),
        }
    d = {
        "type": "scene",
        # grinlight's max_depth counts scattering events, Mitsuba's path segments.
        "integrator": {"type": "volpath" if fog else "path",
                       "max_depth": scene.get("render", {}).get("max_depth", 64) + 1},
        "sensor": {
            "type": "perspective", "fov": cam["fov_y_deg"], "fov_axis": "y",
            "to_world": mi.ScalarTransform4f().look_at(
                origin=cam["position"], target=cam["look_at"], up=cam.get("up", [0, 1, 0])),
            "film": {"type": "hdrfilm", "width": cam["width"], "height": cam["height"],
                     "rfilter": {"type": "box"}, "pixel_format": "rgb"},
            "sampler": {"type": "independent", "sample_count": spp},
        },
    }
    if crop:
        x0, y0, x1, y1 = crop
        d["sensor"]["film"].update(crop_offset_x=x0, crop_offset_y=y0,
                                   crop_width=x1 - x0, crop_height=y1 - y0)
    for i, s in enumerate(scene["shape"]):
        b = bsdf(materials[s["material"]])
        if s["type"] == "sphere":
            d["shape%d" % i] = {"type": "sphere", "center": s["center"],
                                "radius": s["radius"], "bsdf": b}
        elif s["type"] in ("quad", "box"):
            quads = [s["vertices"]] if s["type"] == "quad" else box_quads(s["min"], s["max"])
            d["shape%d" % i] = {"type": "obj", "filename": write_obj(tmp, "s%d" % i, quads),
                                "face_normals": True, "bsdf": b}
        elif s["type"] == "cylinder" and not s.get("capped", True):
            base, axis = s["base"], s.get("axis", [0, 0, 1])
            norm = sum(a * a for a in axis) ** 0.5
            top = [b + a / norm * s["height"] for b, a in zip(base, axis)]
            d["shape%d" % i] = {"type": "cylinder", "p0": base, "p1": top,
                                "radius": s["radius"], "bsdf": b}
        else:
            raise SystemExit("shape type %r is not converted" % s["type"])
    for i, l in enumerate(scene.get("light", [])):
        if l["type"] == "environment" and l.get("sky") == "uniform":
            d["light%d" % i] = {"type": "constant", "radiance": {
                "type": "rgb", "value": rgb(l.get("radiance", 1.0))}}
            continue
        if l["type"] != "quad":
            raise SystemExit("light type %r is not converted" % l["type"])
        d["light%d" % i] = {
            "type": "obj", "filename": write_obj(tmp, "l%d" % i, [l["vertices"]]),
            "face_normals": True,
            "bsdf": {"type": "diffuse", "reflectance": {"type": "rgb", "value": [0, 0, 0]}},
            "emitter": {"type": "area", "radiance": {"type": "rgb", "value": rgb(l["radiance"])}},
        }
    if fog:
        d["sensor"]["medium"] = fog
        for key, value in d.items():
            if key.startswith(("shape", "light")) and value.get("type") != "constant":
                value["exterior"] = fog
    return d


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("scene")
    ap.add_argument("out")
    ap.add_argument("--spp", type=int, default=4096)
    ap.add_argument("--rgb-metals")
    ap.add_argument("--crop", type=int, nargs=4, metavar=("X0", "Y0", "X1", "Y1"))
    ap.add_argument("--variant", default="llvm_ad_rgb")
    ap.add_argument("--seed", type=int, default=0,
                    help="the first pass's seed (passes take seed, seed + 1, ...)")
    a = ap.parse_args()
    with open(a.scene, "rb") as f:
        scene = tomllib.load(f)
    if a.rgb_metals:
        text = open(a.scene).read()
        for name, (eta, k) in RGB_METALS.items():
            text = text.replace('metal = "%s"' % name, "eta = %r\nk = %r" % (eta, k))
        with open(a.rgb_metals, "w") as f:
            f.write(text)
    import drjit as dr
    import mitsuba as mi
    mi.set_variant(a.variant)
    d = mitsuba_scene(mi, scene, a.spp, a.crop)
    loaded = mi.load_dict(d)
    # Passes of 64 samples (fewer if fewer are asked) with their own seeds, averaged: the same
    # estimate as one render of N samples, in bounded memory. The time printed is the
    # rendering's alone (not Python's start or the scene's loading), for equal-time runs.
    per_pass = min(64, a.spp)
    passes = max(1, a.spp // per_pass)
    total = None
    start = time.monotonic()
    for p in range(passes):
        image = mi.TensorXf(mi.render(loaded, spp=per_pass, seed=p + a.seed))
        total = image if total is None else total + image
    # The LLVM variants evaluate lazily: without this the last pass (a one-pass run's whole
    # rendering) would be left out of the time.
    dr.eval(total)
    dr.sync_thread()
    seconds = time.monotonic() - start
    mi.util.write_bitmap(a.out, total / passes)
    print("%s: %d spp in %d passes, variant %s, %.1f s rendering" % (
        a.out, per_pass * passes, passes, mi.variant(), seconds))


if __name__ == "__main__":
    main()
