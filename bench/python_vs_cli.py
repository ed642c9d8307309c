"""The Python package's cost against the command line's for the same renders: each scene
rendered by `grinlight render` (the whole process: load, render, write the EXR and PNG) and
by `grinlight.load(...).render(...)` followed by `image.write` and `image.write_png` (in one
interpreter, the import excluded), alternately, REPEATS times each; medians and their ratio.

    ./test.sh                        # builds target/release/grinlight and the package in .venv
    .venv/bin/python bench/python_vs_cli.py [REPEATS [SCENE-NAME-PART]]
"""

import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import grinlight

ROOT = Path(__file__).resolve().parents[1]
CLI = ROOT / "target" / "release" / "grinlight"

# (scene, settings): the default scene as shipped, and a receiver measurement.
CASES = [
    ("cornell_caustic.toml", {}),
    ("cornell_caustic.toml", {"width": 160, "height": 120, "passes": 8, "spp": 4}),
    ("fiber_led.toml", {"receiver_photons": 1_000_000}),
]


def flags(settings):
    return [f"--{k.replace('_', '-')}={v}" for k, v in settings.items()]


def cli_seconds(scene, settings, out):
    t = time.perf_counter()
    subprocess.run([str(CLI), "render", str(ROOT / "scenes" / scene), "-o", str(out), *flags(settings)],
                   check=True, capture_output=True)
    return time.perf_counter() - t


def python_seconds(scene, settings, out):
    t = time.perf_counter()
    s = grinlight.load(ROOT / "scenes" / scene, **settings)
    if s.camera is None:
        s.measure(progress=False)
    else:
        image = s.render(progress=False)
        image.write(out)
        image.write_png(out.with_suffix(".png"))
    return time.perf_counter() - t


def main():
    repeats = int(sys.argv[1]) if len(sys.argv) > 1 else 5
    only = sys.argv[2] if len(sys.argv) > 2 else ""
    print(f"grinlight {grinlight.__version__}; medians of {repeats}, alternating; seconds")
    print(f"{'scene':<22} {'settings':<44} {'CLI':>8} {'Python':>8} {'ratio':>7}")
    with tempfile.TemporaryDirectory() as tmp:
        for scene, settings in (c for c in CASES if only in c[0]):
            cli, py = [], []
            for i in range(repeats):
                cli.append(cli_seconds(scene, settings, Path(tmp) / f"cli{i}.exr"))
                py.append(python_seconds(scene, settings, Path(tmp) / f"py{i}.exr"))
            c, p = statistics.median(cli), statistics.median(py)
            shown = ", ".join(f"{k}={v}" for k, v in settings.items()) or "as shipped"
            print(f"{scene:<22} {shown:<44} {c:8.2f} {p:8.2f} {p / c:7.3f}")


if __name__ == "__main__":
    main()
