"""Light directions from the photograph alone (thesis §3.4, Fig. 3.10; Lopez-Moreno et
al. 2009): arcus.translucency.detect_lights against photographs whose light is known —
the engine's renders of four geometries as opaque, translucent and very translucent
objects, and a Lambertian sphere in closed form — and its refusals of bad input."""

import numpy as np
import pytest

from arcus.translucency import detect_lights
from arcus._errors import ArgumentError

from photo_scenes import (FIG_3_10_LIGHT, MATERIALS, angle_deg, fig_3_10_photo, geometries, lambertian_sphere,
                          photograph, toward)


@pytest.fixture(scope="module")
def fig_3_10():
    """{(geometry, material): Rendered} under Fig. 3.10's light, (θ, φ) = (145°, 45°)."""
    return {(g, m): fig_3_10_photo(g, m) for g in geometries() for m in MATERIALS}


@pytest.mark.heavy
def test_fig_3_10_every_direction_within_20_degrees(fig_3_10):
    """Each of the twelve photos gives one light within 20° of the truth: the thesis'
    bound, below which its authors found the error goes unnoticed (its worst, 16.3°,
    is geometry 3's opaque zenith).  The detector's stand-in shape is exact only for
    the sphere, and its contour model is Lambertian, so the translucent objects and the
    three other meshes test how far both carry.  Measured: 1.5–4.3° (docs)."""
    truth = toward(*FIG_3_10_LIGHT)
    errors = {}
    for (geometry, material), photo in fig_3_10.items():
        found = detect_lights(photo.image, photo.covered)
        assert len(found.lights) == 1, (geometry, material, found.lights)
        errors[geometry, material] = angle_deg(found.lights[0].direction, truth)
    print("\n".join("%-13s %-17s %.1f°" % (g, m, e) for (g, m), e in errors.items()))
    assert max(errors.values()) < 20, errors


def test_closed_form_sphere_is_found_to_a_fraction_of_a_degree():
    """On a Lambertian sphere the detector's models are exact (the contour's clamped
    cosine, the stand-in's sphere): what is left is the pixel grid (a 50-pixel radius)
    and the zenith's 1° steps, so 1.5° bounds it (measured: 0.15° at most)."""
    for azimuth in (30.0, 145.0, 260.0):
        for zenith, bound in ((20.0, 1.5), (45.0, 1.5), (70.0, 1.5)):
            photo, matte, _ = lambertian_sphere([(azimuth, zenith, 1.0)])
            found = detect_lights(photo, matte)
            assert len(found.lights) == 1
            assert angle_deg(found.lights[0].direction, toward(azimuth, zenith)) < bound, (azimuth, zenith)


@pytest.mark.heavy
def test_two_lights_are_found_as_two():
    """Two lights 125° apart, one 0.6 of the other, on the translucent sphere and the
    closed-form one: two found, each within 20° of its own, the stronger first.  Their
    lobes on the contour overlap (each spans 180°), which k-means alone would merge."""
    lights = [(145.0, 45.0, 1.0), (20.0, 60.0, 0.6)]
    sphere = geometries()["sphere"]
    rendered = photograph(sphere, MATERIALS["translucent"], lights)
    closed_form, matte, _ = lambertian_sphere(lights)
    for photo, mask in ((rendered.image, rendered.covered), (closed_form, matte)):
        found = detect_lights(photo, mask)
        assert len(found.lights) == 2, found.lights
        for light, (a, z, _) in zip(found.lights, lights):
            assert angle_deg(light.direction, toward(a, z)) < 20, (light, a, z)
        assert found.lights[0].intensity > found.lights[1].intensity
        assert sum(light.intensity for light in found.lights) == pytest.approx(1.0)


def test_segmented_without_a_matte():
    """Without a matte the object is what stands above the photo's frame: all of a very
    translucent sphere, whose unlit side still glows (within 1% of the true pixels), and
    its light within 20°."""
    photo = fig_3_10_photo("sphere", "very translucent")
    found = detect_lights(photo.image)
    assert found.segmented
    assert abs(found.object_pixels - photo.covered.sum()) <= 0.01 * photo.covered.sum()
    assert angle_deg(found.lights[0].direction, toward(*FIG_3_10_LIGHT)) < 20


def test_the_same_photo_gives_the_same_lights():
    """A determinism test: k-means starts from a fixed seed."""
    photo, matte, _ = lambertian_sphere([(145.0, 45.0, 1.0), (20.0, 60.0, 0.6)])
    a, b = detect_lights(photo, matte), detect_lights(photo, matte)
    assert [l.direction.tolist() for l in a.lights] == [l.direction.tolist() for l in b.lights]


def rim_glints(count, size=128, radius=50.0):
    """A sphere lit from the camera with `count` bright glints spaced round its rim."""
    photo, matte, _ = lambertian_sphere([(0.0, 0.0, 1.0)], size, radius)
    y, x = np.mgrid[0:size, 0:size] + 0.5
    u, v = (x - size / 2) / radius, -(y - size / 2) / radius
    around, r = np.degrees(np.arctan2(v, u)), np.hypot(u, v)
    glint = np.zeros((size, size))
    for i in range(count):
        off = (around - (360.0 / count * i + 10) + 180) % 360 - 180
        glint += 3 * np.exp(-0.5 * (off / 6) ** 2) * np.exp(-0.5 * ((1 - r) / 0.06) ** 2)
    return (photo + np.where(matte, glint, 0)[..., None]).astype(np.float32), matte


def test_more_than_four_light_clusters_is_refused():
    """Five bright arcs on the contour are more clusters than the estimate takes; four
    are taken (one light each, within 5° of its glint's azimuth)."""
    with pytest.raises(ArgumentError, match="5 separate bright arcs"):
        detect_lights(*rim_glints(5))
    found = detect_lights(*rim_glints(4))
    assert len(found.lights) == 4
    azimuths = sorted(light.azimuth_deg for light in found.lights)
    assert np.allclose(azimuths, [10, 100, 190, 280], atol=5)


def test_bad_photos_are_refused_naming_why():
    photo, matte, _ = lambertian_sphere([(145.0, 45.0, 1.0)])
    with pytest.raises(ArgumentError, match="no object found: every pixel is black"):
        detect_lights(np.zeros_like(photo))
    with pytest.raises(ArgumentError, match="no object found"):
        detect_lights(photo, np.zeros_like(matte))
    big, big_matte, _ = lambertian_sphere([(145.0, 45.0, 1.0)], radius=70)  # wider than the 128-pixel photo
    with pytest.raises(ArgumentError, match="touches the photo's border"):
        detect_lights(big, big_matte)
    bad = photo.copy()
    bad[3, 5, 1] = np.nan
    with pytest.raises(ArgumentError, match="photo"):
        detect_lights(bad)
    with pytest.raises(ArgumentError, match="matte must have the photo's shape"):
        detect_lights(photo, matte[:10])


def test_an_8_bit_photo_is_read_with_a_warning(tmp_path):
    """Display codes are not radiance: the estimate warns, and still finds the light."""
    photo, matte, _ = lambertian_sphere([(145.0, 45.0, 1.0)])
    codes = np.round(np.clip(photo, 0, 1) * 255).astype(np.uint8)
    with pytest.warns(UserWarning, match="8-bit image"):
        found = detect_lights(codes, matte)
    assert angle_deg(found.lights[0].direction, toward(145.0, 45.0)) < 5
