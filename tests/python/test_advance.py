"""Context.advance against closed forms: straight lines, catenaries, lenses, boxes, and
an independent numpy integrator; why rays fail."""

import numpy as np
import pytest

import arcus
from arcus.fields import Constant, Linear, Luneburg, StandardAtmosphere
from closed_forms import catenary, fan

N0, G = 1.0, 0.1
LINEAR = Linear(N0, (0.0, G, 0.0))  # n = 1 + 0.1 y
INTEGRATORS = {"CURVED_STRAIGHT", "CURVED_EULER", "CURVED_RK2", "CURVED_RK4", "CURVED_DP45"}


def catenary_error(result, origins, directions, length):
    end, direction = catenary(N0, G, origins, directions, length)
    return np.abs(result.positions - end).max(), np.abs(result.directions - direction).max()


def dp45_bound(rtol, atol, origins, directions, length):
    """A bound on DP45's end-point error from the tolerance and the closed form alone.

    The controller keeps each step's error relative to |state| under rtol; on a smooth,
    non-focusing path the end then errs by about the tolerance times the sizes involved
    (tolerance proportionality), more where the path turns: 10 (1 + turning) times
    rtol (|r_end| + L) + atol (1 + L / n_min), with n >= 1 on these paths (as
    tests/test_util.h's dp45_bound, which a C++ test calibrates).
    """
    end, direction = catenary(N0, G, origins, directions, length)
    unit = directions / np.linalg.norm(directions, axis=1, keepdims=True)
    turning = np.arccos(np.clip(np.sum(unit * direction, axis=1), -1.0, 1.0))
    tol = rtol * (np.linalg.norm(end, axis=1) + length) + atol * (1.0 + length)
    return (10.0 * (1.0 + turning) * tol).max()


# ---- straight rays ----------------------------------------------------------------------


@pytest.mark.parametrize("method", ["dp45", "rk4"])
def test_constant_field_is_one_exact_straight_segment(ctx, method):
    rng = np.random.default_rng(1)
    origins = rng.normal(size=(37, 3))
    directions = rng.normal(size=(37, 3))  # not unit length on purpose
    result = ctx.advance(Constant(1.4), origins, directions, method=method, length=7.5)
    unit = directions / np.linalg.norm(directions, axis=1, keepdims=True)
    # No truncation error at all; only a few roundings of o + L * d / |d|.
    np.testing.assert_allclose(result.positions, origins + 7.5 * unit, rtol=0, atol=1e-13)
    np.testing.assert_allclose(result.directions, unit, rtol=0, atol=1e-15)
    assert np.all(result.lengths == 7.5)
    assert np.all(result.status == arcus.RAY_DONE)
    assert "CURVED_STRAIGHT" in result.features and not (result.features & (INTEGRATORS - {"CURVED_STRAIGHT"}))
    assert result.feature_bits & arcus.FEATURES["CURVED_STRAIGHT"]


# ---- catenary (n = 1 + 0.1 y) ---------------------------------------------------------------


def test_dp45_catenary(ctx):
    origins, directions = fan(8)
    rtol, atol, length = 1e-10, 1e-12, 10.0
    result = ctx.advance(LINEAR, origins, directions, method="dp45", rtol=rtol, atol=atol, length=length)
    assert np.all(result.status == arcus.RAY_DONE)
    assert np.all(result.lengths == length)
    assert {"CURVED_DP45", "CURVED_FIELD_LINEAR"} <= result.features and "FLOAT" not in result.features
    position_error, direction_error = catenary_error(result, origins, directions, length)
    bound = dp45_bound(rtol, atol, origins, directions, length)
    assert position_error < bound
    # The direction errs by v's share of the tolerance and the position error over the
    # path's radius of curvature (>= n / |grad n| = 10 m here).
    assert direction_error < bound
    np.testing.assert_allclose(np.linalg.norm(result.directions, axis=1), 1.0, rtol=0, atol=1e-15)
    assert result.stats["total_seconds"] > 0 and result.stats["lanes"] >= 1


def test_dp45_catenary_of_the_c_api_dump_job(ctx):
    """The job test_determinism.py runs through C and Python, against the closed form."""
    origins, directions = fan(8)
    rtol, atol, length = 1e-9, 1e-12, 100.0
    result = ctx.advance(LINEAR, origins, directions, method="dp45", rtol=rtol, atol=atol, length=length)
    assert np.all(result.status == arcus.RAY_DONE) and np.all(result.failures == arcus.FAILURE_NONE)
    position_error, direction_error = catenary_error(result, origins, directions, length)
    bound = dp45_bound(rtol, atol, origins, directions, length)
    assert position_error < bound
    assert direction_error < bound


def test_tighter_tolerance_is_more_accurate(ctx):
    origins, directions = fan(8)
    errors = [catenary_error(ctx.advance(LINEAR, origins, directions, rtol=rtol, atol=1e-14, length=10.0),
                             origins, directions, 10.0)[0] for rtol in (1e-5, 1e-8, 1e-11)]
    assert errors[0] > 10 * errors[1] > 100 * errors[2]


# Float rounding is 2^-24 relative; on |r| <= 12 and a few roundings per stage that is
# at most ~4 * 12 * 2^-24 = 3e-6 per step.
FLOAT_ROUNDING = 4 * 12 * 2.0**-24


def test_float_precision_dp45(ctx):
    origins, directions = fan(8)
    length = 10.0
    double = ctx.advance(LINEAR, origins, directions, rtol=1e-10, atol=1e-12, length=length)
    # Tolerances a float state can meet: rtol * |r| well above the rounding.
    rtol, atol = 1e-6, 1e-7
    single = ctx.advance(LINEAR, origins, directions, rtol=rtol, atol=atol, length=length, precision="float")
    assert "FLOAT" in single.features and "FLOAT" not in double.features
    assert np.all(single.status == arcus.RAY_DONE)
    # Everything came back from float buffers.
    np.testing.assert_array_equal(single.positions.astype(np.float32), single.positions)
    float_error, _ = catenary_error(single, origins, directions, length)
    double_error, _ = catenary_error(double, origins, directions, length)
    # Float's own rounding adds no more than a few ulps of |r| a step, compensated (Kahan):
    # 4 (|r| + L) 2^-24 in all, as in tests/test_util.h.
    assert double_error < float_error < dp45_bound(rtol, atol, origins, directions, length) + 4 * 22 * 2.0**-24


def test_float_precision_rk4(ctx):
    """The same fixed steps in float and double: the difference is the rounding alone."""
    origins, directions = fan(8)
    length, step = 4.0, 0.1
    double = ctx.advance(LINEAR, origins, directions, method="rk4", step=step, length=length)
    single = ctx.advance(LINEAR, origins, directions, method="rk4", step=step, length=length, precision="float")
    assert {"CURVED_RK4", "FLOAT"} <= single.features
    float_error, float_direction_error = catenary_error(single, origins, directions, length)
    double_error, double_direction_error = catenary_error(double, origins, directions, length)
    # RK4's truncation error at h = 0.1 is ~4e-10, far below float's rounding.
    # The step count is the job's (L / h), not one the library reports.
    assert 100 * double_error < float_error < np.e * np.ceil(length / step) * FLOAT_ROUNDING
    assert 1e-9 < float_direction_error < 1e-5 and double_direction_error < 1e-14


@pytest.mark.parametrize("method, order, step", [("euler", 1, 0.1), ("rk2", 2, 0.2), ("rk4", 4, 0.4)])
def test_fixed_step_methods_converge_at_their_order(ctx, method, order, step):
    origins, directions = fan(8)
    length = 4.0
    errors = []
    for h in (step, step / 2):
        result = ctx.advance(LINEAR, origins, directions, method=method, step=h, length=length)
        assert "CURVED_" + method.upper() in result.features
        assert np.all(result.status == arcus.RAY_DONE) and np.all(result.lengths == length)
        assert np.all(result.steps == round(length / h))
        errors.append(catenary_error(result, origins, directions, length)[0])
    # Halving the step divides the error by 2^order (asymptotically; 25 % slack).
    assert 0.75 * 2**order < errors[0] / errors[1] < 1.33 * 2**order


def test_fixed_step_that_does_not_divide_the_length(ctx):
    origins, directions = fan(8)
    result = ctx.advance(LINEAR, origins, directions, method="rk4", step=0.3, length=1.0)
    assert np.all(result.steps == 4)  # 3 steps of 0.3 and a last one of 0.1
    assert np.all(result.lengths == 1.0)
    assert catenary_error(result, origins, directions, 1.0)[0] < 1e-6


def test_max_steps_stops_rays(ctx):
    origins, directions = fan(8)
    fixed = ctx.advance(LINEAR, origins, directions, method="rk4", step=0.01, length=1.0, max_steps=5)
    assert np.all(fixed.status == arcus.RAY_STEP_LIMIT) and np.all(fixed.steps == 5)
    np.testing.assert_allclose(fixed.lengths, 0.05, rtol=1e-15)
    adaptive = ctx.advance(LINEAR, origins, directions, method="dp45", length=10.0, max_steps=3)
    assert np.all(adaptive.status == arcus.RAY_STEP_LIMIT) and np.all(adaptive.steps == 3)
    assert np.all(adaptive.lengths < 10.0)
    assert set(adaptive.status_names) == {"STEP_LIMIT"}


def test_max_steps_caps_a_job_of_very_many_fixed_steps(ctx):
    """length / step is 1e12 steps, but max_steps stops every ray after 5 (arcus.h)."""
    result = ctx.advance(LINEAR, [0, 0, 0], [1, 0, 0], method="euler", step=1e-12, length=1.0, max_steps=5)
    assert result.status[0] == arcus.RAY_STEP_LIMIT and result.steps[0] == 5


def test_dp45_gives_up_when_the_tolerance_cannot_be_met(ctx):
    origins, directions = fan(8)
    # Two rejections in a row (max_rejections=1) of steps far too long for the tolerance.
    result = ctx.advance(LINEAR, origins, directions, step=5.0, rtol=1e-14, atol=1e-16, max_rejections=1,
                         length=10.0)
    assert np.all(result.status == arcus.RAY_FAILED)
    assert np.all(result.failures == arcus.FAILURE_TOLERANCE) and result.failures.dtype == np.int32
    assert set(result.failure_names) == {"TOLERANCE"}
    # It stopped at the last state known good: still at its origin, nothing travelled.
    assert np.all(result.lengths < 10.0)


@pytest.mark.parametrize("job", [dict(method="dp45"), dict(method="rk4", step=0.3), dict(method="euler", step=0.01),
                                 dict(method="rk2", step=0.3, box=((-10, -10, -10), (10, 10, 10))),
                                 dict(method="dp45", precision="float", rtol=1e-6, atol=1e-9)],
                         ids=["dp45", "rk4", "euler", "rk2-box", "dp45-float"])
def test_ray_reaching_n_zero_fails_with_that_reason(ctx, job):
    """n = 1 - y: a ray going straight up reaches n = 0 at y = 1 (v = n = 1 - s there)."""
    field = Linear(1.0, (0.0, -1.0, 0.0))
    origins, directions = [[0, 0, 0], [0, 0, 0]], [[0, 1, 0], [1, 1, 0]]
    result = ctx.advance(field, origins, directions, length=2.0, **job)
    assert list(result.status) == [arcus.RAY_FAILED, arcus.RAY_DONE]
    assert list(result.failures) == [arcus.FAILURE_INDEX_NOT_POSITIVE, arcus.FAILURE_NONE]
    assert result.failure_names == ["INDEX_NOT_POSITIVE", "NONE"]
    # The failed ray ends at a state before n = 0, finite.
    assert result.positions[0, 1] <= 1.0 and result.lengths[0] <= 1.0
    assert np.all(np.isfinite(result.positions[0])) and np.all(np.isfinite(result.directions[0]))
    if job["method"] == "dp45":
        # The ray at 45 degrees turns where n = cos 45 degrees, on the catenary of n = 1 - y.
        # (The fixed steps are coarse, to take a step's stages across y = 1: only dp45
        # meets a tolerance worth checking.)
        end, _ = catenary(1.0, -1.0, [[0, 0, 0]], [[1, 1, 0]], 2.0)
        tolerance = 1e-4 if job.get("precision") == "float" else 1e-8
        np.testing.assert_allclose(result.positions[1], end[0], rtol=0, atol=tolerance)


def test_overflowing_state_fails_as_not_finite(ctx):
    """n = 1 + 1e308 (x + y): n and v overflow within any step."""
    field = Linear(1.0, (1e308, 1e308, 0.0))
    for job in (dict(method="dp45"), dict(method="rk4", step=0.1)):
        result = ctx.advance(field, [0, 0, 0], [1, 1, 0], length=1.0, **job)
        assert result.status[0] == arcus.RAY_FAILED, job
        assert result.failures[0] == arcus.FAILURE_NOT_FINITE, job


# ---- boxes ----------------------------------------------------------------------------------

BOX = (np.array([-1.0, -1.0, -0.5]), np.array([2.0, 1.0, 3.0]))


def test_straight_rays_leave_the_box_on_its_faces(ctx):
    rng = np.random.default_rng(2)
    directions = rng.normal(size=(40, 3))
    origins = np.zeros((40, 3))
    origins[-1] = (5.0, 0.0, 0.0)  # starts outside
    result = ctx.advance(Constant(1.0), origins, directions, length=100.0, box=BOX)
    assert "CURVED_BOX" in result.features
    unit = directions / np.linalg.norm(directions, axis=1, keepdims=True)
    # Distance to the first face along each direction.
    with np.errstate(divide="ignore"):
        t = np.where(unit > 0, (BOX[1] - origins) / unit, (BOX[0] - origins) / unit).min(axis=1)
    inside = slice(0, 39)
    np.testing.assert_allclose(result.positions[inside], (origins + t[:, None] * unit)[inside], rtol=0, atol=1e-13)
    np.testing.assert_allclose(result.lengths[inside], t[inside], rtol=1e-14)
    assert np.all(result.status == arcus.RAY_LEFT_BOX)
    assert result.lengths[-1] == 0.0
    np.testing.assert_array_equal(result.positions[-1], origins[-1])
    # A ray too short to reach a face is done.
    short = ctx.advance(Constant(1.0), [0.0, 0.0, 0.0], [1.0, 0.0, 0.0], length=0.5, box=BOX)
    assert short.status[0] == arcus.RAY_DONE and short.positions[0, 0] == 0.5


def test_curved_rays_stop_on_the_box_face(ctx):
    origins, directions = fan(8)
    top = 1.5
    box = ((-1.0, -10.0, -1.0), (100.0, top, 1.0))
    result = ctx.advance(LINEAR, origins, directions, length=50.0, box=box)
    assert np.all(result.status == arcus.RAY_LEFT_BOX)
    # The rays curve up into the higher index and leave through the top face.
    np.testing.assert_allclose(result.positions[:, 1], top, rtol=0, atol=1e-12)
    assert np.all(result.lengths < 50.0)


# ---- lenses and air --------------------------------------------------------------------------


def test_luneburg_lens_focuses_parallel_rays_on_its_far_side(ctx):
    """A Luneburg lens images a parallel beam onto the point of its surface opposite the beam."""
    center, radius = np.array([0.5, -0.25, 0.0]), 2.0
    offsets = np.linspace(-0.9, 0.9, 13) * radius
    origins = center + np.stack([np.full(13, -3 * radius), offsets, np.zeros(13)], axis=1)
    directions = np.tile([1.0, 0.0, 0.0], (13, 1))
    # max_step: outside the lens n is constant, so DP45 grows its step until a step
    # can jump over the lens with no stage inside it (the rays near the rim would pass
    # straight through); a step below the lens' size keeps every ray sampling it.
    result = ctx.advance(Luneburg(center, radius), origins, directions, length=6 * radius, rtol=1e-11,
                         atol=1e-13, max_step=0.25 * radius)
    assert np.all(result.status == arcus.RAY_DONE)
    focus = center + (radius, 0.0, 0.0)
    # Outside the lens rays are straight: each end ray, extended back, passes the focus.
    miss = np.linalg.norm(np.cross(focus - result.positions, result.directions), axis=1)
    # The index's gradient jumps at the surface, which costs DP45 some accuracy there.
    assert miss.max() < 1e-9 * radius
    assert np.ptp(result.directions[:, 1]) > 1.0  # the beam really was bent, into a wide fan


def test_horizontal_ray_in_flat_atmosphere_follows_local_catenary(ctx):
    """Near one height the atmosphere is a linear field; the ray bends down with it."""
    air = StandardAtmosphere()
    height, length = 10.0, 2000.0
    n, gradient = air.evaluate(ctx, [0.0, height, 0.0])
    g = gradient[0, 1]
    result = ctx.advance(air, [0.0, height, 0.0], [1.0, 0.0, 0.0], length=length, rtol=1e-12, atol=1e-12)
    assert "CURVED_FIELD_ATMOSPHERE" in result.features
    end, _ = catenary(n[0] - g * height, g, [[0.0, height, 0.0]], [[1.0, 0.0, 0.0]], length)
    drop = height - result.positions[0, 1]
    assert drop == pytest.approx(-g / n[0] * length**2 / 2, rel=1e-3)  # ~5 cm
    # The gradient changes by ~1e-5 relative over the 5 cm drop; the catenary with the
    # starting gradient is good to well under a micrometre.
    assert abs(result.positions[0, 1] - end[0, 1]) < 1e-6


# ---- an independent integrator ------------------------------------------------------------


def python_rk4(ctx, field, origins, directions, step, count):
    """The kernel's RK4 in numpy, on n and grad n from arcus_field_evaluate.

    State (r, v = n dr/ds); dr/ds = v / n, dv/ds = grad n.
    """

    def derivative(r, v):
        n, gradient = field.evaluate(ctx, r)
        return v / n[:, None], gradient

    r = np.array(origins, dtype=float)
    n, _ = field.evaluate(ctx, r)
    v = n[:, None] * directions / np.linalg.norm(directions, axis=1, keepdims=True)
    for _ in range(count):
        k1 = derivative(r, v)
        k2 = derivative(r + step / 2 * k1[0], v + step / 2 * k1[1])
        k3 = derivative(r + step / 2 * k2[0], v + step / 2 * k2[1])
        k4 = derivative(r + step * k3[0], v + step * k3[1])
        r = r + step / 6 * (k1[0] + 2 * k2[0] + 2 * k3[0] + k4[0])
        v = v + step / 6 * (k1[1] + 2 * k2[1] + 2 * k3[1] + k4[1])
    return r, v / np.linalg.norm(v, axis=1, keepdims=True)


def test_kernel_rk4_matches_numpy_rk4_on_evaluated_field(ctx):
    """The kernel's RK4 against RK4 written out here in numpy, on the same field.

    The field (n, grad n) comes from arcus_field_evaluate, which test_fields.py checks
    against the Luneburg formula; the integration scheme is independent of the kernel's.
    """
    field = Luneburg((0.0, 0.0, 0.0), 1.0)
    origins = np.array([[-0.8, 0.1 * i - 0.3, 0.05 * i] for i in range(6)])
    directions = np.tile([1.0, 0.1, 0.0], (6, 1))
    step, count = 0.05, 24
    result = ctx.advance(field, origins, directions, method="rk4", step=step, length=step * count)
    assert np.all(result.steps == count)
    r, d = python_rk4(ctx, field, origins, directions, step, count)
    # Only rounding differs (the kernel fuses multiply-adds): a few ulps per step.
    np.testing.assert_allclose(result.positions, r, rtol=0, atol=1e-13)
    np.testing.assert_allclose(result.directions, d, rtol=0, atol=1e-13)
    assert np.abs(result.directions - directions / np.linalg.norm(directions, axis=1, keepdims=True)).max() > 0.1
