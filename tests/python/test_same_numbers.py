"""C and Python give the same numbers for the same job."""

import subprocess
from pathlib import Path

import numpy as np
import pytest

import arcus
from arcus.media import Linear, Luneburg
from closed_forms import fan

# The job of the C program tests/c_api_dump (built next to libarcus).
C_JOB = dict(method="dp45", rtol=1e-9, atol=1e-12, length=100.0)
C_FIELD = Linear(1.0, (0.0, 0.1, 0.0))


def test_repeated_runs_are_bitwise_identical(ctx):
    origins, directions = fan(8)
    first = ctx.advance(C_FIELD, origins, directions, **C_JOB)
    second = ctx.advance(C_FIELD, origins, directions, **C_JOB)
    for name in ("positions", "directions", "steps", "status", "lengths"):
        np.testing.assert_array_equal(getattr(first, name), getattr(second, name))


def test_c_program_prints_the_same_end_states(ctx):
    program = Path(arcus.library_path).resolve().parent / "tests" / "c_api_dump"
    if not program.is_file():
        pytest.skip("%s is not built" % program)
    lines = subprocess.run([str(program)], check=True, capture_output=True, text=True, timeout=60).stdout.split("\n")
    table = [line.split() for line in lines if line.strip()]
    assert len(table) == 8 and all(len(row) == 8 for row in table)
    # "%.17g" round-trips a double exactly, so the parsed numbers are the C doubles.
    c_positions = np.array([[float(v) for v in row[0:3]] for row in table])
    c_directions = np.array([[float(v) for v in row[3:6]] for row in table])
    c_steps = np.array([int(row[6]) for row in table], dtype=np.uint64)
    c_status = np.array([int(row[7]) for row in table], dtype=np.int32)

    origins, directions = fan(8)  # the same expressions the C program evaluates
    result = ctx.advance(C_FIELD, origins, directions, **C_JOB)
    np.testing.assert_array_equal(result.positions, c_positions)
    np.testing.assert_array_equal(result.directions, c_directions)
    np.testing.assert_array_equal(result.steps, c_steps)
    np.testing.assert_array_equal(result.status, c_status)


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
    """The device integrates the same field the host evaluates, with the same scheme."""
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


def test_threads_sharing_a_context_get_the_same_numbers(ctx):
    """Calls on one context from several threads are serialised, never mixed up."""
    from concurrent.futures import ThreadPoolExecutor

    jobs = [fan(8, spread=0.1 * k) for k in range(6)]
    serial = [ctx.advance(C_FIELD, o, d, **C_JOB).positions for o, d in jobs]
    with ThreadPoolExecutor(max_workers=3) as pool:
        threaded = list(pool.map(lambda job: ctx.advance(C_FIELD, *job, **C_JOB).positions, jobs))
    for a, b in zip(serial, threaded):
        np.testing.assert_array_equal(a, b)
