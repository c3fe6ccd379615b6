"""Rendering from Python: arcus.render returns the image and figures as numpy."""
import json
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


@pytest.mark.parametrize("replace, key, words", [
    ('"sky": {"type": "daylight"}', "$.sky", "needs the sun that lights it"),
    ('"lights": [{"type": "daylight_sun", "elevation_deg": -12, "azimuth_deg": 0}], "sky": {"type": "daylight"}',
     "$.lights[0].elevation_deg", "-10 to 90"),
    ('"lights": [{"type": "daylight_sun", "elevation_deg": 30, "azimuth_deg": 0}], "sky": {"type": "daylight"},'
     ' "atmosphere": {"ozone_du": 5000}', "$.atmosphere.ozone_du", "ozone_du must lie in [0, 1000]"),
    ('"lights": [{"type": "daylight_sun", "elevation_deg": 30, "azimuth_deg": 0}],'
     ' "sky": {"type": "daylight"}, "atmosphere": {"ground_albedo": 1.5}', "$.atmosphere.ground_albedo",
     "ground_albedo must lie in [0, 1]"),
])
def test_a_bad_daylight_scene_names_its_key(tmp_path, replace, key, words):
    path = small_scene(tmp_path)
    path.write_text(path.read_text().replace('"sky": {"type": "constant", "color": [0, 0, 1]}', replace))
    with pytest.raises(arcus.Error) as e:
        arcus.render(path)
    assert key in str(e.value) and words in str(e.value), str(e.value)


def test_a_daylight_scene_is_lit_by_the_shared_sun_and_sky(tmp_path):
    # The sun's colour is arcus.daylight's (ASTM G173 through the air at 30°): a grey
    # sphere's lit side is warmer than the blue sky behind it, and the sky is bluer
    # overhead than at the horizon.
    path = small_scene(tmp_path)
    path.write_text(path.read_text().replace(
        '"sky": {"type": "constant", "color": [0, 0, 1]}',
        '"lights": [{"type": "daylight_sun", "elevation_deg": 30, "azimuth_deg": 0}], "sky": {"type": "daylight"}')
        .replace('"emission": [0.1, 0.2, 0.3]', '"emission": [0, 0, 0]'))
    image = arcus.render(path).image
    lit, sky = image[12, 16], image[2, 2]
    assert lit[0] / lit[2] > 1.0 > sky[0] / sky[2]


def linear_srgb(nm, spectrum):
    """Linear sRGB of a spectrum sampled at nm (Y = 1 for a flat 1), through the CIE 1931
    table in data/spectra read here, not through arcus."""
    cie = np.loadtxt(ROOT / "data" / "spectra" / "cie1931_2deg_5nm.csv", delimiter=",", skiprows=1)
    bars = np.array([np.interp(nm, cie[:, 0], cie[:, c]) for c in (1, 2, 3)])
    xyz = bars @ spectrum / bars[1].sum()
    return np.array([[3.2404542, -1.5371385, -0.4985314], [-0.9692660, 1.8760108, 0.0415560],
                     [0.0556434, -0.2040259, 1.0572252]]) @ xyz


def test_a_white_ground_under_daylight_has_the_sun_and_skys_light_over_pi(tmp_path):
    # A white disc (albedo 1) seen from above, the daylight sun 30° up: its radiance is
    # (E_sun cos z + E_sky)/π, and arcus.daylight.ground_irradiance integrates the sky
    # over the hemisphere by its own quadrature (no panorama, no renderer).  Tolerance
    # 2 %: the two colour integrations (arcus's band weights, this file's table read at
    # 10 nm) and the panorama's interpolation (0.23 % in tests/unit/test_sky_light.cpp);
    # measured: 0.15 %.
    path = tmp_path / "ground.json"
    path.write_text("""{"name": "ground", "medium": {"type": "constant", "n": 1.0},
      "integrator": {"method": "dp45", "rtol": 1e-12, "atol": 1e-6, "length": 100},
      "camera": {"position": [0, 10, 0], "look_at": [0, 0, 0], "up": [0, 0, 1], "vfov_deg": 10, "width": 8, "height": 8},
      "materials": {"white": {"diffuse": [1, 1, 1]}},
      "objects": [{"type": "disc", "center": [0, 0, 0], "normal": [0, 1, 0], "radius": 50, "material": "white"}],
      "lights": [{"type": "daylight_sun", "elevation_deg": 30, "azimuth_deg": 40}],
      "sky": {"type": "daylight"}, "atmosphere": {"ground_albedo": 0.9}}""")
    seen = arcus.render(path).image.reshape(-1, 3).mean(axis=0) * np.pi
    import arcus.daylight as daylight
    nm = np.arange(365.0, 830.0, 10.0)
    direct, diffuse = daylight.ground_irradiance(nm, 60.0, ground_albedo=0.9)  # the sky the ground lights back
    band = daylight.solar_irradiance(nm, band=10) / daylight.solar_irradiance(nm)  # the renderer's 10 nm bands
    expected = linear_srgb(nm, (direct + diffuse) * band)
    np.testing.assert_allclose(seen, expected, rtol=0.02)


def test_the_daylight_sky_is_brightest_toward_its_sun(tmp_path):
    # The sun 10° up at azimuth 90° (toward +x): looking at it through the aerosol's
    # forward peak the sky is several times brighter than looking away (the renderer's
    # panoramas run the other way round from the rainbow engine's: a mirrored sky would
    # put the glow behind the camera).
    def sky_toward(look_x):
        path = tmp_path / ("look_%+d.json" % look_x)
        path.write_text("""{"name": "look", "medium": {"type": "constant", "n": 1.0},
          "integrator": {"method": "dp45", "rtol": 1e-12, "atol": 1e-6, "length": 100},
          "camera": {"position": [0, 0, 0], "look_at": [%d, 0.18, 0], "vfov_deg": 10, "width": 8, "height": 8},
          "lights": [{"type": "daylight_sun", "elevation_deg": 10, "azimuth_deg": 90}],
          "sky": {"type": "daylight"}}""" % look_x)
        return arcus.render(path).image.mean()
    assert sky_toward(1) > 3 * sky_toward(-1)


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
    path = small_scene(tmp_path)
    from_file = arcus.render(path)
    from_dict = arcus.render(json.loads(path.read_text()), base_dir=tmp_path)
    assert (from_dict.objects == from_file.objects).all()
    assert np.array_equal(from_dict.image, from_file.image)
    assert not list(tmp_path.glob("tmp*.json"))  # the temporary scene file is gone


# A cube of half-side 1 about the origin, two triangles a face wound outward (every
# coordinate exact in single precision, as file readers hand them over).
CUBE_VERTICES = np.array([[x, y, z] for z in (-1.0, 1.0) for y in (-1.0, 1.0) for x in (-1.0, 1.0)])
CUBE_TRIANGLES = np.array([[0, 2, 3], [0, 3, 1], [4, 5, 7], [4, 7, 6], [0, 1, 5], [0, 5, 4],
                           [2, 6, 7], [2, 7, 3], [0, 4, 6], [0, 6, 2], [1, 3, 7], [1, 7, 5]])


def cube_scene(source, translate=(0, 0, -5)):
    return {"name": "cube", "medium": {"type": "constant", "n": 1.0},
            "integrator": {"method": "dp45", "rtol": 1e-12, "atol": 1e-6, "length": 100},
            "camera": {"position": [0, 0, 0], "look_at": [0, 0, -1], "vfov_deg": 40, "width": 32, "height": 24},
            "materials": {"m": {"diffuse": [0.5, 0.5, 0.5], "emission": [0.1, 0.2, 0.3]}},
            "objects": [dict(source, type="mesh", material="m", translate=list(translate))],
            "sky": {"type": "constant", "color": [0, 0, 1]}}


def test_a_mesh_from_memory_is_placed_by_the_scene(tmp_path):
    # A straight ray (n = 1) through pixel (16, 12)'s centre, d = (sx, sy, −1), meets the
    # cube's near face z = t_z + 1 at distance (−t_z − 1)·|d| (closed form); the
    # kernel's crossing ends within its tolerance (atol 1e-6 m + rtol·distance).
    half = np.tan(np.radians(20))
    d = np.array([(2 * 16.5 / 32 - 1) * half * 32 / 24, (1 - 2 * 12.5 / 24) * half, -1])
    for tz in (-5, -7):
        result = arcus.render(cube_scene({"mesh": "cube"}, (0, 0, tz)), base_dir=tmp_path,
                              meshes={"cube": (CUBE_VERTICES, CUBE_TRIANGLES)})
        assert result.objects[12, 16] == 0 and result.objects[0, 0] == -1
        expected = (-tz - 1) * np.linalg.norm(d)
        assert abs(result.distances[12, 16] - expected) < 1e-5, (tz, result.distances[12, 16], expected)


def test_determinism_a_mesh_from_memory_renders_bit_for_bit_as_its_file(tmp_path):
    off = tmp_path / "cube.off"
    off.write_text("OFF\n8 12 0\n" + "".join("%.17g %.17g %.17g\n" % tuple(v) for v in CUBE_VERTICES)
                   + "".join("3 %d %d %d\n" % tuple(t) for t in CUBE_TRIANGLES))
    from_file = arcus.render(cube_scene({"file": str(off)}), base_dir=tmp_path)
    scene_path = tmp_path / "memory.json"
    scene_path.write_text(json.dumps(cube_scene({"mesh": "cube"})))
    with arcus.Context() as ctx:
        for cube in ((CUBE_VERTICES, CUBE_TRIANGLES), (CUBE_VERTICES.tolist(), CUBE_TRIANGLES.astype(np.uint32))):
            from_memory = ctx.render(scene_path, meshes={"cube": cube})
            assert np.array_equal(from_memory.image, from_file.image)
            assert np.array_equal(from_memory.distances, from_file.distances)
            assert np.array_equal(from_memory.primitives, from_file.primitives)


def test_meshes_from_memory_that_do_not_fit_the_scene_are_refused(tmp_path):
    cube = (CUBE_VERTICES, CUBE_TRIANGLES)
    with pytest.raises(arcus.ArgumentError, match=r"\$\.objects\[0\]\.mesh: no mesh named \"cube\" was given"):
        arcus.render(cube_scene({"mesh": "cube"}), base_dir=tmp_path, meshes={"box": cube})
    with pytest.raises(arcus.ArgumentError, match=r"uses no mesh named \"spare\""):
        arcus.render(cube_scene({"mesh": "cube"}), base_dir=tmp_path, meshes={"cube": cube, "spare": cube})
    with pytest.raises(arcus.ArgumentError, match=r"meshes\['cube'\] vertices must have shape \(N, 3\)"):
        arcus.render(cube_scene({"mesh": "cube"}), base_dir=tmp_path, meshes={"cube": (CUBE_VERTICES[:, :2],
                                                                                        CUBE_TRIANGLES)})
    with pytest.raises(arcus.ArgumentError, match=r"indices\[\d+\] = 8 is not below vertex_count 8"):
        arcus.render(cube_scene({"mesh": "cube"}), base_dir=tmp_path, meshes={"cube": (CUBE_VERTICES,
                                                                                        CUBE_TRIANGLES + 1)})
    for bad in ([cube], {"cube": CUBE_VERTICES}, {"": cube}, {1: cube}):
        with pytest.raises(arcus.ArgumentError, match="meshes"):
            arcus.render(cube_scene({"mesh": "cube"}), base_dir=tmp_path, meshes=bad)


def test_the_spectral_sunset_shows_a_green_rim_several_pixels_thick():
    # The bundled telephoto sunset (1.9" a pixel), rendered as a strip of 8 columns at
    # its own scale.  Above the orange disc, rows where only the short wavelengths' image
    # of the sun remains are green: G above R and B.  Their thickness is the angle
    # between the upper edges of the green (~530 nm) and yellow (~580 nm) images: air's
    # refractivity differs by ~0.35 % between them (Ciddor), times the ~2000" of
    # refraction at the horizon, ≈ 7" ≈ 4 rows.  A renderer that traced every
    # wavelength alike, or lost the dispersion, gives 0-1 rows; we ask for 3.
    path = pathlib.Path(__file__).resolve().parents[2] / "scenes" / "sunset_spectral.json"
    scene = json.loads(path.read_text())
    scene["camera"]["width"] = 8
    image = arcus.render(scene, base_dir=path.parent).image[:, 4, :].astype(float)
    disc = np.flatnonzero(image[:, 0] > 0.5 * image[:, 0].max())
    assert disc.size > 100, "the disc is not in the frame"
    above = image[:disc.min()]
    green = np.flatnonzero((above[:, 1] > above[:, 0]) & (above[:, 1] > above[:, 2])
                           & (above[:, 1] > 0.05 * image[disc, 1].mean()))
    assert green.size >= 3, above[-8:]
    # the green band sits on the disc: contiguous, ending at its top
    assert np.all(np.diff(green) == 1) and green.max() >= disc.min() - 2, (green, disc.min())


def bundled_at(tmp_path, name, width, height, inversions=None):
    """A bundled render scene at width × height, its files' paths made absolute, with its
    inversions replaced when given ([] for the standard atmosphere)."""
    scene = json.loads((ROOT / "scenes" / (name + ".json")).read_text())
    scene["camera"]["width"], scene["camera"]["height"] = width, height
    entries = [(o, "file") for o in scene["objects"]] + [(m, "texture") for m in scene["materials"].values()]
    for entry, key in entries:
        if key in entry:
            entry[key] = str((ROOT / "scenes" / entry[key]).resolve())
    if inversions is not None:
        scene["field"]["inversions"] = inversions
    path = tmp_path / ("%s_%s.json" % (name, "own" if inversions is None else "standard"))
    path.write_text(json.dumps(scene))
    return path


def rows_hitting(objects, members):
    rows = np.flatnonzero(np.isin(objects, members).any(axis=1))
    return rows.min(), rows.max(), int(np.isin(objects, members).sum())


def test_the_inferior_mirage_mirrors_the_shuttle_only_over_the_hot_layer(tmp_path):
    # Rays that dip into the 12 K hotter layer turn up (thesis §5.4.2.1): the shuttle's
    # lower part shows again, inverted, below it.  Without the layer the same camera sees
    # the shuttle once.  Measured at 200 × 100: 6531 shuttle pixels reaching row 80
    # against 2910 reaching row 60; the bounds leave room for a coarser integrator.
    _, low_mirage, mirage = rows_hitting(arcus.render(bundled_at(tmp_path, "inferior_mirage", 200, 100)).objects, [0])
    _, low_plain, plain = rows_hitting(arcus.render(bundled_at(tmp_path, "inferior_mirage", 200, 100, [])).objects, [0])
    assert mirage > 1.6 * plain and low_mirage >= low_plain + 10


def test_the_fata_morgana_stretches_the_castle_only_through_its_inversions(tmp_path):
    # Two inversions (10–20 m, 40–60 m) stack erect and inverted images of the castle's
    # bands into a wall more than twice the castle seen through standard air, rising
    # far above its top (measured at 200 × 100: 9566 pixels against 4431, the top at
    # row 19 against 43; both run off the frame's foot).
    top_m, _, mirage = rows_hitting(arcus.render(bundled_at(tmp_path, "fata_morgana", 200, 100)).objects, [0, 1])
    top_p, _, plain = rows_hitting(arcus.render(bundled_at(tmp_path, "fata_morgana", 200, 100, [])).objects, [0, 1])
    assert mirage > 1.8 * plain and top_m <= top_p - 15


def test_the_novaya_zemlya_sun_shows_only_through_its_inversion(tmp_path):
    # The sun 1.5° below the horizon: the duct bends rays ~1.9° and reaches it (a
    # flattened strip: 116 pixels at 100 × 100, a few rows tall); standard refraction
    # bends them 0.6° and shows no sun at all.
    objects = arcus.render(bundled_at(tmp_path, "novaya_zemlya", 100, 100)).objects
    top, low, sun = rows_hitting(objects, [0])
    assert sun > 30 and low - top <= 6
    assert not np.isin(arcus.render(bundled_at(tmp_path, "novaya_zemlya", 100, 100, [])).objects, [0]).any()
