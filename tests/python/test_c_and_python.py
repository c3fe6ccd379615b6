"""Determinism through two doors: per engine, the same physical input gives the same
answer through the C API (the program tests/c_api_dump) and through the public Python
API.

These tests compare arcus with itself — the same libarcus reached from C and from
Python — so they check that the binding passes every input and reads every output
exactly (units, defaults, struct layouts, array orders).  They are NOT validation: a
wrong result, reproduced faithfully, passes them.  The physics is validated elsewhere
(test_rainbow.py against Mie and closed forms, test_ocean_reference.py, test_render.py).

The program is $ARCUS_C_API_DUMP if set, else build/tests/c_api_dump beside libarcus.
It takes the engine as its first argument; a program built before it did (it prints the
curved-light table for every argument) fails these tests loudly: rebuild it.
"""

import os
import subprocess
from pathlib import Path

import numpy as np
import pytest

import arcus
import arcus.mie
import arcus.ocean
import arcus.rainbow
import arcus.translucency

# The inputs tests/c_api_dump.c hard-codes (its header comment lists them).
RAINBOW_TEMPERATURE_K = 283.15
RAINBOW_WAVELENGTHS = (450.0, 550.0, 650.0)
MIE_RADIUS, MIE_WAVELENGTH, MIE_THETA = 10e-6, 550.0, (10.0, 90.0, 137.5, 170.0)
OCEAN_PRESET, OCEAN_GRID = "baltic", (400.0, 700.0, 50.0)  # 400, 450, ..., 700 nm: 7 wavelengths

# A tiny render scene: curved rays (n grows with height), a sphere lit by a sun (curved
# shadow rays), a sky; 8 × 6 pixels.
RENDER_SCENE = """{"name": "c_and_python", "medium": {"type": "linear", "n0": 1.0, "gradient": [0, 0.01, 0]},
 "integrator": {"method": "dp45", "rtol": 1e-9, "atol": 1e-9, "length": 100},
 "camera": {"position": [0, 0, 0], "look_at": [0, 0, -1], "vfov_deg": 40, "width": 8, "height": 6},
 "materials": {"m": {"diffuse": [0.5, 0.5, 0.5], "emission": [0.1, 0.2, 0.3]}},
 "objects": [{"type": "sphere", "center": [0, 0, -5], "radius": 1, "material": "m"}],
 "lights": [{"type": "sun", "direction": [-0.55, 0.55, -0.63], "irradiance": [3, 2.9, 2.7]}],
 "sky": {"type": "gradient", "horizon": [0.75, 0.82, 0.92], "zenith": [0.25, 0.45, 0.8]}}
"""


def c_api_dump():
    """The C program: $ARCUS_C_API_DUMP, else the one built next to libarcus."""
    named = os.environ.get("ARCUS_C_API_DUMP")
    if named:
        program = Path(named)
        assert program.is_file(), "ARCUS_C_API_DUMP=%s is not a file" % named
        return program
    program = Path(arcus.library_path).resolve().parent / "tests" / "c_api_dump"
    if not program.is_file():
        pytest.skip("%s is not built (or set ARCUS_C_API_DUMP)" % program)
    return program


def run_c(*arguments):
    """The program's output for ``arguments``, split into rows of words; fails loudly
    (with its stderr) when it exits non-zero."""
    program = c_api_dump()
    done = subprocess.run([str(program), *map(str, arguments)], capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, ("%s %s exited with %d (built before it took an engine argument? rebuild "
                                  "build/tests/c_api_dump): %s" % (program, " ".join(map(str, arguments)),
                                                                    done.returncode, done.stderr.strip()))
    return [line.split() for line in done.stdout.splitlines() if line.strip()]


def rows_named(table, name, program_arguments):
    rows = [row[1:] for row in table if row[0] == name]
    assert rows, ("no %r lines from c_api_dump %s: an old program that ignores its argument? rebuild "
                  "build/tests/c_api_dump; it printed %r" % (name, program_arguments, table[:2]))
    return rows


# "%.17g" round-trips a double and "%.9g" a float exactly, so the numbers parsed below
# are the very values the C program held, and exact equality is the right test: both
# doors call the same C function with the same doubles.


def test_rainbow_same_answer_through_c_and_python():
    """Water's index (arcus_rainbow_refractive_index, kelvin) and Lorenz–Mie
    (arcus_rainbow_mie) through C and through arcus.rainbow / arcus.mie: identical
    doubles (not validation)."""
    table = run_c("rainbow")
    n_rows = rows_named(table, "n", "rainbow")
    assert [float(r[0]) for r in n_rows] == list(RAINBOW_WAVELENGTHS)
    c_n = np.array([float(r[1]) for r in n_rows])
    py_n = arcus.rainbow.refractive_index("water", np.array(RAINBOW_WAVELENGTHS), temperature_k=RAINBOW_TEMPERATURE_K)
    np.testing.assert_array_equal(py_n, c_n)

    mie_rows = np.array([[float(v) for v in r] for r in rows_named(table, "mie", "rainbow")])
    (efficiencies,) = rows_named(table, "efficiencies", "rainbow")
    # The C program passes water's index at 550 nm (n_im = 0), as mie.phase_function
    # does for n=None: the same doubles go in.
    m = arcus.mie.phase_function(MIE_RADIUS, MIE_WAVELENGTH, np.array(MIE_THETA), temperature_k=RAINBOW_TEMPERATURE_K)
    assert m.n == complex(c_n[RAINBOW_WAVELENGTHS.index(MIE_WAVELENGTH)], 0.0)
    np.testing.assert_array_equal(mie_rows[:, 0], MIE_THETA)
    np.testing.assert_array_equal(m.s1.real, mie_rows[:, 1])
    np.testing.assert_array_equal(m.s1.imag, mie_rows[:, 2])
    np.testing.assert_array_equal(m.s2.real, mie_rows[:, 3])
    np.testing.assert_array_equal(m.s2.imag, mie_rows[:, 4])
    np.testing.assert_array_equal(m.parallel, mie_rows[:, 5])
    np.testing.assert_array_equal(m.perpendicular, mie_rows[:, 6])
    assert (m.q_ext, m.q_sca, m.q_back, m.g) == tuple(float(v) for v in efficiencies)


def test_translucency_same_answer_through_c_and_python():
    """Marble's dipole terms and profile, and the inverse from apple's reflectance
    (arcus_translucency_*), through C and through arcus.translucency: identical doubles
    (not validation: test_translucency.py and ctest's TranslucencyDipole do that)."""
    table = run_c("translucency")
    marble = arcus.translucency.Dipole.from_material("marble")
    for row in rows_named(table, "terms", "translucency"):
        np.testing.assert_array_equal(getattr(marble, row[0]), [float(v) for v in row[1:]], err_msg=row[0])
    rd = np.array([[float(v) for v in row] for row in rows_named(table, "rd", "translucency")])
    np.testing.assert_array_equal(marble.Rd(rd[:, 0]), rd[:, 1:])
    apple = arcus.translucency.Dipole.from_material("apple")
    inverse = arcus.translucency.Dipole.from_reflectance(apple.total_reflectance, apple.diffuse_length, eta=1.3)
    for row in rows_named(table, "inverse", "translucency"):
        np.testing.assert_array_equal(getattr(inverse, row[0]), [float(v) for v in row[1:]], err_msg=row[0])


def test_ocean_same_answer_through_c_and_python(ctx):
    """A preset's water (arcus_bio_optical_preset, arcus_water_create) and its
    coefficients (arcus_water_get_coefficients) through C and through arcus.ocean.Water:
    identical doubles (not validation).  Python copies the preset's struct into its own
    parameters and back, so this also checks that no field is lost on the way."""
    table = run_c("ocean")
    py = arcus.ocean.Water(OCEAN_PRESET).coefficients(grid=OCEAN_GRID, context=ctx)
    assert py["wavelengths"].size == 7
    for name, rows in (("events", 10), ("absorption", 4), ("scattering", 4)):
        c_rows = rows_named(table, name, "ocean")
        assert [int(r[0]) for r in c_rows] == list(range(rows))
        np.testing.assert_array_equal(py[name], np.array([[float(v) for v in r[1:]] for r in c_rows]), err_msg=name)


def test_render_same_answer_through_c_and_python(ctx, tmp_path):
    """One frame of a tiny render scene (arcus_scene_load, arcus_renderer_create,
    arcus_render_frame, arcus_job_get_render_image) through C and through
    Context.render and arcus.render: identical floats, pixel for pixel (not
    validation).  Both render on the default device with the scene's own camera,
    integrator and techniques; a render is deterministic on one device (no random
    numbers without photons, no atomics in the image), so exact equality holds."""
    scene = tmp_path / "c_and_python.json"
    scene.write_text(RENDER_SCENE)
    table = run_c("render", scene)
    assert table[0][0] == "size", ("c_api_dump render printed %r: an old program that ignores its argument? "
                                   "rebuild build/tests/c_api_dump" % (table[:2],))
    width, height = int(table[0][1]), int(table[0][2])
    assert (width, height) == (8, 6)
    c_image = np.array([[float(v) for v in row] for row in table[1:]], dtype=np.float32).reshape(height, width, 3)
    assert np.any(c_image != c_image[0, 0])  # the sphere is in the picture
    result = ctx.render(scene)
    assert result.image.dtype == np.float32
    np.testing.assert_array_equal(result.image, c_image)
    np.testing.assert_array_equal(arcus.render(scene).image, c_image)  # arcus.render: a context of its own
