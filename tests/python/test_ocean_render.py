"""Underwater images: the ray-marched radiance against closed forms and between its
two estimates, the features each image compiles, ablations, determinism, bad input."""

import json
import math

import numpy as np
import pytest

import arcus
import arcus.ocean as ocean


def write_scene(tmp_path, doc, name="scene.json"):
    path = tmp_path / name
    path.write_text(json.dumps(doc))
    return str(path)


def view(width=4, height=3, steps=200, distance=10.0, k=50, estimator="beam", single=True, multiple=True,
         position=(0, 0, -10), look_at=(1, 0, -10), vfov=30):
    return {"camera": {"position": list(position), "look_at": list(look_at), "up": [0, 0, 1], "vfov_deg": vfov,
                       "width": width, "height": height},
            "march": {"steps": steps, "distance": distance, "k": k, "estimator": estimator,
                      "single_scattering": single, "multiple_scattering": multiple}}


def test_single_scattering_matches_the_closed_form(tmp_path, ctx):
    """Isotropic scattering, a point lamp of 4π W/nm (intensity 1 W/sr/nm), one
    wavelength: the radiance toward a pixel is ∫ e^(−c t) b/(4π) e^(−c d)/d² dt along its
    ray, which numpy integrates here independently (composite Simpson, 20 001 points).
    The march's midpoint rule with 2000 steps errs by ~(Δt)²/24·|f''| ≈ 1e-5 relatively
    for these smooth integrands (the lamp is 1 m off every ray)."""
    a, b = 0.05, 0.2
    lamp = np.array([5.0, 0.0, -9.0])
    doc = {"name": "single", "water": {"iops": {"absorption": a, "scattering": b, "phase": {"kind": "isotropic"}}},
           "grid": {"first_nm": 550, "last_nm": 550, "step_nm": 1},
           "lights": [{"type": "point", "position": lamp.tolist(), "spectrum": 4 * math.pi}],
           "view": view(width=3, height=3, steps=2000, distance=12.0, multiple=False)}
    r = ocean.render(write_scene(tmp_path, doc), context=ctx)
    assert "OCEAN_PHOTON_MAP" not in r.features
    c = a + b
    eye = np.array([0.0, 0.0, -10.0])
    half = math.tan(math.radians(30) / 2)
    for py in range(3):
        for px in range(3):
            sx, sy = (2 * (px + 0.5) / 3 - 1) * half, (1 - 2 * (py + 0.5) / 3) * half
            d = np.array([1.0, -sx, sy])  # right = forward × up = −y
            d /= np.linalg.norm(d)
            t = np.linspace(0, 12.0, 20001)
            x = eye + t[:, None] * d
            dist = np.linalg.norm(x - lamp, axis=1)
            f = np.exp(-c * t) * b / (4 * math.pi) * np.exp(-c * dist) / dist**2
            h = t[1] - t[0]
            expect = h / 3 * (f[0] + f[-1] + 4 * f[1:-1:2].sum() + 2 * f[2:-1:2].sum())
            assert r.spectral[py, px, 0] == pytest.approx(expect, rel=1e-4), (px, py)


def camera_rays(position, look_at, up, vfov, width, height):
    """The pinhole camera's pixel rays (unit, (H, W, 3)), built here as render.cpp
    describes it: right = forward × up, up' = right × forward, the image plane at 1."""
    f = np.subtract(look_at, position, dtype=float)
    f /= np.linalg.norm(f)
    r = np.cross(f, up)
    r /= np.linalg.norm(r)
    u = np.cross(r, f)
    half_h = math.tan(math.radians(vfov) / 2)
    half_w = half_h * width / height
    sx = (2 * (np.arange(width) + 0.5) / width - 1) * half_w
    sy = (1 - 2 * (np.arange(height) + 0.5) / height) * half_h
    d = f + sx[None, :, None] * r + sy[:, None, None] * u
    return d / np.linalg.norm(d, axis=2, keepdims=True)


def fresnel(cos_i, n1, n2):
    sin_t = n1 / n2 * np.sqrt(1 - cos_i ** 2)
    cos_t = np.sqrt(np.maximum(0, 1 - sin_t ** 2))
    rs = (n1 * cos_i - n2 * cos_t) / (n1 * cos_i + n2 * cos_t)
    rp = (n2 * cos_i - n1 * cos_t) / (n2 * cos_i + n1 * cos_t)
    return 0.5 * (rs ** 2 + rp ** 2)


def test_the_suns_single_scattering_below_the_surface_matches_the_closed_form(tmp_path, ctx):
    """The sun 30° from the zenith over a flat sea (n = 1.34), plane irradiance 1 W/m²/nm
    on the surface, isotropic water, one wavelength; a camera 5 m down looking 45° up, so
    that its rays reach the surface.  Below the surface the sun is a beam along the
    refracted direction (Snell) carrying T/μ_w per unit area normal to it (T: Fresnel's
    unpolarised transmittance, written here; μ_w: the beam's cosine in the water); at
    depth |z| it has come a slant path |z|/μ_w.  A ray reaching the surface goes on
    reflected by Fresnel's R(μ) (1 outside Snell's window, which cuts this image): its
    path is the straight ray's mirrored, at depth |z(t)| still.  So a pixel's radiance is
    ∫ e^(−ct) b/(4π) (T/μ_w) e^(−c|z(t)|/μ_w) w(t) dt over 12 m, w = 1 before the surface
    and R after, which numpy integrates here (Simpson, 20 001 points a leg).  The march's
    midpoints (2000 steps) take the step holding the surface wholly on one side: up to
    half a step (3 mm) of a path of 12 m where the weight jumps, so 2e-3."""
    a, b, n_water, zenith = 0.05, 0.2, 1.34, 30.0
    eye, look_at = np.array([0.0, 0.0, -5.0]), np.array([1.0, 0.0, -4.0])
    doc = {"name": "sun_single", "water": {"iops": {"absorption": a, "scattering": b, "phase": {"kind": "isotropic"}}},
           "grid": {"first_nm": 550, "last_nm": 550, "step_nm": 1},
           "lights": [{"type": "sun", "zenith_deg": zenith, "azimuth_deg": 0, "spectrum": 1.0}],
           "medium": {"surface": True, "n_water": n_water},
           "view": view(width=3, height=3, steps=2000, distance=12.0, multiple=False, position=eye.tolist(),
                        look_at=look_at.tolist())}
    r = ocean.render(write_scene(tmp_path, doc), context=ctx)
    c = a + b
    cos_i = math.cos(math.radians(zenith))
    sin_t = math.sin(math.radians(zenith)) / n_water
    mu_w = math.sqrt(1 - sin_t ** 2)
    rs = ((cos_i - n_water * mu_w) / (cos_i + n_water * mu_w)) ** 2
    rp = ((n_water * cos_i - mu_w) / (n_water * cos_i + mu_w)) ** 2
    beam = (1 - (rs + rp) / 2) / mu_w
    rays = camera_rays(eye, look_at, [0, 0, 1], 30, 3, 3)
    for py in range(3):
        for px in range(3):
            d = rays[py, px]
            end = min(12.0, -eye[2] / d[2]) if d[2] > 0 else 12.0
            expect = 0.0
            for t0, t1, weight in ((0.0, end, 1.0), (end, 12.0, fresnel(d[2], n_water, 1.0))):
                if t1 <= t0:
                    continue
                t = np.linspace(t0, t1, 20001)
                depth = np.abs(eye[2] + t * d[2])
                f = np.exp(-c * t) * b / (4 * math.pi) * beam * np.exp(-c * depth / mu_w) * weight
                h = t[1] - t[0]
                expect += h / 3 * (f[0] + f[-1] + 4 * f[1:-1:2].sum() + 2 * f[2:-1:2].sum())
            assert r.spectral[py, px, 0] == pytest.approx(expect, rel=2e-3), (px, py)


def test_the_sun_lights_a_disc_of_the_surface(ctx):
    """A sun with a radius sends its photons through that disc of the surface, so that
    an image's photons surround its camera: the emitted power is the plane irradiance
    times the disc's area (π·3² m² here; to rounding) and the band, and in turbid water
    (mean free path 0.2 m) the stored photons lie under the disc: their median distance
    from its axis within 10 % of a uniform disc's R/√2, none beyond R + 2 m."""
    water = ocean.Water.from_iops(0.05, 5.0, phase="isotropic")
    sun = ocean.Light.directional((0.0, 0.0, -1.0), 2.0, radius=3.0)
    r = ocean.trace_photons(water, sun, 20000, 5, 3, grid=(500.0, 500.0, 1.0), store=True, surface=True,
                            context=ctx)
    assert r.tallies["emitted"] == pytest.approx(2.0 * math.pi * 9.0, rel=1e-12)
    radius = np.hypot(r.photons["positions"][:, 0], r.photons["positions"][:, 1])
    assert radius.size > 1000
    assert np.median(radius) == pytest.approx(3.0 / math.sqrt(2), rel=0.1) and radius.max() < 5.0


@pytest.mark.heavy
def test_the_two_estimates_see_the_same_multiple_scattering(ctx):
    """The per-step k-nearest estimate and the beam estimate gather the same photons'
    density along the same rays: with the multiple scattering alone, their images agree
    to the estimates' noise and bias.  k = 100 of 3e5 photons on 8 × 6 pixels, summed
    over four seeds (one seed's colour bins differ by up to 13 %: the beam's radii come
    from each photon's 32 nearest, render.cl); measured within 2.4 %, bound 5 %."""
    step, beam = 0.0, 0.0
    for seed in (2, 3, 4, 5):
        doc = {"name": "ms", "water": {"preset": "mediterranean"},
               "grid": {"first_nm": 450, "last_nm": 650, "step_nm": 50},
               "lights": [{"type": "point", "position": [3, 0, -10], "spectrum": 1.0}],
               "photons": {"count": 300000, "max_interactions": 5, "seed": seed},
               "view": view(width=8, height=6, steps=100, distance=8.0, k=100, single=False)}
        s = ocean.render(doc, estimator="per_step", context=ctx)
        b = ocean.render(doc, estimator="beam", context=ctx)
        assert "OCEAN_BEAM" in b.features and "OCEAN_BEAM" not in s.features
        step, beam = step + s.spectral.sum(axis=(0, 1)), beam + b.spectral.sum(axis=(0, 1))
    np.testing.assert_allclose(beam, step, rtol=0.05)


def stride_scene(stride, single=True, multiple=True):
    v = view(width=64, height=48, steps=60, distance=8.0, k=125, single=single, multiple=multiple, vfov=25)
    v["march"]["estimate_stride"] = stride
    return {"name": "stride", "water": {"preset": "mediterranean"},
            "grid": {"first_nm": 400, "last_nm": 700, "step_nm": 20},
            "lights": [{"type": "point", "position": [3, 0, -10], "spectrum": 1.0}],
            "photons": {"count": 200000, "max_interactions": 5, "seed": 3}, "view": v}


def test_determinism_the_lights_and_the_strided_photon_estimate_add_up(ctx):
    """With estimate_stride 3 the lights' single scattering is marched at every pixel
    and the photon estimate at every third, added bilinearly: the image is, to the
    last bit, the single-scattering image plus the strided multiple-scattering one."""
    both = ocean.render(stride_scene(3), context=ctx).spectral
    lights = ocean.render(stride_scene(3, multiple=False), context=ctx).spectral
    photons = ocean.render(stride_scene(3, single=False), context=ctx).spectral
    np.testing.assert_array_equal(both, lights + photons)


def test_the_photon_estimate_at_every_other_pixel_keeps_the_image(ctx):
    """The photon estimate is smooth over its photons' radii, which span many pixels, so
    sampling it at every other pixel and interpolating changes little.  Here the radii
    are the default scenes' (k/N = 1250/2 M) and the samples 1.04° apart, twice the
    default's spacing (512 pixels over 50°, every fourth): the multiple scattering's
    relative RMS difference against the estimate at every pixel, same photons,
    measured 1.65 %, while two seeds differ by 22 %.  Bound 3 %."""
    every = ocean.render(stride_scene(1, single=False), context=ctx).spectral.sum(axis=2)
    other = ocean.render(stride_scene(2, single=False), context=ctx).spectral.sum(axis=2)
    assert np.sqrt(np.mean((other - every) ** 2) / np.mean(every ** 2)) < 0.03


def test_same_seed_same_image(tmp_path, ctx):
    doc = {"name": "det", "water": {"preset": "baltic"}, "grid": {"first_nm": 400, "last_nm": 700, "step_nm": 20},
           "lights": [{"type": "spot", "position": [2, 0, -10], "direction": [-1, 0, 0], "half_angle_deg": 40,
                       "spectrum": 1.0}],
           "photons": {"count": 50000, "max_interactions": 5, "seed": 9},
           "view": view(width=8, height=6, steps=50)}
    path = write_scene(tmp_path, doc)
    a = ocean.render(path, context=ctx)
    b = ocean.render(doc, context=ctx)  # a dict: the same scene
    np.testing.assert_array_equal(a.spectral, b.spectral)
    assert a.tallies["photons"] == 50000


# ---- The inelastic ablation as physics states it (thesis §5.3, Fig. 5.11) ----------
# Single scattering only: each image is a deterministic march of the lights' first
# scattering, elastic and inelastic (eq. 4.5), with no photon map, so images with and
# without inelastic events differ only by the inelastic term and every comparison
# below is exact to rounding.  The view is the thesis' Fig. 5.10/5.11 view (the camera
# 10 m down looking along +x, vfov 50°, an isotropic lamp of a flat 1 W/nm 4 m ahead,
# 15 m marched in 200 steps) at 8 × 6 pixels, over 380–780 nm at 10 nm: the CIE
# observer's range, so chlorophyll's 685 nm fluorescence lies inside it.
ABLATION_GRID = (380.0, 780.0, 10.0)
ABLATION_LAMP = (4.0, 0.0, -10.0)
ABLATION_WATERS = {"pure": {"chlorophyll": 0.0, "a_d400": 0.0, "a_y440": 0.0},  # Raman is all it re-emits
                   "atlantic": {"preset": "atlantic"}, "north_sea": {"preset": "north_sea"},
                   "cdom_coastal": {"preset": "cdom_coastal"}}
NO_INELASTIC = {"raman_scale": 0, "cdom_yield_scale": 0, "chlorophyll_yield": 0}
_ablation_images = {}


def ablation_image(ctx, water, **switches):
    """The single-scattered image of ABLATION_WATERS[water] with ``switches`` (inelastic
    yields set to 0) applied; renders are exact, so each is made once per session."""
    key = (water, tuple(sorted(switches.items())))
    if key not in _ablation_images:
        doc = {"name": "ablation", "water": dict(ABLATION_WATERS[water], **switches),
               "grid": dict(zip(("first_nm", "last_nm", "step_nm"), ABLATION_GRID)),
               "lights": [{"type": "point", "position": list(ABLATION_LAMP), "spectrum": 1.0}],
               "view": view(width=8, height=6, steps=200, distance=15.0, multiple=False, vfov=50)}
        r = ocean.render(doc, context=ctx)
        if not switches or switches == NO_INELASTIC:  # with every inelastic event, or none
            assert ("OCEAN_INELASTIC" in r.features) == (not switches)
        assert "OCEAN_PHOTON_MAP" not in r.features
        _ablation_images[key] = r
    return _ablation_images[key]


# IEC 61966-2-1: linear sRGB to CIE 1931 XYZ (D65).  Only differences of chromaticities
# made with the same matrix are compared, so its 4-digit rounding cancels.
SRGB_TO_XYZ = np.array([[0.4124, 0.3576, 0.1805], [0.2126, 0.7152, 0.0722], [0.0193, 0.1192, 0.9505]])


def chromaticity(image):
    """CIE 1931 (x, y) of an image's mean colour (linear sRGB, so the mean is the mean radiance's)."""
    xyz = SRGB_TO_XYZ @ image.reshape(-1, 3).astype(float).mean(axis=0)
    return xyz[:2] / xyz.sum()


def test_inelastic_ablations(ctx):
    """Thesis §5.3, Fig. 5.11, as physics says: the relative change of the scattered
    light's colour from the inelastic events is largest in pure water and ordered pure >
    Atlantic > North Sea.  The change is δ = |xy(with) − xy(without)|, the distance
    between the CIE 1931 chromaticities of the single-scattered image's mean radiance
    with every inelastic event and with none (Raman, chlorophyll and CDOM yields 0).  A
    chromaticity does not depend on brightness, so δ is the colour change relative to the
    light the water scatters, however much that is.  Why that order: pure water's only
    inelastic process, Raman (b_R(488) ≈ 2.6e-4 /m, Marshall & Smith 1990), is ~8 % of
    its molecular scattering (b_w(488) ≈ 3.2e-3 /m) and moves blue light ~100 nm into
    the green, so its share of the scattered light is largest where the water is
    clearest (Westberry, Boss & Lee 2013; McKinna et al. 2016: Raman matters most in
    oligotrophic water); the particles of natural water add tens of times pure water's
    elastic scattering, while their fluorescence re-emits 1–10 % of the photons they
    absorb (CDOM ~1–2 %, chlorophyll Γ_p = 0.1, Table 4.3), much of it (chlorophyll's)
    at 685 nm, where the eye responds little.  So the order is the colour's: the
    spectrum's relative change is larger in North Sea water than in Atlantic water
    (0.31 % against 0.11 % of its shape, half the L1 distance of the normalised mean
    spectra; 0.44 % against 0.37 % of its radiance), most of it chlorophyll's
    fluorescence at 685 nm.  The thesis shows its ablation only for the Baltic (below;
    bench/ocean_ablation.py makes the figure).  The test asks for the order, not for any
    preset's numbers; each δ must also exceed 1e-6, far above the rounding of the
    float32 mean colour (~1e-7 in xy), so that the order compares real changes.
    Measured: δ = 2.8e-3 (pure), 1.1e-4 (Atlantic), 3.9e-5 (North Sea)."""
    delta = {}
    for water in ("pure", "atlantic", "north_sea"):
        delta[water] = np.linalg.norm(chromaticity(ablation_image(ctx, water).image)
                                      - chromaticity(ablation_image(ctx, water, **NO_INELASTIC).image))
        assert delta[water] > 1e-6, (water, delta)
    assert delta["pure"] > delta["atlantic"] > delta["north_sea"], delta


def inelastic_light(ctx, water, **switches):
    """The image-mean radiance integrated over the grid [W/m²/sr] that the inelastic
    events switched off by ``switches`` add to the single-scattered image."""
    def total(r):
        return r.spectral.mean(axis=(0, 1)).sum() * ABLATION_GRID[2]
    return total(ablation_image(ctx, water)) - total(ablation_image(ctx, water, **switches))


def test_inelastic_light_is_fluorescence_in_turbid_water_and_raman_in_clear(ctx):
    """Which process makes the inelastic light, each switched off separately (the light
    it adds: the single-scattered image with all inelastic events minus the one with
    that one off, integrated over 380–780 nm).  In turbid coastal water (North Sea,
    the CDOM-rich coast) CDOM and chlorophyll fluorescence make most of it: their
    constituents absorb ~0.3–0.6 /m of blue light and re-emit 1–10 % of those photons,
    against Raman's ~4e-4 /m.  In pure water and clear (Atlantic) water Raman does: pure
    water has nothing that fluoresces, and the open ocean's chlorophyll and CDOM absorb
    too little (Raman's share of the ocean's colour is largest in oligotrophic water:
    Westberry, Boss & Lee 2013; McKinna et al. 2016).  Raman's photons come out of pure
    water's absorption (src/ocean/water.cpp), so switching it off changes no extinction
    and the three contributions add up to the whole inelastic light, which is checked
    too, to 1e-9 relatively: the inelastic light is ≥ 0.3 % of the image here, so the
    rounding of these double sums (~1e-16 each) is amplified at most ~300-fold by the
    subtraction (measured: 2e-13)."""
    for water in ABLATION_WATERS:
        raman = inelastic_light(ctx, water, raman_scale=0)
        cdom = inelastic_light(ctx, water, cdom_yield_scale=0)
        chlorophyll = inelastic_light(ctx, water, chlorophyll_yield=0)
        every = inelastic_light(ctx, water, **NO_INELASTIC)
        assert raman + cdom + chlorophyll == pytest.approx(every, rel=1e-9), water
        assert raman > 0 and cdom >= 0 and chlorophyll >= 0, (water, raman, cdom, chlorophyll)
        if water == "pure":  # nothing in it fluoresces: the switches must change nothing
            assert cdom == 0 and chlorophyll == 0
        elif water == "atlantic":
            assert raman > cdom + chlorophyll, (water, raman, cdom, chlorophyll)
        else:
            assert cdom + chlorophyll > raman, (water, raman, cdom, chlorophyll)


def test_the_inelastic_change_is_bounded_by_what_the_water_scatters(ctx):
    """The absolute change of the image is small where little light scatters: at every
    pixel the light the inelastic events add, counted in photons (radiance × λ, summed
    over the grid), is at most the closed form
        B = Σ_s Δt Σ_i μ(λ_i) λ_i I(λ_i) Δλ e^(−c(λ_i) d_s) / (4π d_s²),
    the inelastic coefficient μ (photons re-emitted per metre: Raman, chlorophyll and
    CDOM fluorescence, the model's own coefficients) × the lamp's irradiance I e^(−c d)/d²
    × the path, summed at the march's own points (midpoints s of Δt = 15 m / 200; d_s
    their distances to the lamp).  It holds because each re-emission makes at most one
    photon, re-emitted isotropically (1/4π), of which only those inside the grid are kept
    (≤ 1, up to half the densities at the grid's two end samples, where no emission here
    has more than a tail: they are normalised by the trapezoid rule, src/ocean/water.cpp,
    and the march sums every sample whole), and the way back to the camera only dims
    them (e^(−c t) ≤ 1); counting photons,
    not energy, makes it hold for anti-Stokes emission too, whose photons carry more
    energy than they took.  The one allowance: the march reads the lamp's light from
    tables linear in distance between 1024 rows over the farthest distance (|lamp −
    camera| + 15 m, src/ocean/render.cpp), which overestimate the convex e^(−c d) by at
    most (c Δd)²/8 · e^(c Δd) relatively, computed here from the largest extinction
    (~6e-4 for c ≈ 3.4 /m).  B is proportional to μ, so the change is small where little
    light scatters inelastically: pure water, whose μ is Raman's alone (~4.5e-4 /m at
    440 nm), and pixels whose rays pass far from the lamp.  Measured: the added photons
    are 0.69–0.72 of B in pure water (what the way back dims), 0.31–0.38 in Atlantic
    water, under 0.05 in the turbid waters (whose extinction dims far more)."""
    rays = camera_rays((0, 0, -10), (1, 0, -10), (0, 0, 1), 50, 8, 6)
    steps, distance = 200, 15.0
    t = (np.arange(steps) + 0.5) * distance / steps
    points = np.array([0.0, 0.0, -10.0]) + t[None, None, :, None] * rays[:, :, None, :]  # (H, W, steps, 3)
    d = np.linalg.norm(points - np.array(ABLATION_LAMP), axis=3)
    intensity = 1.0 / (4 * math.pi)  # a flat 1 W/nm isotropic lamp, per sr
    for water, w in ABLATION_WATERS.items():
        with_all, without = ablation_image(ctx, water), ablation_image(ctx, water, **NO_INELASTIC)
        nm = with_all.wavelengths
        added = ((with_all.spectral - without.spectral) * nm).sum(axis=2) * ABLATION_GRID[2]
        model = ocean.Water(w.get("preset"), **{k: v for k, v in w.items() if k != "preset"})
        coefficients = model.coefficients(grid=ABLATION_GRID, context=ctx)
        mu = coefficients["events"][[ocean.EVENTS.index(e) for e in ("raman", "fluoresce_phyto", "fluoresce_cdom")]]
        source = mu.sum(axis=0) * nm * intensity * ABLATION_GRID[2] / (4 * math.pi)  # per (λ_i)
        bound = (np.exp(-d[..., None] * coefficients["extinction"]) @ source / d**2).sum(axis=2) * distance / steps
        rows = (np.linalg.norm(np.array(ABLATION_LAMP) - (0, 0, -10)) + distance) / 1023
        cd = coefficients["extinction"].max() * rows
        assert np.all(added > 0), water
        assert np.all(added <= bound * (1 + cd**2 / 8 * math.exp(cd))), (water, (added / bound).max())


def test_fig_5_11_the_baltic_without_inelastic_events_and_without_anti_stokes(ctx, repo):
    """Thesis §5.3, Fig. 5.11: Baltic water with every inelastic event, with none, and
    with no anti-Stokes interactions (the bundled scenes scenes/ocean/fig5_11/*.json, at
    8 × 6 pixels and single scattering alone, so exact; bench/ocean_ablation.py renders
    the figure itself).  Counted in photons (radiance × λ over the grid) at every pixel:
    each ablation removes re-emitted photons — without anti-Stokes the photons that
    would come out bluer than they went in are absorbed, without inelastic events all
    of them are — so none < no anti-Stokes < all; and the anti-Stokes part is the
    smaller one, "less common than Stokes" (thesis §2.3.3): a fluorescent molecule
    re-emits bluer only where its absorption and emission bands overlap, and water's
    anti-Stokes Raman band (−3400 cm⁻¹) is weaker than the Stokes one by the Boltzmann
    factor e^(−hcν̃/kT) ≈ 1e-7, so Walrafen's bands leave it out.  Measured: the
    inelastic photons are 0.8 % of the image's, 2.7–3.6 % of them anti-Stokes."""
    photons = {}
    for name in ("baltic_inelastic", "baltic_no_inelastic", "baltic_no_anti_stokes"):
        doc = json.loads((repo / "scenes" / "ocean" / "fig5_11" / (name + ".json")).read_text())
        doc["view"]["camera"].update(width=8, height=6)
        doc["view"]["march"]["multiple_scattering"] = False
        r = ocean.render(doc, context=ctx)
        assert ("OCEAN_INELASTIC" in r.features) == (name != "baltic_no_inelastic")
        photons[name] = (r.spectral * r.wavelengths).sum(axis=2)
    every, none, stokes = photons["baltic_inelastic"], photons["baltic_no_inelastic"], photons["baltic_no_anti_stokes"]
    assert np.all(none < stokes) and np.all(stokes < every)
    assert np.all(every - stokes < stokes - none), ((every - stokes) / (every - none)).max()


def test_bad_views_are_refused(tmp_path, ctx):
    base = {"name": "bad", "water": {"preset": "atlantic"},
            "lights": [{"type": "point", "position": [2, 0, -10], "spectrum": 1.0}]}
    with pytest.raises(arcus.ArgumentError, match="view"):
        ocean.render(write_scene(tmp_path, base), context=ctx)
    doc = dict(base, view=view(k=5000, estimator="per_step"))
    with pytest.raises(arcus.ArgumentError, match=r"march.k: must be in 1..512 \(per-step estimate\)"):
        ocean.render(write_scene(tmp_path, doc), context=ctx)
    doc = dict(base, view=view(k=70000))
    with pytest.raises(arcus.ArgumentError, match=r"march.k"):
        ocean.render(write_scene(tmp_path, doc), context=ctx)
    doc = dict(base, view=view())
    doc["view"]["march"]["estimate_stride"] = 0
    with pytest.raises(arcus.ArgumentError, match="estimate_stride"):
        ocean.render(write_scene(tmp_path, doc), context=ctx)
    doc = dict(base, view=view(), photons={"count": 1000, "wavelengths_per_photon": 5})
    with pytest.raises(arcus.ArgumentError, match="wavelengths_per_photon: must be in 1..4"):
        ocean.render(write_scene(tmp_path, doc), context=ctx)
    doc = dict(base, view=view(look_at=(0, 0, -10)))
    with pytest.raises(arcus.ArgumentError, match="look_at"):
        ocean.render(write_scene(tmp_path, doc), context=ctx)
    # images take the sun and the sky over a surface, and see from the water
    sunlit = dict(base, view=view(),
                  lights=[{"type": "sun", "zenith_deg": 30, "spectrum": 1.0}, {"type": "sky", "spectrum": 0.2}])
    with pytest.raises(arcus.ArgumentError, match=r"lights\[1\]: a sky light needs the surface"):
        ocean.render(write_scene(tmp_path, sunlit), context=ctx)
    sunlit = dict(sunlit, medium={"surface": True, "n_water": 1.34}, lights=sunlit["lights"][:1],
                  view=view(position=(0, 0, 1), look_at=(1, 0, 1)))
    with pytest.raises(arcus.ArgumentError, match="camera.position.*below the surface"):
        ocean.render(write_scene(tmp_path, sunlit), context=ctx)
    beam = dict(base, view=view(), lights=[{"type": "directional", "direction": [0, 0, -1], "spectrum": 1.0}])
    with pytest.raises(arcus.ArgumentError, match=r"lights\[0\]: images are lit by"):
        ocean.render(write_scene(tmp_path, beam), context=ctx)
    # a periodic photon tile needs a scene the same at every horizontal place, and the beam
    for march, lights, message in (({"photon_tile": -1.0}, None, "photon_tile: must be finite and >= 0"),
                                   ({"photon_tile": 4.0, "estimator": "per_step"}, None, "beam estimate only"),
                                   ({"photon_tile": 4.0}, base["lights"], "the same at every horizontal place")):
        tiled = dict(base, medium={"surface": True, "n_water": 1.34}, view=view(),
                     lights=lights or [{"type": "sun", "zenith_deg": 30, "spectrum": 1.0}])
        tiled["view"]["march"].update(march)
        with pytest.raises(arcus.ArgumentError, match=message):
            ocean.render(write_scene(tmp_path, tiled), context=ctx)


@pytest.mark.heavy
@pytest.mark.parametrize("scene, luma_bound", [("north_sea", 0.035), ("sunlit/north_sea", 0.035)])
def test_the_default_water_images_noise_is_within_five_percent(ctx, repo, scene, luma_bound):
    """Issue 22: default water images within 5 % RMS (sRGB) of a 16× reference.  The
    default (scenes/ocean/*.json: 2 M photons of four wavelengths, each photon's radius
    holding 1250, the photon estimate at every fourth pixel; sunlit/*.json: the photons
    of one 8 m tile standing for the whole sea, radii holding 5000 for north_sea, every
    eighth pixel) is rendered with seeds 1 and 2; the RMS of their difference over the
    image's RMS, over √2, is one image's noise, and a 16× reference of the same radii
    would differ from it by √(1 + 1/16) of that.  To keep it cheap the estimate is made
    at every pixel of an image 1/stride the size: the very rays the full-size default
    makes it on.  `north_sea`, the noisiest of the five either way (docs/ocean.md),
    measured 4.48 % in sRGB and 3.07 % in luma (Rec. 709 weights of the sRGB values)
    lamp-lit, where the thesis' settings give 14.7 % and 8.2 %; sunlit, 3.86 % and
    2.65 %, where photons through the 30 m disc the sun lit before gave 11.5 %.
    Bounds: the issue's 5 % (its reference adds 3 %: 4.62 %), and 3.5 % in luma."""
    doc = json.loads((repo / "scenes" / "ocean" / (scene + ".json")).read_text())
    march = doc["view"]["march"]
    camera = doc["view"]["camera"]
    camera.update(width=camera["width"] // march["estimate_stride"], height=camera["height"] // march["estimate_stride"])
    march["estimate_stride"] = 1
    exposure = march["exposure"]
    images = []
    for seed in (1, 2):
        doc["photons"]["seed"] = seed
        linear = np.clip(ocean.render(doc, context=ctx).image * exposure, 0, 1)
        images.append(np.where(linear <= 0.0031308, 12.92 * linear, 1.055 * linear ** (1 / 2.4) - 0.055))
    a, b = images

    def noise(x, y):
        return float(np.sqrt(np.mean((x - y) ** 2) / np.mean(((x + y) / 2) ** 2)) / math.sqrt(2))
    luma = [i @ np.array([0.2126, 0.7152, 0.0722]) for i in images]
    assert noise(a, b) * math.sqrt(1 + 1 / 16) < 0.05 and noise(*luma) < luma_bound, (noise(a, b), noise(*luma))


def test_the_thesis_settings_are_a_named_preset(ctx, repo):
    """`thesis=True` (`arcus render --thesis`) puts the thesis' image settings in place
    of the bundled scenes': 400 000 photons of one wavelength, k = 250, every pixel."""
    doc = json.loads((repo / "scenes" / "ocean" / "north_sea.json").read_text())
    ocean.use_thesis_settings(doc)
    assert doc["photons"]["count"] == 400_000 and doc["photons"]["wavelengths_per_photon"] == 1
    assert doc["view"]["march"]["k"] == 250 and doc["view"]["march"]["estimate_stride"] == 1
    assert doc["view"]["march"]["estimator"] == "beam"  # the scene's own
    doc["view"]["camera"].update(width=8, height=6)
    doc["photons"]["count"] = 20_000
    small = ocean.render(doc, context=ctx)
    assert small.image.shape == (6, 8, 3) and np.all(np.isfinite(small.image))


def sky_scene(absorption, scattering, phase, look, depth=5.0, lights=None, steps=2000):
    """A flat surface over water of these IOPs at one wavelength, lit by a uniform sky of
    plane irradiance 1 W/m²/nm (radiance 1/π), seen by a 3 × 3 camera of 2° at ``depth``
    looking along ``look``; the lights' single scattering only."""
    up = [1, 0, 0] if abs(look[2]) > 0.9 else [0, 0, 1]
    return {"name": "sky", "water": {"iops": {"absorption": absorption, "scattering": scattering, "phase": phase}},
            "grid": {"first_nm": 500, "last_nm": 500, "step_nm": 10}, "medium": {"surface": True, "n_water": 1.34},
            "lights": lights or [{"type": "sky", "spectrum": 1.0}], "photons": {"count": 1000},
            "view": {"camera": {"position": [0, 0, -depth], "look_at": [look[0], look[1], look[2] - depth], "up": up,
                                "vfov_deg": 2, "width": 3, "height": 3},
                     "march": {"steps": steps, "distance": 40.0, "k": 10, "multiple_scattering": False}}}


def test_snells_window_shows_the_sky_through_the_surface(ctx):
    """Looking straight up from 5 m through water that only absorbs (a = 0.2 /m): the
    sky's radiance L_s = 1/π times n² (the n² law of radiance across the surface) times
    the normal-incidence Fresnel transmittance 1 − ((n−1)/(n+1))², times e^(−a·5).
    Exact to rounding (the straight-up view is a node of the window's table).  Outside
    the window (the view 50.8° from the zenith, its 2° of pixels all beyond the critical
    48.3°) nothing comes through: total internal reflection, and the reflected ray sees
    water that scatters nothing."""
    n = 1.34
    up = ocean.render(sky_scene(0.2, 0.0, {"kind": "isotropic"}, (0, 0, 1)), context=ctx).spectral[1, 1, 0]
    expect = n * n * (1 - ((n - 1) / (n + 1)) ** 2) / math.pi * math.exp(-0.2 * 5)
    assert up == pytest.approx(expect, rel=1e-9)
    slant = math.radians(50.8)
    edge = ocean.render(sky_scene(0.2, 0.0, {"kind": "isotropic"}, (math.sin(slant), 0, math.cos(slant))),
                        context=ctx).spectral[1, 1, 0]
    assert edge == 0.0


def test_the_skys_first_scattering_matches_a_quadrature(ctx):
    """Henyey–Greenstein water (g = 0.8, a = 0.2, b = 0.1 /m) under a uniform sky, the
    view 30° above the horizon from 5 m: its single-scattered radiance is
    ∫ e^(−c t) b S(d(t), w(t)) dt over the march's 40 m: up to the surface (10 m away; the
    window is not seen at 30°), then along the totally reflected ray 30° below the
    horizon, S(d, w) = ∫∫_cone n² T(μ) L_s e^(−c d/μ) p(cos Θ) dμ dφ (Θ between the light
    and −w), which numpy integrates here on its own grids (400 μ × 256 φ at 161 depths a
    leg, then Simpson in t).  The library folds the
    azimuth once per view cosine and tabulates S over 256 depths × 129 view cosines,
    bilinear between: linear interpolation over 0.18 m of depth errs by about
    (c Δd/μ)²/8 ≈ 5e-4: measured 3.3e-4 (4.4e-4 for an isotropic view along the
    horizon).  Bound 3e-3."""
    n, a, b, g = 1.34, 0.2, 0.1, 0.8
    c = a + b
    elev = math.radians(30)
    v = (math.cos(elev), 0.0, math.sin(elev))
    got = ocean.render(sky_scene(a, b, {"kind": "hg", "g": g}, v), context=ctx).spectral[1, 1, 0]
    mu_c = math.sqrt(1 - 1 / n ** 2)
    mu = mu_c + (1 - mu_c) * (np.arange(400) + 0.5) / 400
    phi = 2 * math.pi * (np.arange(256) + 0.5) / 256
    M, P = np.meshgrid(mu, phi, indexing="ij")
    mu_air = np.sqrt(np.maximum(0, 1 - n * n * (1 - M ** 2)))
    through = n * n * (1 - fresnel(mu_air, 1.0, n)) / math.pi
    # light going down at (sin θ cos φ, sin θ sin φ, −μ), scattered toward −v
    weight = (1 - mu_c) / 400 * 2 * math.pi / 256
    expect = 0.0
    for t0, t1, w_z in ((0.0, 5.0 / v[2], v[2]), (5.0 / v[2], 40.0, -v[2])):  # up, then reflected
        cos_theta = -(np.sqrt(1 - M ** 2) * np.cos(P) * v[0]) + M * w_z
        hg = (1 - g * g) / (4 * math.pi * (1 + g * g - 2 * g * cos_theta) ** 1.5)
        t = np.linspace(t0, t1, 161)
        S = np.array([np.sum(through * np.exp(-c * abs(ti * v[2] - 5.0) / M) * hg) * weight for ti in t])
        f = np.exp(-c * t) * b * S
        h = t[1] - t[0]
        expect += h / 3 * (f[0] + f[-1] + 4 * f[1:-1:2].sum() + 2 * f[2:-1:2].sum())
    assert abs(got / expect - 1) < 3e-3, got / expect - 1


def test_a_sunlit_water_shows_snells_window(ctx, repo):
    """scenes/ocean/sunlit/atlantic.json, small: the shared daylight's sun and sky over
    clear water, the view 50° up, with the sky's photons and the sun's.  The top of the
    image (inside Snell's window: the sky through the surface) is brighter than its
    bottom (outside: only the water's scattered light), summed over 380-780 nm:
    measured 1.64×, bound 1.3× (100 000 photons: single wavelengths are noisy)."""
    doc = json.loads((repo / "scenes" / "ocean" / "sunlit" / "atlantic.json").read_text())
    doc["view"]["camera"].update(width=32, height=24)
    doc["photons"]["count"] = 100_000
    spectral = ocean.render(doc, context=ctx).spectral
    assert np.all(np.isfinite(spectral)) and np.all(spectral >= 0)
    top, bottom = spectral[:4].sum(), spectral[-4:].sum()
    assert top > 1.3 * bottom, top / bottom


def test_a_periodic_photon_tile_stands_for_the_whole_sea(ctx):
    """The sun straight down on a flat sea (plane irradiance 1 W/m²/nm, T = 1 − ((n−1)/
    (n+1))²) over isotropic water (a = 0.05, b = 2 /m), one wavelength: the light field
    is the same at every horizontal place, so an image's photons may all enter through
    one 1 m tile and stand for its copies across the plane (march.photon_tile).  A fan
    of horizontal rays at depth z sees the photon map's multiple scattering only:
    ∫ e^(−ct) b/(4π) E0_s(z) dt = b E0_s(z) (1 − e^(−cD)) / (4π c), where E0_s is the
    scalar irradiance of the light scattered before, the same photons' first four legs
    after their first interaction (the map holds their 2nd-5th interactions).  A
    separate trace's track-length tallies give it independently: E0 at z minus the
    unscattered beam's T e^(−cz).  This checks the tile's area (the power each photon
    carries), the fold of every ray into it and the copies across its edges (the rays
    cross 5 m of tiles).  The fan's rays all pass the same photons at one depth, so its
    mean keeps the photons' own noise: over four other seeds it came within −1.1 …
    +1.2 % (with 2 m tiles −1.0 … +3.1 %), and the radii (~0.2 m) blur the profile,
    which falls e-fold in 0.9 m here (five interactions at most), by (Kr)²/10 ≈ 0.5 %.
    Bound 5 %: a wrong tile area is off by a large factor, a copy counted twice doubles
    the light, and the copies across the edges, within r ≈ 0.2 m of edges 1 m apart,
    hold about 2r/P, a fifth of it (an estimate)."""
    a, b, n, z, distance = 0.05, 2.0, 1.34, 1.0, 5.0
    c = a + b
    water = ocean.Water.from_iops(a, b, phase="isotropic")
    sun = ocean.Light.directional((0.0, 0.0, -1.0), 1.0)
    tallies = ocean.trace_photons(water, sun, 400_000, 5, 7, grid=(500.0, 500.0, 1.0), depths=[z], layer=0.05,
                                  surface=True, n_water=n, context=ctx)
    transmitted = 1 - ((n - 1) / (n + 1)) ** 2
    e0_scattered = tallies.E0[0, 0] - transmitted * math.exp(-c * z)
    expect = b * e0_scattered * (1 - math.exp(-c * distance)) / (4 * math.pi * c)
    doc = {"name": "tile", "water": {"iops": {"absorption": a, "scattering": b, "phase": {"kind": "isotropic"}}},
           "grid": {"first_nm": 500, "last_nm": 500, "step_nm": 1}, "medium": {"surface": True, "n_water": n},
           "lights": [{"type": "sun", "zenith_deg": 0, "azimuth_deg": 0, "spectrum": 1.0}],
           "photons": {"count": 400_000, "seed": 3},
           "view": {"camera": {"position": [0.3, 0.7, -z], "look_at": [1.3, 0.2, -z], "up": [0, 0, 1],
                               "vfov_deg": 0.5, "width": 24, "height": 1},
                    "march": {"steps": 100, "distance": distance, "k": 1000, "estimator": "beam",
                              "single_scattering": False, "photon_tile": 1.0}}}
    fan = ocean.render(doc, context=ctx).spectral[0, :, 0]
    assert fan.mean() == pytest.approx(expect, rel=0.05), (fan.mean() / expect - 1)
