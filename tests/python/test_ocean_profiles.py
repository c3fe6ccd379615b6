"""The ocean engine's Monte Carlo irradiance profiles against the independent
discrete-ordinates reference (arcus.discrete_ordinates), for elastic scattering.

Every configuration is monochromatic (grid (550, 550, 1): one 1 nm band, so the
profiles are per unit incident plane irradiance) and Raman-free (``from_iops`` default).

How the comparison is made
--------------------------
* Monte Carlo error.  Each configuration is traced as B independent batches (seeds
  ``seed0 .. seed0 + B - 1``); the estimate is the mean of the batch results and its
  standard error SE the standard deviation of the batch results / sqrt(B).  A photon
  crosses a plane any number of times, so a binomial bound would not be honest for
  E_d / E_u and none exists for the track-length E_0; the batch spread needs no
  assumption.  B = 16 (not 4) so that SE itself is known to about +-18 %: with 4
  batches the SE estimate has 3 degrees of freedom and |t| > 4 happens for ~3 % of the
  points by chance alone, i.e. some point of every profile.
* Tolerance.  |MC - ref| < 4 SE + ref_error + 1e-12 (1 + |ref|), where

  - 4 SE: with SE from 16 batches (15 degrees of freedom) a 4-SE deviation has a chance
    of ~1e-3 per point; the seeds are fixed, so the test is deterministic anyway;
  - ref_error: the reference's own error, |ref(streams=32) - ref(streams=64)| (its
    discretisation; 1e-6 .. 1e-10 relative here), plus for E_0 the error of the 12-point
    Gauss rule that averages the reference over the tally's layer (|12-point -
    24-point|).  E_0 from the engine is a track length in a layer of thickness
    ``layer`` about the depth, clipped to the water, divided by the clipped thickness,
    i.e. the layer average of E_0, so the reference is averaged over exactly the same
    interval and no layer bias is left to tolerate;
  - 1e-12: rounding where SE is 0 (E_d(0) without an interface is exactly the beam).

* Fluxes.  The energy the engine tallies as absorbed (and escaped, and taken by the
  bottom) is compared the same way with the reference's closed-form integrals.

* The isotropic, high-albedo case (a = 0.02, b = 0.5 /m, omega = 0.96): a photon
  scatters ~25 times on average; the interaction limit is set to 5000, past which
  0.96^5000 of the energy could remain (nothing, in double precision), and the test
  checks that nothing was carried past it.

* E_u(0) without an interface: every photon that escapes crosses the depth-0 plane
  upward exactly once, so E_u(0) equals the escaped power photon for photon
  (``test_upwelling_at_an_open_top_counts_every_escaping_photon``, exact to rounding).
"""

import math
import time

import numpy as np
import pytest

import arcus.ocean as ocean

import arcus.discrete_ordinates as ref
import arcus.ocean_reference as elastic

GRID = (550.0, 550.0, 1.0)
BATCHES = 16
OPEN_TOP = ((-math.inf, -math.inf, -math.inf), (math.inf, math.inf, 0.0))   # the box of profile(surface=False)
QUANTITIES = ("Ed", "Eu", "E0")


# ------------------------------------------------------------------------ helpers

def _batch_stats(rows):
    """Mean and standard error (batch spread / sqrt(B)) over axis 0."""
    rows = np.asarray(rows, dtype=float)
    return rows.mean(axis=0), rows.std(axis=0, ddof=1) / math.sqrt(rows.shape[0])


def _reference(a, b, phase, depths, layer, bottom_depth=math.inf, **kw):
    """The reference at ``depths``: E_d, E_u at the planes, E_0 averaged over the same
    (clipped) layer as the engine's tally, the fluxes, and each one's own error."""
    depths = np.asarray(depths, dtype=float)

    def solve(streams, order):
        out = ref.solve_profile(a, b, phase, depths, streams=streams, bottom_depth=bottom_depth, **kw)
        x, w = np.polynomial.legendre.leggauss(order)
        lo = np.maximum(depths - 0.5 * layer, 0.0)
        hi = np.minimum(depths + 0.5 * layer, bottom_depth)
        nodes = (lo[:, None] + 0.5 * (hi - lo)[:, None] * (x[None, :] + 1.0)).ravel()
        e0 = ref.solve_profile(a, b, phase, nodes, streams=streams, bottom_depth=bottom_depth, **kw)["E0"]
        out["E0_layer"] = 0.5 * (e0.reshape(depths.size, order) @ w)
        return out

    base, fine, gauss = solve(32, 12), solve(64, 12), solve(32, 24)
    res = dict(Ed=base["Ed"], Eu=base["Eu"], E0=base["E0_layer"], Kd=ref.kd_between(depths, base["Ed"]))
    err = dict(Ed=np.abs(base["Ed"] - fine["Ed"]), Eu=np.abs(base["Eu"] - fine["Eu"]),
               E0=np.abs(base["E0_layer"] - fine["E0_layer"]) + np.abs(base["E0_layer"] - gauss["E0_layer"]),
               Kd=np.abs(res["Kd"] - ref.kd_between(depths, fine["Ed"])))
    for key in ("absorbed", "escaped", "bottom", "incident", "surface_reflectance"):
        res[key] = base[key]
        err[key] = abs(base[key] - fine[key])
    return res, err


class Check:
    """Collects |MC - ref| < 4 SE + ref_error (+ extra) comparisons and a table of them."""

    def __init__(self, label):
        self.label = label
        self.rows = []
        self.failures = []

    def compare(self, name, mc, se, r, r_err, extra=0.0, extra_low=0.0):
        """extra: an allowance on both sides; extra_low: only for MC below the reference
        (a bias known to be one-sided)."""
        tol = 4.0 * se + r_err + extra + 1e-12 * (1.0 + abs(r))
        dev = mc - r
        ok = dev <= tol if dev >= 0 else -dev <= tol + extra_low
        line = (f"{name:>12}  MC {mc:.6e} ± {se:.1e}  ref {r:.6e}  rel {dev / r:+.5f}"
                f"  dev/SE {dev / se if se > 0 else 0.0:+6.2f}  ref_err {r_err:.1e}")
        self.rows.append(line)
        if not ok:
            self.failures.append(line + f"  > tol {tol + (extra_low if dev < 0 else 0.0):.2e}")

    def profile(self, depths, mc, r, r_err, skip=()):
        for q in QUANTITIES:
            mean, se = mc[q]
            for i, z in enumerate(depths):
                if (q, i) in skip:
                    continue
                self.compare(f"{q}({z:g})", mean[i], se[i], r[q][i], r_err[q][i])

    def done(self):
        print(f"\n{self.label}\n" + "\n".join(self.rows))
        assert not self.failures, f"{self.label}: beyond the Monte Carlo error:\n" + "\n".join(self.failures)


def _profiles(ctx, water, sun_zenith, depths, *, photons, seed0, **kw):
    """B batches of arcus.ocean.profile: ({quantity: (mean, SE)}, per-batch results)."""
    results = [ocean.profile(water, sun_zenith, depths, photons=photons, grid=GRID, seed=seed0 + k,
                             context=ctx, **kw) for k in range(BATCHES)]
    stats = {q: _batch_stats([getattr(r, q)[:, 0] for r in results]) for q in QUANTITIES}
    return stats, results


def _flux_stats(results, key):
    return _batch_stats([r.tallies[key] / r.tallies["emitted"] for r in results])


# ------------------------------------------------------------ no interface, HG 0.9

A, B_SCAT, G = 0.1, 0.4, 0.9          # omega = 0.8, ocean-like forward scattering
HG_DEPTHS = np.array([0.0, 1.0, 2.0, 3.0, 5.0, 7.5, 10.0, 12.5, 15.0, 17.5, 20.0])
THIN = 0.05                            # E_0 layer [m]


@pytest.fixture(scope="module", params=[0.0, 40.0], ids=["normal", "40deg"])
def hg_column(request, ctx):
    zenith = request.param
    water = ocean.Water.from_iops(A, B_SCAT, phase=("hg", G))
    t0 = time.perf_counter()
    mc, results = _profiles(ctx, water, zenith, HG_DEPTHS, photons=125_000, seed0=101, surface=False,
                            layer=THIN)
    seconds = time.perf_counter() - t0
    r, r_err = _reference(A, B_SCAT, ref.hg(G), HG_DEPTHS, THIN, mu0=math.cos(math.radians(zenith)))
    return dict(zenith=zenith, mc=mc, results=results, ref=r, ref_err=r_err, seconds=seconds)


def test_hg_column_without_interface(hg_column):
    c = hg_column
    chk = Check(f"HG {G}, a = {A}, b = {B_SCAT}, no interface, {c['zenith']:g} deg in water, "
                f"{BATCHES} x 125k photons in {c['seconds']:.1f} s")
    chk.profile(HG_DEPTHS, c["mc"], c["ref"], c["ref_err"])
    chk.compare("escaped", *_flux_stats(c["results"], "escaped"), c["ref"]["escaped"], c["ref_err"]["escaped"])
    chk.compare("absorbed", *_flux_stats(c["results"], "absorbed"), c["ref"]["absorbed"], c["ref_err"]["absorbed"])
    assert all(r.tallies["past_limit"] == 0 for r in c["results"])   # omega^64 ~ 6e-7: nothing reaches it
    chk.done()


def test_diffuse_attenuation(hg_column):
    """K_d = -ln(E_d(z2) / E_d(z1)) / (z2 - z1) per batch; its batch spread is its SE."""
    c = hg_column
    chk = Check(f"K_d, HG {G}, {c['zenith']:g} deg")
    pairs = [(1, 5), (5, 8), (8, 10), (1, 10)]        # 1-5, 5-10, 10-15 and 1-15 m
    for i, j in pairs:
        zi, zj = HG_DEPTHS[i], HG_DEPTHS[j]
        kd = [-math.log(r.Ed[j, 0] / r.Ed[i, 0]) / (zj - zi) for r in c["results"]]
        ed = c["ref"]["Ed"]
        kd_ref = -math.log(ed[j] / ed[i]) / (zj - zi)
        # the reference's own K_d error from its E_d errors, to first order
        kd_err = (c["ref_err"]["Ed"][i] / ed[i] + c["ref_err"]["Ed"][j] / ed[j]) / (zj - zi)
        chk.compare(f"Kd {zi:g}-{zj:g}", *_batch_stats(kd), kd_ref, kd_err)
    chk.done()


# -------------------------------------------- Fresnel surface, TTHG, Lambertian bottom

TT_A, TT_B = 0.05, 0.25
TT_PHASE = (0.924, -0.20, 0.983)       # g_f, g_b, forward weight: g = 0.905, b_b/b ~ 1.5 %
BOTTOM, ALBEDO, SUN = 10.0, 0.3, 30.0
TT_DEPTHS = np.array([0.0, 0.5, 1.0, 2.0, 3.0, 5.0, 7.5, 9.0, 9.9, 9.99])   # the bottom itself is refused


def test_fresnel_surface_two_term_hg_and_lambertian_bottom(ctx):
    g_f, g_b, zeta = TT_PHASE
    water = ocean.Water.from_iops(TT_A, TT_B, phase=("two_term_hg", g_f, g_b, zeta))
    t0 = time.perf_counter()
    mc, results = _profiles(ctx, water, SUN, TT_DEPTHS, photons=125_000, seed0=201, surface=True,
                            bottom_depth=BOTTOM, bottom_albedo=ALBEDO, layer=THIN)
    seconds = time.perf_counter() - t0
    r, r_err = _reference(TT_A, TT_B, ref.two_term_hg(zeta, g_f, g_b), TT_DEPTHS, THIN, bottom_depth=BOTTOM,
                          fresnel=True, sun_zenith_deg=SUN, bottom_albedo=ALBEDO)
    chk = Check(f"TTHG({g_f}, {g_b}, {zeta}), a = {TT_A}, b = {TT_B}, sun {SUN:g} deg over a Fresnel "
                f"surface, bottom {BOTTOM:g} m albedo {ALBEDO}: {BATCHES} x 125k photons in {seconds:.1f} s")
    chk.profile(TT_DEPTHS, mc, r, r_err)
    # The engine's "escaped" includes the sun's light the surface reflects (R of it).
    escaped = _batch_stats([t.tallies["escaped"] - r["surface_reflectance"] for t in results])
    chk.compare("escaped", *escaped, r["escaped"], r_err["escaped"])
    chk.compare("absorbed", *_flux_stats(results, "absorbed"), r["absorbed"], r_err["absorbed"])
    # The bottom absorbs (1 - albedo) of what reaches it = E_d(H) - E_u(H), the reference's "bottom".
    chk.compare("bottom", *_flux_stats(results, "bottom"), r["bottom"], r_err["bottom"])
    chk.done()


# ------------------------------------------------ isotropic, high albedo, untruncated

ISO_A, ISO_B = 0.02, 0.5               # omega = 0.96: ~25 interactions a photon
BIN = 1.0                              # the E_0 layer
ISO_DEPTHS = np.array([0.0, 1.0, 2.0, 3.0, 4.0, 6.0, 8.0, 10.0, 12.0, 14.0, 16.0, 18.0, 20.0])
LIMIT = 5000                           # 0.96^5000: nothing can be left past it


def test_isotropic_high_albedo_multiple_scattering(ctx):
    water = ocean.Water.from_iops(ISO_A, ISO_B, phase="isotropic")
    t0 = time.perf_counter()
    # Deep tallies come from few long paths, so the batch results are skewed there;
    # 200k photons a batch keep the batch spread a fair estimate at 20 m.
    _, results = _profiles(ctx, water, 0.0, ISO_DEPTHS, photons=200_000, seed0=300, surface=False, layer=BIN,
                           max_interactions=LIMIT)
    seconds = time.perf_counter() - t0
    assert all(res.tallies["past_limit"] == 0 for res in results)
    mc = {q: _batch_stats([getattr(res, q)[:, 0] for res in results]) for q in QUANTITIES}
    r, r_err = _reference(ISO_A, ISO_B, ref.isotropic(), ISO_DEPTHS, BIN, mu0=1.0)
    chk = Check(f"isotropic, a = {ISO_A}, b = {ISO_B}, no interface, normal incidence, E_0 layer {BIN:g} m: "
                f"{BATCHES} batches of 200k photons in {seconds:.1f} s")
    for q in QUANTITIES:
        mean, se = mc[q]
        for i, z in enumerate(ISO_DEPTHS):
            chk.compare(f"{q}({z:g})", mean[i], se[i], r[q][i], r_err[q][i])
    chk.compare("absorbed", *_flux_stats(results, "absorbed"), r["absorbed"], r_err["absorbed"])
    chk.done()


# ------------------------------------------------------------ an open top, exactly

def test_upwelling_at_an_open_top_counts_every_escaping_photon(ctx):
    """Without an interface every photon that escapes crosses the depth-0 plane upward
    exactly once and nothing else does: E_u(0) must equal the escaped power, photon for
    photon (no statistics involved)."""
    water = ocean.Water.from_iops(A, B_SCAT, phase=("hg", G))
    r = ocean.profile(water, 0.0, [0.0, 1.0], photons=100_000, grid=GRID, surface=False, context=ctx, seed=7)
    assert r.Eu[0, 0] == pytest.approx(r.tallies["escaped"] / r.tallies["emitted"], rel=1e-9)


# ------------------------------------- the presets' waters: arcus.ocean_reference

PRESET_GRID = (440.0, 640.0, 100.0)    # blue, green, red: three wavelengths
PRESET_DEPTHS = np.array([0.0, 0.5, 1.0, 2.0, 3.0])
SKY = 0.2                              # the profile scenes' sky, W/m²/nm of plane irradiance
N_WATER = 1.34


def test_a_preset_water_under_sun_and_sky_matches_its_elastic_reference(ctx):
    """The gallery's profiles are drawn over arcus.ocean_reference's solution, which
    takes the preset's coefficients and its three scatterers' phase functions (pure
    water's 1 + 0.835 cos², the detritus' two-term HG, isotropic phytoplankton) and
    sums suns for the sky.  With Raman and both fluorescences off, the photons must
    agree with it within their own error: this checks that reading of the water, the
    sky's quadrature and the Fresnel surface for every angle at once.  The reference's
    error is its change from 32 to 64 streams plus from 12 to 24 sky nodes."""
    water = ocean.Water("north_sea", raman_scale=0.0, chlorophyll_yield=0.0, cdom_yield_scale=0.0)
    t0 = time.perf_counter()
    results = [ocean.profile(water, SUN, PRESET_DEPTHS, photons=150_000, grid=PRESET_GRID, sky=SKY, seed=400 + k,
                             layer=THIN, context=ctx) for k in range(BATCHES)]
    seconds = time.perf_counter() - t0
    lights = [ocean.Light.sun(SUN, 1.0), ocean.Light.sky(SKY)]
    kw = dict(grid=PRESET_GRID, layer=THIN, context=ctx)
    r = elastic.elastic_profile(water, lights, PRESET_DEPTHS, **kw)
    fine = elastic.elastic_profile(water, lights, PRESET_DEPTHS, streams=64, sky_nodes=24, **kw)
    chk = Check(f"north_sea without inelastic light, sun {SUN:g} deg and a sky of {SKY}: "
                f"{BATCHES} x 150k photons over 3 wavelengths in {seconds:.1f} s")
    for k, nm in enumerate(r["wavelengths"]):
        for q in QUANTITIES:
            mean, se = _batch_stats([getattr(res, q)[:, k] for res in results])
            for i, z in enumerate(PRESET_DEPTHS):
                chk.compare(f"{q}({z:g}) {nm:g}", mean[i], se[i], r[q][i, k], abs(r[q][i, k] - fine[q][i, k]))
    chk.done()


def test_the_sky_as_a_sum_of_suns_against_its_closed_form(ctx):
    """Without scattering, a uniform sky of plane irradiance E gives
    E_d(z) = E ∫ 2μ T(μ) exp(−a z / μ_w(μ)) dμ (T: Fresnel's transmittance, μ_w the
    refracted cosine), here by adaptive quadrature: the Gauss sum over suns must match
    it to its quadrature error (12 nodes: measured 3e-7 relative at 5 m; bound 1e-5)."""
    quad = pytest.importorskip("scipy.integrate").quad
    a, depths = 0.2, np.array([0.0, 1.0, 5.0])
    water = ocean.Water.from_iops(a, 0.0)
    r = elastic.elastic_profile(water, [ocean.Light.sky(1.0)], depths, grid=GRID, context=ctx)

    def ed(z):
        def f(mu):
            mu_w = ref.snell_cosine(mu, 1.0, N_WATER)
            return 2 * mu * (1 - ref.fresnel_reflectance(mu, 1.0, N_WATER)) * math.exp(-a * z / mu_w)
        return quad(f, 0.0, 1.0, epsabs=0, epsrel=1e-12)[0]
    want = np.array([ed(z) for z in depths])
    np.testing.assert_allclose(r["Ed"][:, 0], want, rtol=1e-5)
    assert np.all(r["Eu"] == pytest.approx(0.0, abs=1e-12))


def test_the_reference_refuses_what_is_not_a_plane_parallel_column(ctx):
    water = ocean.Water.from_iops(0.1, 0.2)
    with pytest.raises(ValueError, match="neither a sun nor a sky"):
        elastic.elastic_profile(water, [], [0.0, 1.0], grid=GRID, context=ctx)
    with pytest.raises(ValueError, match="depths"):
        elastic.elastic_profile(water, [ocean.Light.sun(0.0, 1.0)], [-1.0], grid=GRID, context=ctx)
    with pytest.raises(ValueError, match=r"lights\[1\]: a plane-parallel column"):
        elastic.elastic_profile(water, [ocean.Light.sky(1.0), ocean.Light.point((0, 0, -1), 1.0)], [0.0],
                                grid=GRID, context=ctx)
