"""The sun and the clear atmosphere every engine shares (``arcus_daylight.h``).

::

    import numpy as np
    import arcus.daylight as daylight

    nm = np.arange(360.0, 831.0, 5.0)
    top = daylight.solar_irradiance(nm, band=5)            # W m⁻² nm⁻¹ above the air
    t = daylight.sun_transmittance(nm, apparent_zenith=80, aerosol_depth_500=0.05)
    ground = top * t                                       # the direct sun at the ground
    d = daylight.optical_depths(nm)                        # straight up: .rayleigh, .ozone, .aerosol

The atmosphere is the US Standard Atmosphere 1976's air (Rayleigh scattering as
Bodhaine et al. 1999 compute it), an ozone layer (Serdyuchenko et al. 2014's
cross-section at 233 K, a tent from 10 to 40 km) and an aerosol layer (an optical
depth at 500 nm, Ångström's exponent, an exponential profile), along the path a ray
takes as refraction bends it over the round Earth; water vapour and the O2 bands are
left out.  The sun's spectrum above the air is ASTM G173-03's; its disc darkens toward
the limb as Neckel (2005) fitted.  Host code in the library (no context, no device).

Units: wavelengths in nanometres (vacuum, 360–830 nm for the atmosphere), heights in
metres, angles in degrees; ``apparent_zenith`` is the direction the ray leaves the
observer in (0 = up, 90 = the horizon), i.e. where the sun is seen, refraction included.
"""

from ctypes import byref, c_float
from dataclasses import dataclass, fields, replace

import numpy as np

from . import _lib
from ._args import to_float, to_int, to_real_array
from ._errors import ArgumentError
from ._lib import lib

__all__ = ["Atmosphere", "OpticalDepths", "default_atmosphere", "optical_depths", "sun_transmittance",
           "sky_radiance", "sky_image", "ground_irradiance", "solar_irradiance", "limb_darkening"]


@dataclass(frozen=True)
class Atmosphere:
    """A clear atmosphere (``arcus_daylight_desc``); :func:`default_atmosphere` gives the
    library's defaults.

    Attributes:
        site_height: the observer's geometric height [m], 0–80 000.
        ozone_du: the ozone column above sea level [Dobson units], 0–1000.
        aerosol_depth_500: the aerosol's vertical optical depth above the site at 500 nm.
        angstrom_exponent: α in τ(λ) = τ(500)·(λ/500 nm)^−α.
        aerosol_scale_height: the aerosol's density falls as exp(−(h − site)/H) [m].
        co2_ppm: CO2 in the air's King factor and refractive index.
        aerosol_albedo: the aerosol's single-scattering albedo (what it does not absorb).
        aerosol_asymmetry: g of the aerosol's Henyey–Greenstein phase function.
        ground_albedo: the Lambertian ground's albedo, 0–1: the light it reflects back
            into the sky (0: a black ground).
    """

    site_height: float
    ozone_du: float
    aerosol_depth_500: float
    angstrom_exponent: float
    aerosol_scale_height: float
    co2_ppm: float
    aerosol_albedo: float
    aerosol_asymmetry: float
    ground_albedo: float = 0.0

    def _struct(self):
        return _lib.DaylightDescStruct(*(to_float(getattr(self, f.name), f.name) for f in fields(self)))


@dataclass(frozen=True, eq=False)
class OpticalDepths:
    """Optical depths per wavelength (:func:`optical_depths`); ``total`` is their sum."""

    wavelength: np.ndarray
    rayleigh: np.ndarray
    ozone: np.ndarray
    aerosol: np.ndarray

    @property
    def total(self):
        return self.rayleigh + self.ozone + self.aerosol


def default_atmosphere():
    """The library's clear day: sea level, 300 DU, τ(500) = 0.1, α = 1.3, H = 1200 m, 415 ppm,
    aerosol albedo 0.95 and g = 0.7, over a black ground."""
    desc = _lib.DaylightDescStruct()
    _lib.check(lib.arcus_daylight_desc_init(byref(desc)))
    return Atmosphere(*(getattr(desc, f.name) for f in fields(Atmosphere)))


def _atmosphere(atmosphere, overrides):
    if atmosphere is None:
        atmosphere = default_atmosphere()
    elif not isinstance(atmosphere, Atmosphere):
        raise ArgumentError("atmosphere must be an arcus.daylight.Atmosphere or None, got %r" % (atmosphere,))
    names = {f.name for f in fields(Atmosphere)}
    unknown = sorted(set(overrides) - names)
    if unknown:
        raise ArgumentError("unknown atmosphere parameter %s (known: %s)" % (unknown[0], ", ".join(sorted(names))))
    atmosphere = replace(atmosphere, **overrides)
    # The library checks the ranges (naming the field): asked for no wavelengths, it
    # does nothing else.
    _lib.check(lib.arcus_daylight_optical_depths(byref(atmosphere._struct()), 0.0, 0, None, None))
    return atmosphere


def _wavelengths(wavelength):
    wl = to_real_array(wavelength, "wavelength")
    return wl, np.ascontiguousarray(wl.reshape(-1))


def optical_depths(wavelength, apparent_zenith=0.0, atmosphere=None, **overrides):
    """The air's, ozone's and aerosol's optical depths along the refracted ray leaving
    the observer at ``apparent_zenith`` degrees (0: straight up) to the top of the
    atmosphere, at each ``wavelength`` (nm, 360–830).  ``atmosphere`` (an
    :class:`Atmosphere`, default :func:`default_atmosphere`) with any of its fields
    replaced by keyword: ``optical_depths(nm, 60, ozone_du=250)``."""
    desc = _atmosphere(atmosphere, overrides)._struct()
    wl, flat = _wavelengths(wavelength)
    out = (_lib.OpticalDepthsStruct * max(flat.size, 1))()
    _lib.check(lib.arcus_daylight_optical_depths(byref(desc), to_float(apparent_zenith, "apparent_zenith"), flat.size,
                                                 _lib.ptr(flat), out))
    get = lambda name: np.array([getattr(out[i], name) for i in range(flat.size)]).reshape(wl.shape)
    return OpticalDepths(wavelength=wl.copy(), rayleigh=get("rayleigh"), ozone=get("ozone"), aerosol=get("aerosol"))


def sun_transmittance(wavelength, apparent_zenith, atmosphere=None, **overrides):
    """The direct sun's transmittance exp(−τ) along the refracted path at
    ``apparent_zenith`` degrees (see :func:`optical_depths`)."""
    return np.exp(-optical_depths(wavelength, apparent_zenith, atmosphere, **overrides).total)


def sky_radiance(wavelength, sun_zenith, view_zenith, view_azimuth=0.0, atmosphere=None, **overrides):
    """The clear sky's radiance (single scattering and, by Hillaire's approximation, the
    light scattered more than once) per unit of the sun's irradiance
    above the air [sr⁻¹] (times :func:`solar_irradiance` it is W m⁻² nm⁻¹ sr⁻¹): shape
    (directions..., wavelengths), for the sun at ``sun_zenith`` degrees (up to 120:
    twilight) and views at ``view_zenith`` and ``view_azimuth`` degrees (broadcast
    against each other; the azimuth counted from the sun's).  The paths are straight
    (see ``arcus_daylight.h``)."""
    desc = _atmosphere(atmosphere, overrides)._struct()
    wl, flat = _wavelengths(wavelength)
    zenith, azimuth = np.broadcast_arrays(to_real_array(view_zenith, "view_zenith"),
                                          to_real_array(view_azimuth, "view_azimuth"))
    shape = zenith.shape
    zenith, azimuth = np.ascontiguousarray(zenith.reshape(-1)), np.ascontiguousarray(azimuth.reshape(-1))
    out = np.zeros(zenith.size * flat.size)
    _lib.check(lib.arcus_daylight_sky_radiance(byref(desc), to_float(sun_zenith, "sun_zenith"), zenith.size,
                                               _lib.ptr(zenith), _lib.ptr(azimuth), flat.size, _lib.ptr(flat),
                                               _lib.ptr(out)))
    return out.reshape(shape + wl.shape)


def sky_image(width, height, sun_zenith, sun_azimuth=0.0, atmosphere=None, **overrides):
    """The sky as an equirectangular panorama (height, width, 3) float32 of linear sRGB
    radiance [W m⁻² nm⁻¹ sr⁻¹; Y = 1 for a flat spectrum of 1] under ASTM G173's sun at
    ``sun_zenith``, ``sun_azimuth`` degrees: column u = azimuth/360° (from +z toward +x),
    row v = (90° − elevation)/180°, the horizon's below it; what a rainbow scene's
    ``sky_image`` takes."""
    desc = _atmosphere(atmosphere, overrides)._struct()
    width, height = to_int(width, "width", 1, 8192), to_int(height, "height", 1, 8192)
    out = np.zeros((height, width, 3), dtype=np.float32)
    _lib.check(lib.arcus_daylight_sky_image(byref(desc), to_float(sun_zenith, "sun_zenith"),
                                            to_float(sun_azimuth, "sun_azimuth"), width, height,
                                            _lib.ptr(out, c_float)))
    return out


def ground_irradiance(wavelength, sun_zenith, atmosphere=None, **overrides):
    """(direct, diffuse): what falls on horizontal ground [W m⁻² nm⁻¹] at each
    ``wavelength``, the sun at ``sun_zenith`` degrees (apparent): the direct sun through
    its refracted path times cos z, and the sky over the hemisphere."""
    desc = _atmosphere(atmosphere, overrides)._struct()
    wl, flat = _wavelengths(wavelength)
    direct, diffuse = np.zeros(flat.size), np.zeros(flat.size)
    _lib.check(lib.arcus_daylight_ground_irradiance(byref(desc), to_float(sun_zenith, "sun_zenith"), flat.size,
                                                    _lib.ptr(flat), _lib.ptr(direct), _lib.ptr(diffuse)))
    return direct.reshape(wl.shape), diffuse.reshape(wl.shape)


def solar_irradiance(wavelength, band=0.0):
    """The sun's spectral irradiance above the atmosphere at 1 AU [W m⁻² nm⁻¹] (ASTM
    G173-03, 300–1000 nm): at each ``wavelength`` (band = 0) or averaged over
    [λ − band/2, λ + band/2] nm."""
    wl, flat = _wavelengths(wavelength)
    out = np.zeros(flat.size)
    _lib.check(lib.arcus_daylight_solar_irradiance(flat.size, _lib.ptr(flat), to_float(band, "band"), _lib.ptr(out)))
    return out.reshape(wl.shape)


def limb_darkening(wavelength, mu):
    """The sun's radiance at ``mu`` (the cosine between the line of sight and the sun's
    surface normal: 1 at the disc's centre, 0 at its limb) over the centre's, at
    ``wavelength`` nm (300–1100); the two broadcast against each other."""
    wl, m = np.broadcast_arrays(to_real_array(wavelength, "wavelength"), to_real_array(mu, "mu"))
    wl_flat, mu_flat = np.ascontiguousarray(wl.reshape(-1)), np.ascontiguousarray(m.reshape(-1))
    out = np.zeros(wl_flat.size)
    _lib.check(lib.arcus_daylight_limb_darkening(wl_flat.size, _lib.ptr(wl_flat), _lib.ptr(mu_flat), _lib.ptr(out)))
    return out.reshape(wl.shape)
