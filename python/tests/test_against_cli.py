"""The package gives what the command line gives for the same scene and settings: the
render's EXR bit for bit, a traced ray's CSV, a receiver's CSV, shards merged."""

import csv
from pathlib import Path

import numpy as np
import OpenEXR
import pytest

import grinlight
from conftest import run

# A small, quick render of the default scene: a few passes so the progressive caustic radius
# shrinks, with every layer (direct, caustic, secondary by final gathering).
SMALL = dict(width=48, height=36, spp=1, passes=2, photons=20000, caustic_photons=20000, seed=7)


def cli_flags(values):
    return [f"--{k.replace('_', '-')}={v}" for k, v in values.items()]


def read_exr(path):
    """Every layer of an EXR (one part each) as (height, width, 3) float32 arrays, by layer
    name: OpenEXR's own reader, independent of the package's writer."""
    with OpenEXR.File(str(path), separate_channels=True) as f:
        return {
            part.name(): np.stack([part.channels[c].pixels for c in "RGB"], axis=-1)
            for part in f.parts
        }


def test_render_writes_the_command_lines_exr_bit_for_bit(cli, scenes, tmp_path):
    run(cli, "render", scenes / "cornell_caustic.toml", "-o", tmp_path / "cli.exr", *cli_flags(SMALL), cwd=tmp_path)
    image = grinlight.load(scenes / "cornell_caustic.toml").render(progress=False, **SMALL)
    image.write(tmp_path / "py.exr")
    assert (tmp_path / "py.exr").read_bytes() == (tmp_path / "cli.exr").read_bytes()
    from_cli = read_exr(tmp_path / "cli.exr")
    assert sorted(from_cli) == sorted(image.names)
    for name in image.names:
        layer = image[name]
        assert layer.dtype == np.float32 and layer.shape == (36, 48, 3)
        np.testing.assert_array_equal(layer, from_cli[name])
    assert image["caustic"].max() > 0, "the ball's caustic reaches the floor"


def test_stokes_layers_are_the_command_lines(cli, tmp_path):
    """stokes=True writes S0–S3 as --stokes true does; S0 is beauty, and every pixel's Stokes
    vector is one light can have."""
    scene = Path(__file__).resolve().parents[2] / "tests" / "data" / "mitsuba" / "polarized_spheres.toml"
    small = dict(width=32, height=32, spp=2, seed=3)
    run(cli, "render", scene, "-o", tmp_path / "cli.exr", *cli_flags(small), "--stokes", "true", cwd=tmp_path)
    image = grinlight.load(scene).render(progress=False, stokes=True, **small)
    from_cli = read_exr(tmp_path / "cli.exr")
    s = [image[f"S{k}"] for k in range(4)]
    for k in range(4):
        np.testing.assert_array_equal(s[k], from_cli[f"S{k}"])
    np.testing.assert_allclose(s[0], image["beauty"], rtol=1e-6)
    assert np.all(s[1] ** 2 + s[2] ** 2 + s[3] ** 2 <= s[0] ** 2 * (1 + 1e-5))
    assert np.abs(s[1]).max() > 0.01 * s[0].max(), "the balls polarize what they reflect"
    assert "S1" not in grinlight.load(scene).render(progress=False, **small).names


def test_load_overrides_are_the_command_lines(cli, scenes, tmp_path):
    """Settings given to load() and to render() act as the command line's options."""
    scene = grinlight.load(scenes / "cornell_caustic.toml", width=48, height=36, seed=7)
    rest = {k: v for k, v in SMALL.items() if k not in ("width", "height", "seed")}
    a = scene.render(progress=False, **rest)
    b = grinlight.load(scenes / "cornell_caustic.toml").render(progress=False, **SMALL)
    np.testing.assert_array_equal(a["beauty"], b["beauty"])
    c = scene.render(progress=False, **dict(rest, seed=8))
    assert not np.array_equal(a["beauty"], c["beauty"]), "a render-time seed replaces the load-time one"


def test_a_cropped_camera_renders_its_window_as_the_command_line_does(cli, scenes, tmp_path):
    tomllib = pytest.importorskip("tomllib")
    data = tomllib.loads((scenes / "cornell_caustic.toml").read_text())
    data["camera"].update(width=48, height=36, crop=[8, 4, 24, 16])
    small = {k: v for k, v in SMALL.items() if k not in ("width", "height")}
    scene = grinlight.load_dict(data, base_dir=scenes)
    assert scene.camera == (24, 16)
    image = scene.render(progress=False, **small)
    assert image["beauty"].shape == (16, 24, 3)
    whole = grinlight.load(scenes / "cornell_caustic.toml").render(progress=False, **SMALL)
    np.testing.assert_array_equal(image["beauty"], whole["beauty"][4:20, 8:32])


def test_a_dict_scene_renders_as_its_file(scenes):
    tomllib = pytest.importorskip("tomllib")
    path = scenes / "cornell_caustic.toml"
    data = tomllib.loads(path.read_text())
    from_file = grinlight.load(path).render(progress=False, **SMALL)
    from_dict = grinlight.load_dict(data, base_dir=scenes).render(progress=False, **SMALL)
    for name in from_file.names:
        np.testing.assert_array_equal(from_file[name], from_dict[name])


def test_trace_gives_the_command_lines_csv(cli, scenes, tmp_path):
    scene = scenes / "grin_lens_chromatic.toml"
    ray = dict(origin=[0.3, 0.1, 0.0], direction=[0.0, 0.05, 1.0], length=9.0)
    run(
        cli, "trace", scene, "--medium", "rod", "--from", "0.3,0.1,0", "--dir", "0,0.05,1",
        "--length", "9", "--stepper", "rkn", "--wavelength", "486.1", "--csv", tmp_path / "ray.csv",
        cwd=tmp_path,
    )
    with open(tmp_path / "ray.csv") as f:
        assert f.readline().startswith("# grinlight ")
        rows = [{k: float(v) for k, v in r.items()} for r in csv.DictReader(f)]
    traced = grinlight.trace(scene, medium="rod", stepper="rkn", wavelength=486.1, **ray)
    assert traced.reason == "length reached"
    assert len(rows) == len(traced.s) == traced.steps + 1
    # The CSV prints each number's shortest exact representation: equal, not close.
    np.testing.assert_array_equal([r["s"] for r in rows], traced.s)
    np.testing.assert_array_equal([[r["x"], r["y"], r["z"]] for r in rows], traced.points)
    np.testing.assert_array_equal([[r["dx"], r["dy"], r["dz"]] for r in rows], traced.directions)
    np.testing.assert_array_equal([r["n"] for r in rows], traced.n)
    assert traced.opl[-1] == traced.optical_path
    assert np.all(np.diff(traced.opl) > 0)


def test_trace_carries_the_field_as_the_command_line_does(cli, scenes, tmp_path):
    """The field and geometric phase of a skew ray in a GRIN rod: the command line's numbers
    (printed to 12 decimals), None without ``polarization``, a field along the ray refused."""
    scene = scenes / "media.toml"
    done = run(
        cli, "trace", scene, "--medium", "grin_rod", "--from", "0.5,0,0", "--dir", "0,0.2,1",
        "--length", "30", "--polarization", "1,0,0", cwd=tmp_path,
    )
    line = next(l for l in done.stdout.splitlines() if "geometric phase" in l)
    traced = grinlight.trace(
        scene, [0.5, 0, 0], [0, 0.2, 1], 30.0, medium="grin_rod", polarization=[1, 0, 0]
    )
    assert f"geometric phase {traced.phase:.12f} rad" in line
    assert "field ({:.12f}, {:.12f}, {:.12f})".format(*traced.field) in line
    assert abs(np.dot(traced.field, traced.directions[-1])) < 1e-12
    plain = grinlight.trace(scene, [0.5, 0, 0], [0, 0.2, 1], 30.0, medium="grin_rod")
    assert plain.field is None and plain.phase is None
    with pytest.raises(ValueError, match="polarization"):
        grinlight.trace(scene, [0.5, 0, 0], [0, 0.2, 1], 30.0, medium="grin_rod", polarization=[0, 0.4, 2])


def test_measure_gives_the_receivers_csv(cli, scenes, tmp_path):
    settings = dict(receiver_photons=30000, seed=3)
    run(cli, "render", scenes / "fiber_led.toml", "-o", tmp_path / "fiber.exr", *cli_flags(settings), cwd=tmp_path)
    with open(tmp_path / "fiber.exit.csv") as f:
        assert f.readline().startswith("# grinlight ")
        rows = list(csv.DictReader(f))
    m = grinlight.load(scenes / "fiber_led.toml").measure(photons=30000, seed=3, progress=False)
    exit_ = m.receivers["exit"]
    assert exit_["irradiance"].shape == (64, 64)
    # The CSV rounds to 7 significant digits: the arrays rounded the same way are equal.
    rounded = lambda a: np.array([float(f"{v:.6e}") for v in a.ravel()])
    np.testing.assert_array_equal(rounded(exit_["irradiance"]), [float(r["irradiance"]) for r in rows])
    np.testing.assert_array_equal(rounded(exit_["stderr"]), [float(r["stderr"]) for r in rows])
    xs, ys = np.meshgrid(exit_["x"], exit_["y"])
    np.testing.assert_array_equal(rounded(xs), [float(r["x"]) for r in rows])
    np.testing.assert_array_equal(rounded(ys), [float(r["y"]) for r in rows])
    flux = exit_["irradiance"].sum() * (1.6 / 64) ** 2
    assert flux == pytest.approx(exit_["flux"], rel=1e-12)
    budget = m.budget
    booked = budget["reflected"] + budget["missed"] + budget["absorbed"] + budget["lost"]
    booked += sum(budget["out_through"].values()) + sum(budget["absorbed_in"].values())
    assert booked == pytest.approx(budget["emitted"], rel=1e-9), "every photon's power is booked"


POLARIZERS = """
[[light]]
type = "directional"
direction = [0, 0, 1]
irradiance = [1, 1, 1]
[[receiver]]
name = "r"
center = [0, 0, 4]
size = [1, 1]
bins = [4, 4]
[[material]]
name = "first"
type = "polarizer"
axis = [1, 0, 0]
[[material]]
name = "second"
type = "polarizer"
axis = [0.8660254037844387, 0.5, 0]
[[shape]]
type = "quad"
material = "first"
vertices = [[-2, -2, 1], [2, -2, 1], [2, 2, 1], [-2, 2, 1]]
[[shape]]
type = "quad"
material = "second"
vertices = [[-2, -2, 2], [2, -2, 2], [2, 2, 2], [-2, 2, 2]]
"""


def test_a_polarized_measure_gives_the_receivers_stokes_columns(cli, tmp_path):
    scene = tmp_path / "polarizers.toml"
    scene.write_text(POLARIZERS)
    run(cli, "render", scene, "-o", tmp_path / "p.exr", "--receiver-photons=20000", "--seed=2", cwd=tmp_path)
    with open(tmp_path / "p.r.csv") as f:
        f.readline()
        rows = list(csv.DictReader(f))
    r = grinlight.load(scene).measure(photons=20000, seed=2, progress=False).receivers["r"]
    rounded = lambda a: np.array([float(f"{v:.6e}") for v in a.ravel()])
    for name, part in zip(["S1", "S2", "S3"], r["stokes"]):
        assert part["irradiance"].shape == (4, 4)
        np.testing.assert_array_equal(rounded(part["irradiance"]), [float(row[name]) for row in rows])
    # Through polarizers at 0° and 30° the light is polarized along the second: S1/S0 = cos 60°,
    # S2/S0 = sin 60°, S3 = 0 (every photon alike; the shares are kept in f32).
    s1, s2, s3 = (part["flux"] / r["flux"] for part in r["stokes"])
    assert (s1, s2, s3) == pytest.approx((0.5, 0.8660254, 0.0), abs=1e-6)
    # Without polarized transport a receiver measures no Stokes components.
    plain = tmp_path / "plain.toml"
    plain.write_text(POLARIZERS.split("[[material]]")[0])
    assert grinlight.load(plain).measure(photons=2000, progress=False).receivers["r"]["stokes"] is None


def test_shards_merge_to_the_whole_render(scenes, tmp_path):
    scene = grinlight.load(scenes / "cornell_caustic.toml")
    settings = dict(SMALL, passes=3)
    whole = scene.render(progress=False, **settings)
    parts = [scene.render(progress=False, shard=(k, 2), output=tmp_path / f"part{k}.partial", **settings) for k in (1, 2)]
    assert all(p.exists() for p in parts)
    merged = grinlight.merge(parts, output=tmp_path / "merged.exr")
    assert merged.passes == whole.passes == 3
    for name in whole.names:
        np.testing.assert_array_equal(merged[name], whole[name])
    assert (tmp_path / "merged.exr").exists()


def test_a_target_error_ends_the_render(scenes):
    scene = grinlight.load(scenes / "cornell_diffuse.toml", width=32, height=32, spp=4, integrator="path")
    image = scene.render(target_error=0.15, seed=3, progress=False)
    assert image.passes >= 4 and image.error <= 0.15
    assert image["error"].shape == (32, 32, 3) and (image["error"] >= 0).all()
    assert any(line.startswith("estimated error") for line in image.report)


def test_a_dyes_budget_closes_from_python(scenes):
    m = grinlight.load(scenes / "solar_concentrator.toml").measure(photons=20000, seed=1, progress=False)
    budget = m.budget
    dye = budget["dyes"]["dyed_pmma"]
    assert 0 < dye["emitted"] < dye["absorbed"] and 0 < dye["reabsorbed"] < dye["absorbed"]
    part = budget["fluoresced"]
    booked = part["reflected"] + part["missed"] + part["absorbed"] + part["lost"]
    booked += sum(part["out_through"].values()) + sum(part["absorbed_in"].values())
    assert booked == pytest.approx(part["emitted"], rel=1e-9), "the dye's light is booked"
    edges = sum(m.receivers[f"edge_{side}"]["bands"][1]["flux"] for side in ("east", "west", "north", "south"))
    assert edges > 0
