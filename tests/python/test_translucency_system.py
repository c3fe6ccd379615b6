"""The estimate's linear system (thesis eq. 3.16–3.18) against float64 NumPy and SciPy
written here: A assembled from the sources the job reports, pair by pair, for the
piecewise-constant and Haar families (whose functions are constant on the kernel's fine
distance bins, so the sums are exact); the weights against a dense SVD least-squares
solve (numpy.linalg.lstsq), a dense ridge solve and SciPy's non-negative least squares;
and Table 3.2's five families all re-rendering the photo they came from."""

import numpy as np
import pytest
from scipy.optimize import nnls

from arcus.translucency import BASIS_FAMILIES, Dipole, estimate_bssrdf, render

from test_translucency_render import SPHERE, SPHERE_LIGHTS

VIEW = {"position": (0, 0, 5), "look_at": (0, 0, 0), "width": 48, "height": 48}
TRUTH = Dipole.from_material("wholemilk")  # Table 3.2's material


@pytest.fixture(scope="module")
def photo():
    return render(TRUTH, SPHERE, SPHERE_LIGHTS, VIEW, ortho_height=2.2, mm_per_unit=20, highlight_deg=0).image


def estimate(photo, **kwargs):
    return estimate_bssrdf(photo, SPHERE, SPHERE_LIGHTS, VIEW, ortho_height=2.2, mm_per_unit=20,
                           subtract_minimum=False, keep_system=True, **kwargs)


def reference_basis(family, m, x):
    """B_h(x) for x = r / r_max in [0, 1): the definitions of basis.h, written again."""
    if family == "piecewise_constant":
        return (np.floor(x * m)[:, None] == np.arange(m)).astype(float)
    b = np.empty((len(x), m))
    b[:, 0] = 1
    for h in range(1, m):
        level = int(np.floor(np.log2(h)))
        width = 2.0 ** -level
        start = (h - 2 ** level) * width
        inside = (x >= start) & (x < start + width)
        b[:, h] = np.where(inside, np.where(x < start + width / 2, 1.0, -1.0), 0.0)
    return b


# Haar's assembly is the same code with other basis values (tests/unit's basis suite runs
# them instrumented): heavy, left out of the sanitizer run.
@pytest.mark.parametrize("family", ["piecewise_constant", pytest.param("haar", marks=pytest.mark.heavy)])
def test_the_assembly_equals_numpy_pair_by_pair(photo, family):
    m = 16
    e = estimate(photo, basis=m, family=family)
    s = e.system
    r_max, rho = e.profile[0][-1], s["near_radius_mm"]
    for c in range(3):
        # eq. 3.16 over the sources beyond ρ — out to the refined radius the back points
        # and the front points' sub-pixels, beyond it every pixel's front and back
        # point — plus the row's own irradiance over the disc within ρ: ∫₀^ρ 2πr B_h(r) dr,
        # exact over rings r_max/256 wide (on which both families at m = 16 are
        # constant), the last one ending at ρ.
        refined = s["refined_radius_mm"]
        back = np.arange(len(s["sources"])) >= len(s["sources"]) // 2
        r = np.linalg.norm(s["rows"][:, None, :] - s["sources"][None, :, :], axis=2)
        keep = (r >= refined) & (r < r_max) | (r >= rho) & (r < refined) & back
        r_sub = np.linalg.norm(s["rows"][:, None, :] - s["sub_sources"][None, :, :], axis=2)
        keep_sub = (r_sub >= rho) & (r_sub < refined)
        a = np.zeros((len(r), m))
        for i in range(len(r)):
            a[i] = s["source_weights"][keep[i], c] @ reference_basis(family, m, r[i, keep[i]] / r_max)
            a[i] += (s["sub_source_weights"][keep_sub[i], c]
                     @ reference_basis(family, m, r_sub[i, keep_sub[i]] / r_max))
        rings = np.union1d(np.arange(0, rho, r_max / 256), [rho])
        middles = 0.5 * (rings[1:] + rings[:-1]) / r_max
        disc = (np.pi * np.diff(rings ** 2)) @ reference_basis(family, m, middles)
        a += s["near_irradiance"][:, c:c + 1] * disc
        # Both sum the same doubles in another order: 1e-5 of the largest entry allows
        # for that and for a pair within rounding of a bin's edge, and nothing more.
        np.testing.assert_allclose(s["A"][c], a, rtol=0, atol=1e-5 * np.abs(a).max())


def test_the_weights_are_the_dense_svd_least_squares_solution(photo):
    e = estimate(photo)
    s = e.system
    for c in range(3):
        x_svd, *_ = np.linalg.lstsq(s["A"][c], s["b"][c], rcond=None)
        # QMR stops at a relative residual of 1e-12 on AᵀA x = Aᵀb; the forward error
        # is at most cond(AᵀA) (~1e6 here) times that, relative to |x|.
        bound = 10 * e.condition["AtA"][c] * 1e-12
        assert np.linalg.norm(s["x"][c] - x_svd) <= bound * np.linalg.norm(x_svd), c


def test_tikhonov_is_the_dense_ridge_solution(photo):
    e = estimate(photo, tikhonov=1e-3)
    s = e.system
    for c in range(3):
        a, b = s["A"][c], s["b"][c]
        normal = a.T @ a
        ridge = normal + 1e-3 * np.mean(np.diag(normal)) * np.eye(len(normal))
        x = np.linalg.solve(ridge, a.T @ b)
        np.testing.assert_allclose(s["x"][c], x, rtol=1e-6, atol=1e-9 * np.abs(x).max())


def test_nonnegative_weights_are_scipys_nnls(photo):
    e = estimate(photo, nonnegative=True)
    s = e.system
    for c in range(3):
        # Columns scaled to unit norm for SciPy (the optimum's support does not change).
        a, b = s["A"][c], s["b"][c]
        norms = np.linalg.norm(a, axis=0)
        x, _ = nnls(a / norms, b)
        x /= norms
        # The near field's two columns are nearly parallel, so optima that share weight
        # between them differently cost the same: compare the costs, not the weights
        # (as close as the two solvers' tolerances allow: 1e-9 relative).
        assert (s["x"][c] >= 0).all()
        cost, scipy_cost = np.linalg.norm(a @ s["x"][c] - b), np.linalg.norm(a @ x - b)
        assert abs(cost - scipy_cost) <= 1e-9 * scipy_cost, (c, cost, scipy_cost)
        assert (s["x"][c] == 0).sum() >= 1  # the constraint binds: something was clamped


@pytest.mark.parametrize("family", sorted(BASIS_FAMILIES))
def test_every_family_re_renders_its_photo(photo, family):
    # Table 3.2's families at 10 functions: each reproduces the photo's equation pixels
    # within 3% mean absolute error (the thesis measured 2.7–3.2% for whole milk at 10;
    # measured here 0.7–1.1%), and the reported family is the one asked for.
    e = estimate(photo, basis=10, family=family)
    assert (e.solve["image_error"] < 0.03).all(), e.solve["image_error"]
    assert e.solve["dropped_columns"].sum() == 0
