"""Bad input raises arcus.Error with a message; partial results are never lost."""

import numpy as np
import pytest

import arcus
from arcus.fields import Constant, Grid, Linear, StandardAtmosphere
from closed_forms import fan

LINEAR = Linear(1.0, (0.0, 0.1, 0.0))
JOB = dict(method="dp45", rtol=1e-9, atol=1e-12, length=10.0)


@pytest.mark.parametrize(
    "component, value",
    [("directions", [np.nan, 1.0, 0.0]), ("directions", [0.0, 0.0, 0.0]), ("directions", [1.0, np.inf, 0.0]),
     ("origins", [0.0, np.nan, 0.0]), ("origins", [-np.inf, 0.0, 0.0])],
    ids=["nan-direction", "zero-direction", "inf-direction", "nan-origin", "inf-origin"],
)
def test_invalid_ray_is_flagged_and_the_others_are_unharmed(ctx, component, value):
    origins, directions = fan(8)
    clean = ctx.advance(LINEAR, origins, directions, **JOB)
    bad = 3
    rays = {"origins": np.insert(origins, bad, [0.0, 0.3, 0.0], axis=0),
            "directions": np.insert(directions, bad, [1.0, 0.0, 0.0], axis=0)}
    rays[component][bad] = value
    with pytest.raises(arcus.Error) as caught:
        ctx.advance(LINEAR, rays["origins"], rays["directions"], **JOB)
    error = caught.value
    assert error.status == "ARCUS_ERROR_INVALID_RAYS" and error.message
    result = error.result
    assert isinstance(result, arcus.AdvanceResult) and len(result) == 9
    assert result.status[bad] == arcus.RAY_INVALID_INPUT
    others = np.arange(9) != bad
    # The same rays give the same numbers, bit for bit, with or without a bad neighbour.
    np.testing.assert_array_equal(result.positions[others], clean.positions)
    np.testing.assert_array_equal(result.directions[others], clean.directions)
    np.testing.assert_array_equal(result.steps[others], clean.steps)
    np.testing.assert_array_equal(result.status[others], clean.status)
    np.testing.assert_array_equal(result.lengths[others], clean.lengths)


@pytest.mark.parametrize(
    "options, argument",
    [(dict(rtol=0.0), "rtol"), (dict(rtol=-1e-9), "rtol"), (dict(atol=0.0), "atol"), (dict(length=0.0), "length"),
     (dict(length=-1.0), "length"), (dict(length=np.nan), "length"), (dict(method="rk4", step=0.0), "step"),
     (dict(box=((0, 0, 0), (-1, 1, 1))), "box")],
    ids=["rtol-zero", "rtol-negative", "atol-zero", "length-zero", "length-negative", "length-nan", "rk4-step-zero",
         "box-inverted"],
)
def test_invalid_parameters_are_rejected_by_the_library(ctx, options, argument):
    origins, directions = fan(2)
    with pytest.raises(arcus.ArgumentError) as caught:
        ctx.advance(LINEAR, origins, directions, **options)
    assert caught.value.status == "ARCUS_ERROR_INVALID_ARGUMENT"
    assert caught.value.result is None
    assert argument in caught.value.message.lower()


@pytest.mark.parametrize(
    "origins, directions, message",
    [(np.zeros((4, 3)), np.ones((5, 3)), "same number of rays"),
     (np.zeros((4, 2)), np.ones((4, 2)), "origins must have shape"),
     (np.zeros((4, 3)), np.ones((4, 3, 1)), "directions must have shape"),
     (np.zeros((4, 3)), np.ones(3), "same number of rays"),
     ([[0, 0, "x"]], [[1, 0, 0]], "origins must be an array")],
)
def test_mismatched_shapes_are_caught_before_the_library(ctx, monkeypatch, origins, directions, message):
    def never(*args):
        raise AssertionError("arcus_curved_advance was called")

    monkeypatch.setattr(arcus._lib.lib, "arcus_curved_advance", never)
    with pytest.raises(arcus.ArgumentError, match=message) as caught:
        ctx.advance(LINEAR, origins, directions)
    assert isinstance(caught.value, ValueError)


@pytest.mark.parametrize(
    "options, message",
    [(dict(method="rk45"), "method must be one of"), (dict(precision="half"), "precision must be one of"),
     (dict(max_steps=-1), "max_steps"), (dict(path_capacity=2**32), "path_capacity"),
     (dict(max_rejections=1.5), "max_rejections"), (dict(box=(0, 1)), "box"), (dict(rtol="tight"), "rtol")],
)
def test_python_side_argument_checks(ctx, options, message):
    with pytest.raises(arcus.ArgumentError, match=message):
        ctx.advance(LINEAR, [0, 0, 0], [1, 0, 0], **options)


def test_field_must_be_a_field(ctx):
    with pytest.raises(arcus.ArgumentError, match="field"):
        ctx.advance(1.0, [0, 0, 0], [1, 0, 0])


def test_single_ray_and_list_input(ctx):
    # Along the gradient the ray stays straight: dr/ds = v / n = (0, 1, 0) throughout.
    result = ctx.advance(LINEAR, [0, 0, 0], (0, 2, 0), length=3.0)
    assert result.positions.shape == (1, 3) and result.steps.dtype == np.uint64
    assert result.status.dtype == np.int32
    np.testing.assert_allclose(result.positions[0], [0.0, 3.0, 0.0], rtol=0, atol=1e-14)


def test_no_rays_is_an_empty_result(ctx):
    result = ctx.advance(LINEAR, np.empty((0, 3)), np.empty((0, 3)), record_path=True)
    assert len(result) == 0 and result.positions.shape == (0, 3) and result.paths == []


# ---- strictness: no silent coercions (regressions from a reliability probe) -------------


@pytest.mark.parametrize("value", ["no", "yes", "False", "", 1, 0, 1.0, [True]])
def test_record_path_takes_only_bools(ctx, value):
    """record_path='no' used to turn recording on (bool('no') is True)."""
    with pytest.raises(arcus.ArgumentError, match="record_path must be True or False"):
        ctx.advance(LINEAR, [0, 0, 0], [1, 0, 0], record_path=value)


@pytest.mark.parametrize("value, recorded", [(True, True), (False, False), (np.True_, True), (np.False_, False)])
def test_record_path_bools_and_numpy_bools(ctx, value, recorded):
    result = ctx.advance(LINEAR, [0, 0, 0], [1, 0, 0], record_path=value)
    assert (result.paths is not None) == recorded and ("CURVED_RECORD_PATH" in result.features) == recorded


def test_spherical_takes_only_bools(ctx):
    for value in ("no", "False", 0, 1, None):
        with pytest.raises(arcus.ArgumentError, match="spherical must be True or False"):
            StandardAtmosphere(spherical=value)
    assert StandardAtmosphere(spherical=np.True_).spherical is True
    # and the flag reaches the library: a spherical atmosphere has sea-level air at
    # (0, EARTH_RADIUS, 0), where a flat one (height = y) has none.
    n_flat, _ = StandardAtmosphere(spherical=False).evaluate(ctx, [0.0, 0.0, 0.0])
    n_sphere, _ = StandardAtmosphere(spherical=True).evaluate(ctx, [0.0, arcus.EARTH_RADIUS, 0.0])
    assert n_flat[0] == pytest.approx(n_sphere[0], abs=1e-12)


@pytest.mark.parametrize("path", ["grid.raw\0.txt", b"grid.raw\0", 7, None],
                         ids=["nul-str", "nul-bytes", "int", "none"])
def test_grid_file_path_is_checked_when_described(path):
    """A NUL ends the C string: the library would read another, shorter path."""
    with pytest.raises(arcus.ArgumentError, match="path"):
        Grid.from_file(path, (2, 2, 2), (0, 0, 0), (1, 1, 1))


def test_big_endian_grid_dtype_is_refused():
    """The file is little-endian; '>f4' names float32 too and would be misread."""
    with pytest.raises(arcus.ArgumentError, match="little-endian"):
        Grid.from_file("x.raw", (2, 2, 2), (0, 0, 0), (1, 1, 1), dtype=">f4")
    assert Grid.from_file("x.raw", (2, 2, 2), (0, 0, 0), (1, 1, 1), dtype="<f8").dtype == "float64"


@pytest.mark.parametrize(
    "options, message",
    [(dict(rtol="1e-9"), "rtol must be a real number"), (dict(length=True), "length must be a real number"),
     (dict(max_steps=True), "max_steps must be an integer"), (dict(max_steps="5"), "max_steps must be an integer"),
     (dict(max_steps=float("inf")), "max_steps must be an integer"), (dict(method=3), "method must be one of"),
     (dict(box=("abc", "def")), "box min"), (dict(box="ab"), "box must be"),
     (dict(box=((0, 0, 0), (1, 1, 1j))), "box max")],
)
def test_numbers_are_never_read_from_strings_or_bools(ctx, monkeypatch, options, message):
    def never(*args):
        raise AssertionError("arcus_curved_advance was called")

    monkeypatch.setattr(arcus._lib.lib, "arcus_curved_advance", never)
    with pytest.raises(arcus.ArgumentError, match=message):
        ctx.advance(LINEAR, [0, 0, 0], [1, 0, 0], **options)


@pytest.mark.parametrize(
    "make, message",
    [(lambda: Constant("1.5"), "n must be a real number"), (lambda: Linear(1.0, ["0", "1", "0"]), "gradient"),
     (lambda: Linear(True, (0, 1, 0)), "n0 must be a real number"),
     (lambda: Grid(np.full((2, 2, 2), "1.0"), (0, 0, 0), (1, 1, 1)), "values"),
     (lambda: StandardAtmosphere(inversions=[("0", 10, 5)]), r"inversions\[0\].base")],
    ids=["constant-str", "linear-str-vector", "linear-bool", "grid-str", "inversion-str"],
)
def test_field_parameters_are_never_read_from_strings_or_bools(make, message):
    with pytest.raises(arcus.ArgumentError, match=message):
        make()


def test_rays_are_never_read_from_strings(ctx):
    with pytest.raises(arcus.ArgumentError, match="origins must be an array of real numbers"):
        ctx.advance(LINEAR, ["0", "0", "0"], [1, 0, 0])
    with pytest.raises(arcus.ArgumentError, match="directions must be an array of real numbers"):
        ctx.advance(LINEAR, [0, 0, 0], [True, False, False])


def test_error_callback_must_be_callable(ctx):
    with pytest.raises(arcus.ArgumentError, match="callback must be a callable"):
        ctx.set_error_callback("print")
