"""Determinism: the same job gives the same numbers, bit for bit.

These tests compare arcus with itself (a job run twice; the C program tests/c_api_dump
and Python through the same libarcus; one thread and several).  They are NOT
validation: a wrong result, reproduced faithfully, passes them.  The physics of these
very jobs is validated against closed forms in test_advance.py
(test_dp45_catenary_of_the_c_api_dump_job and the others).
"""

import os
import subprocess
from pathlib import Path

import numpy as np
import pytest

import arcus
from arcus.fields import Linear
from closed_forms import fan

# The job of the C program tests/c_api_dump (built next to libarcus).
C_JOB = dict(method="dp45", rtol=1e-9, atol=1e-12, length=100.0)
C_FIELD = Linear(1.0, (0.0, 0.1, 0.0))


def test_determinism_repeated_runs_are_bitwise_identical(ctx):
    """The same job twice on one context: identical results (not validation)."""
    origins, directions = fan(8)
    first = ctx.advance(C_FIELD, origins, directions, **C_JOB)
    second = ctx.advance(C_FIELD, origins, directions, **C_JOB)
    for name in ("positions", "directions", "steps", "status", "lengths", "failures"):
        np.testing.assert_array_equal(getattr(first, name), getattr(second, name))


def test_determinism_c_program_and_python_print_the_same_end_states(ctx):
    """tests/c_api_dump and Context.advance run the same job through the same library and
    get the same doubles: the binding passes and reads everything exactly (not validation).
    """
    # $ARCUS_C_API_DUMP: a program built elsewhere (as test_c_and_python.py takes it).
    program = Path(os.environ.get("ARCUS_C_API_DUMP") or Path(arcus.library_path).resolve().parent / "tests" / "c_api_dump")
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


def test_determinism_threads_sharing_a_context_get_the_same_numbers(ctx):
    """Calls on one context from several threads are serialised, never mixed up (not validation)."""
    from concurrent.futures import ThreadPoolExecutor

    jobs = [fan(8, spread=0.1 * k) for k in range(6)]
    serial = [ctx.advance(C_FIELD, o, d, **C_JOB).positions for o, d in jobs]
    with ThreadPoolExecutor(max_workers=3) as pool:
        threaded = list(pool.map(lambda job: ctx.advance(C_FIELD, *job, **C_JOB).positions, jobs))
    for a, b in zip(serial, threaded):
        np.testing.assert_array_equal(a, b)
