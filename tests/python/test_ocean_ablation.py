"""The ocean engine's inelastic ablation as physics states it (thesis §5.3, Fig. 5.11):
the colour change by water, the inelastic light's sources, a closed-form bound on what
it adds, and the Baltic with and without inelastic events and anti-Stokes ones."""

import json
import math

import numpy as np
import pytest

import arcus.ocean as ocean
from test_ocean_render import camera_rays, view

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
