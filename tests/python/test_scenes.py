"""Scenes read by the library (Context.load_scene): attributes, physics of the bundled
scenes against closed forms and invariants, wavelengths, progress, errors, lifetime."""

import gc
import json
from pathlib import Path

import numpy as np
import pytest

import arcus
from closed_forms import catenary, ciddor

SCENES = Path(__file__).resolve().parents[2] / "scenes"


def write_scene(directory, document, name="scene.json"):
    path = directory / name
    path.write_text(document if isinstance(document, str) else json.dumps(document))
    return path


def linear_scene(**extra):
    """n = 1 + 0.1 y, three explicit rays."""
    scene = {
        "name": "linear",
        "medium": {"type": "linear", "n0": 1.0, "gradient": [0, 0.1, 0]},
        "rays": {"origins": [[0, 0, 0], [0, 0.5, 0], [1, 0, 0]], "directions": [[1, 0, 0], [1, 0.2, 0], [1, -0.1, 0]]},
        "integrator": {"method": "dp45", "rtol": 1e-10, "atol": 1e-12, "length": 10},
    }
    scene.update(extra)
    return scene


@pytest.fixture(scope="module")
def mirage(ctx):
    scene = ctx.load_scene(SCENES / "mirage.json")
    return scene, scene.advance()


# ---- what a scene holds ------------------------------------------------------------------


def test_scene_attributes_are_the_files(mirage):
    scene, _ = mirage
    source = json.loads((SCENES / "mirage.json").read_text())
    assert isinstance(scene, arcus.Scene) and "mirage" in repr(scene)
    assert (scene.name, scene.engine) == ("mirage", "curved")
    assert scene.description == source["description"]
    assert json.loads(scene.document) == source
    # The fan: from (0, 1.6, 0), +x turned about +z by -0.6 .. 0.1 degrees in 64 rays.
    assert len(scene) == 64 and scene.origins.shape == (64, 3) and scene.directions.shape == (64, 3)
    np.testing.assert_array_equal(scene.origins, np.tile([0.0, 1.6, 0.0], (64, 1)))
    angles = np.radians(np.linspace(-0.6, 0.1, 64))
    np.testing.assert_allclose(scene.directions, np.stack([np.cos(angles), np.sin(angles), np.zeros(64)], axis=1),
                               rtol=0, atol=1e-15)
    assert scene.wavelengths is None
    assert scene.params == dict(method="dp45", precision="double", length=2000.0, step=0.0, rtol=1e-10, atol=1e-12,
                                min_step=1e-12, max_step=5.0, max_rejections=64, max_steps=10_000_000,
                                box=((-1.0, 0.0, -1.0), (2001.0, 100.0, 1.0)), record_path=True, path_capacity=0)
    # Snapshots: the library keeps its own rays and settings.
    with pytest.raises(ValueError):
        scene.origins[0, 0] = 1.0
    scene.params["record_path"] = False
    assert scene.params["record_path"] is True


def test_scene_field_is_the_scenes_medium(ctx, mirage):
    scene, _ = mirage
    assert isinstance(scene.field, arcus.SceneField) and isinstance(scene.field, arcus.fields.Field)
    assert ctx.field_kind(scene.field) == "ATMOSPHERE"
    # The medium is air at 550 nm with a hot ground layer (+12 K, fading out at 2 m).  At
    # sea level it thins the air by 288.15 / 300.15.  Above 2 m the standard temperatures
    # hold, the pressure a little higher (the layer's column is lighter, by ~ 2 m / 8.4 km
    # * 6 K / 294 K = 5e-6).
    n, _ = scene.field.evaluate(ctx, [[0.0, 0.0, 0.0], [0.0, 50.0, 0.0]])
    standard, _ = arcus.fields.StandardAtmosphere().evaluate(ctx, [[0.0, 0.0, 0.0], [0.0, 50.0, 0.0]])
    assert (n[0] - 1) / (standard[0] - 1) == pytest.approx(288.15 / 300.15, rel=2e-3)
    assert (n[1] - 1) / (standard[1] - 1) == pytest.approx(1 + 5e-6, rel=2e-6)


# ---- physics of the bundled scenes ---------------------------------------------------------


def test_mirage_scene_keeps_snells_invariant_and_grounds_the_rays_it_predicts(ctx, mirage):
    """In layered air n(y) dx/ds is conserved (n does not vary in x).

    A ray reaches the ground (y = 0, the box's face: LEFT_BOX) iff n(0) exceeds that
    invariant; otherwise it turns above the ground and climbs (the mirage).
    """
    scene, result = mirage
    assert "CURVED_RECORD_PATH" in result.features and len(result.paths) == 64
    unit = scene.directions / np.linalg.norm(scene.directions, axis=1, keepdims=True)
    n_start, _ = scene.field.evaluate(ctx, scene.origins)
    n_end, _ = scene.field.evaluate(ctx, result.positions)
    invariant = n_start * unit[:, 0]
    np.testing.assert_allclose(n_end * result.directions[:, 0], invariant, rtol=0, atol=1e-11)
    n_ground = scene.field.evaluate(ctx, [0.0, 0.0, 0.0])[0][0]
    grounded = invariant < n_ground
    assert 10 < grounded.sum() < 54  # both kinds of ray are in the fan (33 reach the ground)
    np.testing.assert_array_equal(result.status, np.where(grounded, arcus.RAY_LEFT_BOX, arcus.RAY_DONE))
    np.testing.assert_allclose(result.positions[grounded, 1], 0.0, rtol=0, atol=1e-9)
    turned = ~grounded & (unit[:, 1] < 0)  # dipped, turned, climbed
    assert turned.sum() > 10
    assert np.all(result.positions[turned, 1] > 0) and np.all(result.directions[turned, 1] > 0)


def test_fisheye_scene_rays_are_circles_through_the_image_point(ctx):
    """Maxwell's fish-eye n = 2 / (1 + r^2): every ray is a circle, and the rays from
    P = (-0.5, 0, 0) all pass through its image P' = -P / |P|^2 = (2, 0, 0)."""
    scene = ctx.load_scene(SCENES / "fisheye.json")
    result = scene.advance()
    assert np.all(result.status == arcus.RAY_DONE)
    p, image = scene.origins[0], np.array([2.0, 0.0, 0.0])
    unit = scene.directions / np.linalg.norm(scene.directions, axis=1, keepdims=True)
    normal = np.stack([-unit[:, 1], unit[:, 0], np.zeros(len(unit))], axis=1)  # in the plane
    # The circle tangent to the start direction at P through P': centre P + rho * normal,
    # |P + rho * normal - P'| = rho.
    across = (p - image) @ normal.T
    curved = np.abs(across) > 1e-9  # the ray along the axis is a straight line (rho infinite)
    assert curved.sum() == len(scene) - 1
    rho = -np.sum((p - image) ** 2) / (2 * across[curved])
    centre = p + rho[:, None] * normal[curved]
    radial = result.positions[curved] - centre
    np.testing.assert_allclose(np.linalg.norm(radial, axis=1), np.abs(rho), rtol=0, atol=1e-8)
    np.testing.assert_allclose(np.sum(radial * result.directions[curved], axis=1), 0.0, rtol=0, atol=1e-8)
    straight = ~curved
    np.testing.assert_allclose(result.positions[straight, 1:], 0.0, rtol=0, atol=1e-12)


def test_luneburg_scene_point_on_the_surface_leaves_as_a_parallel_beam(ctx):
    scene = ctx.load_scene(SCENES / "luneburg.json")
    result = scene.advance()
    assert np.all(result.status == arcus.RAY_DONE)
    assert np.all(np.linalg.norm(result.positions, axis=1) > 1.0)  # all out of the lens
    np.testing.assert_allclose(result.directions[:, 1:], 0.0, rtol=0, atol=1e-8)
    assert np.ptp(scene.directions[:, 1]) > 1.5  # the fan really was wide (+-75 degrees)


def test_scene_of_a_linear_medium_follows_the_catenary(ctx, tmp_path):
    scene = ctx.load_scene(write_scene(tmp_path, linear_scene()))
    result = scene.advance()
    assert {"CURVED_DP45", "CURVED_FIELD_LINEAR"} <= result.features and result.paths is None
    end, direction = catenary(1.0, 0.1, scene.origins, scene.directions, 10.0)
    np.testing.assert_allclose(result.positions, end, rtol=0, atol=1e-7)
    np.testing.assert_allclose(result.directions, direction, rtol=0, atol=1e-7)


def test_grid_scene_reads_its_file_relative_to_the_scene(ctx, tmp_path):
    """n = 1.2 + 0.01 x + 0.02 y z is trilinear: the grid reproduces it exactly."""
    shape = (3, 4, 5)  # (nz, ny, nx)
    k, j, i = np.meshgrid(*(np.arange(s) for s in shape), indexing="ij")
    x, y, z = -1.0 + 0.5 * i, 0.25 * j, 2.0 + k
    (tmp_path / "data").mkdir()
    (1.2 + 0.01 * x + 0.02 * y * z).astype("<f8").tofile(tmp_path / "data" / "n.raw")
    document = linear_scene(medium={"type": "grid", "file": "data/n.raw", "dtype": "float64", "dims": [5, 4, 3],
                                    "origin": [-1, 0, 2], "spacing": [0.5, 0.25, 1]})
    scene = ctx.load_scene(write_scene(tmp_path, document))
    assert ctx.field_kind(scene.field) == "GRID"
    points = np.array([[0.3, 0.6, 2.5], [-0.9, 0.1, 3.9], [0.7, 0.7, 2.1]])
    n, gradient = scene.field.evaluate(ctx, points)
    np.testing.assert_allclose(n, 1.2 + 0.01 * points[:, 0] + 0.02 * points[:, 1] * points[:, 2], rtol=0, atol=1e-14)
    np.testing.assert_allclose(gradient[:, 0], 0.01, rtol=0, atol=1e-13)


def test_determinism_scene_advance_and_context_advance_with_its_params(ctx, mirage):
    """Not validation: arcus_curved_advance_scene and arcus_curved_advance with the scene's rays, field
    and params read back agree bit for bit, so ``params`` misses no setting."""
    scene, result = mirage
    again = ctx.advance(scene.field, scene.origins, scene.directions, wavelengths=scene.wavelengths, **scene.params)
    for name in ("positions", "directions", "steps", "status", "lengths", "failures", "path_offsets", "path_points"):
        np.testing.assert_array_equal(getattr(again, name), getattr(result, name))
    assert again.features == result.features


# ---- wavelengths ----------------------------------------------------------------------------


def test_scene_wavelengths_reach_the_rays(ctx, tmp_path):
    """Stars at 30 degrees altitude in blue and red: the refraction ratio is Ciddor's."""
    altitude = np.radians(30.0)
    direction = [np.cos(altitude), np.sin(altitude), 0.0]
    document = linear_scene(
        medium={"type": "atmosphere", "spherical": True},
        rays={"origins": [[0, arcus.EARTH_RADIUS, 0]] * 2, "directions": [direction] * 2, "wavelengths": [400, 700]},
        integrator={"method": "dp45", "rtol": 1e-11, "atol": 1e-14, "length": 3.0e6})
    scene = ctx.load_scene(write_scene(tmp_path, document))
    np.testing.assert_array_equal(scene.wavelengths, [400.0, 700.0])
    result = scene.advance()
    assert "CURVED_DISPERSION" in result.features
    unit = np.array(direction) / np.linalg.norm(direction)
    bending = np.arccos(np.clip(result.directions @ unit, -1.0, 1.0))
    assert bending[0] / bending[1] == pytest.approx(ciddor(400.0) / ciddor(700.0), rel=2e-5)


def test_scene_fan_wavelengths_are_wavelength_major(ctx, tmp_path):
    fan = {"direction": [1, 0, 0], "plane_normal": [0, 0, 1], "min_deg": -1, "max_deg": 1, "count": 3}
    document = linear_scene(rays={"origin": [0, 10, 0], "fan": fan, "wavelengths": [450, 650]})
    scene = ctx.load_scene(write_scene(tmp_path, document))
    np.testing.assert_array_equal(scene.wavelengths, [450.0] * 3 + [650.0] * 3)
    np.testing.assert_array_equal(scene.directions[:3], scene.directions[3:])
    one = ctx.load_scene(write_scene(tmp_path, linear_scene(rays={"origin": [0, 10, 0], "fan": fan,
                                                                  "wavelengths": 500}), "one.json"))
    np.testing.assert_array_equal(one.wavelengths, [500.0] * 3)


# ---- progress ----------------------------------------------------------------------------


def test_scene_advance_progress_cancels_and_reraises(ctx, tmp_path):
    endless = linear_scene(integrator={"method": "rk4", "step": 1e-5, "length": 1e4, "max_steps": 2000000000})
    scene = ctx.load_scene(write_scene(tmp_path, endless))
    seen = []
    with pytest.raises(arcus.Error) as caught:
        scene.advance(progress=lambda fraction: seen.append(fraction) or True)
    assert caught.value.status == "ARCUS_ERROR_CANCELLED" and len(seen) == 1
    result = caught.value.result
    assert np.all(result.status == arcus.RAY_CANCELLED) and np.all(result.lengths > 0)
    for i in range(len(scene)):
        end, _ = catenary(1.0, 0.1, scene.origins[i:i + 1], scene.directions[i:i + 1], result.lengths[i])
        np.testing.assert_allclose(result.positions[i], end[0], rtol=0, atol=1e-9)

    def boom(fraction):
        raise KeyError("from progress")

    with pytest.raises(KeyError, match="from progress"):
        scene.advance(progress=boom)
    with pytest.raises(arcus.ArgumentError, match="progress callback must not call"):
        scene.advance(progress=lambda fraction: scene.advance())
    with pytest.raises(arcus.ArgumentError, match="progress must be a callable"):
        scene.advance(progress="no")


# ---- errors ---------------------------------------------------------------------------------


def test_missing_scene_file_is_an_io_error(ctx, tmp_path):
    with pytest.raises(arcus.Error) as caught:
        ctx.load_scene(tmp_path / "absent.json")
    assert caught.value.status == "ARCUS_ERROR_IO" and "absent.json" in caught.value.message
    with pytest.raises(arcus.Error) as caught:
        ctx.load_scene(tmp_path)  # a directory
    assert caught.value.status == "ARCUS_ERROR_IO"


@pytest.mark.parametrize(
    "document, where",
    [('{"name": "x"', "not valid JSON"),
     (linear_scene(medium={"type": "linear", "n0": 1, "gradient": [0, 0.1, 0], "bogus": 1}), "$.medium.bogus"),
     (linear_scene(rays={"origins": [[0, 0, 0]], "directions": [[0, 0, 0]]}), "$.rays.directions[0]"),
     (json.dumps(linear_scene())[:-1] + ', "name": "again"}', "$.name")],
    ids=["json", "unknown-key", "zero-direction", "repeated-key"],
)
def test_invalid_scene_names_the_file_and_key(ctx, tmp_path, document, where):
    path = write_scene(tmp_path, document)
    with pytest.raises(arcus.ArgumentError) as caught:
        ctx.load_scene(path)
    assert str(path) in caught.value.message and where in caught.value.message


def test_invalid_integrator_settings_are_refused_when_the_scene_is_read(ctx, tmp_path):
    """The library checks a scene's integrator values as it reads the file, naming it."""
    path = write_scene(tmp_path, linear_scene(integrator={"length": -1}))
    with pytest.raises(arcus.ArgumentError, match=r"\$\.integrator.*length") as caught:
        ctx.load_scene(path)
    assert str(path) in str(caught.value)


@pytest.mark.parametrize("path", ["scenes/mirage.json\0ignored", b"scenes/mirage.json\0", 42, None, ["a.json"]],
                         ids=["nul-str", "nul-bytes", "int", "none", "list"])
def test_bad_scene_paths_are_refused_before_the_library(ctx, monkeypatch, path):
    """A NUL would end the C string early: the library would read another file."""

    def never(*args):
        raise AssertionError("arcus_scene_load was called")

    monkeypatch.setattr(arcus._lib.lib, "arcus_scene_load", never)
    with pytest.raises(arcus.ArgumentError, match="path"):
        ctx.load_scene(path)


def test_scene_path_may_be_str_bytes_or_pathlike(ctx):
    path = SCENES / "luneburg.json"
    for form in (path, str(path), bytes(path)):
        assert ctx.load_scene(form).name == "luneburg"


def test_scene_field_refuses_another_context(ctx, mirage):
    scene, _ = mirage
    with arcus.Context() as other:
        with pytest.raises(arcus.ArgumentError, match="belongs to the arcus.Context that loaded the scene"):
            other.advance(scene.field, [0, 1, 0], [1, 0, 0])
        with pytest.raises(arcus.ArgumentError, match="loaded the scene"):
            scene.field.evaluate(other, [0.0, 1.0, 0.0])
        # Its own scenes' fields are fine there.
        mine = other.load_scene(SCENES / "mirage.json")
        assert other.field_kind(mine.field) == "ATMOSPHERE"


# ---- lifetime ---------------------------------------------------------------------------------


def test_scene_handles_are_released_with_the_scene_and_the_context(tmp_path):
    context = arcus.Context()
    scene = context.load_scene(write_scene(tmp_path, linear_scene()))
    field = scene.field
    assert len(context._state.objects) == 2  # the scene and its field
    del scene
    gc.collect()
    assert len(context._state.objects) == 1  # the field lives on by itself
    assert context.advance(field, [0, 0, 0], [1, 0, 0], length=1.0).status[0] == arcus.RAY_DONE
    again = context.load_scene(write_scene(tmp_path, linear_scene()))
    finalizers = [handle._finalizer for handle in context._state.objects]
    context.close()
    assert not any(f.alive for f in finalizers)
    with pytest.raises(arcus.ArgumentError, match="closed"):
        again.advance()
    with pytest.raises(arcus.ArgumentError, match="closed"):
        field.evaluate(context, [0.0, 0.0, 0.0])


def test_scene_field_is_not_copied_into_the_field_cache(ctx, tmp_path):
    """A scene's field is its one library object, used as it is."""
    scene = ctx.load_scene(write_scene(tmp_path, linear_scene()))
    before = len(ctx._state.fields)
    assert ctx.advance(scene.field, [0, 0, 0], [1, 0, 0]).status[0] == arcus.RAY_DONE
    n, gradient = scene.field.evaluate(ctx, [0.0, 1.0, 0.0])
    assert len(ctx._state.fields) == before
    assert n[0] == pytest.approx(1.1, abs=1e-15) and list(gradient[0]) == [0.0, 0.1, 0.0]
