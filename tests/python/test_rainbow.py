"""arcus.rainbow, arcus.mie and apps/rainbow/arcus_rainbow.py: the phase function's
shapes and normalisation, the geometric rainbow angles (thesis eq. 4.20), errors naming
the parameter, Lorenz–Mie against Bohren & Huffman's worked example and its own
normalisation, the Debye terms, and the command line's files.  Small grids (≤ 400 rays
a side) and few wavelengths keep each test to seconds on two cores."""

import csv
import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import arcus
import arcus.halo as halo
import arcus.mie as mie
import arcus.rainbow as rainbow

TOOL = Path(__file__).resolve().parents[2] / "apps" / "rainbow" / "arcus_rainbow.py"
RADIUS = 500e-6  # m
NM = 650.0
THETA = np.round(np.arange(130.0, 145.0 + 1e-9, 0.05), 10)  # degrees, 301 angles
GRID = 400


def primary_angle(n):
    """Descartes' primary rainbow as a scattering angle, thesis eq. 4.20 [deg]."""
    return 180.0 - 2.0 * math.degrees(math.asin(((4.0 - n * n) / 3.0) ** 1.5 / (n * n)))


@pytest.fixture(scope="module")
def coherent(ctx):
    return rainbow.phase_function(rainbow.Sphere(RADIUS), NM, THETA, grid=GRID, context=ctx)


@pytest.fixture(scope="module")
def incoherent(ctx):
    return rainbow.phase_function(rainbow.Sphere(RADIUS), NM, THETA, grid=GRID, coherent=False, context=ctx)


# ---- refractive index -----------------------------------------------------------------


def test_temperature_in_celsius_is_the_deprecated_spelling_of_temperature_k():
    # arcus 0.9 took °C; the same water through both spellings is the same index.
    with pytest.warns(DeprecationWarning, match="temperature_k"):
        old = rainbow.refractive_index("water", 589.3, temperature=20.0)
    assert old == rainbow.refractive_index("water", 589.3, 20.0 + 273.15)
    with pytest.raises(arcus.ArgumentError, match="temperature_k"):  # 20 read as kelvin: out of range, named
        rainbow.refractive_index("water", 589.3, 20.0)


def test_refractive_index_of_water_and_ice():
    n = rainbow.refractive_index("water", 589.3, 293.15)
    assert 1.3325 < n < 1.3340  # sodium D at 20 °C: 1.3330 (CRC), IAPWS R9-97 within 1e-4
    warm = rainbow.refractive_index("water", 589.3, 353.15)
    assert warm < n - 1e-3  # water's index falls with temperature, faster when warm
    ice = rainbow.refractive_index("ice", [400.0, 589.3, 700.0])
    assert ice.shape == (3,)
    assert np.all(np.diff(ice) < 0)  # normal dispersion
    assert 1.305 < ice[1] < 1.312 and ice[1] < n  # ice Ih at the D line: 1.3098
    with pytest.raises(arcus.ArgumentError, match="wavelength"):
        rainbow.refractive_index("water", 150.0)
    with pytest.raises(arcus.ArgumentError, match="material"):
        rainbow.refractive_index("glass", 550.0)


# ---- the phase function ---------------------------------------------------------------


def test_phase_function_shapes_and_values(coherent):
    r = coherent
    t = THETA.size
    assert r.theta.shape == (t,) and np.array_equal(r.theta, THETA)
    assert r.phi == 0.0
    for name in ("parallel", "perpendicular", "unpolarized", "value"):
        a = getattr(r, name)
        assert a.shape == (t,), name
        assert np.all(np.isfinite(a)) and np.all(a >= 0), name
    assert r.per_bounce.shape == (t, 4)
    assert np.all(np.isfinite(r.per_bounce)) and np.all(r.per_bounce >= 0)
    np.testing.assert_allclose(r.unpolarized, r.parallel + r.perpendicular, rtol=1e-12)
    assert r.value is r.unpolarized and r.polarization == "unpolarized"
    assert r.unpolarized.max() > 0.05  # the primary bow is in range
    assert r.refractive_index == pytest.approx(rainbow.refractive_index("water", NM), rel=1e-12)
    s = r.stats
    assert s["rays"] == GRID * GRID and 0 < s["hits"] <= s["rays"] and s["patches"] > 0
    assert s["patches_rejected"] >= 0 and s["patches_folded"] >= 0
    assert s["scattered"].shape == (4,)
    # Every intercepted ray's power leaves in p = 0..3 or is still inside (absorption-free).
    assert s["scattered"].sum() + s["remaining"] == pytest.approx(1.0, abs=1e-6)
    assert s["intercepted"] == pytest.approx(math.pi * RADIUS ** 2, rel=0.02)


def test_polarization_selects_the_component(ctx, coherent):
    r = rainbow.phase_function(rainbow.Sphere(RADIUS), NM, THETA, grid=GRID, polarization="perpendicular",
                               context=ctx)
    np.testing.assert_array_equal(r.value, r.perpendicular)
    np.testing.assert_allclose(r.unpolarized, coherent.unpolarized, rtol=1e-12)  # deterministic
    # Near the primary bow the light is strongly polarised perpendicular to the plane.
    bow = (THETA > 137.8) & (THETA < 139.0)
    assert r.perpendicular[bow].sum() > 5 * r.parallel[bow].sum()
    with pytest.raises(arcus.ArgumentError, match="polarization"):
        rainbow.phase_function(rainbow.Sphere(RADIUS), NM, THETA, grid=GRID, polarization="circular", context=ctx)


def test_incoherent_terms_add_up(incoherent, coherent):
    r = incoherent
    np.testing.assert_allclose(r.per_bounce.sum(axis=1), r.unpolarized, rtol=1e-9, atol=1e-15)
    np.testing.assert_allclose(r.unpolarized, r.parallel + r.perpendicular, rtol=1e-12)
    # p = 1 (two refractions) turns light by at most ~83°: nothing at 130-145°.
    assert np.all(r.per_bounce[:, 1] == 0)
    # Interference matters: the coherent sum is not the incoherent one.
    assert np.abs(coherent.unpolarized - r.unpolarized).max() > 0.1 * r.unpolarized.max()


def test_geometric_rainbow_angles(ctx):
    """Incoherent, p = 2 is zero on the dark side of Descartes' angle (eq. 4.20) and
    lit right past it; p = 3 likewise for the secondary bow, on its other side."""
    theta = np.round(np.arange(125.0, 145.0 + 1e-9, 0.01), 10)
    r = rainbow.phase_function(rainbow.Sphere(RADIUS), NM, theta, grid=GRID, coherent=False, context=ctx)
    n = r.refractive_index
    primary = primary_angle(n)
    assert primary == pytest.approx(rainbow.rainbow_angle(n, 2), abs=1e-9)
    assert 137.0 < primary < 138.5
    p2 = r.per_bounce[:, 2]
    assert np.all(p2[theta < primary - 0.05] == 0)
    assert np.all(p2[(theta > primary) & (theta <= primary + 0.1)] > 0)
    secondary = rainbow.rainbow_angle(n, 3)
    assert 128.5 < secondary < 130.5
    p3 = r.per_bounce[:, 3]
    assert np.all(p3[theta > secondary + 0.05] == 0)
    assert np.all(p3[(theta < secondary) & (theta >= secondary - 0.1)] > 0)


def test_uniform_caustics_put_the_primary_bow_where_mie_has_it(ctx):
    """At the rainbow angle the rays' plain sum (eq. 4.31, caustics="rays") peaks at the
    geometric caustic; the uniform (Airy) approximation of the same two rays puts the
    primary maximum in Mie's 0.1° bin (means of 0.01° samples, 500 µm at 650 nm)."""
    theta = np.arange(134.005, 142.0, 0.01)
    edges = np.arange(134.0, 142.0 + 1e-9, 0.1)
    centres = 0.5 * (edges[1:] + edges[:-1])

    def binned(y):
        idx = np.digitize(theta, edges) - 1
        return np.array([y[idx == k].mean() for k in range(len(centres))])

    uniform = rainbow.phase_function(rainbow.Sphere(RADIUS), NM, theta, grid=600, context=ctx)
    rays = rainbow.phase_function(rainbow.Sphere(RADIUS), NM, theta, grid=600, caustics="rays", context=ctx)
    m = mie.phase_function(RADIUS, NM, theta, n=uniform.refractive_index)
    peak = lambda y: centres[np.argmax(binned(y))]  # noqa: E731
    assert abs(peak(uniform.unpolarized) - peak(m.unpolarized)) < 0.051
    assert abs(peak(rays.unpolarized) - peak(m.unpolarized)) > 0.25
    assert np.corrcoef(binned(uniform.unpolarized), binned(m.unpolarized))[0, 1] >= 0.95
    with pytest.raises(arcus.ArgumentError, match="caustics"):
        rainbow.phase_function(rainbow.Sphere(RADIUS), NM, theta, grid=16, caustics="airy", context=ctx)


@pytest.mark.heavy
def test_phi_scalar_and_two_dimensional(ctx, incoherent):
    phis = [0.0, 45.0, 90.0]
    r = rainbow.phase_function(rainbow.Sphere(RADIUS), NM, THETA, phi=phis, grid=GRID, coherent=False, context=ctx)
    t = THETA.size
    assert r.theta.shape == (t,) and np.array_equal(r.phi, phis)
    for name in ("parallel", "perpendicular", "unpolarized"):
        assert getattr(r, name).shape == (t, 3), name
    assert r.per_bounce.shape == (t, 3, 4)
    # φ = 0 of the full table is the fast 1-D table (which keeps only that half-plane).
    np.testing.assert_allclose(r.unpolarized[:, 0], incoherent.unpolarized, rtol=1e-9, atol=1e-15)
    assert r.stats["patches"] > incoherent.stats["patches"]
    # A sphere in unpolarised light: the same at every azimuth (to the grid's sampling).
    means = r.unpolarized.mean(axis=0)
    np.testing.assert_allclose(means, means[0], rtol=0.02)
    one = rainbow.phase_function(rainbow.Sphere(RADIUS), NM, THETA, phi=45.0, grid=GRID, coherent=False,
                                 context=ctx)
    assert one.phi == 45.0 and one.unpolarized.shape == (t,)
    np.testing.assert_allclose(one.unpolarized, r.unpolarized[:, 1], rtol=1e-9, atol=1e-15)


def icosphere_obj(path, radius, subdivisions=2):
    """A closed icosphere of ``radius`` (file units) as an OBJ file."""
    t = (1 + 5 ** 0.5) / 2
    v = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t), (0, -1, -t), (0, 1, -t),
         (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    v = [np.array(p, float) / np.linalg.norm(p) for p in v]
    f = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4), (11, 10, 2), (10, 7, 6),
         (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10),
         (8, 6, 7), (9, 8, 1)]
    for _ in range(subdivisions):
        mids, g = {}, []

        def mid(a, b):
            key = (min(a, b), max(a, b))
            if key not in mids:
                m = v[a] + v[b]
                v.append(m / np.linalg.norm(m))
                mids[key] = len(v) - 1
            return mids[key]

        for a, b, c in f:
            ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
            g += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        f = g
    with open(path, "w") as out:
        for p in v:
            out.write("v %.9f %.9f %.9f\n" % tuple(radius * p))
        for a, b, c in f:
            out.write("f %d %d %d\n" % (a + 1, b + 1, c + 1))
    return len(f)


def test_mesh_and_raindrop_particles(ctx, tmp_path):
    path = tmp_path / "ball.obj"
    triangles = icosphere_obj(path, 0.5)  # mm
    ball = rainbow.Mesh(path, scale=1e-3)
    assert ball.smooth is True and "smooth=True" in repr(ball)
    info = ball.info(ctx)
    assert info["kind"] == "mesh" and info["triangles"] == triangles
    assert 0.95 * 0.5e-3 < info["equivalent_radius"] < 0.5e-3  # inscribed polyhedron
    theta = np.arange(100.0, 180.0, 0.5)
    r = rainbow.phase_function(ball, NM, theta, grid=200, max_bounces=2, context=ctx)
    assert "RAINBOW_MESH" in r.features
    assert r.per_bounce.shape == (theta.size, 3)
    assert np.all(np.isfinite(r.unpolarized)) and np.all(r.unpolarized >= 0)
    # The cast intercepts the ball's disc (a little less: the facets cut it).
    assert r.stats["hits"] > 0
    assert r.stats["intercepted"] == pytest.approx(math.pi * 0.5e-3 ** 2, rel=0.1)
    with pytest.raises(arcus.ArgumentError, match="smooth"):
        rainbow.Mesh(path, scale=1e-3, smooth=1)
    drop = rainbow.Raindrop(2e-3)
    assert drop.info(ctx)["equivalent_radius"] == pytest.approx(1e-3, rel=0.01)
    d = rainbow.phase_function(drop, NM, theta, grid=200, context=ctx)
    assert "RAINBOW_IMPLICIT" in d.features and d.unpolarized.max() > 0


def test_smooth_and_flat_icosphere(ctx, repo):
    """data/meshes/icosphere.obj (1280 triangles; its chords depart from the sphere by
    ~0.2 %) read as a smooth surface has a sphere's geometric primary bow: p = 2 starts
    within 0.1° of Descartes' angle for the cast's index.  Read as flat faces, each face
    sequence sends its light into one direction that no patch holds: no p = 2 light in
    the table there (documented, arcus.rainbow.Mesh), though the stats still carry it."""
    path = repo / "data" / "meshes" / "icosphere.obj"
    theta = np.round(np.arange(130.0, 145.0 + 1e-9, 0.01), 10)
    smooth = rainbow.phase_function(rainbow.Mesh(path, scale=1e-3, smooth=True), NM, theta, grid=GRID,
                                    coherent=False, context=ctx)
    primary = rainbow.rainbow_angle(smooth.refractive_index, 2)
    p2 = smooth.per_bounce[:, 2]
    lit = theta[p2 > 0]
    assert lit.size > 0 and abs(lit[0] - primary) < 0.1
    assert p2[theta > primary + 0.1].max() > 0.05
    flat = rainbow.phase_function(rainbow.Mesh(path, scale=1e-3, smooth=False), NM, theta, grid=GRID,
                                  coherent=False, context=ctx)
    assert flat.refractive_index == smooth.refractive_index
    assert np.all(flat.per_bounce[:, 2] == 0)
    assert flat.stats["scattered"][2] == pytest.approx(smooth.stats["scattered"][2], rel=0.3)


@pytest.mark.parametrize("call, match", [
    (lambda c: rainbow.phase_function(rainbow.Sphere(-1e-3), NM, THETA, grid=GRID, context=c), "radius"),
    (lambda c: rainbow.phase_function(rainbow.Raindrop(0.5e-3), NM, THETA, grid=GRID, context=c), "diameter"),
    (lambda c: rainbow.phase_function(rainbow.Sphere(RADIUS), 150.0, THETA, grid=GRID, context=c), "wavelength"),
    (lambda c: rainbow.phase_function(rainbow.Sphere(RADIUS), NM, THETA, grid=2, context=c), "grid"),
    (lambda c: rainbow.phase_function(rainbow.Sphere(RADIUS), NM, THETA, grid=GRID, max_bounces=99, context=c),
     "max_bounces"),
    (lambda c: rainbow.phase_function(rainbow.Sphere(RADIUS), NM, [130.0, 200.0], grid=GRID, context=c), "theta"),
    (lambda c: rainbow.phase_function(rainbow.Sphere(RADIUS), [600.0, 650.0], THETA, grid=GRID, context=c),
     "wavelength"),
    (lambda c: rainbow.phase_function(rainbow.Sphere(RADIUS), NM, THETA, grid=GRID, material="mercury", context=c),
     "material"),
    (lambda c: rainbow.phase_function(rainbow.Sphere(RADIUS), NM, THETA, grid=GRID, rotation=np.diag([1, 1, -1.0]),
                                      context=c), "rotation"),
])
def test_bad_input_names_the_parameter(ctx, call, match):
    with pytest.raises(arcus.ArgumentError, match=match) as info:
        call(ctx)
    assert info.value.status == "ARCUS_ERROR_INVALID_ARGUMENT"


def test_bad_meshes(ctx, tmp_path):
    missing = tmp_path / "nowhere.obj"
    with pytest.raises(arcus.Error, match="nowhere.obj"):
        rainbow.phase_function(rainbow.Mesh(missing), NM, THETA, grid=GRID, context=ctx)
    open_mesh = tmp_path / "triangle.obj"
    open_mesh.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
    with pytest.raises(arcus.ArgumentError, match="not closed") as info:
        rainbow.phase_function(rainbow.Mesh(open_mesh, 1e-3), NM, THETA, grid=GRID, context=ctx)
    assert "3 of its 3 edges" in info.value.message


def _prism_arrays():
    """A hexagonal column (arcus.halo's) with coordinates exact in single precision,
    as the library reads files: the same mesh from arrays and from a file."""
    vertices, triangles = halo.hexagonal_prism(2.0)
    return vertices.astype(np.float32).astype(np.float64), triangles


def test_mesh_from_arrays_is_the_mesh_from_its_file(ctx, tmp_path):
    """Determinism: Mesh.from_arrays and Mesh(path) of the same vertices and triangles
    give the same particle and, cast, the same table, stats and glints, exactly."""
    vertices, triangles = _prism_arrays()
    path = tmp_path / "column.obj"
    path.write_text("".join("v %r %r %r\n" % tuple(float(c) for c in v) for v in vertices)
                    + "".join("f %d %d %d\n" % tuple(int(i) + 1 for i in t) for t in triangles))
    theta = np.arange(0.0, 180.0, 0.5)
    c, s = math.cos(0.4), math.sin(0.4)
    rotation = np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]]) @ np.array([[1.0, 0, 0], [0, c, -s], [0, s, c]])
    for smooth in (True, False):
        from_file = rainbow.Mesh(path, scale=1e-4, smooth=smooth)
        from_arrays = rainbow.Mesh.from_arrays(vertices, triangles, scale=1e-4, smooth=smooth)
        assert from_arrays.info(ctx) == from_file.info(ctx)
        a, b = (rainbow.phase_function(m, NM, theta, grid=64, rotation=rotation, context=ctx)
                for m in (from_file, from_arrays))
        for name in ("parallel", "perpendicular", "per_bounce"):
            np.testing.assert_array_equal(getattr(a, name), getattr(b, name), err_msg=name)
        for key, value in a.stats.items():
            if "seconds" not in key:
                np.testing.assert_array_equal(value, b.stats[key], err_msg=key)
        assert (a.glints is None) == (b.glints is None) == smooth
        for key in a.glints or {}:
            np.testing.assert_array_equal(a.glints[key], b.glints[key], err_msg=key)


def test_mesh_from_arrays_copies_and_checks_its_arrays(ctx):
    """Shapes and types are refused at once, values by the library at first use, each
    naming the array; the arrays are copied."""
    vertices, triangles = _prism_arrays()
    mine = vertices.copy()
    mesh = rainbow.Mesh.from_arrays(mine, triangles.tolist(), scale=1e-4, smooth=False)
    mine[:] = np.nan
    info = mesh.info(ctx)
    assert info["kind"] == "mesh" and info["triangles"] == 20
    assert repr(mesh) == "Mesh.from_arrays(<12 vertices>, <20 triangles>, scale=0.0001, smooth=False)"
    assert mesh.path is None and not mesh.vertices.flags.writeable

    def refused(v, t, match):
        with pytest.raises(arcus.ArgumentError, match=match) as info:
            rainbow.Mesh.from_arrays(v, t, scale=1e-4).info(ctx)
        assert info.value.status == "ARCUS_ERROR_INVALID_ARGUMENT"

    bad = vertices.copy()
    bad[1, 1] = np.nan
    refused(bad, triangles, r"vertices\[4\] = nan is not finite")
    bad = triangles.copy()
    bad[2, 1] = 12
    refused(vertices, bad, r"indices\[7\] = 12 is not below vertex_count 12")
    refused(vertices, np.zeros((0, 3), dtype=int), "triangle_count is 0")
    refused(vertices, triangles[:-1], "the mesh is not closed")
    refused(vertices[:, :2], triangles, r"vertices must have shape \(N, 3\)")
    refused(vertices, triangles.astype(float), "triangles must be an")
    refused(vertices, triangles.ravel(), "triangles must be an")
    bad = triangles.copy()
    bad[0, 1] = -1
    refused(vertices, bad, r"triangles\[0, 1\] = -1 is not a vertex index")
    refused("vertices", triangles, "vertices must be an array of real numbers")
    with pytest.raises(arcus.ArgumentError, match="smooth"):
        rainbow.Mesh.from_arrays(vertices, triangles, smooth=1)


def test_progress_and_cancel(ctx):
    seen = []
    rainbow.phase_function(rainbow.Sphere(RADIUS), NM, THETA, grid=GRID, context=ctx, progress=seen.append)
    assert len(seen) >= 2 and seen == sorted(seen) and 0 < seen[0] < 1 and seen[-1] == 1.0
    # Cancelling after the first slice of rays (400² rays make more than one).
    with pytest.raises(arcus.Error) as info:
        rainbow.phase_function(rainbow.Sphere(RADIUS), NM, THETA, grid=GRID, context=ctx, progress=lambda f: True)
    assert info.value.status == "ARCUS_ERROR_CANCELLED"
    assert np.all(info.value.result.unpolarized == 0)  # the job holds no patches
    with pytest.raises(arcus.ArgumentError, match="progress"):
        rainbow.phase_function(rainbow.Sphere(RADIUS), NM, THETA, grid=GRID, context=ctx, progress=1)


# ---- Lorenz–Mie -----------------------------------------------------------------------


def test_mie_bohren_huffman_example():
    """Bohren & Huffman (1983), Appendix A's BHMIE run: a sphere of radius 0.525 µm,
    m = 1.55, at 0.6328 µm (x = 5.213): Q_sca = Q_ext = 3.1054, Q_back = 2.9253."""
    r = mie.phase_function(0.525e-6, 632.8, [0.0, 90.0, 180.0], n=1.55)
    assert r.size_parameter == pytest.approx(5.2128, abs=1e-4)
    assert r.q_ext == pytest.approx(3.1054, abs=2e-4)
    assert r.q_sca == pytest.approx(3.1054, abs=2e-4)
    assert r.q_back == pytest.approx(2.9253, abs=2e-4)
    assert r.s1.dtype == np.complex128 and r.s1.shape == (3,)
    # Symmetry: S1 = S2 forward, S1 = −S2 backward.
    assert r.s1[0] == pytest.approx(r.s2[0], rel=1e-12)
    assert r.s1[2] == pytest.approx(-r.s2[2], rel=1e-12)
    # Q_back from the amplitudes (4|S(π)|²/x²); the optical theorem gives Q_ext.
    assert r.q_back == pytest.approx(4 * abs(r.s1[2]) ** 2 / r.size_parameter ** 2, rel=1e-9)
    assert r.q_ext == pytest.approx(4 * r.s1[0].real / r.size_parameter ** 2, rel=1e-9)


def test_mie_normalisation_and_water():
    x, nm = 5.0, 500.0
    radius = x * nm * 1e-9 / (2 * math.pi)
    theta = np.linspace(0.0, 180.0, 20001)
    r = mie.phase_function(radius, nm, theta, n=1.33)
    t = np.radians(theta)
    assert np.trapezoid(r.unpolarized * np.sin(t) * 2 * np.pi, t) == pytest.approx(1.0, abs=1e-4)
    np.testing.assert_allclose(r.unpolarized, r.parallel + r.perpendicular, rtol=1e-12)
    xs = r.size_parameter
    np.testing.assert_allclose(r.perpendicular, np.abs(r.s1) ** 2 / (2 * np.pi * xs ** 2 * r.q_sca), rtol=1e-9)
    assert -1 < r.g < 1 and r.q_ext == pytest.approx(r.q_sca, rel=1e-9)  # no absorption
    # n None: water at the wavelength and temperature.
    w = mie.phase_function(radius, nm, [90.0], temperature_k=283.15)
    assert w.n == rainbow.refractive_index("water", nm, 283.15)
    # An absorbing sphere extinguishes more than it scatters.
    a = mie.phase_function(radius, nm, [90.0], n=1.33 + 0.05j)
    assert a.q_ext > 1.05 * a.q_sca
    with pytest.raises(arcus.ArgumentError, match="radius|x"):
        mie.phase_function(-1e-6, nm, [90.0])
    with pytest.raises(arcus.ArgumentError, match="theta"):
        mie.phase_function(radius, nm, [190.0])


def test_debye_terms():
    theta = np.round(np.arange(120.0, 145.0 + 1e-9, 0.05), 10)
    d = mie.debye(RADIUS, NM, theta, max_p=3)
    t = theta.size
    for name in ("parallel", "perpendicular", "unpolarized"):
        a = getattr(d, name)
        assert a.shape == (t, 4) and np.all(np.isfinite(a)) and np.all(a >= 0), name
    assert d.s1.shape == (t, 4) and d.s2.shape == (t, 4) and d.s1.dtype == np.complex128
    np.testing.assert_allclose(d.unpolarized, d.parallel + d.perpendicular, rtol=1e-12)
    n = d.n.real
    primary, secondary = primary_angle(n), rainbow.rainbow_angle(n, 3)
    # The primary bow's term lives on the bright side of eq. 4.20's angle, the
    # secondary's on its own; a degree or two into the dark side each is far fainter
    # (the Airy tail of a 500 µm drop: x ≈ 4800).
    p2, p3 = d.unpolarized[:, 2], d.unpolarized[:, 3]
    assert p2[theta < primary - 1.5].max() < 1e-4 * p2.max()
    assert p3[theta > secondary + 2.0].max() < 1e-3 * p3.max()
    peak = theta[np.argmax(p2)] - primary  # the Airy peak lies just past Descartes' angle
    assert 0 < peak < 1.0
    # p = 1 is not in this range at all (it turns light by ≤ 83°).
    assert d.unpolarized[:, 1].max() < 1e-6 * p2.max()
    with pytest.raises(arcus.ArgumentError, match="max_p"):
        mie.debye(100e-6, NM, theta, max_p=-1)


# ---- the command line -----------------------------------------------------------------


def run_tool(*args):
    return subprocess.run([sys.executable, str(TOOL), *args, "--quiet"], capture_output=True, text=True,
                          timeout=300)


def has_matplotlib():
    try:
        import matplotlib  # noqa: F401
    except ImportError:
        return False
    return True


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def test_cli_table(tmp_path):
    prefix = tmp_path / "out" / "drop"
    extra = ["--plot", str(tmp_path / "bow.png"), "--per-bounce"] if has_matplotlib() else []
    r = run_tool("table", "--particle", "sphere:0.5mm", "--wavelengths", "600", "650", "2", "--theta", "135", "140",
                 "0.05", "--grid", "200", "-o", str(prefix), *extra)
    assert r.returncode == 0, r.stderr
    rows = read_csv(prefix.with_suffix(".csv"))
    assert list(rows[0]) == ["wavelength_nm", "theta_deg", "parallel", "perpendicular", "unpolarized", "p0", "p1",
                             "p2", "p3"]
    assert len(rows) == 2 * 101
    assert {float(row["wavelength_nm"]) for row in rows} == {600.0, 650.0}
    for row in rows[:20]:
        assert float(row["unpolarized"]) == pytest.approx(float(row["parallel"]) + float(row["perpendicular"]),
                                                          rel=1e-8)
    d = np.load(prefix.with_name("drop.npz"))
    assert d["unpolarized"].shape == (2, 101) and d["per_bounce"].shape == (2, 101, 4)
    np.testing.assert_allclose(d["theta"], np.linspace(135, 140, 101))
    np.testing.assert_array_equal(d["wavelength"], [600.0, 650.0])
    np.testing.assert_array_equal(d["phi"], [0.0])
    assert d["refractive_index"][0] > d["refractive_index"][1]  # dispersion
    np.testing.assert_array_equal(np.load(prefix.with_name("drop_unpolarized.npy")), d["unpolarized"])
    # The same numbers as the Python API.
    api = rainbow.phase_function(rainbow.Sphere(5e-4), 650.0, d["theta"], grid=200)
    np.testing.assert_allclose(d["unpolarized"][1], api.unpolarized, rtol=1e-9, atol=1e-15)
    if extra:
        assert (tmp_path / "bow.png").stat().st_size > 10_000
    assert "drop.csv" in r.stdout and "drop.npz" in r.stdout


def test_cli_table_phi(tmp_path):
    prefix = tmp_path / "grid2d"
    r = run_tool("table", "--particle", "sphere:0.5mm", "--wavelengths", "650", "650", "1", "--theta", "136", "140",
                 "0.5", "--phi", "0", "90", "45", "--grid", "100", "-o", str(prefix))
    assert r.returncode == 0, r.stderr
    rows = read_csv(tmp_path / "grid2d.csv")
    assert list(rows[0])[:3] == ["wavelength_nm", "theta_deg", "phi_deg"] and len(rows) == 9 * 3
    d = np.load(tmp_path / "grid2d.npz")
    assert d["unpolarized"].shape == (1, 9, 3) and d["per_bounce"].shape == (1, 9, 3, 4)
    np.testing.assert_array_equal(d["phi"], [0.0, 45.0, 90.0])


def test_cli_mie(tmp_path):
    prefix = tmp_path / "mie"
    r = run_tool("mie", "--particle", "sphere:100um", "--wavelengths", "500", "600", "2", "--theta", "130", "145",
                 "0.1", "--debye", "2", "-o", str(prefix))
    assert r.returncode == 0, r.stderr
    rows = read_csv(tmp_path / "mie.csv")
    assert list(rows[0]) == ["wavelength_nm", "theta_deg", "parallel", "perpendicular", "unpolarized", "p0", "p1",
                             "p2"]
    assert len(rows) == 2 * 151
    d = np.load(tmp_path / "mie.npz")
    assert d["unpolarized"].shape == (2, 151) and d["per_bounce"].shape == (2, 151, 3)
    assert d["q_ext"].shape == (2,) and np.all(np.abs(d["q_ext"] - 2) < 0.05)  # large sphere: extinction paradox
    m = mie.phase_function(100e-6, 600.0, d["theta"])
    np.testing.assert_allclose(d["unpolarized"][1], m.unpolarized, rtol=1e-9)
    assert (tmp_path / "mie_unpolarized.npy").is_file()


def test_cli_mesh_smooth_and_flat(tmp_path, repo):
    """mesh:PATH:SCALE is a smooth surface, mesh:PATH:SCALE:flat flat faces."""
    mesh = repo / "data" / "meshes" / "icosphere.obj"
    p2 = {}
    for suffix in ("", ":flat"):
        prefix = tmp_path / ("ball" + suffix.replace(":", "_"))
        r = run_tool("table", "--particle", "mesh:%s:1e-3%s" % (mesh, suffix), "--wavelengths", "650", "650", "1",
                     "--theta", "137", "140", "0.1", "--grid", "200", "--incoherent", "-o", str(prefix))
        assert r.returncode == 0, r.stderr
        d = np.load(prefix.with_name(prefix.name + ".npz"))
        assert str(d["particle"]) == "mesh:%s:1e-3%s" % (mesh, suffix)
        p2[suffix] = d["per_bounce"][0, :, 2]
    assert p2[""].max() > 0 and np.all(p2[":flat"] == 0)


@pytest.mark.parametrize("args, message", [
    (["table", "--particle", "cube:1mm"], "sphere:RADIUS"),
    (["table", "--particle", "sphere:-1e-3", "--wavelengths", "650", "650", "1", "--grid", "50"], "radius"),
    (["table", "--particle", "sphere:1mm", "--wavelengths", "650", "650", "1", "--grid", "2"], "grid"),
    (["mie", "--particle", "raindrop:2mm", "--wavelengths", "650", "650", "1"], "spheres only"),
])
def test_cli_bad_arguments_exit_nonzero(tmp_path, args, message):
    r = run_tool(*args, "-o", str(tmp_path / "x"))
    assert r.returncode == 2
    assert message in r.stderr
    assert not (tmp_path / "x.csv").exists()


def test_incident_polarisation(ctx):
    """Eq. 4.32-4.34: any incident polarisation from the four phasors.  The two linear
    ones average to the unpolarised phase function (to rounding); for a sphere at φ = 0,
    light polarised in the scattering plane (x) scatters |S2|², so its phase function is
    twice the "parallel" half of the unpolarised one (cross terms vanish by symmetry;
    1e-6 of the peak: the patches' interpolation is not exactly symmetric)."""
    kw = dict(grid=300, context=ctx)
    x = rainbow.phase_function(rainbow.Sphere(RADIUS), NM, THETA, incident=(1, 0), **kw)
    y = rainbow.phase_function(rainbow.Sphere(RADIUS), NM, THETA, incident=(0, 1), **kw)
    np.testing.assert_allclose(0.5 * (x.incident + y.incident), x.unpolarized, rtol=1e-9, atol=1e-15)
    np.testing.assert_allclose(x.incident, 2 * x.parallel, rtol=0, atol=1e-6 * x.incident.max())
    np.testing.assert_allclose(y.incident, 2 * y.perpendicular, rtol=0, atol=1e-6 * y.incident.max())
    circular = rainbow.phase_function(rainbow.Sphere(RADIUS), NM, THETA, incident=(1, 1j), **kw)
    np.testing.assert_allclose(circular.incident, x.unpolarized, rtol=1e-6, atol=1e-6 * x.incident.max())
    assert x.incident.shape == THETA.shape
    with pytest.raises(arcus.ArgumentError, match="incident"):
        rainbow.phase_function(rainbow.Sphere(RADIUS), NM, THETA, incident=(0, 0), **kw)
    with pytest.raises(arcus.ArgumentError, match="incident"):
        rainbow.phase_function(rainbow.Sphere(RADIUS), NM, THETA, incident=(1, 0), coherent=False, **kw)


def test_flat_meshes_give_glints(ctx, repo):
    """A flat-faced icosphere in one orientation: its light is glints whose books per term
    equal the cast's (1e-12 relative) and whose directions are unit vectors; a smooth
    mesh and a sphere have none."""
    path = repo / "data" / "meshes" / "icosphere.obj"
    flat = rainbow.phase_function(rainbow.Mesh(path, scale=1e-3, smooth=False), NM, THETA, grid=200, context=ctx)
    g = flat.glints
    assert g is not None and len(g["term"]) > 10
    np.testing.assert_allclose(np.linalg.norm(g["direction"], axis=1), 1, atol=1e-12)
    for p in range(flat.max_bounces + 1):
        books = g["cross_section"][g["term"] == p].sum() / flat.stats["intercepted"]
        np.testing.assert_allclose(books, flat.stats["scattered"][p], rtol=1e-12)
    assert rainbow.phase_function(rainbow.Sphere(RADIUS), NM, THETA, grid=64, context=ctx).glints is None
    assert rainbow.phase_function(rainbow.Mesh(path, scale=1e-3), NM, THETA, grid=64, context=ctx).glints is None


@pytest.mark.heavy
def test_raindrop_tables_stay_finite_where_a_ray_leaves_degenerate(ctx):
    # A 2 mm raindrop under an 8° sun at 380 nm: a few rays of p = 2 leave with a
    # non-finite direction near grazing; their patches must be left out, not turn the
    # table to NaN (a 2-D sky table once held NaN at θ 164°, φ 60°/120°).
    from arcus import sky
    r = rainbow.phase_function(rainbow.Raindrop(2e-3), 380.0, [164.0, 164.05], [60.0, 120.0], grid=1000,
                               rotation=sky.upright_rotation(8.0), context=ctx)
    assert np.all(np.isfinite(r.unpolarized)) and np.all(r.unpolarized > 0)
