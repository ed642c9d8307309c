"""How well a render's own error estimate describes its true error: each scene rendered at
32 × 32 (4 samples a pixel a pass) by both integrators, against a path-traced reference of
REF_PASSES passes from another seed. Per case: the share of pixel-channels whose 95 %
t-interval (the render's standard error and the reference's combined) holds the reference,
and the estimated relative RMSE against the one measured (the reference's own noise taken
out).

    ./test.sh                        # builds the package into .venv
    .venv/bin/python bench/error_coverage.py [REF_PASSES]
"""

import math
import sys
from pathlib import Path

import numpy as np

import grinlight

ROOT = Path(__file__).resolve().parents[1]
T975 = {15: 2.131450, 63: 1.998341}  # Student's t, two-sided 95 %


def main():
    ref_passes = int(sys.argv[1]) if len(sys.argv) > 1 else 4096
    print(f"grinlight {grinlight.__version__}; 32 × 32, 4 spp a pass; reference: path tracer, {ref_passes} passes")
    print(f"{'scene':<22} {'integrator':<11} {'passes':>6} {'coverage':>9} {'estimated':>10} {'measured':>9}")
    for name in ("cornell_diffuse.toml", "cornell_caustic.toml"):
        scene = grinlight.load(ROOT / "scenes" / name, width=32, height=32, spp=4)
        ref = scene.render(integrator="path", passes=ref_passes, seed=99, progress=False)
        r, rse = ref["beauty"].astype(float), ref["error"].astype(float)
        for integrator in ("path", "photon_map"):
            for passes in (16, 64):
                image = scene.render(integrator=integrator, passes=passes, seed=1, progress=False)
                m, se = image["beauty"].astype(float), image["error"].astype(float)
                coverage = np.mean(np.abs(m - r) <= T975[passes - 1] * np.sqrt(se**2 + rse**2))
                squares = np.mean((m - r) ** 2) - np.mean(rse**2)
                measured = math.sqrt(max(squares, 0.0)) / np.mean(r)
                print(f"{name:<22} {integrator:<11} {passes:>6} {coverage:>9.3f} {image.error:>10.4f} {measured:>9.4f}")


if __name__ == "__main__":
    main()
