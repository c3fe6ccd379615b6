"""Sky images in rainbow scenes (arcus.image.read, background.sky.image): through empty
air the panorama comes out as it went in, times its scale, with the mapping and the
bilinear read recomputed here from the header's words; files are read top row first;
bad input is explained."""

import json
import math

import numpy as np
import pytest

import arcus
from arcus import sky
from image_files import write_pfm


def bilinear(image, u, v):
    """Texel (i, j) centred at ((i + ½)/W, (j + ½)/H); wraps in u, clamps in v."""
    h, w, _ = image.shape
    x, y = u * w - 0.5, np.clip(v * h - 0.5, 0, h - 1)
    x0, y0 = np.floor(x).astype(int), np.minimum(np.floor(y).astype(int), h - 2)
    fx, fy = (x - x0)[..., None], (y - y0)[..., None]
    x0, x1 = x0 % w, (x0 + 1) % w
    return ((1 - fy) * ((1 - fx) * image[y0, x0] + fx * image[y0, x1])
            + fy * ((1 - fx) * image[y0 + 1, x0] + fx * image[y0 + 1, x1]))


def scene_with_sky(sky_spec, width=24, height=16):
    return {
        "image": {"width": width, "height": height, "fov_deg": 70, "exposure": 1},
        "camera": {"position": [0, 1.7, 0], "look_azimuth_deg": 150, "look_elevation_deg": 35},
        "sun": {"elevation_deg": 10, "azimuth_deg": 180, "diameter_deg": 0, "samples": 1, "spectrum": "flat"},
        "rain": {"box_min": [-100, 0, -1100], "box_max": [100, 100, -1000],  # small and far: out of view
                 "populations": [{"shape": "sphere", "radius": 5e-4, "density": 300}]},
        "background": {"sky": sky_spec, "ground": {"radiance": 0.0}},
        "tables": {"wavelengths": {"linspace": [380, 700, 16]}},
    }


def empty_table(count=16):
    wl = np.linspace(380, 700, count)
    return sky.VolumeTable(wavelengths=wl, theta=np.array([100.0, 180.0]), phi=np.array([0.0]),
                           beta=np.zeros((count, 1, 2)), extinction=np.zeros(count), computed=0, cached=0,
                           seconds=0.0)


def test_read_returns_files_top_row_first(tmp_path):
    image = np.random.default_rng(3).random((5, 7, 3)).astype(np.float32)
    write_pfm(tmp_path / "a.pfm", image)
    np.testing.assert_array_equal(arcus.image.read(tmp_path / "a.pfm"), image)
    with pytest.raises(arcus.Error) as err:
        arcus.image.read(tmp_path / "missing.exr")
    assert err.value.status == "ARCUS_ERROR_IO" and "missing.exr" in str(err.value)


def test_sky_image_comes_out_as_it_went_in(ctx, tmp_path):
    # No rain in view (β = 0, σ = 0): every pixel is the panorama in its direction times
    # the scale.  The pinhole (+x to the right looking along +z), the mapping (u =
    # azimuth/360°, v = (90° − elevation)/180°) and the bilinear read are the header's,
    # recomputed here; the spectra round-trip the colour exactly (double sums), leaving
    # float32 storage: 1e-5 relative.
    image = np.random.default_rng(5).random((32, 64, 3)).astype(np.float32)
    write_pfm(tmp_path / "sky.pfm", image)
    scene = scene_with_sky({"image": "sky.pfm", "scale": 2.5})
    path = tmp_path / "scene.json"
    path.write_text(json.dumps(scene))  # the image's name is relative to the scene's folder
    out = sky.render(path, table=empty_table(), context=ctx)

    h, w = out.image.shape[:2]
    a, e = math.radians(150), math.radians(35)
    f = np.array([math.cos(e) * math.sin(a), math.sin(e), math.cos(e) * math.cos(a)])
    right = np.array([f[2], 0.0, -f[0]]) / math.hypot(f[0], f[2])
    up = np.cross(f, right)
    half_w = math.tan(math.radians(35))
    x = (2 * (np.arange(w) + 0.5) / w - 1) * half_w
    y = (1 - 2 * (np.arange(h) + 0.5) / h) * half_w * h / w
    d = f + x[None, :, None] * right + y[:, None, None] * up
    d /= np.linalg.norm(d, axis=-1, keepdims=True)
    assert d[..., 1].min() > 0  # all sky
    u = np.mod(np.arctan2(d[..., 0], d[..., 2]), 2 * np.pi) / (2 * np.pi)
    v = np.arccos(d[..., 1]) / np.pi
    expected = 2.5 * bilinear(image.astype(float), u, v)
    np.testing.assert_allclose(out.image, expected, rtol=1e-5, atol=1e-7)


# A scene file is checked by the library's reader first (the key's path), a dict by
# arcus.sky itself.
@pytest.mark.parametrize("spec, words", [
    ({"image": "nowhere.png"}, "does not exist"),
    ({"image": "sky.pfm", "radiance": 0.1}, "$.background.sky.radiance: unknown key (allowed here: image, scale)"),
    ({"image": "sky.pfm", "scale": -1}, "scale"),
    ({"image": 3}, "$.background.sky.image: expected a string"),
])
def test_bad_sky_images_are_explained(ctx, tmp_path, spec, words):
    write_pfm(tmp_path / "sky.pfm", np.ones((4, 8, 3), np.float32))
    path = tmp_path / "scene.json"
    path.write_text(json.dumps(scene_with_sky(spec)))
    with pytest.raises(arcus.ArgumentError) as err:
        sky.render(path, table=empty_table(), context=ctx)
    assert words in str(err.value)


def test_only_the_sky_may_be_an_image(ctx, tmp_path):
    scene = scene_with_sky({"radiance": 0.1})
    scene["background"]["ground"] = {"image": "ground.png"}
    with pytest.raises(arcus.ArgumentError, match="only the sky may be an image"):
        sky.render(scene, table=empty_table(), context=ctx)


def test_negative_pixels_are_refused_by_the_library(ctx, tmp_path):
    image = np.ones((4, 8, 3), np.float32)
    image[2, 5, 1] = -0.5
    write_pfm(tmp_path / "sky.pfm", image)
    path = tmp_path / "scene.json"
    path.write_text(json.dumps(scene_with_sky({"image": "sky.pfm"})))
    with pytest.raises(arcus.ArgumentError, match=r"pixel \(5, 2\) channel 1"):
        sky.render(path, table=empty_table(), context=ctx)
