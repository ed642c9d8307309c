"""A GRIN rod lens's back focal distance against wavelength: a parameter sweep from Python.

The rod of `scenes/grin_lens_chromatic.toml` (n = n0(λ)(1 − g(λ)² r²/2), F2 glass, g from
0.33/mm at 400 nm to 0.31/mm at 700 nm, 4 mm long) is traced at each wavelength: a ray
parallel to the axis at height h = 0.05 mm enters the front face, is followed through the
rod's index by `grinlight.trace` to the exit face (z = L), refracts into air there, and
crosses the axis at the back focal distance. Paraxial optics gives
BFD = 1 / (n0 g tan(gL)) for comparison. Blue focuses first (the rod's g falls with λ).

    pip install ".[examples]"      # once, from the repository (matplotlib)
    python examples/python/rod_focus_sweep.py [--out rod_focus.png]
"""

import argparse
import math
from pathlib import Path

import numpy as np

import grinlight

SCENE = Path(__file__).resolve().parents[2] / "scenes" / "grin_lens_chromatic.toml"
LENGTH = 4.0  # mm, the rod's length (the scene's cylinder height)
HEIGHT = 0.05  # mm, the ray's height above the axis


def back_focal_distance(scene: grinlight.Scene, nm: float) -> tuple:
    """The traced back focal distance at `nm`, and the index on the axis there."""
    ray = grinlight.trace(
        scene, origin=[HEIGHT, 0.0, 0.0], direction=[0.0, 0.0, 1.0], length=LENGTH * 1.01,
        medium="rod", stepper="rkn", control="fixed", step=1e-3, wavelength=nm,
    )
    z = ray.points[:, 2]
    k = int(np.searchsorted(z, LENGTH))  # first point past the exit face
    t = (LENGTH - z[k - 1]) / (z[k] - z[k - 1])
    at = lambda a: a[k - 1] + t * (a[k] - a[k - 1])
    x, d, n = at(ray.points[:, 0]), at(ray.directions), at(ray.n)
    d = d / np.linalg.norm(d)
    # Snell's law at the flat face (normal +z) from index n into air.
    tangential = n * d[:2]
    out = np.array([tangential[0], tangential[1], math.sqrt(1.0 - tangential @ tangential)])
    n_axis = n / (1.0 - 0.5 * g_of(nm) ** 2 * x * x)
    return -x * out[2] / out[0], n_axis


def g_of(nm: float) -> float:
    """The scene's tabulated g at 400, 550 and 700 nm (1/mm), interpolated linearly for
    the paraxial comparison (the renderer's table is a monotone cubic: equal at the knots)."""
    return float(np.interp(nm, [400.0, 550.0, 700.0], [0.33, 0.32, 0.31]))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default="rod_focus.png", help="the plot to write")
    args = parser.parse_args()
    scene = grinlight.load(SCENE)
    rows = []
    print(f"{'nm':>6} {'traced BFD mm':>14} {'paraxial BFD mm':>16}")
    for nm in np.arange(400.0, 701.0, 20.0):
        bfd, n0 = back_focal_distance(scene, nm)
        g = g_of(nm)
        paraxial = 1.0 / (n0 * g * math.tan(g * LENGTH))
        rows.append((nm, bfd, paraxial))
        knot = "  (g tabulated here)" if nm in (400.0, 700.0) else ""
        print(f"{nm:6.0f} {bfd:14.6f} {paraxial:16.6f}{knot}")
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib is not installed (pip install '.[examples]'): no plot")
        return
    nm, bfd, paraxial = np.array(rows).T
    fig, ax = plt.subplots(figsize=(6, 4))
    ax.plot(nm, bfd, "o-", label=f"traced (ray at h = {HEIGHT} mm)")
    ax.plot(nm, paraxial, "--", label="paraxial 1/(n0 g tan gL)")
    ax.set_xlabel("wavelength (nm)")
    ax.set_ylabel("back focal distance (mm)")
    ax.set_title("GRIN rod lens (F2, L = 4 mm): focus against wavelength")
    ax.legend()
    fig.tight_layout()
    fig.savefig(args.out, dpi=120)
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
