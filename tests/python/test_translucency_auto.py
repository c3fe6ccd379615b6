"""The BSSRDF from an uncontrolled photograph (thesis §3.4, §5.2): estimate_bssrdf with
neither mesh nor lights, on synthetic photographs whose material is known — the lights
and shape found in the photo, a closed mesh from the depth, §3.3.1's estimate on it —
against the material's closed-form R_total and the photo itself, re-rendered."""

import numpy as np
import pytest

from arcus.translucency import detect_lights, estimate_bssrdf, estimate_shape, render
from arcus._errors import ArgumentError

from photo_scenes import (COLOURED_R_TOTAL as R_TOTAL, FIG_3_10_LIGHT, MM_PER_UNIT, SIZE, coloured_photograph,
                          angle_deg, geometries, lambertian_sphere, toward)

@pytest.mark.heavy
@pytest.mark.parametrize("geometry", ["sphere", "lumpy sphere"])
def test_the_photo_alone_gives_its_material_back(geometry):
    """No mesh, no lights, no matte: the estimate's Hermite profile re-renders the photo
    on the estimated mesh under the estimated lights within 10% RMS of its mean radiance
    (measured 4.9% and 7.3%), and its R_total is within 15% of the material's in every
    channel (measured +6% and +10%); the dipole, reported beside it as approximate,
    within 15% too (+6–8%, +6–9%).  Both bounds are the issue's; what is left over is
    the shape's: the mesh is the convex stand-in, mirrored at the back, pixelated at the
    contour.  The ellipsoid misses (+22%, docs), so it is not asserted here; the thesis
    restricts the method to simple shapes."""
    photo, mm_per_pixel = coloured_photograph(geometry)
    estimate = estimate_bssrdf(photo.image, mm_per_pixel=mm_per_pixel)
    assert estimate.lights.segmented and len(estimate.lights.lights) == 1
    assert estimate.fit == "hermite" and estimate.fitted is estimate.hermite
    camera = {"position": (0, 0, 4 * SIZE), "look_at": (0, 0, 0), "up": (0, 1, 0), "width": SIZE, "height": SIZE}
    lights = [(light.direction, light.intensity) for light in estimate.lights.lights]
    again = render(estimate.hermite, estimate.relief, lights, camera, ortho_height=SIZE, mm_per_unit=mm_per_pixel,
                   highlight_deg=0)
    both = again.covered & photo.covered
    rmse = np.sqrt(np.mean((again.image[both] - photo.image[both]) ** 2)) / photo.image[photo.covered].mean()
    assert rmse <= 0.10, rmse
    assert np.all(np.abs(estimate.hermite.total_reflectance / R_TOTAL - 1) <= 0.15), estimate.hermite.total_reflectance
    assert np.all(np.abs(estimate.dipole.total_reflectance / R_TOTAL - 1) <= 0.15), estimate.dipole.total_reflectance


def test_what_the_photo_gave_is_reported():
    """The lights, the shape and the closed mesh come back; the mesh covers the mask."""
    photo, matte, _ = lambertian_sphere([(145.0, 45.0, 1.0)], size=64, radius=24)
    estimate = estimate_bssrdf(photo, matte=matte)
    assert len(estimate.lights.lights) == 1
    assert estimate.shape.depth.shape == (64, 64) and estimate.shape.mask.sum() > 0.9 * matte.sum()
    vertices, triangles = estimate.relief
    assert vertices.shape[1] == 3 and triangles.shape[1] == 3 and triangles.max() < len(vertices)
    assert np.abs(vertices[:, :2]).max() <= 32  # pixels about the photo's centre


def test_half_given_and_bad_numbers_are_refused():
    photo, matte, _ = lambertian_sphere([(145.0, 45.0, 1.0)], size=64, radius=24)
    with pytest.raises(ArgumentError, match="give both mesh and lights, or neither"):
        estimate_bssrdf(photo, lights=[((0, 0, 1), 1.0)])
    with pytest.raises(ArgumentError, match="irradiance"):
        estimate_bssrdf(photo, irradiance=0)
    with pytest.raises(ArgumentError, match="mm_per_pixel"):
        estimate_bssrdf(photo, mm_per_pixel=-1)
    with pytest.raises(ArgumentError, match="shape: unknown option"):
        estimate_bssrdf(photo, shape={"depth": 2})
    with pytest.raises(ArgumentError, match="no object found"):
        estimate_bssrdf(np.zeros_like(photo))
    with pytest.warns(UserWarning, match="8-bit image"):
        estimate_bssrdf(np.round(np.clip(photo, 0, 1) * 255).astype(np.uint8), matte=matte)


@pytest.mark.heavy
def test_fig_3_11_the_estimate_against_wrong_lights():
    """Fig. 3.11: the estimate on the sphere's estimated mesh, given a light turned from
    the truth by 0–40° in azimuth or in zenith, its Hermite profile then rendered on the
    true mesh under the true light against the photo.  The error rises with the
    light's: never by less than it fell (0.5% of slack for the renders' noise-free
    rounding).  Turned in azimuth it stays within the thesis' 10% up to 20° (measured
    6.2%, and 8.5% at 30°).  Turned in zenith it does not (measured 9.2% at 5°, 18% at
    10°, 38% at 20°): a wrong zenith moves light between the seen and the unseen side,
    and R_total follows (+13% at 5°, +51% at 20°); docs/translucency-photo.md."""
    photo, mm_per_pixel = coloured_photograph("sphere")
    found = estimate_bssrdf(photo.image, mm_per_pixel=mm_per_pixel)
    seen = {"position": (0, 0, 4 * SIZE), "look_at": (0, 0, 0), "up": (0, 1, 0)}
    mesh = geometries()["sphere"]
    extent = float(np.abs(mesh[0][:, :2]).max())
    truth = {"position": (0, 0, 5), "look_at": (0, 0, 0), "up": (0, 1, 0), "width": SIZE, "height": SIZE}
    errors = {}
    for turned in ("azimuth", "zenith"):
        for degrees in (0, 10, 20, 40):
            azimuth, zenith = FIG_3_10_LIGHT
            azimuth, zenith = (azimuth + degrees, zenith) if turned == "azimuth" else (azimuth, zenith + degrees)
            estimate = estimate_bssrdf(photo.image, found.relief, [(toward(azimuth, zenith), 1.0)], seen,
                                       ortho_height=SIZE, mm_per_unit=mm_per_pixel, matte=found.shape.mask,
                                       nonnegative=True, remove_highlights=False, fit="hermite")
            again = render(estimate.hermite, mesh, [(toward(*FIG_3_10_LIGHT), 1.0)], truth, ortho_height=2.4 * extent,
                           mm_per_unit=MM_PER_UNIT, highlight_deg=0)
            inside = photo.covered
            errors[turned, degrees] = (np.sqrt(np.mean((again.image[inside] - photo.image[inside]) ** 2))
                                       / photo.image[inside].mean())
    print("\n" + "\n".join("%-7s %2d°: %.3f" % (t, d, e) for (t, d), e in errors.items()))
    for turned in ("azimuth", "zenith"):
        series = [errors[turned, d] for d in (0, 10, 20, 40)]
        assert all(b >= a - 0.005 for a, b in zip(series, series[1:])), (turned, series)
    assert errors["azimuth", 0] <= 0.03
    assert errors["azimuth", 20] <= 0.10


def test_a_large_photo_is_worked_on_at_512_pixels_a_side():
    """A 1300 × 1000 photo is box-filtered by 3 to 434 × 334 for the lights, the shape and
    the mesh, and read back at its own size: the light within 1.5° (the closed form's
    bound), the depth at the centre the sphere's radius in the photo's pixels within 3%
    (a working pixel is three of them), the mask the photo's to within the blocks'
    edges, and the estimate runs on it."""
    photo, matte, _ = lambertian_sphere([(145.0, 45.0, 1.0)], size=1300, radius=420)
    photo, matte = photo[150:1150], matte[150:1150]  # 1000 rows, the sphere inside
    found = detect_lights(photo, matte)
    assert angle_deg(found.lights[0].direction, toward(145.0, 45.0)) < 1.5
    shape = estimate_shape(photo, matte)
    assert shape.depth.shape == (1000, 1300)
    assert shape.depth[500, 650] == pytest.approx(420, rel=0.03)
    assert np.mean(shape.mask != matte) < 0.005
    estimate = estimate_bssrdf(photo, matte=matte)
    assert estimate.pixels["width"] <= 200 and np.abs(estimate.relief[0][:, :2]).max() <= 650
