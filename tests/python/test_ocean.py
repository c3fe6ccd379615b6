"""The ocean engine through Python: water, photon traces and irradiance profiles.

Physics checks compare with conservation laws, closed forms and the ocean-optics
literature; tolerances are justified where they are set.  The comparison with an
independent plane-parallel solution is in test_ocean_profiles.py.
"""

import json
import math

import numpy as np
import pytest

import arcus
import arcus.ocean as ocean


def balanced(result, rel=1e-9):
    """Emitted = absorbed + escaped + past the limit + taken by the bottom: every photon's
    power is booked once, so the identity holds to rounding, not just within noise."""
    t = result.tallies
    booked = t["absorbed"] + t["escaped"] + t["past_limit"] + t["bottom"]
    return abs(booked - t["emitted"]) <= rel * t["emitted"]


def test_presets_and_parameters():
    for name in ocean.PRESETS:
        w = ocean.Water(name)
        assert w.parameters["chlorophyll"] >= 0
    with pytest.raises(arcus.ArgumentError, match="atlantic"):
        ocean.Water("lake_geneva")
    with pytest.raises(arcus.ArgumentError, match="unknown parameter"):
        ocean.Water(chlorophyl=1)


def test_bad_coefficients_name_the_parameter(ctx):
    with pytest.raises(arcus.ArgumentError, match="chlorophyll"):
        ocean.Water(chlorophyll=-1).coefficients(context=ctx)
    with pytest.raises(arcus.ArgumentError, match="a_y440"):
        ocean.Water(a_y440=float("nan")).coefficients(context=ctx)
    with pytest.raises(arcus.ArgumentError, match="absorption"):
        ocean.Water.from_iops(([400, 500], [0.1, -0.1]), 0.1).coefficients(context=ctx)
    with pytest.raises(arcus.ArgumentError, match="grid"):
        ocean.Water().coefficients(grid=(200, 300, 5), context=ctx)
    with pytest.raises(arcus.ArgumentError, match=r"lights\[0\].spectrum"):
        ocean.trace_photons(ocean.Water(), ocean.Light.point((0, 0, 0), ([500, 600], [1, -1])), 100, context=ctx)
    with pytest.raises(arcus.ArgumentError, match="max_interactions"):
        ocean.trace_photons(ocean.Water(), ocean.Light.point((0, 0, 0), 1), 100, max_interactions=0, context=ctx)


def test_coefficients_sum_to_the_inherent_optical_properties(ctx):
    c = ocean.Water("baltic").coefficients(context=ctx)
    # The ten events split absorption and scattering: their sum is a + b at every sample.
    total = c["absorption"].sum(axis=0) + c["scattering"].sum(axis=0)
    np.testing.assert_allclose(c["extinction"], total, rtol=1e-12)
    assert np.all(c["events"] >= 0)


def test_every_trace_balances_its_energy(ctx):
    w = ocean.Water("north_sea")
    r = ocean.profile(w, 40, [0, 1, 3], photons=50_000, sky=0.3, bottom_depth=4, bottom_albedo=0.2, context=ctx)
    assert balanced(r)
    assert r.tallies["bottom"] > 0 and r.tallies["escaped"] > 0
    p = ocean.trace_photons(w, ocean.Light.spot((0, 0, -3), (0, 0, -1), 20, 1.0), 50_000, context=ctx)
    assert balanced(p)


def test_same_seed_same_result_different_seeds_agree(ctx):
    w = ocean.Water("mediterranean")
    light = ocean.Light.point((0, 0, 0), 1.0)
    a = ocean.trace_photons(w, light, 100_000, seed=5, store=True, context=ctx)
    b = ocean.trace_photons(w, light, 100_000, seed=5, store=True, context=ctx)
    c = ocean.trace_photons(w, light, 100_000, seed=6, context=ctx)
    np.testing.assert_array_equal(a.absorbed_by_interaction, b.absorbed_by_interaction)
    np.testing.assert_array_equal(a.photons["positions"], b.photons["positions"])
    # The share absorbed at the first interaction is a binomial proportion over 1e5
    # photons (equal powers): σ ≤ 1.6e-3, so two seeds differ by < 5·√2·σ = 0.011.
    fa = a.absorbed_by_interaction[1] / a.tallies["emitted"]
    fc = c.absorbed_by_interaction[1] / c.tallies["emitted"]
    assert abs(fa - fc) < 0.011
    assert not np.array_equal(a.absorbed_by_interaction, c.absorbed_by_interaction)


def test_only_the_effects_the_water_has_are_compiled(ctx):
    light = ocean.Light.point((0, 0, 0), 1.0)
    elastic = ocean.Water(raman_scale=0, cdom_yield_scale=0, chlorophyll_yield=0)
    r = ocean.trace_photons(elastic, light, 20_000, context=ctx)
    assert "OCEAN_INELASTIC" not in r.features
    full = ocean.trace_photons(elastic, light, 20_000, force_inelastic=True, context=ctx)
    assert "OCEAN_INELASTIC" in full.features
    # No inelastic event has a coefficient, so both kernels draw the same events.
    np.testing.assert_array_equal(r.tallies["count"], full.tallies["count"])
    assert "OCEAN_INELASTIC" in ocean.trace_photons(ocean.Water(), light, 20_000, context=ctx).features
    prof = ocean.profile(elastic, 0, [1], photons=1000, context=ctx)
    assert {"OCEAN_BOUNDARIES", "OCEAN_DEPTHS"} <= prof.features


def test_raman_fills_in_red_light_at_depth(ctx):
    """Raman scattering shifts blue-green light, which clear water lets through, into the
    red, which it absorbs within metres: deep down the red irradiance is mostly Raman
    (Marshall & Smith 1990; Mobley 1994 §5.14), near the surface a trace of it."""
    depths = [2.0, 30.0]
    clear = dict(chlorophyll=0.05, a_d400=0.0, a_y440=0.0, chlorophyll_yield=0.0, cdom_yield_scale=0.0)
    # E_0 over 28-32 m (layer 4 m): few photons get that deep in the red, the layer
    # gathers enough of them; 3e6 photons take about 0.8 s.
    kw = dict(photons=3_000_000, grid=(450.0, 700.0, 10.0), context=ctx, seed=3, layer=4.0)
    with_raman = ocean.profile(ocean.Water(**clear), 0, depths, **kw)
    without = ocean.profile(ocean.Water(raman_scale=0, **clear), 0, depths, **kw)
    red = with_raman.wavelengths >= 640
    ratio = with_raman.E0[:, red].sum(axis=1) / without.E0[:, red].sum(axis=1)
    # Measured: 1.0004 at 2 m; 6.0 and 4.7 at 30 m for two seeds (the elastic red
    # light there is a few tens of photons, hence the loose bound).
    assert ratio[0] < 1.02
    assert ratio[1] > 3


def test_hard_cases(ctx):
    light = ocean.Light.point((0, 0, 0), 1.0)
    # No scattering: every photon is absorbed at its first interaction.
    clear = ocean.Water.from_iops(0.2, 0.0)
    r = ocean.trace_photons(clear, light, 10_000, context=ctx)
    assert r.tallies["interactions"] == 10_000 and balanced(r)
    # Albedo → 1: photons scatter many times; the limit ends them and keeps the books.
    white = ocean.Water.from_iops(1e-6, 1.0, phase="isotropic")
    r = ocean.trace_photons(white, light, 10_000, max_interactions=64, context=ctx)
    assert r.tallies["past_limit"] > 0.99 * r.tallies["emitted"] and balanced(r)
    # A light on the surface: half its photons leave at once (or reflect back).
    r = ocean.trace_photons(ocean.Water(), ocean.Light.point((0, 0, 0), 1.0), 20_000, surface=True, context=ctx)
    assert r.escaped_by_interaction[0] > 0 and balanced(r)
    # One wavelength: no inelastic re-emission can land in a zero-width range.
    r = ocean.trace_photons(ocean.Water(), light, 20_000, grid=(550, 550, 1), context=ctx)
    assert r.tallies["count"][1] == 0 and r.tallies["count"][4] == 0 and balanced(r)


def test_thesis_energy_convergence_by_interaction(ctx):
    """Thesis Fig. 5.9 (C = 0.1, a_d(400) = a_y(440) = 0.1): most of the energy is
    absorbed within the first interactions, and what is left past the fifth is small."""
    w = ocean.Water(chlorophyll=0.1, a_d400=0.1, a_y440=0.1)
    r = ocean.trace_photons(w, ocean.Light.point((0, 0, 0), 1.0), 200_000, max_interactions=5, context=ctx)
    absorbed = r.absorbed_by_interaction / r.tallies["emitted"]
    assert np.all(np.diff(absorbed[1:]) < 0)  # each interaction absorbs less than the one before
    assert r.tallies["past_limit"] / r.tallies["emitted"] < 0.1


def test_without_anti_stokes_no_photon_gains_energy(ctx):
    """Thesis Fig. 5.11 (right): with re-emission toward longer wavelengths only, photons
    from a 440 nm line never come back below 440 nm (the excitation is a grid sample,
    and re-emission then starts above it), and the inelastic coefficients shrink by the
    anti-Stokes share."""
    grid = (400.0, 700.0, 5.0)
    both, stokes = ocean.Water("baltic"), ocean.Water("baltic", anti_stokes=False)
    cb, cs = both.coefficients(grid=grid, context=ctx), stokes.coefficients(grid=grid, context=ctx)
    inelastic = [1, 4, 6]
    assert np.all(cs["events"][inelastic] <= cb["events"][inelastic] * (1 + 1e-12))
    assert cs["events"][inelastic].sum() < cb["events"][inelastic].sum()
    np.testing.assert_allclose(cs["extinction"], cb["extinction"], rtol=1e-12)  # only the split changes
    line = ocean.Light.point((0, 0, 0), ([439, 440, 441], [0, 1, 0]))
    kw = dict(grid=grid, store=True, max_interactions=5, context=ctx)
    r = ocean.trace_photons(stokes, line, 200_000, **kw)
    inelastic_photons = np.isin(r.photons["events"], inelastic)
    assert inelastic_photons.sum() > 100
    assert r.photons["wavelengths"].min() >= 440.0
    r = ocean.trace_photons(both, line, 200_000, **kw)
    assert r.photons["wavelengths"].min() < 440.0  # with anti-Stokes some do


def daylight_scene(tmp_path, lights, atmosphere=None):
    doc = {"name": "d", "water": {"preset": "atlantic"}, "lights": lights, "medium": {"surface": True},
           "profile": {"depths": [0, 5]}}
    if atmosphere:
        doc["atmosphere"] = atmosphere
    path = tmp_path / "daylight.json"
    path.write_text(json.dumps(doc))
    return path


def test_a_daylight_sun_and_sky_are_the_shared_daylights_irradiance_on_the_sea(tmp_path):
    # Determinism of the wiring: the scene's "daylight" spectra become arcus.daylight's
    # direct and diffuse plane irradiance at the sun's zenith in the scene's atmosphere
    # (that function is checked against SPCTRAL2 and closed forms in test_daylight.py),
    # and the library's document shows them as numbers.
    from arcus import _scene_file
    import arcus.daylight as daylight
    path = daylight_scene(tmp_path, [{"type": "sun", "zenith_deg": 40, "spectrum": "daylight"},
                                     {"type": "sky", "spectrum": "daylight"}], {"aerosol_depth_500": 0.3})
    lights = _scene_file.read(path, ("ocean",))[1]["lights"]
    nm = np.asarray(lights[0]["spectrum"]["nm"])
    assert nm[0] == 360 and nm[-1] == 830
    direct, diffuse = daylight.ground_irradiance(nm, 40.0, aerosol_depth_500=0.3)
    np.testing.assert_allclose(lights[0]["spectrum"]["values"], direct, rtol=1e-12)
    np.testing.assert_allclose(lights[1]["spectrum"]["values"], diffuse, rtol=1e-12)


@pytest.mark.parametrize("lights, words", [
    ([{"type": "sky", "spectrum": "daylight"}], ["$.lights[0].spectrum", "needs the sun"]),
    ([{"type": "point", "position": [0, 0, -1], "spectrum": "daylight"}], ["$.lights[0].spectrum", "sun or a sky"]),
    ([{"type": "sun", "zenith_deg": 10, "spectrum": "sunny"}], ["$.lights[0].spectrum", "daylight"]),
])
def test_a_bad_daylight_light_names_its_key(tmp_path, lights, words):
    from arcus import _scene_file
    with pytest.raises(arcus.ArgumentError) as e:
        _scene_file.read(daylight_scene(tmp_path, lights), ("ocean",))
    for w in words:
        assert w in str(e.value), str(e.value)


def stored_power_per_sample(water, carried, seeds, photons, grid):
    """The stored photons' power summed per grid sample, one row per seed."""
    first, last, step = grid
    rows = []
    for seed in seeds:
        r = ocean.trace_photons(water, ocean.Light.point((0, 0, 0), 1.0), photons, 5, seed, grid=grid, store=True,
                                wavelengths_per_photon=carried)
        p = r.photons
        k = np.rint((p["wavelengths"] - first) / step).astype(int)
        rows.append(np.bincount(k, weights=p["powers"], minlength=int(round((last - first) / step)) + 1))
    return np.array(rows)


def test_stored_photons_carry_the_closed_form_power_per_wavelength(ctx):
    """Unbounded water lit by an isotropic lamp of 1 W/nm: the photon map keeps a photon
    at its n-th interaction (n = 2..5) when all n were scatterings, so the power stored
    per grid sample is P(λ) Σ_{n=2..5} ω(λ)^n, P = 1 W/nm × 5 nm, ω = b/(a + b),
    whatever the paths' geometry.  Checked with one wavelength per photon (the thesis')
    and with four (hero wavelengths, trace.cl: the power split among the carried
    wavelengths by the balance heuristic), where the albedo runs from 0.86 to 0.38 over
    the grid so that the split matters.  Bound: 5.5 standard errors of the mean over 16
    seeds, per sample (Student's t with 15 degrees of freedom passes 5.5 with
    probability 5·10⁻⁵ per sample, 120 samples).  Four carried wavelengths put every
    photon's light into four samples, so each sample's noise falls (measured 2.4× at 8
    seeds; asserted ≥ 1.5×)."""
    grid = (400.0, 695.0, 5.0)  # 60 samples: four carried wavelengths, 75 nm apart
    nm = np.arange(400.0, 696.0, 5.0)
    absorption = (nm, 0.05 + 0.45 * (nm - 400) / 295)
    water = ocean.Water.from_iops(absorption, 0.3, phase="isotropic")
    albedo = 0.3 / (0.3 + absorption[1])
    expected = 5.0 * sum(albedo ** n for n in range(2, 6))
    spread = {}
    for carried in (1, 4):
        rows = stored_power_per_sample(water, carried, range(1, 17), 25_000, grid)
        mean, se = rows.mean(axis=0), rows.std(axis=0, ddof=1) / math.sqrt(len(rows))
        assert np.all(np.abs(mean - expected) < 5.5 * se), (carried, np.max(np.abs(mean - expected) / se))
        spread[carried] = np.sqrt(np.mean((se / expected) ** 2))
    assert spread[1] > 1.5 * spread[4], spread


def test_wavelengths_per_photon_is_checked(ctx):
    water = ocean.Water("atlantic")
    for bad in (0, 5, 2.5):
        with pytest.raises(arcus.ArgumentError, match="wavelengths_per_photon"):
            ocean.trace_photons(water, ocean.Light.point((0, 0, 0), 1.0), 100, wavelengths_per_photon=bad)


def test_carried_wavelengths_agree_with_one_per_photon_through_inelastic_events(ctx):
    """With Raman and both fluorescences, light changes wavelength on the way, and only
    the hero's is re-emitted (the set it carried goes on as the hero alone).  No closed
    form here, so the two estimators of the same stored power per grid sample — one
    wavelength per photon, and four — are compared with each other: they must agree
    within 5.5 combined standard errors (16 seeds each), in Baltic water, where 2.1 %
    of the emitted power reaches an inelastic event before the fifth interaction
    (mostly chlorophyll fluorescence: the samples about 685 nm hold re-emitted light)."""
    water = ocean.Water("baltic")
    grid = (400.0, 715.0, 5.0)  # 64 samples
    means, ses = [], []
    for carried in (1, 4):
        rows = stored_power_per_sample(water, carried, range(1, 17), 25_000, grid)
        means.append(rows.mean(axis=0))
        ses.append(rows.std(axis=0, ddof=1) / math.sqrt(len(rows)))
    combined = np.hypot(*ses)
    keep = combined > 0
    z = np.abs(means[0] - means[1])[keep] / combined[keep]
    assert np.all(z < 5.5), np.max(z)
