"""record_path: the kept points of every path, and what happens when they overflow."""

import numpy as np
import pytest

import arcus
from arcus.fields import Linear
from closed_forms import catenary_height, fan

N0, G = 1.0, 0.1
LINEAR = Linear(N0, (0.0, G, 0.0))
JOB = dict(method="dp45", rtol=1e-10, atol=1e-12, length=10.0, record_path=True)


@pytest.fixture(scope="module")
def recorded(ctx):
    origins, directions = fan(8)
    return origins, directions, ctx.advance(LINEAR, origins, directions, **JOB)


def test_paths_run_from_origin_to_end(recorded):
    origins, directions, result = recorded
    assert "CURVED_RECORD_PATH" in result.features
    assert len(result.paths) == 8
    offsets = result.path_offsets.astype(np.int64)
    assert offsets[0] == 0 and offsets[-1] == len(result.path_points) and np.all(np.diff(offsets) > 0)
    for i, path in enumerate(result.paths):
        assert len(path) == result.steps[i] + 1  # the origin and every accepted step
        assert result.path_needed[i] == len(path)
        np.testing.assert_array_equal(path[0], origins[i])
        np.testing.assert_array_equal(path[-1], result.positions[i])
        # Every kept point lies on the ray's catenary (to the integration accuracy).
        np.testing.assert_allclose(path[:, 1], catenary_height(N0, G, origins[i], directions[i], path[:, 0]),
                                   rtol=0, atol=1e-7)
        assert np.all(np.diff(path[:, 0]) > 0)


def test_recording_does_not_change_the_end_states(ctx, recorded):
    origins, directions, result = recorded
    plain = ctx.advance(LINEAR, origins, directions, **dict(JOB, record_path=False))
    assert plain.paths is None and plain.path_offsets is None and "CURVED_RECORD_PATH" not in plain.features
    np.testing.assert_allclose(plain.positions, result.positions, rtol=0, atol=1e-13)
    np.testing.assert_array_equal(plain.steps, result.steps)


def test_overflow_raises_with_every_result_attached(ctx, recorded):
    origins, directions, full = recorded
    capacity = 3
    assert full.steps.min() + 1 > capacity  # every path overflows
    with pytest.raises(arcus.Error) as caught:
        ctx.advance(LINEAR, origins, directions, **JOB, path_capacity=capacity)
    error = caught.value
    assert error.status == "ARCUS_ERROR_PATH_OVERFLOW" and error.message
    result = error.result
    assert result is not None and len(result.paths) == 8
    np.testing.assert_array_equal(result.path_needed, full.path_needed)
    for kept, whole in zip(result.paths, full.paths):
        np.testing.assert_array_equal(kept, whole[:capacity])
    # The rays themselves went the whole way.
    np.testing.assert_array_equal(result.positions, full.positions)
    assert np.all(result.status == arcus.RAY_DONE)
