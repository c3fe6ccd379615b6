"""arcus.translucency.render and `arcus bssrdf render`: the image of a wide slab against
the closed form written here (eq. 3.6–3.8 at normal incidence), a mesh from memory and
from a file alike, the outputs following their names, progress and cancellation, and bad
input as ArgumentError (Python) or exit status 2 (the command) naming what is wrong."""

import os
import subprocess
import sys

import numpy as np
import pytest

import arcus
from arcus import image
from arcus.translucency import Dipole, read_mesh, render

from conftest import BINDINGS
from test_translucency import reference_fresnel


def box(lo, hi):
    """The box [lo, hi]: 8 vertices, 12 triangles wound outwards."""
    v = np.array([[hi[0] if k & 1 else lo[0], hi[1] if k & 2 else lo[1], hi[2] if k & 4 else lo[2]]
                  for k in range(8)], float)
    quads = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    t = np.array([tri for a, b, c, d in quads for tri in ((a, b, c), (a, c, d))], np.uint32)
    return v, t


def write_off(path, vertices, triangles):
    with open(path, "w") as f:
        f.write("OFF\n%d %d 0\n" % (len(vertices), len(triangles)))
        for p in vertices:
            f.write("%r %r %r\n" % tuple(float(x) for x in p))
        for t in triangles:
            f.write("3 %d %d %d\n" % tuple(t))


MEDIUM = Dipole([0.1, 0.2, 0.4], [2.0, 2.5, 3.0], 1.3)
SLAB = box((-20, -20, -10), (20, 20, 0))
LOOKING_DOWN = {"position": (0, 0, 50), "look_at": (0, 0, 0), "up": (0, 1, 0), "width": 4, "height": 4}


def closed_total(sigma_a, sigma_s_prime, eta):
    """R_total in closed form (Jensen et al. 2001), from the paper's definitions."""
    albedo = sigma_s_prime / (sigma_a + sigma_s_prime)
    f_dr = -1.440 / eta**2 + 0.710 / eta + 0.668 + 0.0636 * eta
    a = (1 + f_dr) / (1 - f_dr)
    s = np.sqrt(3 * (1 - albedo))
    return albedo / 2 * (1 + np.exp(-4 / 3 * a * s)) * np.exp(-s)


def test_a_wide_slab_shows_the_closed_form_at_its_centre(ctx):
    # 40 × 40 × 10 mm, diffusion lengths 0.5–1.3 mm: the profile's tail beyond the slab
    # is below e^-16 of R_total; the lattice of samples stands for the integral to 1e-4
    # (tests/test_translucency_render.cpp): 1e-3 holds both.
    r = render(MEDIUM, SLAB, [((0, 0, 1), 2.0)], LOOKING_DOWN, ortho_height=0.4, highlight_deg=0,
               gather="brute_force", context=ctx)
    t = 1 - reference_fresnel(1.0, 1.0, MEDIUM.eta)
    expected = 2.0 * t * t / np.pi * closed_total(MEDIUM.sigma_a, MEDIUM.sigma_s_prime, MEDIUM.eta)
    assert r.image.shape == (4, 4, 3) and r.covered.all()
    np.testing.assert_allclose(r.image, np.broadcast_to(expected, (4, 4, 3)), rtol=1e-3)
    assert r.features == {"TRANSLUCENCY_DIPOLE"}
    normalized = render(MEDIUM, SLAB, [((0, 0, 1), 2.0)], LOOKING_DOWN, ortho_height=0.4, highlight_deg=0,
                        gather="brute_force", exit="normalized", context=ctx)
    np.testing.assert_allclose(normalized.image * MEDIUM.exit_transmittance, r.image, rtol=1e-5)


def test_a_mesh_file_and_its_arrays_render_bit_for_bit_alike(ctx, tmp_path):
    # A determinism test: the same triangles from an OFF file and from memory.
    v, t = box((-1, -1, -1), (1, 1, 1))
    write_off(tmp_path / "cube.off", v, t)
    rv, rt = read_mesh(tmp_path / "cube.off", context=ctx)
    np.testing.assert_array_equal(rv, v)
    np.testing.assert_array_equal(rt, t)
    camera = {"position": (3, 4, 5), "look_at": (0, 0, 0), "width": 24, "height": 16}
    lights = [((1, 2, 3), (1.0, 0.9, 0.8))]
    a = render(MEDIUM, tmp_path / "cube.off", lights, camera, mm_per_unit=5, context=ctx)
    b = render(MEDIUM, (v, t), lights, camera, mm_per_unit=5, context=ctx)
    np.testing.assert_array_equal(a.image, b.image)
    assert a.image.shape == (16, 24, 3) and 0 < a.covered.sum() < 16 * 24
    assert a.stats["samples"] == b.stats["samples"] > 0
    assert a.features == {"TRANSLUCENCY_DIPOLE", "TRANSLUCENCY_HIERARCHICAL"}


def test_outputs_follow_their_names(ctx, tmp_path):
    v, t = box((-1, -1, -1), (1, 1, 1))
    camera = {"position": (3, 4, 5), "look_at": (0, 0, 0), "width": 20, "height": 20}
    r = render(MEDIUM, (v, t), [((1, 2, 3), 1.0)], camera, mm_per_unit=5,
               out=[tmp_path / "c.exr", tmp_path / "c.png"], context=ctx)
    exr, png = image.read(tmp_path / "c.exr"), image.read(tmp_path / "c.png")
    np.testing.assert_array_equal(exr, r.image)  # EXR keeps the radiance
    assert png.max() > 0.5  # PNG: exposed, so the object is not near black


def test_progress_is_reported_and_can_cancel(ctx):
    v, t = box((-1, -1, -1), (1, 1, 1))
    camera = {"position": (3, 4, 5), "look_at": (0, 0, 0), "width": 64, "height": 64}
    seen = []
    render(MEDIUM, (v, t), [((1, 2, 3), 1.0)], camera, mm_per_unit=5, progress=seen.append, context=ctx)
    assert seen and seen[-1] == pytest.approx(1.0) and seen == sorted(seen)
    with pytest.raises(arcus.Error) as info:
        render(MEDIUM, (v, t), [((1, 2, 3), 1.0)], camera, mm_per_unit=5, progress=lambda f: True, context=ctx)
    assert info.value.status == "ARCUS_ERROR_CANCELLED"


@pytest.mark.parametrize("kwargs, words", [
    ({"lights": []}, ["lights"]),
    ({"lights": [((0, 0, 0), 1.0)]}, ["lights[0].direction"]),
    ({"lights": [((0, 0, 1), (1, -1, 1))]}, ["lights[0].irradiance[1]"]),
    ({"camera": {"fov": 30}}, ["camera", "fov"]),
    ({"camera": {"width": 0}}, ["camera['width']"]),
    ({"exit": "fancy"}, ["exit", "normalized"]),
    ({"gather": "octree"}, ["gather", "brute_force"]),
    ({"mm_per_unit": -1}, ["mm_per_unit"]),
    ({"highlight_deg": 95}, ["highlight_deg"]),
    ({"sample_spacing_mm": 1e-5}, ["sample_spacing_mm", "samples"]),
    ({"mesh": "no_such_mesh.ply"}, ["no_such_mesh.ply"]),
    ({"mesh": (np.zeros((3, 3)), np.array([[0, 1, 7]]))}, ["indices"]),
    ({"dipole": "marble"}, ["dipole"]),
])
def test_bad_input_is_refused_naming_it(ctx, kwargs, words):
    args = {"dipole": MEDIUM, "mesh": box((-1, -1, -1), (1, 1, 1)), "lights": [((0, 0, 1), 1.0)],
            "camera": None}
    args.update(kwargs)
    with pytest.raises(arcus.Error) as info:
        render(args.pop("dipole"), args.pop("mesh"), args.pop("lights"), args.pop("camera"), context=ctx, **args)
    for word in words:
        assert word in str(info.value), (word, str(info.value))


def arcus_command(*args, cwd):
    env = dict(os.environ, PYTHONPATH=str(BINDINGS))
    return subprocess.run([sys.executable, "-m", "arcus.cli", *args], cwd=cwd, env=env, capture_output=True,
                          text=True, timeout=600)


@pytest.mark.end_to_end
def test_the_command_renders_a_bundled_mesh_from_anywhere(tmp_path):
    r = arcus_command("bssrdf", "render", "torus", "--material", "skin1", "--quick", "-o", "t.png", "-o", "t.exr",
                      "--quiet", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    assert image.read(tmp_path / "t.png").shape == (64, 64, 3)
    assert image.read(tmp_path / "t.exr").max() > 0
    assert "irradiance samples" in r.stdout


@pytest.mark.end_to_end
@pytest.mark.parametrize("args, words", [
    (["no_such_mesh"], ["no_such_mesh", "torus"]),
    (["torus", "--material", "jelly"], ["jelly", "marble"]),
    (["torus", "--light", "0", "1"], ["--light"]),
    (["torus", "-o", "x.gif"], ["x.gif"]),
    (["torus", "--sigma-a", "1", "1", "1"], ["--sigma-s-prime"]),
])
def test_the_commands_bad_input_exits_2(tmp_path, args, words):
    r = arcus_command("bssrdf", "render", *args, "--quiet", cwd=tmp_path)
    assert r.returncode == 2, (r.returncode, r.stderr)
    for word in words:
        assert word in r.stderr, (word, r.stderr)
