"""Progress and cancellation: Context.advance(progress=...).

Long jobs run in slices; after each the callable sees the fraction done, and a true
return value (or an exception, which advance re-raises) cancels the job.
"""

import os
import subprocess
import sys
import time

import numpy as np
import pytest

import arcus
from arcus.fields import Linear
from closed_forms import catenary, fan

N0, G = 1.0, 0.1
LINEAR = Linear(N0, (0.0, G, 0.0))
# RK4 with steps of 1e-5 m over 10 km: 1e9 steps per ray, hours of work, so a job that
# finishes in a test's time was cancelled.  max_steps: the default 10^7 would stop it first.
ENDLESS = dict(method="rk4", step=1e-5, length=1e4, max_steps=2 * 10**9)


class Stop(Exception):
    pass


def test_progress_sees_the_fraction_grow_to_one(ctx):
    origins, directions = fan(8)
    seen = []
    # dp45's first slice is 256 attempts per ray; max_step makes these rays take 1000 steps.
    result = ctx.advance(LINEAR, origins, directions, length=10.0, rtol=1e-10, max_step=0.01,
                         progress=lambda fraction: seen.append(fraction))
    assert np.all(result.status == arcus.RAY_DONE)
    assert result.stats["launches"] >= 2 and len(seen) == result.stats["launches"]
    assert seen[-1] == 1.0 and all(0.0 < f <= 1.0 for f in seen)
    assert seen == sorted(seen)
    assert all(isinstance(f, float) for f in seen)
    end, _ = catenary(N0, G, origins, directions, 10.0)
    np.testing.assert_allclose(result.positions, end, rtol=0, atol=1e-7)


def test_returning_true_cancels_and_keeps_the_results_so_far(ctx):
    origins, directions = fan(8)
    seen = []
    start = time.monotonic()
    with pytest.raises(arcus.Error) as caught:
        ctx.advance(LINEAR, origins, directions, **ENDLESS, progress=lambda f: seen.append(f) or True)
    assert time.monotonic() - start < 30.0
    error = caught.value
    assert error.status == "ARCUS_ERROR_CANCELLED" and error.code == 10 and "cancel" in error.message
    assert len(seen) == 1 and 0.0 < seen[0] < 0.01
    result = error.result
    assert isinstance(result, arcus.AdvanceResult) and len(result) == 8
    assert np.all(result.status == arcus.RAY_CANCELLED) and set(result.status_names) == {"CANCELLED"}
    assert np.all(result.failures == arcus.FAILURE_NONE)
    # Each ray stopped somewhere along its path, after whole steps: the catenary at the
    # arc length reported (RK4 at 1e-5 m errs far below 1e-9 m over this stretch).
    assert np.all((result.lengths > 0) & (result.lengths < 1e4))
    np.testing.assert_array_equal(result.steps, np.round(result.lengths / 1e-5).astype(np.uint64))
    for i in range(8):
        end, _ = catenary(N0, G, origins[i:i + 1], directions[i:i + 1], result.lengths[i])
        np.testing.assert_allclose(result.positions[i], end[0], rtol=0, atol=1e-9)


def test_an_exception_in_progress_cancels_and_is_raised_by_advance(ctx):
    calls = []

    def progress(fraction):
        calls.append(fraction)
        raise Stop("enough at %g" % fraction)

    start = time.monotonic()
    with pytest.raises(Stop, match="enough at"):
        ctx.advance(LINEAR, *fan(8), **ENDLESS, progress=progress)
    assert time.monotonic() - start < 30.0 and len(calls) == 1
    # The context is fine afterwards.
    assert ctx.advance(LINEAR, [0, 0, 0], [1, 0, 0]).status[0] == arcus.RAY_DONE


def test_an_exception_on_the_last_call_is_raised_too(ctx):
    """The call at 1.0 comes after the job finished: nothing to cancel, but nothing lost."""

    def progress(fraction):
        if fraction == 1.0:
            raise Stop("at the end")

    with pytest.raises(Stop, match="at the end"):
        ctx.advance(LINEAR, *fan(8), length=10.0, max_step=0.01, progress=progress)


def test_progress_must_not_call_its_own_context(ctx):
    """The library holds the context's lock during the callback: a call would deadlock."""

    def progress(fraction):
        ctx.advance(LINEAR, [0, 0, 0], [1, 0, 0])

    with pytest.raises(arcus.ArgumentError, match="progress callback must not call"):
        ctx.advance(LINEAR, *fan(8), **ENDLESS, progress=progress)
    with pytest.raises(arcus.ArgumentError, match="progress callback must not call"):
        ctx.advance(LINEAR, *fan(8), **ENDLESS, progress=lambda f: LINEAR.evaluate(ctx, [0.0, 0.0, 0.0]))
    with pytest.raises(arcus.ArgumentError, match="progress callback must not call"):
        ctx.advance(LINEAR, *fan(8), **ENDLESS, progress=lambda f: ctx.close())
    assert not ctx.closed
    assert ctx.advance(LINEAR, [0, 0, 0], [1, 0, 0]).status[0] == arcus.RAY_DONE


RELEASE_IN_CALLBACK = r"""
import gc, sys
import arcus
from arcus import context as context_module
from arcus.fields import Constant, Linear

ctx = arcus.Context()
held = [Constant(1.25)]
held[0].evaluate(ctx, [0.0, 0.0, 0.0])  # realised on ctx
deferred = []

def progress(fraction):
    held.clear()  # the last reference: its library object is released ...
    gc.collect()
    deferred.append(len(context_module._deferred))  # ... after the job, not here
    return True

try:
    ctx.advance(Linear(1.0, (0.0, 0.1, 0.0)), [0, 0, 0], [1, 0, 0], method="rk4", step=1e-5, length=1e4,
                max_steps=2 * 10**9, progress=progress)
except arcus.Error as error:
    assert error.status == "ARCUS_ERROR_CANCELLED", error
print(deferred, len(context_module._deferred))
"""


def test_an_object_released_during_progress_is_released_after_the_job(repo):
    """Releasing an object takes its context's lock, which the job holds during the callback.

    The release waits until the job returns.  Run in a fresh interpreter: a deadlock there
    fails this test by its timeout instead of hanging the suite.
    """
    env = dict(os.environ, PYTHONPATH=str(repo / "bindings" / "python"))
    run = subprocess.run([sys.executable, "-c", RELEASE_IN_CALLBACK], env=env, capture_output=True, text=True,
                         timeout=120)
    assert run.returncode == 0, run.stderr
    assert run.stdout.split() == ["[1]", "0"]  # deferred during the callback, none left after


@pytest.mark.parametrize("progress", [1, "yes", True])
def test_progress_must_be_callable(ctx, monkeypatch, progress):
    def never(*args):
        raise AssertionError("arcus_curved_advance was called")

    monkeypatch.setattr(arcus._lib.lib, "arcus_curved_advance", never)
    with pytest.raises(arcus.ArgumentError, match="progress must be a callable"):
        ctx.advance(LINEAR, [0, 0, 0], [1, 0, 0], progress=progress)
