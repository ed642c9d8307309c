"""Bad input raises ValueError naming the key; nothing panics; an interrupt returns at once
with the finished passes."""

import math
import os
import signal
import threading
import time

import numpy as np
import pytest

import grinlight

ROD = {"name": "rod", "profile": "linear", "n0": 1.5, "gradient": [0.0, 0.1, 0.0]}
CALCITE = {"name": "calcite", "profile": "uniaxial", "no": 1.6584, "ne": 1.4864, "optic_axis": [0, 0, 1]}


@pytest.mark.parametrize(
    "data, key",
    [
        ({"medium": [dict(ROD, n0=math.nan)]}, "medium[0].n0"),
        ({"medium": [dict(ROD, n0=math.inf)]}, "medium[0].n0"),
        ({"medium": [dict(ROD, gradient=[0.0, math.nan, 0.0])]}, "medium[0].gradient"),
        ({"medium": [dict(ROD, n0="high")]}, "medium[0].n0"),
        ({"medium": [dict(ROD, n0=None)]}, "medium[0].n0"),
        ({"medium": [dict(ROD, colour=1)]}, "medium[0]"),
        ({"medium": [ROD, dict(ROD, name="b", profile="luneburg", radius=-1.0)]}, "medium[1].radius"),
        ({"mediums": [ROD]}, "mediums"),
        ({"medium": [ROD], "camera": {"position": [0, 0, 1], "look_at": [0, 0, 0], "fov_y_deg": "wide"}}, "camera.fov_y_deg"),
        ({"medium": [ROD], "render": {"spp": -3}}, "render.spp"),
        ({"medium": [ROD], "render": {"spp": 2**70}}, "render.spp"),
        ({"medium": [{"name": object()}]}, "medium[0].name"),
        ({"medium": [{1: "rod"}]}, "medium[0]"),
        ({"medium": [dict(CALCITE, ne=-1.0)]}, "medium[0].ne"),
        ({"medium": [dict(CALCITE, no=math.nan)]}, "medium[0].no"),
        ({"medium": [dict(CALCITE, optic_axis=[0.0, 0.0, 0.0])]}, "medium[0].optic_axis"),
    ],
)
def test_a_bad_dict_names_its_key(data, key):
    with pytest.raises(ValueError) as e:
        grinlight.load_dict(data)
    assert str(e.value).startswith(key), str(e.value)


def test_a_ray_is_not_traced_in_a_crystal():
    """A crystal's light travels as two waves that part at its faces: `trace` names it and
    raises, it does not follow one of them silently."""
    with pytest.raises(ValueError, match="'calcite' is a uniaxial crystal"):
        grinlight.trace({"medium": [CALCITE]}, [0, 0, 0], [0, 0, 1], 1.0, medium="calcite")


def test_a_list_that_holds_itself_or_nests_too_deep_is_refused():
    loop = []
    loop.append(loop)
    deep = [1.0]
    for _ in range(10000):
        deep = [deep]
    for data in ({"shape": loop}, {"shape": deep}, {"medium": [{"name": {"a": loop}}]}):
        with pytest.raises(ValueError, match="nested more than 64 lists or dicts deep"):
            grinlight.load_dict(data)


@pytest.mark.parametrize("data", [None, 3, "scene.toml", [ROD]])
def test_a_scene_that_is_not_a_dict_is_refused(data):
    with pytest.raises(ValueError, match="a scene is a dict of the scene file's tables, got"):
        grinlight.load_dict(data)


def test_shards_and_merges_check_their_arguments(scenes, tmp_path):
    scene = grinlight.load(scenes / "cornell_caustic.toml")
    for shard in [(1,), (1, 2, 3), "1/2", (0, 2), (3, 2), (1.0, 2)]:
        with pytest.raises(ValueError, match="shard: expected"):
            scene.render(shard=shard, progress=False)
    with pytest.raises(ValueError, match="partials: expected a list"):
        grinlight.merge(str(tmp_path / "s1.partial"))
    with pytest.raises(ValueError, match="resume"):
        scene.render(resume=True, progress=False)


def test_numpy_values_are_accepted():
    scene = grinlight.load_dict({"medium": [dict(ROD, gradient=np.array([0.0, 0.1, 0.0]), n0=np.float32(1.5))]})
    assert scene.media == ["rod"]


def test_numpy_numbers_are_settings(scenes):
    scene = grinlight.load(scenes / "cornell_caustic.toml", width=np.int64(8), height=np.int32(6), radius=np.float32(0.5))
    assert scene.camera == (8, 6)


@pytest.mark.parametrize(
    "overrides, key",
    [
        (dict(spp=0), "spp expected an integer ≥ 1, got 0"),
        (dict(target_error=-1.0), "target_error must be a number"),
        (dict(passes=0), "passes expected"),
        (dict(width=0), "width expected"),
        (dict(spp=-1), "spp"),
        (dict(spp=1.5), "spp"),
        (dict(radius=math.nan), "radius"),
        (dict(time_budget=math.inf), "time_budget"),
        (dict(integrator="bidirectional"), "integrator"),
        (dict(threads=10**6), "threads"),
        (dict(sppp=4), "sppp"),
    ],
)
def test_bad_settings_name_their_key(scenes, overrides, key):
    with pytest.raises(ValueError) as e:
        grinlight.load(scenes / "cornell_caustic.toml", **overrides)
    assert key in str(e.value), str(e.value)


@pytest.mark.parametrize(
    "overrides, words",
    [
        (dict(spp=1.5), 'spp expected an integer ≥ 1, got 1.5'),
        (dict(spp=4.0), 'spp expected an integer ≥ 1, got 4.0'),
        (dict(gather=70000), "gather must be at most 65536, got 70000"),
        (dict(radius=-1.5), "radius must be a number in (0, 1e30], got -1.5"),
        (dict(integrator="bidirectional"), "integrator expected 'photon_map' or 'path', got \"bidirectional\""),
        (dict(deflection_table="yes"), 'deflection_table expected true or false, got "yes"'),
        (dict(passes=[2]), "passes expected an integer ≥ 1, got a list"),
        (dict(sppp=4), "sppp: unknown key `sppp` (expected one of: integrator, sampler, deflection_table, spp, seed, max_depth, threads, max_steps, world_radius, polarized, stokes, photons, caustic_photons, gather, knn, radius, passes, time_budget, target_error, receiver_photons, width, height, no_table)"),
    ],
)
def test_a_setting_is_refused_in_the_scene_files_words(scenes, overrides, words):
    """The settings table reads a keyword as it reads the scene file's key and the command
    line's flag (tests/cli.rs checks those two give these words)."""
    with pytest.raises(ValueError) as e:
        grinlight.load(scenes / "cornell_caustic.toml").render(progress=False, **overrides)
    assert str(e.value) == words


def test_the_render_docstring_lists_every_setting():
    doc = grinlight.Scene.render.__doc__
    for name, _, values, default in grinlight._grinlight.render_settings():
        assert f"``{name}``" in doc and values in doc and default in doc, name


def test_a_scene_files_error_names_file_line_and_key(tmp_path):
    path = tmp_path / "bad.toml"
    path.write_text('[[medium]]\nname = "rod"\nprofile = "luneburg"\nradius = -1\n')
    with pytest.raises(ValueError, match=r"bad.toml:4:1: .*key `radius`"):
        grinlight.load(path)
    with pytest.raises(OSError):
        grinlight.load(tmp_path / "missing.toml")


@pytest.mark.parametrize(
    "ray, key",
    [
        (dict(origin=[0, math.nan, 0]), "origin"),
        (dict(origin=[0, 0]), "origin"),
        (dict(direction=[0, 0, 0]), "direction must be a non-zero vector"),
        (dict(length=math.nan), "length"),
        (dict(length=-1.0), "length"),
        (dict(stepper="euler"), "stepper"),
        (dict(tolerance=0.0), "tolerance must be a number"),
        (dict(max_steps=2**40, control="fixed", step=1e-9), "max_steps"),
        (dict(wavelength=100.0), "wavelength"),
        (dict(bogus=1), "bogus"),
    ],
)
def test_bad_rays_name_their_key(ray, key):
    args = dict(origin=[0, 0, 0], direction=[1, 0, 0], length=1.0)
    args.update(ray)
    with pytest.raises(ValueError) as e:
        grinlight.trace({"medium": [ROD]}, **args)
    assert key in str(e.value), str(e.value)


def test_writes_never_replace_what_is_not_theirs(scenes, tmp_path):
    image = grinlight.load(scenes / "cornell_caustic.toml").render(progress=False, width=16, height=12, spp=1, passes=1, photons=1000, caustic_photons=1000)
    precious = tmp_path / "notes.exr"
    precious.write_text("not an image")
    with pytest.raises(ValueError, match="refusing"):
        image.write(precious)
    assert precious.read_text() == "not an image"
    with pytest.raises(ValueError, match=".exr"):
        image.write(tmp_path / "image.tiff")
    image.write(tmp_path / "image.exr")
    image.write(tmp_path / "image.exr")  # its own kind of file is replaced
    image.write_png(tmp_path / "image.png", exposure=2.0)
    with pytest.raises(ValueError, match="exposure"):
        image.write_png(tmp_path / "image.png", exposure=math.nan)


def test_ctrl_c_returns_within_a_second_with_the_passes_done(scenes):
    scene = grinlight.load(scenes / "cornell_caustic.toml")
    sent = {}

    def interrupt():
        sent["at"] = time.monotonic()
        os.kill(os.getpid(), signal.SIGINT)

    # Python's own Ctrl-C handler, whatever this process inherited (a shell's background job
    # starts with SIGINT ignored).
    inherited = signal.signal(signal.SIGINT, signal.default_int_handler)
    timer = threading.Timer(2.0, interrupt)
    try:
        timer.start()
        with pytest.raises(KeyboardInterrupt) as e:
            # The budget bounds the test should the signal never arrive.
            scene.render(progress=False, width=96, height=72, time_budget=60, photons=20000, caustic_photons=20000)
    finally:
        timer.join()
        signal.signal(signal.SIGINT, inherited)
    returned = time.monotonic() - sent["at"]
    assert returned < 1.0, f"returned {returned:.2f} s after the interrupt"
    image = e.value.image
    assert image is not None and image.interrupted and image.passes >= 1
    assert any("PARTIAL" in line or "interrupted" in line for line in image.report), image.report
    assert np.isfinite(image["beauty"]).all() and image["beauty"].mean() > 0


def test_progress_is_reported(scenes):
    seen = []
    grinlight.load(scenes / "cornell_caustic.toml").render(
        progress=lambda done, total, stage: seen.append((done, total, stage)),
        width=96, height=72, spp=2, passes=3, photons=200000, caustic_photons=200000,
    )
    assert seen, "a render of several tenths of a second reports progress"
    assert all(stage in ("rendering", "measuring", "") for _, _, stage in seen)
    assert all(0 <= done <= total for done, total, stage in seen if stage == "rendering")


def test_an_interrupted_shard_resumes_to_the_same_partial(scenes, tmp_path):
    scene = grinlight.load(scenes / "cornell_caustic.toml", width=48, height=36, spp=1, photons=20000, caustic_photons=20000, passes=60)
    whole = scene.render(shard=(1, 1), output=tmp_path / "whole.partial", progress=False)
    inherited = signal.signal(signal.SIGINT, signal.default_int_handler)
    timer = threading.Timer(0.8, lambda: os.kill(os.getpid(), signal.SIGINT))
    try:
        timer.start()
        with pytest.raises(KeyboardInterrupt) as e:
            scene.render(shard=(1, 1), output=tmp_path / "cut.partial", progress=False)
    finally:
        timer.join()
        signal.signal(signal.SIGINT, inherited)
    assert "resume=True" in str(e.value), str(e.value)
    cut = scene.render(shard=(1, 1), output=tmp_path / "cut.partial", resume=True, progress=False)
    a = grinlight.merge([whole], output=tmp_path / "a.exr")
    b = grinlight.merge([cut], output=tmp_path / "b.exr")
    np.testing.assert_array_equal(a["beauty"], b["beauty"])


def test_the_cameras_size_is_what_renders_use(scenes):
    plain = grinlight.load(scenes / "cornell_caustic.toml")
    sized = grinlight.load(scenes / "cornell_caustic.toml", width=40, height=30)
    assert plain.camera == (256, 256)
    assert sized.camera == (40, 30)
    image = sized.render(progress=False, spp=1, passes=1, photons=1000, caustic_photons=1000)
    assert (image.width, image.height) == sized.camera
