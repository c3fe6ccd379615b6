"""arcus.sky.render and `arcus render` on a rainbow scene: a rendered
bow against its own phase table (the brightest red row where the table's red peaks, to
the pixel), Alexander's dark band, the secondary's reversed colours, the volume table's
energy against the drops' cross-sections, size distributions, and bad input (explained,
not crashed).  Small tables (8 wavelengths, grid 300) keep it to seconds on two cores."""

import math
import os
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import arcus
import arcus.mie as mie
from arcus import sky, sky_profile

from conftest import BINDINGS

SCENES = Path(__file__).resolve().parents[2] / "scenes" / "rainbow"
WIDTH, HEIGHT, SPAN = 41, 401, 40.0  # a strip of 40° up the sky, 0.1° a row


def strip_scene(populations, **tables):
    """Looking 46° up at the top of the bows with the sun on the horizon behind: rows
    run over scattering angles 180° − (26°…66°) (≈ 114°…154°), one row ≈ 0.1°."""
    half_width = math.tan(math.radians(SPAN / 2)) * WIDTH / HEIGHT
    return {
        "image": {"width": WIDTH, "height": HEIGHT, "fov_deg": 2 * math.degrees(math.atan(half_width)),
                  "exposure": 1},
        "camera": {"position": [0, 1.7, 0], "look_azimuth_deg": 0, "look_elevation_deg": 46},
        "sun": {"elevation_deg": 0, "azimuth_deg": 180, "diameter_deg": 0, "samples": 1, "spectrum": "flat"},
        "rain": {"box_min": [-5000, 0, 200], "box_max": [5000, 5000, 1200], "march_steps": 64,
                 "populations": populations},
        "background": {"sky": {"radiance": 0.0}, "ground": {"radiance": 0.0}},
        "tables": dict({"wavelengths": {"linspace": [400, 700, 8]}, "theta": {"range": [100, 180, 0.05]}, "grid": 300,
                        "max_bounces": 3},
                       **tables),
    }


DROPS = [{"shape": "sphere", "radius": 5e-4, "density": 300, "method": "rays"}]


@pytest.fixture(scope="module")
def bows(ctx, tmp_path_factory):
    """The 500 µm bows rendered down the strip, and the table they were rendered with."""
    return sky.render(strip_scene(DROPS), cache_dir=tmp_path_factory.mktemp("tables"), context=ctx)


def column(result):
    """The centre column (through the antisolar point): θ, linear R, G, B and Y."""
    c = WIDTH // 2
    return result.theta[:, c].astype(float), result.image[:, c, :].astype(float), result.xyz[:, c, 1].astype(float)


def table_rgb(result, theta):
    """The table's own colour at angles θ: Σ_λ E(λ)·β(λ, θ)·w(λ) through the same
    XYZ → linear sRGB matrix (IEC 61966-2-1), with the CIE band weights recomputed here
    from the 1931 functions by trapezoids (independent of the library's weights)."""
    t = result.table
    beta = np.array([np.interp(theta, t.theta, t.beta[l, 0]) for l in range(t.wavelengths.size)])  # (L, rows)
    cmf = np.loadtxt(Path(__file__).resolve().parents[2] / "data" / "spectra" / "cie1931_2deg_5nm.csv",
                     delimiter=",", skiprows=1)
    xyz = np.array([np.interp(t.wavelengths, cmf[:, 0], cmf[:, k]) for k in (1, 2, 3)])  # (3, L)
    m = np.array([[3.2406, -1.5372, -0.4986], [-0.9689, 1.8758, 0.0415], [0.0557, -0.2040, 1.0570]])
    return (m @ xyz @ beta).T  # (rows, 3), up to a common scale


def test_red_edge_of_the_primary_sits_where_the_table_puts_it(bows):
    # The brightest red row of the primary (θ 134°-142°) against the angle where the
    # table's red peaks, sampled at the rows' own θ: the march's attenuation varies by
    # < 1 % across the bow (the rain box is wide), far too little to move a peak whose
    # width is ~1°, so they must agree to the pixel (0.1°).
    theta, rgb, _ = column(bows)
    band = (theta > 134) & (theta < 142)
    row_image = np.flatnonzero(band)[np.argmax(rgb[band, 0])]
    expected = table_rgb(bows, theta[band])[:, 0]
    row_table = np.flatnonzero(band)[np.argmax(expected)]
    assert abs(int(row_image) - int(row_table)) <= 1, (theta[row_image], theta[row_table])
    # and that angle is the primary bow of water near 650 nm (eq. 4.20 gives 137.7°-138°
    # for the red end; interference moves the maximum inside by a few tenths)
    assert 137.0 < theta[row_image] < 139.0


def test_alexanders_dark_band_is_darker_than_both_sides(bows):
    theta, _, y = column(bows)
    band = y[(theta > 131) & (theta < 136.5)].mean()      # between the bows
    inside = y[(theta > 140) & (theta < 150)].mean()      # inside the primary
    outside = y[(theta > 116) & (theta < 126)].mean()     # outside the secondary
    assert band < 0.5 * inside and band < 0.9 * outside, (band, inside, outside)


def test_the_secondarys_colours_are_reversed(bows):
    # Primary: red outside (smaller θ), blue inside.  Secondary (p = 3): the reverse.
    theta, rgb, _ = column(bows)

    def peak(lo, hi, channel):
        sel = (theta > lo) & (theta < hi)
        return theta[sel][np.argmax(rgb[sel, channel])]

    assert peak(134, 142, 0) < peak(134, 142, 2)
    assert peak(123, 132, 0) > peak(123, 132, 2)


def supernumerary_maxima(theta, y, primary):
    """The maxima of y(θ) inside the primary's (θ above it), each with its Michelson
    contrast against the minimum before it: [(θ, contrast), …]."""
    out, last = [], primary
    for i in range(1, theta.size - 1):
        if theta[i] > theta[primary] and y[i] > y[i - 1] and y[i] >= y[i + 1]:
            low = y[last:i + 1].min()
            out.append((float(theta[i]), float((y[i] - low) / (y[i] + low))))
            last = i
    return out


def bow_top_profile(scene, ctx, cache):
    """A sun-8°-up scene rendered down a strip of 10° through the top of its primary
    (41.5° above the antisolar point), 0.05° a row: θ and Y up the centre column, in
    increasing θ, and the row of the primary's maximum."""
    rows, columns, span = 201, 11, 10.0
    half_width = math.tan(math.radians(span / 2)) * columns / rows
    scene["image"].update(width=columns, height=rows, fov_deg=2 * math.degrees(math.atan(half_width)))
    scene["camera"]["look_elevation_deg"] = 31.0
    result = sky.render(scene, cache_dir=cache, context=ctx)
    theta, y = result.theta[:, columns // 2].astype(float), result.xyz[:, columns // 2, 1].astype(float)
    order = np.argsort(theta)
    theta, y = theta[order], y[order]
    return theta, y, int(np.argmax(np.where((theta > 137) & (theta < 140), y, 0)))


def test_the_supernumerary_scene_shows_two_distinct_supernumerary_arcs(ctx, tmp_path):
    # The bundled scene (its drops, tables, sun disc, spectrum and dark cloud) rendered
    # down a strip through the top of the bow, 0.05° a row.  Lorenz–Mie at 2 nm through
    # the sun's disc (an independent profile) puts the first two supernumerary maxima
    # 1.0° and 1.7° inside the primary's maximum, with Michelson contrasts of 18 % and
    # 13 % in the drops' light, ~12 % and 9 % over the cloud; the eye sees ~2 %.  A
    # render that smears them (too few wavelengths, sun points or angles) or loses the
    # interference falls below 5 %.
    scene = sky.load_scene(SCENES / "supernumerary.json")
    theta, y, primary = bow_top_profile(scene, ctx, tmp_path)
    maxima = supernumerary_maxima(theta, y, primary)
    assert len(maxima) >= 2, maxima
    (first, c1), (second, c2) = maxima[:2]
    assert 0.7 < first - theta[primary] < 1.3 and 1.4 < second - theta[primary] < 2.0, (theta[primary], maxima)
    assert c1 > 0.05 and c2 > 0.05, maxima


def test_drops_of_half_a_millimetre_leave_only_a_shoulder(ctx, tmp_path):
    # The thesis' 500 µm drops (Fig. 5.22a) through the sun's disc: Mie at 2 nm gives no
    # maximum within 1.3° inside the primary (the first supernumerary is a shoulder).
    scene = sky.load_scene(SCENES / "supernumerary_500um.json")
    # the rays method's tables are slow at 1000 grid points; Mie's are the physics here
    scene["rain"]["populations"][0]["method"] = "mie"
    theta, y, primary = bow_top_profile(scene, ctx, tmp_path)
    near = [m for m in supernumerary_maxima(theta, y, primary) if m[0] - theta[primary] < 1.3 and m[1] > 0.01]
    assert not near, near


def test_volume_table_conserves_energy(tmp_path):
    # White sun, non-absorbing drops: the light the rain scatters, ∫ β dΩ over the whole
    # sphere, equals what the drops take out of the beam, N·C_sca, per wavelength.
    # Mie: C_sca = Q_sca·πa² (from the efficiencies, not from the phase function).  The
    # 0.01° quadrature of the 50 µm drop's forward peak (width ~λ/2a ≈ 0.3°) is good to
    # well below 0.5 %.
    scene = strip_scene([{"shape": "sphere", "radius": 5e-5, "density": 1e5, "method": "mie"}],
                        theta={"range": [0, 180, 0.01]}, wavelengths=[450, 550, 650])
    table = sky.volume_table(scene, cache_dir=tmp_path)
    th = np.radians(table.theta)
    for l, nm in enumerate(table.wavelengths):
        scattered = 2 * math.pi * np.trapezoid(table.beta[l, 0] * np.sin(th), th)
        m = mie.phase_function(5e-5, nm, [90.0])
        assert scattered == pytest.approx(1e5 * m.q_sca * math.pi * 5e-5**2, rel=5e-3)
        assert table.extinction[l] == pytest.approx(1e5 * m.q_ext * math.pi * 5e-5**2, rel=1e-12)


def test_ray_tables_scatter_what_the_drops_intercept(tmp_path):
    # Rays: every term p ≤ 15 of a non-absorbing drop leaves it, so ∫ β dΩ = N·πa²·(1 −
    # remaining) with remaining < 1e-3: the sky's scattered light is the sun's light the
    # drops intercept.  Integrated by the 0.02° trapezoid rule over a coherent table whose
    # fringes (~0.1° at 500 µm) it resolves; 2 % covers the caustics' spikes.
    scene = strip_scene([{"shape": "sphere", "radius": 5e-4, "density": 10, "method": "rays"}],
                        theta={"range": [0, 180, 0.02]}, wavelengths=[550, 650], max_bounces=15,
                        grid=400)
    table = sky.volume_table(scene, cache_dir=tmp_path)
    th = np.radians(table.theta)
    for l in range(table.wavelengths.size):
        scattered = 2 * math.pi * np.trapezoid(table.beta[l, 0] * np.sin(th), th)
        assert scattered == pytest.approx(10 * math.pi * 5e-4**2, rel=2e-2)


def test_marshall_palmer_bins_hold_the_rain_rate_s_drops():
    # Marshall & Palmer: ∫ N0 e^{−ΛD} dD over [a, b] in closed form, Λ = 4.1 R^−0.21.
    pops = sky.populations({"populations": [{"shape": "sphere", "distribution": "marshall_palmer",
                                             "rain_rate_mm_h": 5, "diameter_range_mm": [0.4, 1.6], "bins": 6,
                                             "nonspherical_above_mm": 1.0}]}, 10.0)
    lam = 4.1 * 5**-0.21
    exact = 8000 / lam * (math.exp(-lam * 0.4) - math.exp(-lam * 1.6))
    assert sum(d for _, d in pops) == pytest.approx(exact, rel=1e-9)
    kinds = {s["kind"] for s, _ in pops}
    assert kinds == {"sphere", "raindrop"}  # the bigger bins take the falling drop's shape
    for s, _ in pops:
        if s["kind"] == "raindrop":
            assert s["diameter"] >= 1e-3
            r = np.array(s["rotation"])
            assert np.allclose(r @ r.T, np.eye(3), atol=1e-12) and np.linalg.det(r) == pytest.approx(1)


@pytest.mark.parametrize("distribution", ["gamma", "lognormal"])
def test_cloud_droplet_bins_hold_the_effective_radius_and_variance(distribution):
    # Hansen & Travis (1974) define a cloud's sizes by the effective radius a = ∫r³n/∫r²n
    # and effective variance b = ∫(r − a)²r²n/(a²∫r²n): the Gauss–Legendre bins over the
    # default range (all but 1e-4 of the cross-section at each end; by the rays method,
    # which keeps fixed bins) must hold both.  The range's cut tails shift a by 1-2e-4
    # and b by 3-5e-3 of themselves (measured; 12 bins already integrate the smooth n(r)
    # to far better), hence 1e-3 and 1e-2.
    pops = sky.populations({"populations": [{"shape": "sphere", "distribution": distribution,
                                             "effective_radius": 10e-6, "effective_variance": 0.1,
                                             "total_density": 1e8, "bins": 48, "method": "rays"}]}, 10.0)
    r = np.array([s["radius"] for s, _ in pops])
    n = np.array([d for _, d in pops])
    assert n.sum() == pytest.approx(1e8, rel=1e-12)
    a = np.sum(r ** 3 * n) / np.sum(r ** 2 * n)
    b = np.sum((r - a) ** 2 * r ** 2 * n) / (a ** 2 * np.sum(r ** 2 * n))
    assert a == pytest.approx(10e-6, rel=1e-3)
    assert b == pytest.approx(0.1, rel=1e-2)


@pytest.mark.parametrize("distribution", ["gamma", "lognormal"])
def test_moving_mie_sizes_hold_the_cross_section_and_stratify_it(distribution):
    """By Mie, cloud droplets take sizes that move from one wavelength to the next
    (arcus._drop_sizes.stratified_nodes): each wavelength's row has one size in each of
    the bins' strata of equal cross-section, and holds the distribution's cross-section
    exactly.  The strata and the cross-section here come from scipy's distributions
    (Hansen & Travis' gamma: r²n is a gamma of shape α + 3; the lognormal's r²n a
    lognormal of median r_g e^{2σ²}), not from the code's own tabulated ones."""
    stats = pytest.importorskip("scipy.stats")
    a_eff, b_eff, total, bins, rows = 10e-6, 0.1, 1e8, 48, 66
    pops = sky.populations({"populations": [{"shape": "sphere", "distribution": distribution,
                                             "effective_radius": a_eff, "effective_variance": b_eff,
                                             "total_density": total, "bins": bins, "method": "mie"}]}, 10.0, rows)
    r = np.array([s["radius"] for s, _ in pops]).T  # (rows, bins)
    n = np.array([d for _, d in pops]).T
    assert r.shape == n.shape == (rows, bins) and all(s["method"] == "mie" for s, _ in pops)
    if distribution == "gamma":
        alpha = (1 - 3 * b_eff) / b_eff
        number, cross = stats.gamma(alpha + 1, scale=a_eff * b_eff), stats.gamma(alpha + 3, scale=a_eff * b_eff)
        r2 = (alpha + 1) * (alpha + 2) * (a_eff * b_eff) ** 2
    else:
        sigma2 = math.log1p(b_eff)
        r_g = a_eff / (1 + b_eff) ** 2.5
        number = stats.lognorm(math.sqrt(sigma2), scale=r_g)
        cross = stats.lognorm(math.sqrt(sigma2), scale=r_g * math.exp(2 * sigma2))
        r2 = r_g ** 2 * math.exp(2 * sigma2)
    lo, hi = cross.ppf(1e-4), cross.isf(1e-4)  # the default range
    # <r²> over the range: ∫r²n / ∫n, each the share of its distribution in the range
    mean_r2 = r2 * (cross.cdf(hi) - cross.cdf(lo)) / (number.cdf(hi) - number.cdf(lo))
    # every row: the distribution's cross-section (the code's trapezoids over 8193
    # points err by ~1e-7: bound 1e-5) ...
    np.testing.assert_allclose(np.sum(n * r ** 2, axis=1), total * mean_r2, rtol=1e-5)
    # ... one size per stratum (the numeric CDF's error is ~1e-7 of a stratum) ...
    F = (cross.cdf(r) - cross.cdf(lo)) / (cross.cdf(hi) - cross.cdf(lo))
    assert np.array_equal(np.floor(F * bins), np.tile(np.arange(bins), (rows, 1)))
    # ... at an offset in it that differs from row to row
    offsets = (F * bins) % 1.0
    assert np.ptp(offsets[:, bins // 2]) > 0.9
    # Over the rows the number and Hansen & Travis' moments come back: each row's scatter
    # (its extreme strata's sizes move the most; b per row up to 18 % off at 48 bins, 31 %
    # for the lognormal's longer tail) averages out as the offsets fill the strata
    # (measured over 66 rows: number 8e-4 and 5e-4, a 3e-4 and 4e-4, b 7e-3 and 1.2e-2):
    # bounds 5e-3, 2e-3, 2e-2.
    a = np.sum(r ** 3 * n, axis=1) / np.sum(r ** 2 * n, axis=1)
    b = np.sum((r - a[:, None]) ** 2 * r ** 2 * n, axis=1) / (a ** 2 * np.sum(r ** 2 * n, axis=1))
    assert np.mean(n.sum(axis=1)) == pytest.approx(total, rel=5e-3)
    assert np.mean(a) == pytest.approx(a_eff, rel=2e-3)
    assert np.mean(b) == pytest.approx(b_eff, rel=2e-2)


@pytest.mark.parametrize("population, words", [
    ({"distribution": "gamma", "effective_radius": 1e-5, "effective_variance": 0.4}, "(0, 1/3)"),
    ({"distribution": "lognormal", "effective_radius": 1e-5, "effective_variance": 0}, "effective_variance"),
    ({"distribution": "lognormal", "effective_radius": -1e-5}, "effective_radius"),
    ({"distribution": "gamma", "mode_radius": 1e-5, "effective_radius": 1e-5}, "not both"),
    ({"distribution": "lognormal", "effective_radius": 1e-5, "mu": 3}, "mode_radius"),
])
def test_bad_cloud_droplets_are_explained(population, words):
    with pytest.raises(arcus.ArgumentError, match=re.escape(words)):
        sky.populations({"populations": [dict(population, shape="sphere", total_density=1e8, method="mie")]}, 10.0)


@pytest.mark.parametrize("change, words", [
    (lambda s: s["rain"].update(populations=[]), "non-empty list"),
    (lambda s: s["rain"]["populations"][0].update(density=-1), "density"),
    (lambda s: s["sun"].update(elevation_deg=-2), "below the horizon"),
    (lambda s: s["tables"].update(wavelengths={"linspace": [150, 700, 4]}), "wavelength"),
    (lambda s: s["tables"].update(theta=[100, 120, 180]), "uniform"),
    (lambda s: s["rain"].update(box_min=[0, 0]), "box_min"),
    (lambda s: s["rain"]["populations"][0].update(shape="cube"), "shape"),
    (lambda s: s["rain"]["populations"][0].update(distribution="weibull", bins=3), "distribution"),
    (lambda s: s.update(atmosphere={"ozone": 300}), "unknown atmosphere parameter ozone"),
    (lambda s: s.update(atmosphere={"ozone_du": -5}), "desc.ozone_du"),
    (lambda s: s["sun"].update(spectrum="daylight", irradiance=2), "remove irradiance"),
    (lambda s: s["background"].update(ground={"type": "daylight", "albedo": 2}), "albedo"),
    (lambda s: s["background"].update(sky={"type": "daylight", "albedo": 0.3}), "daylight background takes type only"),
])
def test_bad_scenes_are_explained(ctx, tmp_path, change, words):
    scene = strip_scene([dict(DROPS[0])])
    scene["image"].update(width=3, height=3)
    change(scene)
    with pytest.raises(arcus.Error) as err:
        sky.render(scene, cache_dir=tmp_path, context=ctx)
    assert words in str(err.value)


def test_a_daylight_sun_is_the_suns_spectrum_through_the_air_at_its_elevation():
    # The scene's sun is arcus.daylight's: ASTM G173 through the refracted path.  Lower,
    # it is dimmer and redder (2° up: air mass 19).
    wl = np.array([450.0, 550.0, 650.0])
    high = sky.sun_spectrum({"elevation_deg": 40, "spectrum": "daylight"}, wl)
    low = sky.sun_spectrum({"elevation_deg": 2, "spectrum": "daylight"}, wl)
    expected = arcus.daylight.solar_irradiance(wl, band=100) * arcus.daylight.sun_transmittance(wl, 50)
    np.testing.assert_allclose(high, expected, rtol=1e-12)
    assert np.all(low < high) and low[0] / low[2] < 0.3 * high[0] / high[2]


def test_bundled_scenes_parse():
    # Every bundled scene names valid populations (no tables are computed here).
    for path in sorted(SCENES.glob("*.json")):
        scene = sky.load_scene(path)
        assert sky.populations(scene["rain"], scene["sun"]["elevation_deg"]), path
        assert sky.wavelengths_of(scene["tables"]).size >= 33, path  # the issue's ≥ 33 wavelengths


def test_command_line_writes_images_and_explains_errors(tmp_path):
    import json
    scene = strip_scene([{"shape": "sphere", "radius": 2e-4, "density": 300, "method": "mie"}])
    scene["image"].update(width=16, height=12)
    path = tmp_path / "scene.json"
    path.write_text(json.dumps(scene))
    env = dict(os.environ, PYTHONPATH=str(BINDINGS), ARCUS_CACHE_DIR=str(tmp_path / "cache"))
    command = [sys.executable, "-m", "arcus.cli", "render", str(path), "--quiet"]
    out = subprocess.run(command + ["-o", str(tmp_path / "sky.exr"), "-o", str(tmp_path / "sky.png")],
                         capture_output=True, text=True, timeout=300, env=env)
    assert out.returncode == 0, out.stderr
    assert (tmp_path / "sky.exr").stat().st_size > 0 and (tmp_path / "sky.png").stat().st_size > 0
    assert "wrote" in out.stdout
    scene["sun"]["elevation_deg"] = -5
    path.write_text(json.dumps(scene))
    bad = subprocess.run(command + ["-o", str(tmp_path / "bad.png")], capture_output=True, text=True, timeout=300,
                         env=env)
    assert bad.returncode == 2 and "below the horizon" in bad.stderr
    assert not (tmp_path / "bad.png").exists()


def test_arcus_rainbow_render_is_the_deprecated_name_of_arcus_sky_render():
    with pytest.warns(DeprecationWarning, match="arcus.sky.render"):
        assert arcus.rainbow.render is arcus.sky.render


def test_the_radial_profile_is_each_bins_mean_light():
    # Four pixels, three 0.1° bins: Y is the mean of each bin's pixels, (x, y) the
    # chromaticity of their mean XYZ (not the mean of their chromaticities).
    theta = np.array([[0.05, 0.15], [0.16, 0.35]])
    xyz = np.array([[[1, 1, 1], [2, 2, 0]], [[0, 4, 2], [3, 3, 3]]], dtype=float)
    image = sky.SkyImage(image=xyz, xyz=xyz, theta=theta, table=None, features=frozenset(), seconds={})
    p = sky_profile.radial_profile(image, 0.1)
    np.testing.assert_allclose(p["theta"], [0.05, 0.15, 0.35])
    np.testing.assert_array_equal(p["pixels"], [1, 2, 1])
    np.testing.assert_allclose(p["Y"], [1, 3, 3])
    np.testing.assert_allclose(p["x"], [1 / 3, 1 / 5, 1 / 3])  # the second bin's mean XYZ: (1, 3, 1)
    np.testing.assert_allclose(p["y"], [1 / 3, 3 / 5, 1 / 3])
    with pytest.raises(arcus.ArgumentError):
        sky_profile.radial_profile(image, 0)


def test_the_reference_angles_are_the_closed_forms_of_each_scenes_particles():
    # Descartes' bows of water (137.6–139.4° and 126.4–129.8° over 400–700 nm), the
    # minimum deviations of ice's 60° and 90° prisms (21.6–22.6°, 45.1–47.8°), and for
    # plates with vertical axes Bravais' parhelia, farther out as the sun rises.
    bows = sky_profile.reference_angles(SCENES / "twinned.json")  # two populations of drops, named once
    assert [label for _, _, label in bows] == ["primary bow", "secondary bow"]
    assert 137.4 < bows[0][0] < bows[0][1] < 139.6 and 126.2 < bows[1][0] < bows[1][1] < 130.0
    halos = {label: (low, high) for low, high, label in sky_profile.reference_angles(SCENES / "halo.json")}
    assert 21.5 < halos["22° halo"][0] < halos["22° halo"][1] < 22.7
    assert 45.0 < halos["46° halo"][0] < halos["46° halo"][1] < 48.0
    (low, high, label), = sky_profile.reference_angles(SCENES / "sundogs.json")  # the sun 20° up
    assert label == "parhelia" and halos["22° halo"][1] < low < high < 24.0


def test_a_daylight_ground_is_the_atmospheres_ground_given_once():
    # The ground a rainbow scene shows (background.ground, albedo 0.2 by default) is the
    # one that lights its sky back; an atmosphere.ground_albedo beside it is refused.
    scene = sky.load_scene(SCENES / "double_bow.json")
    assert sky.ground_lit_atmosphere(scene).ground_albedo == scene["background"]["ground"].get("albedo", 0.2)
    scene["atmosphere"] = dict(scene.get("atmosphere", {}), ground_albedo=0.5)
    with pytest.raises(arcus.ArgumentError) as e:
        sky.ground_lit_atmosphere(scene)
    assert "atmosphere.ground_albedo" in str(e.value) and "background.ground.albedo" in str(e.value)
