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

// Henyey–Greenstein's phase function per steradian.
double henyey_greenstein(double cos_theta, double g);

}  // namespace arcus::sky
