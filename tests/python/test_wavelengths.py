"""Per-ray wavelengths (Context.advance(wavelengths=...)): dispersion in the atmosphere.

The references are written out in the tests, not taken from the library: Ciddor's
(1996) refractivity of standard air (closed_forms.ciddor), and Laplace's series for
astronomical refraction.
"""

import numpy as np
import pytest

import arcus
from arcus.fields import Linear, StandardAtmosphere
from closed_forms import catenary, ciddor, fan


# Stars at 30 and 45 degrees altitude seen from sea level, each in blue and in red light.
ALTITUDES = np.radians([30.0, 45.0, 30.0, 45.0])
WAVELENGTHS = np.array([400.0, 400.0, 700.0, 700.0])
STAR_JOB = dict(method="dp45", length=3.0e6, rtol=1e-11, atol=1e-14)  # far above the air


def star_rays():
    origins = np.tile([0.0, arcus.EARTH_RADIUS, 0.0], (4, 1))
    directions = np.stack([np.cos(ALTITUDES), np.sin(ALTITUDES), np.zeros(4)], axis=1)
    return origins, directions


def bending(start, end):
    """Angle between the (unit) start and end directions, per ray."""
    return np.arctan2(np.linalg.norm(np.cross(start, end), axis=1), np.sum(start * end, axis=1))


@pytest.fixture(scope="module")
def stars(ctx):
    origins, directions = star_rays()
    result = ctx.advance(StandardAtmosphere(spherical=True), origins, directions, wavelengths=WAVELENGTHS,
                         **STAR_JOB)
    return directions, result


def test_refraction_at_400_and_700_nm_in_one_job_scales_as_ciddors_refractivity(stars):
    directions, result = stars
    assert "CURVED_DISPERSION" in result.features and "CURVED_FIELD_ATMOSPHERE" in result.features
    assert np.all(result.status == arcus.RAY_DONE)
    refraction = bending(directions, result.directions)
    # Refraction R = (n0 - 1)(1 - b) tan z - (n0 - 1)(b - (n0 - 1)/2) tan^3 z + ... is
    # linear in n0 - 1 but for the (n0 - 1)^2 / 2 term, whose share differs between 400
    # and 700 nm by (delta(n0 - 1) / 2) tan^2 z ~ 5e-6.  The integration errs by < 1e-7
    # relative (steps * rtol).  So R400 / R700 = K400 / K700 to 2e-5.
    ratio = ciddor(400.0) / ciddor(700.0)
    assert ratio > 1.025  # meaningful: blue is bent 2.5 % more than red
    np.testing.assert_allclose(refraction[:2] / refraction[2:], ratio, rtol=2e-5, atol=0)


def test_astronomical_refraction_matches_laplaces_series(stars):
    """The absolute refraction against Laplace's series (Smart, Spherical Astronomy §56).

    R = (n0 - 1)(1 - b) tan z - (n0 - 1)(b - (n0 - 1)/2) tan^3 z holds for any spherically
    layered atmosphere in hydrostatic equilibrium, with b = l / a the height of the
    homogeneous atmosphere l = R* T0 / (M0 g0) over the Earth's radius a (US Standard
    Atmosphere 1976 constants).  The next terms are ~ (n0 - 1) b^2 tan^5 z, below 1e-5
    relative at z <= 60 degrees; n0 - 1 is Ciddor's.
    """
    directions, result = stars
    l = 8.31432 * 288.15 / (0.0289644 * 9.80665)  # 8434.5 m
    b = l / arcus.EARTH_RADIUS
    k = ciddor(WAVELENGTHS)
    tan_z = np.tan(np.pi / 2 - ALTITUDES)
    laplace = k * (1 - b) * tan_z - k * (b - k / 2) * tan_z**3  # ~1e-4 rad ~ 1 arc minute
    np.testing.assert_allclose(bending(directions, result.directions), laplace, rtol=1e-4, atol=0)


def test_each_ray_gets_what_a_field_of_its_wavelength_gives(ctx, stars):
    """Consistency of two library paths: a per-ray wavelength acts as the field's own would."""
    directions, result = stars
    origins, _ = star_rays()
    for nm in (400.0, 700.0):
        mono = ctx.advance(StandardAtmosphere(spherical=True, wavelength=nm), origins, directions, **STAR_JOB)
        assert "CURVED_DISPERSION" not in mono.features
        mine = WAVELENGTHS == nm
        np.testing.assert_allclose(bending(directions[mine], result.directions[mine]),
                                   bending(directions[mine], mono.directions[mine]), rtol=1e-9, atol=0)


def test_one_number_is_every_rays_wavelength(ctx):
    origins, directions = star_rays()
    air = StandardAtmosphere(spherical=True)
    job = dict(STAR_JOB, length=2.0e5)
    one = ctx.advance(air, origins, directions, wavelengths=400.0, **job)
    each = ctx.advance(air, origins, directions, wavelengths=np.full(4, 400.0), **job)
    np.testing.assert_array_equal(one.directions, each.directions)
    assert "CURVED_DISPERSION" in one.features
    # and the scalar really reached the library: 400 nm bends more than the field's 550 nm
    plain = ctx.advance(air, origins, directions, **job)
    assert np.all(bending(directions, one.directions) > 1.01 * bending(directions, plain.directions))


def test_non_dispersive_fields_ignore_the_wavelengths(ctx):
    origins, directions = fan(8)
    field = Linear(1.0, (0.0, 0.1, 0.0))
    # Not even checked: the field has no use for them.
    result = ctx.advance(field, origins, directions, wavelengths=np.linspace(-5.0, 1e4, 8), length=10.0, rtol=1e-10)
    assert "CURVED_DISPERSION" not in result.features and np.all(result.status == arcus.RAY_DONE)
    end, _ = catenary(1.0, 0.1, origins, directions, 10.0)
    np.testing.assert_allclose(result.positions, end, rtol=0, atol=1e-7)


def test_a_wavelength_outside_ciddors_range_flags_only_its_ray(ctx):
    air = StandardAtmosphere()
    origins = np.array([[0.0, 10.0 + i, 0.0] for i in range(5)])
    directions = np.tile([1.0, -0.001, 0.0], (5, 1))
    wavelengths = np.array([450.0, 299.0, np.nan, 1691.0, 650.0])
    job = dict(length=1000.0, rtol=1e-10)
    with pytest.raises(arcus.Error) as caught:
        ctx.advance(air, origins, directions, wavelengths=wavelengths, **job)
    error = caught.value
    assert error.status == "ARCUS_ERROR_INVALID_RAYS" and "wavelength" in error.message
    assert list(error.result.status) == [arcus.RAY_DONE] + [arcus.RAY_INVALID_INPUT] * 3 + [arcus.RAY_DONE]
    good = [0, 4]
    alone = ctx.advance(air, origins[good], directions[good], wavelengths=wavelengths[good], **job)
    np.testing.assert_array_equal(error.result.positions[good], alone.positions)


@pytest.mark.parametrize(
    "wavelengths, message",
    [(np.full(3, 550.0), r"shape \(4,\)"), (np.full((4, 1), 550.0), r"shape \(4,\)"), ("550", "real numbers"),
     (True, "real numbers"), ([550, 550, "x", 550], "real numbers"), (550 + 0j, "real numbers")],
    ids=["too-few", "column", "string", "bool", "string-element", "complex"],
)
def test_wavelengths_are_checked_before_the_library(ctx, monkeypatch, wavelengths, message):
    def never(*args):
        raise AssertionError("arcus_curved_advance was called")

    monkeypatch.setattr(arcus._lib.lib, "arcus_curved_advance", never)
    origins, directions = fan(4)
    with pytest.raises(arcus.ArgumentError, match="wavelengths must .*" + message):
        ctx.advance(StandardAtmosphere(), origins, directions, wavelengths=wavelengths)
