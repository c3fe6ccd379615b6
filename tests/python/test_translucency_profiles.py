"""Tabulated profiles (arcus.translucency.Profile, arcus_translucency_render_table) and
§3.4's Hermite fit: a table sampled from the dipole renders as the dipole does; eq. 3.6
is linear in R_d, so a blend renders as the same blend of renders, and a profile
stretched by s (§5.2) as the dipole stretched by s; the Hermite profile estimated from a
photo is monotone and re-renders the photo (tests/unit/test_translucency_hermite.cpp
checks its shape and energy against closed forms)."""

import numpy as np
import pytest

import arcus
from arcus.translucency import Dipole, Profile, estimate_bssrdf, render

from test_translucency_render import SPHERE, SPHERE_LIGHTS

VIEW = {"position": (0, 0, 5), "look_at": (0, 0, 0), "width": 40, "height": 40}
SKIM, APPLE = Dipole.from_material("skimmilk"), Dipole.from_material("apple")
# One sample spacing for every render compared here, so the samples are the same.
SETTINGS = dict(ortho_height=2.2, mm_per_unit=20, highlight_deg=0, sample_spacing_mm=0.5)


def relative_rms(a, b):
    m = a.covered
    return np.sqrt(np.mean((a.image[m] - b.image[m]) ** 2)) / np.mean(b.image[m])


@pytest.mark.parametrize("gather", ["brute_force", "hierarchical"])
def test_a_table_of_the_dipole_renders_as_the_dipole(ctx, gather):
    # 4096 samples linear in √r: interpolation error ~1e-7 of R_d (measured 4e-6 of
    # the image with float32 pixels); 60 mm reach holds all but e^-9 of apple's tail.
    table = Profile.from_dipole(APPLE, reach_mm=60)
    np.testing.assert_allclose(table.total_reflectance, APPLE.total_reflectance, rtol=1e-4)
    a = render(table, SPHERE, SPHERE_LIGHTS, VIEW, gather=gather, context=ctx, **SETTINGS)
    b = render(APPLE, SPHERE, SPHERE_LIGHTS, VIEW, gather=gather, context=ctx, **SETTINGS)
    assert relative_rms(a, b) < 1e-4
    assert "TRANSLUCENCY_TABLE" in a.features and "TRANSLUCENCY_DIPOLE" not in a.features


def test_a_blend_renders_as_the_blend_of_renders(ctx):
    # Eq. 3.6 is linear in R_d: render(w a + (1 − w) b) = w render(a) + (1 − w) render(b).
    w = np.array([0.25, 0.5, 0.8])
    blend = Profile.blend([SKIM, APPLE], [w, 1 - w])
    mixed = render(blend, SPHERE, SPHERE_LIGHTS, VIEW, context=ctx, gather="brute_force", **SETTINGS)
    a = render(SKIM, SPHERE, SPHERE_LIGHTS, VIEW, context=ctx, gather="brute_force", **SETTINGS)
    b = render(APPLE, SPHERE, SPHERE_LIGHTS, VIEW, context=ctx, gather="brute_force", **SETTINGS)
    expected = w * a.image + (1 - w) * b.image
    m = a.covered
    assert np.sqrt(np.mean((mixed.image[m] - expected[m]) ** 2)) / np.mean(expected[m]) < 1e-4
    np.testing.assert_allclose(blend.total_reflectance,
                               w * SKIM.total_reflectance + (1 - w) * APPLE.total_reflectance, rtol=5e-3)


@pytest.mark.parametrize("scaling", ["energy", "thesis"])
def test_a_stretched_table_renders_as_the_stretched_dipole(ctx, scaling):
    table = Profile.from_dipole(APPLE, reach_mm=60)
    kw = dict(SETTINGS, profile_scale=1.5, profile_scaling=scaling, gather="brute_force", context=ctx)
    assert relative_rms(render(table, SPHERE, SPHERE_LIGHTS, VIEW, **kw),
                        render(APPLE, SPHERE, SPHERE_LIGHTS, VIEW, **kw)) < 1e-4


def test_profiles_from_samples_and_bad_profiles():
    r = np.linspace(0, 10, 101)
    p = Profile.from_samples(r, np.exp(-r)[:, None] * [1, 2, 3])
    np.testing.assert_allclose(p.Rd([0.0, 1.0, 9.99])[:, 0], np.exp(-np.array([0.0, 1.0, 9.99])), rtol=2e-3)
    assert (p.Rd([10.5]) == 0).all()
    with pytest.raises(arcus.ArgumentError, match="radii"):
        Profile.from_samples([1, 2], np.ones((2, 3)))
    with pytest.raises(arcus.ArgumentError, match="values"):
        Profile(5.0, -np.ones((4, 3)))
    with pytest.raises(arcus.ArgumentError, match="eta"):
        Profile.blend([SKIM, Dipole.from_material("marble")], [0.5, 0.5])
    with pytest.raises(arcus.ArgumentError, match="one weight per profile"):
        Profile.blend([SKIM, APPLE], [1.0])


def test_the_hermite_profile_is_monotone_and_re_renders_the_photo(ctx):
    view = dict(VIEW, width=100, height=100)
    photo = render(SKIM, SPHERE, SPHERE_LIGHTS, view, ortho_height=2.2, mm_per_unit=20, highlight_deg=0,
                   context=ctx)
    e = estimate_bssrdf(photo.image, SPHERE, SPHERE_LIGHTS, view, ortho_height=2.2, mm_per_unit=20,
                        subtract_minimum=False, fit="hermite", context=ctx)
    h = e.fitted
    assert h is e.hermite and isinstance(h, Profile) and h.reach_mm == pytest.approx(e.profile[0][-1])
    assert (np.diff(h.values, axis=0) <= 1e-15).all() and (h.values >= 0).all()
    # §3.4 asks for a plausible profile: the re-render within 5% RMS of the mean
    # radiance (the bound issue 21 sets for re-renders; measured 1.6–2.3%) and R_total
    # within 5% of the truth (measured 1.8–4.2%: the 1.7 mm bins smooth R_d's peak).
    again = render(h, SPHERE, SPHERE_LIGHTS, view, ortho_height=2.2, mm_per_unit=20, highlight_deg=0, context=ctx)
    assert relative_rms(again, photo) < 0.05
    np.testing.assert_allclose(h.total_reflectance, SKIM.total_reflectance, rtol=0.05)
