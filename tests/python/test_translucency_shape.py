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


@pytest.mark.heavy
def test_fig_3_9_layers_against_the_simplest_method(fig_3_9):
    """The simplest method (luminance as depth) puts the bulge where the light is: its
    normals are 34–37° off.  The base layer's convex stand-in (inflated from the contour:
    exact for spheres and ellipsoids) brings them to 2–3° on the three convex shapes,
    what the pixel grid leaves at the rim, and 18° on the torus, which is not convex.
    The bounds, 5° and 20°, leave the grid and the lumps their due; the simplest must be
    at least five times as far off.  The thesis finds base + detail best; here the
    detail layer costs 0.1–0.2° (docs say why), so the test asserts only that it does
    not cost more than 1°."""
    for geometry, error in fig_3_9.items():
        bound = 20 if geometry == "torus" else 5
        assert error["base+detail"] < bound, (geometry, error)
        assert error["luminance"] > (1.5 if geometry == "torus" else 5) * error["base+detail"], (geometry, error)
        assert error["base+detail"] < error["base"] + 1.0, (geometry, error)


def test_a_sphere_is_inflated_to_itself():
    """Without the inflation spline (the default) and the detail, the base layer is the
    convex stand-in, sqrt(4u) with ∇²u = −1 inside the disc: a sphere of the disc's
    radius.  On a closed-form sphere only the pixel grid is left: 0.4° RMS where the
    surface faces the camera within 60°, 2.2° over all (the rim's last pixel, where the
    normals turn fastest, is up to 29° off); bounds of 1° and 3°."""
    photo, matte, truth = lambertian_sphere([(145.0, 45.0, 1.0)])
    shape = estimate_shape(photo, matte, method="base")
    assert rms_normal_error(shape, truth, matte) < 3
    facing = matte & (truth[..., 2] > 0.5)
    assert rms_normal_error(shape, truth, facing) < 1
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
