"""Devices and the lifetime of contexts."""

import gc

import numpy as np
import pytest

import arcus
from arcus.fields import Constant, Luneburg


def test_devices_describe_at_least_one_device():
    found = arcus.devices()
    assert found, "arcus sees no OpenCL device"
    for position, info in enumerate(found):
        assert info.index == position
        assert info.name and info.platform and info.version.startswith("OpenCL")
        assert isinstance(info.is_gpu, bool) and isinstance(info.fp64, bool)
        assert info.compute_units >= 1 and info.global_memory > 0 and info.lanes >= 1


def test_context_device_by_index_name_and_default(ctx):
    first = arcus.devices()[0]
    with arcus.Context(0) as by_index:
        assert by_index.device == first
    # A case-changed part of the name selects the same device.
    with arcus.Context(first.name[: max(3, len(first.name) // 2)].swapcase()) as by_name:
        assert by_name.device.index == first.index
    assert ctx.device in arcus.devices()


def test_unknown_device_index_raises_with_message():
    with pytest.raises(arcus.Error) as caught:
        arcus.Context(999)
    assert caught.value.status == "ARCUS_ERROR_DEVICE_NOT_FOUND"
    assert caught.value.message and "(the library gave no message)" not in caught.value.message


def test_unknown_device_name_lists_devices():
    with pytest.raises(arcus.Error) as caught:
        arcus.Context("no-such-device-anywhere")
    assert caught.value.status == "ARCUS_ERROR_DEVICE_NOT_FOUND"
    assert arcus.devices()[0].name in caught.value.message


@pytest.mark.parametrize("device", [True, 2.5, object(), 2**40])
def test_bad_device_argument(device):
    with pytest.raises(arcus.ArgumentError):
        arcus.Context(device)


def test_close_releases_and_blocks_further_use():
    context = arcus.Context()
    field = Constant(1.5)
    n, _ = field.evaluate(context, [0.0, 0.0, 0.0])
    assert n[0] == 1.5
    assert len(context._state.fields) == 1
    context.close()
    context.close()  # idempotent
    assert context.closed and "closed" in repr(context)
    with pytest.raises(arcus.Error, match="closed"):
        field.evaluate(context, [0.0, 0.0, 0.0])
    with pytest.raises(arcus.Error, match="closed"):
        context.advance(field, [0, 0, 0], [1, 0, 0])
    # The description is independent of the context that realised it.
    with arcus.Context() as other:
        assert field.evaluate(other, [1.0, 2.0, 3.0])[0][0] == 1.5


def test_field_handles_are_cached_per_context_and_released_with_the_field(ctx):
    field = Luneburg((0, 0, 0), 2.0)
    handle = ctx._field(field)
    assert ctx._field(field) == handle
    # An equal but distinct description is a distinct library object.
    assert ctx._field(Luneburg((0, 0, 0), 2.0)) != handle
    count = len(ctx._state.fields)
    del field
    gc.collect()
    assert len(ctx._state.fields) < count


def test_garbage_collected_context_is_released_quietly():
    context = arcus.Context()
    Constant(1.0).evaluate(context, np.zeros(3))
    finalizer = context._finalizer
    del context
    gc.collect()
    assert not finalizer.alive


def test_error_callback_sees_the_error(ctx):
    seen = []
    ctx.set_error_callback(lambda status, message: seen.append((status, message)))
    try:
        with pytest.raises(arcus.Error) as caught:
            Luneburg((0, 0, 0), -1.0).evaluate(ctx, [0.0, 0.0, 0.0])
    finally:
        ctx.set_error_callback(None)
    assert seen == [(caught.value.status, caught.value.message)]
    with pytest.raises(arcus.Error):
        Luneburg((0, 0, 0), -2.0).evaluate(ctx, [0.0, 0.0, 0.0])
    assert len(seen) == 1
