"""The BSSRDF from an uncontrolled photograph (thesis §3.4, §5.2): estimate_bssrdf with
neither mesh nor lights, on synthetic photographs whose material is known — the lights
and shape found in the photo, a closed mesh from the depth, §3.3.1's estimate on it —
against the material's closed-form R_total and the photo itself, re-rendered."""

import numpy as np
import pytest

from arcus.translucency import Dipole, estimate_bssrdf, render
from arcus._errors import ArgumentError

from photo_scenes import FIG_3_10_LIGHT, MM_PER_UNIT, SIZE, geometries, lambertian_sphere, toward

# A coloured material: R_total and ℓ_d (mm) per channel, so that each channel is its own
# check; on objects 40–52 mm across.
R_TOTAL, DIFFUSE_LENGTH = np.array([0.85, 0.6, 0.35]), [6.0, 4.0, 2.0]


def synthetic_photograph(geometry):
    """The engine's render of `geometry` in the coloured material under Fig. 3.10's light
    (irradiance 1), orthographic; and the photo's scale, mm a pixel."""
    mesh = geometries()[geometry]
    extent = float(np.abs(mesh[0][:, :2]).max())
    camera = {"position": (0, 0, 5), "look_at": (0, 0, 0), "up": (0, 1, 0), "width": SIZE, "height": SIZE}
    photo = render(Dipole.from_reflectance(R_TOTAL, DIFFUSE_LENGTH, eta=1.3), mesh, [(toward(*FIG_3_10_LIGHT), 1.0)],
                   camera, ortho_height=2.4 * extent, mm_per_unit=MM_PER_UNIT, highlight_deg=0)
    return photo, 2.4 * extent / SIZE * MM_PER_UNIT


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
    photo, mm_per_pixel = synthetic_photograph(geometry)
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
