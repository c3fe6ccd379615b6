/*
 * arcus daylight: the sun and the clear atmosphere every engine shares (src/sky/).  The
 * sun's spectral irradiance above the atmosphere (ASTM G173-03) and its disc's limb
 * darkening (Neckel 2005); the optical depths of the US Standard Atmosphere 1976's air
 * (Rayleigh scattering, Bodhaine et al. 1999), an ozone layer (Serdyuchenko et al. 2014
 * at 233 K) and an aerosol layer (Ångström's law, an exponential profile) along the
 * path a ray takes as refraction bends it over the round Earth.  Water vapour and the
 * O2 bands are left out.  Host code: no context, no device (errors: arcus_last_error).
 * Include arcus.h.
 *
 * Units (arcus_core.h): metres, nanometres in vacuum, degrees where a name ends in
 * _deg.  Wavelengths of the atmosphere's calls lie in [360, 830] nm.
 */
#ifndef ARCUS_DAYLIGHT_H
#define ARCUS_DAYLIGHT_H

#include "arcus_core.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct arcus_daylight_desc {
  double site_height;          /* m, the observer's geometric height, 0..80 000            */
  double ozone_du;             /* ozone column above sea level, Dobson units, 0..1000      */
  double aerosol_depth_500;    /* the aerosol's vertical optical depth above the site at
                                * 500 nm, 0..10                                            */
  double angstrom_exponent;    /* τ(λ) = τ(500)·(λ/500 nm)^−α, −1..4                       */
  double aerosol_scale_height; /* m, 100..20 000: density ∝ exp(−(h − site)/H)              */
  double co2_ppm;              /* 0..10 000, in the air's King factor and index             */
  double aerosol_albedo;       /* its single-scattering albedo, 0..1                         */
  double aerosol_asymmetry;    /* g of its Henyey–Greenstein phase function, −0.99..0.99     */
  double ground_albedo;        /* the Lambertian ground under the air, 0..1: the light it
                                * reflects back into the sky (its multiple scattering)     */
} arcus_daylight_desc;

/* Fills desc with a clear mid-latitude day: sea level, 300 DU, τ(500) = 0.1, α = 1.3,
 * H = 1200 m, 415 ppm, albedo 0.95, g = 0.7, over a black ground (ground_albedo 0). */
ARCUS_API arcus_status arcus_daylight_desc_init(arcus_daylight_desc* desc);

typedef struct arcus_optical_depths {
  double rayleigh, ozone, aerosol;
} arcus_optical_depths;

/* The optical depths along the ray that leaves the site at apparent zenith angle
 * apparent_zenith_deg (0 = straight up, 90 = the horizon) and bends with the air's index
 * to the top of the atmosphere (86 km): the direct sun's transmittance is
 * exp(−(rayleigh + ozone + aerosol)).  depths has count entries. */
ARCUS_API arcus_status arcus_daylight_optical_depths(const arcus_daylight_desc* desc, double apparent_zenith_deg,
                                                     size_t count, const double* wavelength_nm,
                                                     arcus_optical_depths* depths);

/* The clear sky's radiance (Rayleigh and aerosol; single scattering, and the light
 * scattered more than once by Hillaire's 2020 approximation), per unit of the
 * sun's irradiance above the air (sr⁻¹; times arcus_daylight_solar_irradiance it is
 * W m⁻² nm⁻¹ sr⁻¹), seen from the site along each of direction_count directions
 * (view_zenith_deg 0..180, view_azimuth_deg counted from the sun's), the sun at
 * sun_zenith_deg (0..120: beyond 90 it is below the horizon and lights only the air
 * above Earth's shadow).  Straight paths (the sky's are not refracted) to 86 km or the
 * ground; the ground reflects nothing back.
 * radiance[d * wavelength_count + k] for direction d and wavelength k (360–830 nm). */
ARCUS_API arcus_status arcus_daylight_sky_radiance(const arcus_daylight_desc* desc, double sun_zenith_deg,
                                                   size_t direction_count, const double* view_zenith_deg,
                                                   const double* view_azimuth_deg, size_t wavelength_count,
                                                   const double* wavelength_nm, double* radiance);

/* The same sky as an equirectangular panorama of width × height pixels (1..8192 each),
 * 3 floats a pixel, top row first: a direction at azimuth a (from +z toward +x) and
 * elevation e at column u = a/360°, row v = (90° − e)/180°, as arcus_rainbow_sky's
 * sky_image takes it.  Linear sRGB of the radiance in W m⁻² nm⁻¹ sr⁻¹ (Y = 1 for a flat
 * spectrum of 1) under ASTM G173-03's sun at (sun_zenith_deg, sun_azimuth_deg); below the
 * horizon the horizon's.  Computed on a grid (61 elevations, dense at the horizon, by
 * 61 azimuths) and interpolated (about 1 s). */
ARCUS_API arcus_status arcus_daylight_sky_image(const arcus_daylight_desc* desc, double sun_zenith_deg,
                                                double sun_azimuth_deg, uint32_t width, uint32_t height, float* rgb);

/* What falls on horizontal ground at the site, W m⁻² nm⁻¹ at each wavelength: the
 * direct sun through its refracted path times cos z (sun_zenith_deg taken as apparent;
 * 0 below the horizon) and the diffuse sky, cosine-weighted over the upper hemisphere.  Either output may be NULL. */
ARCUS_API arcus_status arcus_daylight_ground_irradiance(const arcus_daylight_desc* desc, double sun_zenith_deg,
                                                        size_t count, const double* wavelength_nm, double* direct,
                                                        double* diffuse);

/* The sun's spectral irradiance above the atmosphere at 1 AU (W m⁻² nm⁻¹, ASTM G173-03):
 * band_nm = 0 gives the table's value at each wavelength (linear between its points),
 * band_nm > 0 the mean over [λ − band/2, λ + band/2].  The table spans 300–1000 nm. */
ARCUS_API arcus_status arcus_daylight_solar_irradiance(size_t count, const double* wavelength_nm, double band_nm,
                                                       double* irradiance);

/* The sun's limb darkening I(μ)/I(1) at each (wavelength_nm[i], mu[i]), μ the cosine
 * of the angle between the line of sight and the sun's surface normal (1 at the disc's
 * centre, 0 at its limb); 300–1100 nm. */
ARCUS_API arcus_status arcus_daylight_limb_darkening(size_t count, const double* wavelength_nm, const double* mu,
                                                     double* ratio);

#ifdef __cplusplus
}
#endif

#endif /* ARCUS_DAYLIGHT_H */
