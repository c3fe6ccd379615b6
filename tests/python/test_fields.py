"""Fields through arcus_field_evaluate against their formulas (arcus.h, field kinds)."""

import numpy as np
import pytest

import arcus
from arcus.fields import (Constant, FishEye, Grid, GridFile, Inversion, Linear, LinearN2, Luneburg,
                          StandardAtmosphere)
from closed_forms import ciddor

RNG = np.random.default_rng(7)
POINTS = RNG.uniform(-1.5, 1.5, size=(64, 3))

# Analytic fields evaluate in double precision with a handful of operations, so they
# agree with numpy's evaluation of the same formula to a few ulps.
TIGHT = dict(rtol=1e-14, atol=1e-14)


def test_arcus_media_is_the_deprecated_name_of_arcus_fields():
    import importlib
    import sys
    sys.modules.pop("arcus.media", None)  # so that the import runs (and warns) here
    with pytest.warns(DeprecationWarning, match="arcus.fields"):
        media = importlib.import_module("arcus.media")
    assert media.Linear is Linear and arcus.media.StandardAtmosphere is StandardAtmosphere


def test_constant(ctx):
    n, gradient = Constant(1.33).evaluate(ctx, POINTS)
    assert n.shape == (64,) and gradient.shape == (64, 3)
    assert np.all(n == 1.33) and np.all(gradient == 0.0)


def test_linear(ctx):
    g = np.array([0.1, -0.2, 0.05])
    n, gradient = Linear(1.5, g).evaluate(ctx, POINTS)
    np.testing.assert_allclose(n, 1.5 + POINTS @ g, **TIGHT)
    np.testing.assert_allclose(gradient, np.broadcast_to(g, (64, 3)), **TIGHT)


def test_linear_n2(ctx):
    k = np.array([0.3, 0.1, -0.2])
    n, gradient = LinearN2(2.0, k).evaluate(ctx, POINTS)
    expected = np.sqrt(2.0 + POINTS @ k)
    np.testing.assert_allclose(n, expected, **TIGHT)
    np.testing.assert_allclose(gradient, k / (2 * expected[:, None]), **TIGHT)


def test_luneburg_inside_and_outside(ctx):
    center, radius = np.array([0.2, -0.1, 0.3]), 1.0
    n, gradient = Luneburg(center, radius).evaluate(ctx, POINTS)
    rel = POINTS - center
    r2 = np.sum(rel**2, axis=1) / radius**2
    inside = r2 < 1
    assert 0 < inside.sum() < len(POINTS)  # the sample covers both regions
    np.testing.assert_allclose(n[inside], np.sqrt(2 - r2[inside]), **TIGHT)
    np.testing.assert_allclose(gradient[inside], -rel[inside] / (radius**2 * n[inside, None]), **TIGHT)
    assert np.all(n[~inside] == 1.0) and np.all(gradient[~inside] == 0.0)


def test_fisheye(ctx):
    center, radius, n0 = np.array([0.0, 0.5, 0.0]), 0.8, 2.0
    n, gradient = FishEye(center, radius, n0).evaluate(ctx, POINTS)
    rel = POINTS - center
    q = 1 + np.sum(rel**2, axis=1) / radius**2
    np.testing.assert_allclose(n, n0 / q, **TIGHT)
    np.testing.assert_allclose(gradient, -2 * n0 * rel / (radius**2 * q[:, None] ** 2), **TIGHT)


def test_single_point_gives_batch_of_one(ctx):
    n, gradient = Linear(1.0, (0, 1, 0)).evaluate(ctx, (0.0, 2.0, 0.0))
    assert n.shape == (1,) and gradient.shape == (1, 3) and n[0] == 3.0


@pytest.mark.parametrize("positions", [np.zeros((4, 2)), np.zeros(4), np.zeros((2, 3, 3)), "abc"])
def test_evaluate_rejects_bad_shapes(ctx, positions):
    with pytest.raises(arcus.ArgumentError, match="positions"):
        Constant(1.0).evaluate(ctx, positions)


def test_field_kinds(ctx):
    fields = {
        "CONSTANT": Constant(1.0),
        "LINEAR": Linear(1.0, (0, 1, 0)),
        "LINEAR_N2": LinearN2(1.0, (0, 1, 0)),
        "LUNEBURG": Luneburg((0, 0, 0), 1.0),
        "FISHEYE": FishEye((0, 0, 0), 1.0, 2.0),
        "ATMOSPHERE": StandardAtmosphere(),
        "GRID": Grid(np.ones((2, 2, 2)), (0, 0, 0), (1, 1, 1)),
    }
    assert {kind: ctx.field_kind(f) for kind, f in fields.items()} == {k: k for k in fields}


# ---- grids ------------------------------------------------------------------------------

ORIGIN = np.array([-1.0, 0.5, 2.0])
SPACING = np.array([0.5, 0.25, 1.0])
SHAPE = (4, 5, 6)  # (nz, ny, nx): deliberately all different, to catch swapped axes


def trilinear_function(p):
    """A function trilinear interpolation reproduces exactly, and different in every axis."""
    x, y, z = p[..., 0], p[..., 1], p[..., 2]
    return 1.2 + 0.01 * x + 0.02 * y * z + 0.003 * x * y * z


def trilinear_gradient(p):
    x, y, z = p[..., 0], p[..., 1], p[..., 2]
    return np.stack([0.01 + 0.003 * y * z, 0.02 * z + 0.003 * x * z, 0.02 * y + 0.003 * x * y], axis=-1)


def grid_values():
    k, j, i = np.meshgrid(*(np.arange(s) for s in SHAPE), indexing="ij")
    nodes = ORIGIN + np.stack([i, j, k], axis=-1) * SPACING  # values[k, j, i] at origin + (i, j, k) spacing
    return trilinear_function(nodes)


def grid_interior(count):
    upper = ORIGIN + (np.array(SHAPE[::-1]) - 1) * SPACING
    return RNG.uniform(ORIGIN, upper, size=(count, 3))


def test_grid_reproduces_trilinear_function(ctx):
    grid = Grid(grid_values(), ORIGIN, SPACING)
    assert grid.dims == (6, 5, 4)
    points = grid_interior(200)
    n, gradient = grid.evaluate(ctx, points)
    np.testing.assert_allclose(n, trilinear_function(points), rtol=0, atol=1e-14)
    # Within a cell the gradient of the interpolant is that of the trilinear function.
    np.testing.assert_allclose(gradient, trilinear_gradient(points), rtol=0, atol=1e-12)


def test_grid_clamps_outside(ctx):
    grid = Grid(grid_values(), ORIGIN, SPACING)
    upper = ORIGIN + (np.array(SHAPE[::-1]) - 1) * SPACING
    inside = np.array([[0.1, 0.9, 3.3]])
    outside = inside.copy()
    outside[0, 0] = upper[0] + 3.0  # beyond the +x face
    face = inside.copy()
    face[0, 0] = upper[0]
    n_out, g_out = grid.evaluate(ctx, outside)
    n_face, g_face = grid.evaluate(ctx, face)
    assert n_out[0] == pytest.approx(n_face[0], abs=1e-15)
    assert g_out[0, 0] == 0.0
    np.testing.assert_allclose(g_out[0, 1:], trilinear_gradient(face)[0, 1:], atol=1e-12)


def test_grid_values_are_a_frozen_copy():
    values = grid_values()
    grid = Grid(values, ORIGIN, SPACING)
    values[0, 0, 0] = 99.0
    assert grid.values[0, 0, 0] != 99.0
    with pytest.raises(ValueError):
        grid.values[0, 0, 0] = 1.0


@pytest.mark.parametrize("dtype", ["float32", "float64"])
def test_grid_from_file_matches_in_memory_grid(ctx, tmp_path, dtype):
    values = grid_values()
    stored = values.astype("<f4" if dtype == "float32" else "<f8")
    path = tmp_path / "grid.raw"
    stored.tofile(path)
    from_file = Grid.from_file(path, values.shape, ORIGIN, SPACING, dtype=dtype)
    assert isinstance(from_file, GridFile)
    points = grid_interior(50)
    n_file, g_file = from_file.evaluate(ctx, points)
    n_mem, g_mem = Grid(stored.astype(np.float64), ORIGIN, SPACING).evaluate(ctx, points)
    np.testing.assert_array_equal(n_file, n_mem)
    np.testing.assert_array_equal(g_file, g_mem)
    # and both are the function sampled, to the file's rounding (n ~ 1.2: float32 2^-24).
    rounding = 1.2 * 2.0**-24 if dtype == "float32" else 1e-14
    np.testing.assert_allclose(n_file, trilinear_function(points), rtol=0, atol=2 * rounding)


def test_grid_from_missing_file_is_an_io_error(ctx, tmp_path):
    field = Grid.from_file(tmp_path / "absent.raw", (2, 2, 2), (0, 0, 0), (1, 1, 1))
    with pytest.raises(arcus.Error) as caught:
        field.evaluate(ctx, [0.0, 0.0, 0.0])
    assert caught.value.status == "ARCUS_ERROR_IO"
    assert "absent.raw" in caught.value.message


def test_grid_from_short_file_fails(ctx, tmp_path):
    path = tmp_path / "short.raw"
    np.ones(7, dtype="<f4").tofile(path)  # 2*2*2 = 8 values expected
    with pytest.raises(arcus.Error) as caught:
        Grid.from_file(path, (2, 2, 2), (0, 0, 0), (1, 1, 1)).evaluate(ctx, [0.0, 0.0, 0.0])
    assert caught.value.message


def test_grid_description_errors():
    with pytest.raises(arcus.ArgumentError, match="3D"):
        Grid(np.ones((3, 3)), (0, 0, 0), (1, 1, 1))
    with pytest.raises(arcus.ArgumentError, match="spacing"):
        Grid(np.ones((2, 2, 2)), (0, 0, 0), (1, 1))
    with pytest.raises(arcus.ArgumentError, match="dtype"):
        Grid.from_file("x.raw", (2, 2, 2), (0, 0, 0), (1, 1, 1), dtype="int16")
    with pytest.raises(arcus.ArgumentError, match="shape"):
        Grid.from_file("x.raw", (2, 0, 2), (0, 0, 0), (1, 1, 1))


# ---- invalid field parameters: the library checks them when it creates the field ---------

@pytest.mark.parametrize(
    "field, argument",
    [
        (Luneburg((0, 0, 0), 0.0), "radius"),
        (Luneburg((0, 0, 0), -1.0), "radius"),
        (FishEye((0, 0, 0), 0.0, 1.0), "radius"),
        (Grid(np.where(np.arange(8).reshape(2, 2, 2) == 5, np.nan, 1.0), (0, 0, 0), (1, 1, 1)), "value"),
        (Grid(np.ones((2, 2, 2)), (0, 0, 0), (1, 0, 1)), "spacing"),
        (Constant(float("nan")), "n"),
        (StandardAtmosphere(wavelength=100.0), "wavelength"),
    ],
    ids=["luneburg-zero", "luneburg-negative", "fisheye-zero", "grid-nan", "grid-spacing", "constant-nan",
         "atmosphere-wavelength"],
)
def test_invalid_field_parameters_raise_with_message(ctx, field, argument):
    with pytest.raises(arcus.ArgumentError) as caught:
        field.evaluate(ctx, [0.0, 0.0, 0.0])
    assert caught.value.status == "ARCUS_ERROR_INVALID_ARGUMENT"
    assert argument in caught.value.message.lower()
    assert field not in ctx._state.fields  # a failed creation is not cached


# ---- atmosphere ---------------------------------------------------------------------------


def test_flat_atmosphere_sea_level_and_profile(ctx):
    heights = np.array([0.0, 10.0, 100.0, 1000.0, 5000.0, 11000.0])
    points = np.stack([np.zeros(6), heights, np.zeros(6)], axis=1)
    n, gradient = StandardAtmosphere().evaluate(ctx, points)
    # Ciddor (1996) standard dry air at 550 nm, 288.15 K, 101325 Pa:
    # (n - 1) 1e8 = 5792105 / (238.0185 - s2) + 167917 / (57.362 - s2), s2 = (1/0.55)^2
    # = 27784; 0.1 % covers the CO2 and compressibility details an implementation may drop.
    s2 = (1 / 0.55) ** 2
    ciddor = (5792105 / (238.0185 - s2) + 167917 / (57.362 - s2)) * 1e-8
    assert n[0] - 1 == pytest.approx(ciddor, rel=1e-3)
    assert np.all(np.diff(n) < 0)  # denser air below
    assert np.all(gradient[:, 1] < 0) and np.all(gradient[:, [0, 2]] == 0)
    # Refractivity falls with the density scale height, ~8.4 km near the ground; the
    # lapse rate lengthens it to ~ (n-1) / |dn/dy| ≈ 10 km.
    scale_height = (n[0] - 1) / -gradient[0, 1]
    assert 8e3 < scale_height < 12e3


def test_shorter_wavelength_refracts_more_as_ciddor_says(ctx):
    blue, _ = StandardAtmosphere(wavelength=450.0).evaluate(ctx, [0.0, 1000.0, 0.0])
    red, _ = StandardAtmosphere(wavelength=650.0).evaluate(ctx, [0.0, 1000.0, 0.0])
    assert blue[0] > red[0]
    # Density, CO2 and compressibility scale n - 1 alike at every wavelength: the ratio
    # is that of Ciddor's dispersion formula alone (closed_forms.ciddor).
    assert (blue[0] - 1) / (red[0] - 1) == pytest.approx(ciddor(450.0) / ciddor(650.0), rel=1e-9)


def test_inversion_layer(ctx):
    standard = StandardAtmosphere()
    inverted = StandardAtmosphere(inversions=[Inversion(base=10.0, top=50.0, delta_t=-10.0)])
    points = np.array([[0.0, 5.0, 0.0], [0.0, 30.0, 0.0]])
    n_std, g_std = standard.evaluate(ctx, points)
    n_inv, g_inv = inverted.evaluate(ctx, points)
    # 10 K colder air under the base is denser: n - 1 grows by about 10/288.
    assert (n_inv[0] - 1) / (n_std[0] - 1) == pytest.approx(288.15 / 278.15, rel=2e-3)
    # Between base and top the air warms by 10 K over 40 m: n falls much faster.
    assert g_inv[1, 1] < 3 * g_std[1, 1] < 0


def test_spherical_atmosphere_gradient_is_radial(ctx):
    direction = np.array([0.3, 0.9, -0.2])
    direction /= np.linalg.norm(direction)
    points = np.outer(arcus.EARTH_RADIUS + np.array([0.0, 100.0, 2000.0]), direction)
    n, gradient = StandardAtmosphere(spherical=True).evaluate(ctx, points)
    flat_n, flat_gradient = StandardAtmosphere().evaluate(ctx, [[0.0, h, 0.0] for h in (0.0, 100.0, 2000.0)])
    np.testing.assert_allclose(n, flat_n, rtol=0, atol=1e-12)
    np.testing.assert_allclose(gradient, np.outer(flat_gradient[:, 1], direction), rtol=1e-9, atol=0)


def test_inversion_tuples_are_normalised():
    atmosphere = StandardAtmosphere(inversions=[(0, 20, 5)])
    assert atmosphere.inversions == (Inversion(0.0, 20.0, 5.0),)
    with pytest.raises(arcus.ArgumentError, match="inversions"):
        StandardAtmosphere(inversions=[(0, 20)])
