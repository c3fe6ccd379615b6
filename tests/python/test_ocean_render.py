"""Underwater images: the ray-marched radiance against closed forms and between its
two estimates, the features each image compiles, determinism, bad input (the inelastic
ablations: test_ocean_ablation.py)."""

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
