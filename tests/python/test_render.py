"""Rendering from Python: arcus.render returns the image and figures as numpy."""
import pathlib

import numpy as np
import pytest

import arcus

ROOT = pathlib.Path(__file__).resolve().parents[2]


def small_scene(tmp_path, medium='{"type": "constant", "n": 1.0}'):
    text = """{"name": "py", "medium": %s,
      "integrator": {"method": "dp45", "rtol": 1e-12, "atol": 1e-6, "length": 100},
      "camera": {"position": [0, 0, 0], "look_at": [0, 0, -1], "vfov_deg": 40, "width": 32, "height": 24},
      "materials": {"m": {"diffuse": [0.5, 0.5, 0.5], "emission": [0.1, 0.2, 0.3]}},
      "objects": [{"type": "sphere", "center": [0, 0, -5], "radius": 1, "material": "m"}],
      "sky": {"type": "constant", "color": [0, 0, 1]}}""" % medium
    path = tmp_path / "py.json"
    path.write_text(text)
    return path


def test_render_returns_the_image_and_the_hits(tmp_path):
    result = arcus.render(small_scene(tmp_path), techniques=["smart_step"])
    assert result.image.shape == (24, 32, 3) and result.image.dtype == np.float32
    centre = result.objects[12, 16]
    assert centre == 0 and result.objects[0, 0] == -1
    # A straight ray down the axis meets the unit sphere 4 units away (closed form).
    assert abs(result.distances[12, 16] - 4.0) < 0.01
    assert np.allclose(result.image[0, 0], [0, 0, 1])
    assert result.stats["pixels"] == 32 * 24 and result.stats["techniques"] == 1


def test_a_bad_scene_raises_with_the_file_and_key(tmp_path):
    path = tmp_path / "bad.json"
    path.write_text('{"name": "b", "medium": {"type": "constant", "n": 1}, "integrator": {"length": 1},'
                    ' "camera": {"position": [0, 0, 0], "look_at": [1, 0, 0], "vfov_deg": 400,'
                    ' "width": 4, "height": 4}}')
    with pytest.raises(arcus.Error) as e:
        arcus.render(path)
    assert "$.camera" in str(e.value) and "bad.json" in str(e.value)


def test_unknown_techniques_and_symmetry_of_an_asymmetric_medium_are_refused(tmp_path):
    with pytest.raises(arcus.ArgumentError):
        arcus.render(small_scene(tmp_path), techniques=["warp"])
    # The camera looks along -z with x to its right: a gradient along x is not symmetric.
    asymmetric = small_scene(tmp_path, '{"type": "linear", "n0": 1.0, "gradient": [0.01, 0, 0]}')
    with pytest.raises(arcus.Error) as e:
        arcus.render(asymmetric, techniques=["symmetry"])
    assert "symmetry" in str(e.value)


def test_every_technique_gives_the_straight_image(tmp_path):
    plain = arcus.render(small_scene(tmp_path))
    for techniques in (["smart_step"], ["symmetry"], ["path_cache"], ["smart_step", "symmetry", "path_cache"]):
        result = arcus.render(small_scene(tmp_path), techniques=techniques, frames=2)
        assert (result.objects == plain.objects).all(), techniques


def test_a_scene_built_in_python_renders_like_its_file(tmp_path):
    import json
    path = small_scene(tmp_path)
    from_file = arcus.render(path)
    from_dict = arcus.render(json.loads(path.read_text()), base_dir=tmp_path)
    assert (from_dict.objects == from_file.objects).all()
    assert np.array_equal(from_dict.image, from_file.image)
    assert not list(tmp_path.glob("tmp*.json"))  # the temporary scene file is gone
