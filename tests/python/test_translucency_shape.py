"""Shape from the photograph alone (thesis §3.4, Fig. 3.9; Khan et al. 2006):
arcus.translucency.estimate_shape's normals against the true mesh's, cast in numpy, on
Fig. 3.10's translucent photos, for the three depth methods the figure compares."""

import numpy as np
import pytest

from arcus.translucency import estimate_shape
from arcus._errors import ArgumentError

from photo_scenes import fig_3_10_photo, geometries, lambertian_sphere, seen_normals

METHODS = ("base+detail", "base", "luminance")


def rms_normal_error(shape, truth, seen):
    """The RMS angle (degrees) between estimated and true normals where both exist."""
    both = shape.mask & seen
    cosine = np.clip((shape.normals * truth).sum(-1), -1, 1)[both]
    return float(np.sqrt(np.mean(np.degrees(np.arccos(cosine)) ** 2)))


@pytest.fixture(scope="module")
def fig_3_9():
    """{geometry: {method: RMS normal error}} on the translucent photos."""
    errors = {}
    for geometry, mesh in geometries().items():
        truth, seen = seen_normals(mesh)
        photo = fig_3_10_photo(geometry, "translucent")
        assert np.array_equal(seen, photo.covered)  # the numpy cast sees what the render saw
        errors[geometry] = {m: rms_normal_error(estimate_shape(photo.image, photo.covered, method=m), truth, seen)
                            for m in METHODS}
    print("\n" + "\n".join("%-13s " % g + " ".join("%s %.1f°" % kv for kv in e.items()) for g, e in errors.items()))
    return errors


def test_fig_3_9_layers_against_the_simplest_method(fig_3_9):
    """The simplest method (luminance as depth) puts the bulge where the light is: its
    normals are 29–37° off.  The base layer's convexity (the contour at 0, a sphere's
    profile) brings them to 10–11° on the three convex shapes and 19° on the torus, which
    is not convex.  The bounds, 12° and 20°, are those figures with a degree to spare;
    the simplest must be at least twice as far off.  The thesis finds base + detail
    best; here the detail layer moves the error by 0.3° at most either way (docs say
    why), so the test asserts only that it does not cost more than 1°."""
    for geometry, error in fig_3_9.items():
        bound = 20 if geometry == "torus" else 12
        assert error["base+detail"] < bound, (geometry, error)
        assert error["luminance"] > 1.5 * error["base+detail"], (geometry, error)
        assert error["base+detail"] < error["base"] + 1.0, (geometry, error)


def test_a_sphere_without_inflation_is_its_own_profile():
    """With the inflation spline flat (inflation 0) and no detail, the base layer is a
    sphere's profile from the contour's distance: on a closed-form sphere only the pixel
    grid is left, worst at the rim where the normals turn fastest: 6° RMS."""
    photo, matte, truth = lambertian_sphere([(145.0, 45.0, 1.0)])
    shape = estimate_shape(photo, matte, method="base", inflation=0)
    assert rms_normal_error(shape, truth, matte) < 6
    radius = 50.0  # photo_scenes' default
    assert shape.depth.max() == pytest.approx(radius, rel=0.03)


def test_relief_scales_the_depth_and_flattens_the_normals():
    """The bas-relief parameter multiplies the depth: normals turn toward the camera."""
    photo, matte, _ = lambertian_sphere([(145.0, 45.0, 1.0)])
    deep, shallow = estimate_shape(photo, matte), estimate_shape(photo, matte, relief=0.5)
    assert np.allclose(shallow.depth, 0.5 * deep.depth)
    assert shallow.normals[..., 2][matte].mean() > deep.normals[..., 2][matte].mean()


def test_bad_shape_parameters_are_refused():
    photo, matte, _ = lambertian_sphere([(145.0, 45.0, 1.0)])
    with pytest.raises(ArgumentError, match="method must be one of"):
        estimate_shape(photo, matte, method="sculpt")
    with pytest.raises(ArgumentError, match="params->relief"):
        estimate_shape(photo, matte, relief=0)
    with pytest.raises(ArgumentError, match="params->sigma_spatial"):
        estimate_shape(photo, matte, sigma_spatial=float("nan"))
    with pytest.raises(ArgumentError, match="touches the photo's border"):
        estimate_shape(*lambertian_sphere([(145.0, 45.0, 1.0)], radius=70)[:2])
