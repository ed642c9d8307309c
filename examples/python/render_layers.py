"""Render a scene from Python and look at its layers — written as notebook cells (`# %%`),
so it runs as a script or cell by cell in Jupyter or VS Code.

    pip install ".[examples]"      # once, from the repository (matplotlib)
    python examples/python/render_layers.py [--scene scenes/cornell_caustic.toml] [--out layers.png]
"""

# %% Load the scene; keyword arguments replace its [render] and [camera] keys.
import argparse
from pathlib import Path

import numpy as np

import grinlight

ROOT = Path(__file__).resolve().parents[2]
parser = argparse.ArgumentParser(description="render a scene and show its layers")
parser.add_argument("--scene", default=str(ROOT / "scenes" / "cornell_caustic.toml"))
parser.add_argument("--out", default="layers.png")
parser.add_argument("--passes", type=int, default=4)
args, _ = parser.parse_known_args()  # a notebook's own arguments are left alone

scene = grinlight.load(args.scene, width=320, height=240)
print(scene.path, "media:", scene.media)

# %% Render: a progress bar in a terminal or a notebook; Ctrl-C (or the notebook's stop
# button) ends it with the finished passes in the KeyboardInterrupt's .image.
try:
    image = scene.render(passes=args.passes, seed=1)
except KeyboardInterrupt as stop:
    image = stop.image
print("\n".join(image.report[-2:]))

# %% Every layer is a float32 array of shape (height, width, 3), linear RGB.
for name, layer in image.layers.items():
    print(f"{name:>10}: mean {layer.mean(axis=(0, 1))}, max {layer.max():.3g}")

# The radiance layers add up to the beauty layer.
radiance = ["direct", "caustic", "secondary", "emitted"]
parts = sum(image[n].astype(np.float64) for n in radiance if n in image.names)
print("beauty − sum of radiance layers, largest:", float(np.abs(image["beauty"] - parts).max()))


# %% Show them side by side (sRGB-encoded after an exposure).
def display(rgb: np.ndarray, exposure: float = 1.0) -> np.ndarray:
    v = np.clip(rgb * exposure, 0.0, 1.0)
    return np.where(v <= 0.0031308, 12.92 * v, 1.055 * v ** (1 / 2.4) - 0.055)


try:
    import matplotlib

    if __name__ == "__main__":
        matplotlib.use("Agg")
    import matplotlib.pyplot as plt
except ImportError:
    plt = None
    print("matplotlib is not installed (pip install '.[examples]'): no figure")

if plt is not None:
    names = image.names
    cols = 4
    rows = (len(names) + cols - 1) // cols
    fig, axes = plt.subplots(rows, cols, figsize=(4 * cols, 3.2 * rows))
    for ax in axes.flat:
        ax.axis("off")
    for ax, name in zip(axes.flat, names):
        layer = image[name]
        if name == "normal":
            shown = 0.5 * (layer + 1.0)  # unit normals, −1…1 per axis
        elif name == "albedo":
            shown = np.clip(layer, 0.0, 1.0)
        else:
            shown = display(layer)
        ax.imshow(shown)
        ax.set_title(name)
    fig.tight_layout()
    fig.savefig(args.out, dpi=80)
    print("wrote", args.out)

# %% The whole render as the command line writes it: a multi-layer EXR and a PNG preview.
image.write(Path(args.out).with_suffix(".exr"))
image.write_png(Path(args.out).with_suffix(".preview.png"))
