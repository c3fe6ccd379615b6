// The clear sky's radiance by single scattering (Rayleigh and aerosol, src/sky/
// atmosphere.h) integrated along view rays through the spherical atmosphere, each
// point lit by the sun through its own path to the top (Earth's shadow included).
// Straight rays: refraction, which the direct sun's path has (SlantPath), bends the
// sky's paths by less than 0.6° and is left out here.  Light scattered more than once
// is left out too (it adds ~10–30 % at noon, more toward twilight).  Host code.
#pragma once

#include <vector>

#include "sky/atmosphere.h"

namespace arcus::sky {

// The top of the atmosphere the sky integrates to: the standard's 86 km.
class SingleScatteringSky {
 public:
  // `sun_zenith` in radians (beyond π/2: twilight), from the site.
  SingleScatteringSky(const Atmosphere& atmosphere, double sun_zenith);

  // Radiance per unit of the sun's irradiance above the air (sr⁻¹), at each
  // wavelength, seen from the site along (view_zenith, view_azimuth) radians, the
  // azimuth counted from the sun's; a view into the ground sees only the air in front
  // of it.  radiance[k] for wavelengths_nm[k].
  void radiance(double view_zenith, double view_azimuth, const std::vector<double>& wavelengths_nm,
                double* radiance) const;

 private:
  struct Column {
    double air = 0, ozone = 0, aerosol = 0;  // m⁻², m⁻² per DU, m (relative density × length)
  };
  struct Density {
    double air, ozone, aerosol;
  };
  Density density(double height_m) const;
  // The columns along the straight ray from the point at radius r whose direction has
  // cosine mu with the local vertical, to the top; false when it meets the ground.
  bool column_to_top(double r, double mu, Column* out) const;
  Column segment(const double start[3], const double dir[3], double length, bool dense_at_end, int steps) const;

  Atmosphere atmosphere_;
  double sun_[3];
  std::vector<double> log_air_;  // ln N(h) on a 50 m grid, the standard's density
};

// The sky as an equirectangular panorama, `width` × `height` pixels of 3 floats, top
// row first: a direction at azimuth a (from +z toward +x) and elevation e at column
// u = a/360°, row v = (90° − e)/180° (the rainbow engine's sky images).  Linear sRGB of
// the radiance in W m⁻² nm⁻¹ sr⁻¹ (Y = 1 for a flat spectrum of 1) under ASTM G173's
// sun, the sun at (sun_zenith, sun_azimuth) radians; 0 below the horizon (the ground is
// the caller's).  The radiance is computed on a 1.5° × 3° grid of zenith angle and
// azimuth from the sun (the sky is symmetric about the sun's vertical) and
// interpolated bilinearly in XYZ.
std::vector<float> sky_panorama(const Atmosphere& atmosphere, double sun_zenith, double sun_azimuth, int width,
                                int height);

// What falls on a horizontal ground at the site (W m⁻² nm⁻¹) at each wavelength: the
// direct sun through its refracted path (sun_zenith taken as apparent) times cos z, and
// the single-scattering sky over the upper hemisphere weighted by cos θ (16-point
// Gauss–Legendre in cos θ, 24 azimuths over the half the sky is symmetric in).
void ground_irradiance(const Atmosphere& atmosphere, double sun_zenith, const std::vector<double>& wavelengths_nm,
                       double* direct, double* diffuse);

// Henyey–Greenstein's phase function per steradian.
double henyey_greenstein(double cos_theta, double g);

}  // namespace arcus::sky
