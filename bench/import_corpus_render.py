#!/usr/bin/env python3
"""The Mitsuba scenes of a directory that grinlight converts (exactly, or with --approximate),
rendered by both renderers: image means per channel and their ratio — the check that a
conversion renders what Mitsuba renders, on files nobody wrote for grinlight.

    python3 bench/import_corpus_render.py DIR [--spp N] [--runs K] [--match TEXT]

DIR is the mitsuba-data repository (`git clone https://github.com/mitsuba-renderer/mitsuba-data`).
Each scene converts with `grinlight convert` (--approximate if it must) and renders with
`grinlight render --approximate --integrator path` (N/4 samples a pixel in 4 passes, its release
build) and with Mitsuba 3 (`llvm_ad_rgb`, K runs of N samples, seeds 0..K-1) at the scene's own
resolution. A ratio far from 1 is a conversion to look into, or a difference the conversion's
notes explain. Needs `pip install mitsuba openexr numpy`, `apt-get install libllvm19` and
DRJIT_LIBLLVM_PATH set to the `libLLVM-19.so` it installs.
"""
import argparse
import os
import subprocess
import tempfile

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
EXE = os.path.join(ROOT, "target", "release", "grinlight")


def converts(path):
    """'exact', 'approximate', or None."""
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "s.toml")
        for flags, kind in (([], "exact"), (["--approximate"], "approximate")):
            r = subprocess.run([EXE, "convert", path, "-o", out] + flags, capture_output=True, timeout=120)
            if r.returncode == 0:
                return kind
    return None


def beauty(path):
    import OpenEXR

    with OpenEXR.File(path, separate_channels=True) as f:
        part = next(p for p in f.parts if p.name() == "beauty")
        return np.stack([part.channels[c].pixels for c in "RGB"], axis=-1).astype(np.float64)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("dir")
    ap.add_argument("--spp", type=int, default=256)
    ap.add_argument("--runs", type=int, default=4)
    ap.add_argument("--match", default="", help="only the files whose path holds this text")
    a = ap.parse_args()
    import mitsuba as mi

    mi.set_variant("llvm_ad_rgb")
    print(f"{'scene':58} {'conversion':12} {'Mitsuba mean':>26} {'ratio':>22}")
    for base, _, names in sorted(os.walk(a.dir)):
        for name in sorted(n for n in names if n.endswith(".xml")):
            path = os.path.join(base, name)
            if a.match not in path:
                continue
            kind = converts(path)
            if kind is None:
                continue
            shown = os.path.relpath(path, a.dir)
            try:
                scene = mi.load_file(path)
                theirs = np.mean([np.array(mi.render(scene, seed=k, spp=a.spp))[:, :, :3]
                                  for k in range(a.runs)], axis=0).astype(np.float64)
            except Exception as e:  # a scene Mitsuba itself cannot render (a missing file)
                print(f"{shown:58} {kind:12} Mitsuba fails: {str(e).splitlines()[0][:60]}")
                continue
            with tempfile.TemporaryDirectory() as tmp:
                exr = os.path.join(tmp, "g.exr")
                r = subprocess.run([EXE, "render", path, "--approximate", "--integrator", "path",
                                    "--spp", str(max(1, a.spp // 16)), "--passes", "4", "-o", exr],
                                   capture_output=True, text=True)
                if r.returncode != 0:
                    print(f"{shown:58} {kind:12} grinlight fails: {r.stderr.strip().splitlines()[-1][:80]}")
                    continue
                ours = beauty(exr)
            m, g = theirs.mean(axis=(0, 1)), ours.mean(axis=(0, 1))
            ratio = g / np.maximum(m, 1e-12)
            print(f"{shown:58} {kind:12} {np.array2string(m, precision=4):>26} {np.array2string(ratio, precision=4):>22}",
                  flush=True)


if __name__ == "__main__":
    main()
