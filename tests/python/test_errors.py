"""Bad input raises arcus.Error with a message; partial results are never lost."""

import numpy as np
import pytest

import arcus
from arcus.media import Linear
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
        raise AssertionError("arcus_advance was called")

    monkeypatch.setattr(arcus._lib.lib, "arcus_advance", never)
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
