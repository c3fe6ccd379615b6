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
    # §5.2's blend of two materials, through a tabulated profile.
    r = arcus_command("bssrdf", "render", "torus", "--blend", "skimmilk", "0.3", "--blend", "apple", "0.7", "--quick",
                      "-o", "b.exr", "--quiet", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    assert image.read(tmp_path / "b.exr").max() > 0


@pytest.mark.end_to_end
@pytest.mark.parametrize("args, words", [
    (["no_such_mesh"], ["no_such_mesh", "torus"]),
    (["torus", "--material", "jelly"], ["jelly", "marble"]),
    (["torus", "--light", "0", "1"], ["--light"]),
    (["torus", "-o", "x.gif"], ["x.gif"]),
    (["torus", "--sigma-a", "1", "1", "1"], ["--sigma-s-prime"]),
    (["torus", "--blend", "apple", "half"], ["--blend", "half"]),
    (["torus", "--blend", "apple", "1", "--blend", "marble", "1"], ["eta"]),
])
def test_the_commands_bad_input_exits_2(tmp_path, args, words):
    r = arcus_command("bssrdf", "render", *args, "--quiet", cwd=tmp_path)
    assert r.returncode == 2, (r.returncode, r.stderr)
    for word in words:
        assert word in r.stderr, (word, r.stderr)


# ---- estimation from a photograph ---------------------------------------------------


def icosphere(levels):
    """A unit icosphere with shared vertices (each edge's midpoint made once)."""
    p = (1 + 5 ** 0.5) / 2
    v = [np.array(x, float) / np.linalg.norm(x) for x in
         [[-1, p, 0], [1, p, 0], [-1, -p, 0], [1, -p, 0], [0, -1, p], [0, 1, p], [0, -1, -p], [0, 1, -p],
          [p, 0, -1], [p, 0, 1], [-p, 0, -1], [-p, 0, 1]]]
    t = [[0, 11, 5], [0, 5, 1], [0, 1, 7], [0, 7, 10], [0, 10, 11], [1, 5, 9], [5, 11, 4], [11, 10, 2], [10, 7, 6],
         [7, 1, 8], [3, 9, 4], [3, 4, 2], [3, 2, 6], [3, 6, 8], [3, 8, 9], [4, 9, 5], [2, 4, 11], [6, 2, 10],
         [8, 6, 7], [9, 8, 1]]
    for _ in range(levels):
        made, nt = {}, []

        def mid(a, b):
            key = (min(a, b), max(a, b))
            if key not in made:
                m = v[a] + v[b]
                v.append(m / np.linalg.norm(m))
                made[key] = len(v) - 1
            return made[key]
        for a, b, c in t:
            ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
            nt += [[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]
        t = nt
    return np.array(v), np.array(t, np.uint32)


SPHERE = icosphere(4)
SPHERE_LIGHTS = [((0.3, 0.5, 1), 1.0), ((-1, 0.2, 0.3), 0.3)]
SPHERE_VIEW = {"position": (0, 0, 5), "look_at": (0, 0, 0), "width": 120, "height": 120}


@pytest.mark.heavy
def test_an_estimate_recovers_skim_milk_from_its_render(ctx):
    # A 40 mm sphere of skim milk rendered through the dipole and estimated back
    # (tests/test_translucency_estimate.cpp has the 200-pixel version and its bounds):
    # at 120 pixels, R_total within 3% and ℓ_d within 15% (measured 0.4–0.9%, 3–5%).
    truth = Dipole.from_material("skimmilk")
    photo = render(truth, SPHERE, SPHERE_LIGHTS, SPHERE_VIEW, ortho_height=2.2, mm_per_unit=20, highlight_deg=0,
                   context=ctx)
    est = arcus.translucency.estimate_bssrdf(photo.image, SPHERE, SPHERE_LIGHTS, SPHERE_VIEW, ortho_height=2.2,
                                            mm_per_unit=20, subtract_minimum=False, context=ctx)
    np.testing.assert_allclose(est.dipole.total_reflectance, truth.total_reflectance, rtol=0.03)
    np.testing.assert_allclose(est.dipole.diffuse_length, truth.diffuse_length, rtol=0.15)
    edges, weights = est.profile
    assert edges.shape == (25,) and weights.shape == (24, 3) and edges[-1] == pytest.approx(40, rel=1e-6)
    assert (est.condition["A"] > 1).all() and set(est.timings) == {"geometry", "histograms", "solve", "total"}
    assert est.pixels["equations"] <= est.pixels["object"] <= 120 * 120
    assert est.features == {"TRANSLUCENCY_HISTOGRAM"}


def test_an_hdr_file_is_read_and_an_8_bit_one_refused(ctx, tmp_path):
    truth = Dipole.from_material("skimmilk")
    view = dict(SPHERE_VIEW, width=48, height=48)
    photo = render(truth, SPHERE, SPHERE_LIGHTS, view, ortho_height=2.2, mm_per_unit=20, highlight_deg=0,
                   out=[tmp_path / "p.exr", tmp_path / "p.png"], context=ctx)
    from_file = arcus.translucency.estimate_bssrdf(tmp_path / "p.exr", SPHERE, SPHERE_LIGHTS, view, ortho_height=2.2,
                                                  mm_per_unit=20, context=ctx)
    from_array = arcus.translucency.estimate_bssrdf(photo.image, SPHERE, SPHERE_LIGHTS, view, ortho_height=2.2,
                                                   mm_per_unit=20, context=ctx)
    np.testing.assert_array_equal(from_file.dipole.sigma_a, from_array.dipole.sigma_a)  # EXR keeps the floats
    with pytest.raises(arcus.ArgumentError, match="8-bit"):
        arcus.translucency.estimate_bssrdf(tmp_path / "p.png", SPHERE, SPHERE_LIGHTS, view, context=ctx)


@pytest.mark.parametrize("change, words", [
    (lambda p: np.full_like(p, 0.5), ["clipped"]),
    (lambda p: np.where(np.arange(p.size).reshape(p.shape) == 100, np.nan, p), ["photo[100]", "pixel 1, 1", "not a finite"]),
    (lambda p: p - 1.0, ["not a finite radiance >= 0"]),
])
def test_bad_photos_are_refused_naming_why(ctx, change, words):
    view = dict(SPHERE_VIEW, width=32, height=32)
    photo = render(Dipole.from_material("skimmilk"), SPHERE, SPHERE_LIGHTS, view, ortho_height=2.2, mm_per_unit=20,
                   context=ctx).image
    with pytest.raises(arcus.ArgumentError) as info:
        arcus.translucency.estimate_bssrdf(change(photo), SPHERE, SPHERE_LIGHTS, view, ortho_height=2.2,
                                           mm_per_unit=20, context=ctx)
    for word in words:
        assert word in str(info.value), (word, str(info.value))


def test_a_misaligned_matte_and_an_open_mesh_are_refused(ctx):
    view = dict(SPHERE_VIEW, width=32, height=32)
    photo = render(Dipole.from_material("skimmilk"), SPHERE, SPHERE_LIGHTS, view, ortho_height=2.2, mm_per_unit=20,
                   context=ctx).image
    matte = np.zeros((32, 32), bool)
    matte[:, :12] = True
    with pytest.raises(arcus.ArgumentError, match="IoU"):
        arcus.translucency.estimate_bssrdf(photo, SPHERE, SPHERE_LIGHTS, view, ortho_height=2.2, mm_per_unit=20,
                                           matte=matte, context=ctx)
    with pytest.raises(arcus.ArgumentError, match="closed"):
        arcus.translucency.estimate_bssrdf(photo, (SPHERE[0], SPHERE[1][1:]), SPHERE_LIGHTS, view, ortho_height=2.2,
                                           mm_per_unit=20, context=ctx)


@pytest.mark.end_to_end
def test_the_command_estimates_what_it_rendered(tmp_path):
    write_off(tmp_path / "sphere.off", *SPHERE)
    view = ["--ortho-height", "2.2", "--mm-per-unit", "20", "--light", "0.3", "0.5", "1", "--light", "-1", "0.2",
            "0.3", "0.3", "--quiet"]
    r = arcus_command("bssrdf", "render", "sphere.off", "--material", "apple", "--highlight", "0", "--width", "96",
                      "--height", "96", "-o", "photo.exr", "-o", "photo.png", *view, cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    r = arcus_command("bssrdf", "estimate", "photo.exr", "--mesh", "sphere.off", "--compare", "cmp", *view,
                      cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    assert "R_total" in r.stdout and "cond(A)" in r.stdout
    strip = image.read(tmp_path / "cmp" / "compare.png")
    assert strip.shape == (96, 3 * 96, 3)
    assert (tmp_path / "cmp" / "profile.png").stat().st_size > 1000
    r = arcus_command("bssrdf", "estimate", "photo.png", "--mesh", "sphere.off", *view, cwd=tmp_path)
    assert r.returncode == 2 and "8-bit" in r.stderr, r.stderr
    r = arcus_command("bssrdf", "estimate", "photo.exr", "--mesh", "sphere.off", "--family", "legendre", "--basis",
                      "12", "--nonnegative", "--tikhonov", "1e-4", "--fit", "hermite", "--compare", "hermite",
                      *view, cwd=tmp_path)
    assert r.returncode == 0 and "12 legendre functions" in r.stdout and "image error" in r.stdout, r.stderr
    assert "Hermite R_total" in r.stdout and image.read(tmp_path / "hermite" / "compare.png").shape == (96, 288, 3)
    r = arcus_command("bssrdf", "estimate", "photo.exr", "--mesh", "sphere.off", "--tikhonov", "-1", *view,
                      cwd=tmp_path)
    assert r.returncode == 2 and "tikhonov" in r.stderr, r.stderr


@pytest.mark.end_to_end
def test_the_command_estimates_from_the_photo_alone(tmp_path):
    """arcus bssrdf estimate PHOTO --auto: the light found and printed, the shape and the
    re-render written; a mesh or light beside --auto, or an 8-bit photo's codes, are
    refused or warned of on the command line."""
    write_off(tmp_path / "sphere.off", *SPHERE)
    r = arcus_command("bssrdf", "render", "sphere.off", "--material", "apple", "--highlight", "0", "--width", "80",
                      "--height", "80", "--ortho-height", "2.6", "--mm-per-unit", "20", "--light", "-0.5", "0.4", "0.7",
                      "-o", "photo.exr", "-o", "photo.png", "--quiet", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    r = arcus_command("bssrdf", "estimate", "photo.exr", "--auto", "--mm-per-pixel", "0.65", "--compare", "out",
                      "--quiet", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    assert "1 light:" in r.stdout and "Hermite R_total" in r.stdout, r.stdout
    for name in ("compare.png", "profile.png", "depth.exr", "normals.png", "relief.obj"):
        assert (tmp_path / "out" / name).stat().st_size > 500, name
    assert image.read(tmp_path / "out" / "depth.exr").max() > 10  # pixels: a sphere ~30 pixels in radius
    r = arcus_command("bssrdf", "estimate", "photo.exr", "--auto", "--mesh", "sphere.off", cwd=tmp_path)
    assert r.returncode == 2 and "give neither --mesh nor --light" in r.stderr, r.stderr
    r = arcus_command("bssrdf", "estimate", "photo.exr", cwd=tmp_path)
    assert r.returncode == 2 and "--auto" in r.stderr, r.stderr
    r = arcus_command("bssrdf", "estimate", "photo.png", "--auto", "--quiet", cwd=tmp_path)
    assert "warning: photo: photo.png is an 8-bit image" in r.stderr, r.stderr
    assert r.returncode == 2 and "clipped?" in r.stderr, r.stderr  # the PNG's exposure clips the highlight
