"""Mitsuba 3 and pbrt-v4 scenes from Python: ``grinlight.load("scene.xml")`` (or
``"scene.pbrt"``) renders what ``grinlight render`` renders; parameters and approximations are
keywords; what cannot be converted raises ValueError naming the file and line."""

from pathlib import Path

import numpy as np
import pytest

import grinlight

ROOT = Path(__file__).resolve().parents[2]
BOX = ROOT / "scenes" / "mitsuba" / "cornell_box.xml"


def test_a_mitsuba_scene_loads_with_its_parameters_and_renders():
    scene = grinlight.load(BOX, defines={"res": 16, "spp": 2})
    assert scene.camera == (16, 16)
    image = scene.render(threads=1)
    beauty = image["beauty"]
    assert beauty.shape == (16, 16, 3)
    assert np.all(np.isfinite(beauty)) and beauty.mean() > 0


def test_an_unsupported_element_is_refused_by_line(tmp_path):
    xml = tmp_path / "s.xml"
    xml.write_text(
        '<scene version="3.0.0">\n<sensor type="perspective"><film type="hdrfilm">'
        '<rfilter type="box"/></film></sensor>\n<shape type="sphere"><bsdf type="principled"/></shape>\n</scene>'
    )
    with pytest.raises(ValueError) as e:
        grinlight.load(xml)
    assert "s.xml:3:" in str(e.value) and "'principled' is not supported" in str(e.value)


def test_an_approximation_is_made_only_when_asked(tmp_path):
    xml = tmp_path / "s.xml"
    xml.write_text(
        '<scene version="3.0.0"><sensor type="perspective"><film type="hdrfilm">'
        '<integer name="width" value="4"/><integer name="height" value="4"/>'
        '<rfilter type="tent"/></film></sensor>'
        '<emitter type="constant"/></scene>'
    )
    with pytest.raises(ValueError, match="--approximate"):
        grinlight.load(xml)
    image = grinlight.load(xml, approximate=True).render(spp=1)
    assert any("approximated" in w and "'tent'" in w for w in image.warnings)


def test_defines_belong_to_other_renderers_scenes():
    with pytest.raises(ValueError, match="other renderers"):
        grinlight.load(ROOT / "scenes" / "cornell_caustic.toml", defines={"a": 1})


PBRT_BOX = ROOT / "scenes" / "pbrt" / "cornell_box.pbrt"


def test_a_pbrt_scene_loads_and_renders():
    scene = grinlight.load(PBRT_BOX, width=16, height=16, spp=2)
    assert scene.camera == (16, 16)
    beauty = scene.render(threads=1)["beauty"]
    assert beauty.shape == (16, 16, 3)
    assert np.all(np.isfinite(beauty)) and beauty.mean() > 0


def test_a_pbrt_scene_is_refused_by_line_and_column(tmp_path):
    pbrt = tmp_path / "s.pbrt"
    pbrt.write_text('Camera "perspective"\nPixelFilter "box"\nWorldBegin\nMaterial "hair"\n')
    with pytest.raises(ValueError) as e:
        grinlight.load(pbrt)
    assert "s.pbrt:4:1:" in str(e.value) and 'the material "hair" is not supported' in str(e.value)
    with pytest.raises(ValueError, match="no \\$parameters"):
        grinlight.load(PBRT_BOX, defines={"spp": 4})
