// The clear sky's radiance: single scattering (Rayleigh and aerosol, src/sky/
// atmosphere.h) integrated along view rays through the spherical atmosphere, each
// point lit by the sun through its own path to the top (Earth's shadow included), and
// light scattered more than once by Hillaire's (2020, "A Scalable and Production Ready
// Sky and Atmosphere Rendering Technique", EGSR) approximation: the second order with
// isotropic phase, its transfer factor f summed as the series 1/(1 − f), tabulated per
// height and sun angle.  Straight rays: refraction, which the direct sun's path has
// (SlantPath), bends the sky's paths by less than 0.6° and is left out here.  A
// Lambertian ground of the atmosphere's ground_albedo lights the sky back through the
// same table (its light in the second order, its bounces in f).  Host code.
#pragma once

#include <array>
#include <vector>

#include "sky/atmosphere.h"

namespace arcus::sky {

// The top of the atmosphere the sky integrates to: the standard's 86 km.
class ClearSky {
 public:
  // `sun_zenith` in radians (beyond π/2: twilight), from the site; `multiple`: with the
  // light scattered more than once (about 1 s to tabulate), else single scattering only.
  ClearSky(const Atmosphere& atmosphere, double sun_zenith, bool multiple = true);

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
  bool column_to_top(double r, double mu, Column* out, int steps) const;
  Column segment(const double start[3], const double dir[3], double length, bool dense_at_end, int steps) const;
  // The midpoint rule along start + s·dir, s = length·u² (dense at the start): calls
  // visit(point, radius, density there, column from the start to the point, ds).
  template <class Visit>
  void march(const double start[3], const double dir[3], double length, int steps, Visit&& visit) const;
  // Hillaire's Ψ_ms per unit of the sun above the air: the radiance that light
  // scattered more than once brings to each unit of scattering coefficient (sr⁻¹),
  // tabulated per band of 10 nm, height and sun cosine, and read bilinearly (linear
  // between the bands' centres).
  void tabulate_multiple_scattering();
  double multiple_scattering(double wavelength_nm, double height_m, double mu_sun) const;

  Atmosphere atmosphere_;
  double sun_[3];
  std::vector<double> log_air_;  // ln N(h) on a 50 m grid, the standard's density
  std::vector<double> ms_;       // [band][height][sun cosine]; empty: single scattering only
};

// The sky as an equirectangular panorama, `width` × `height` pixels of 3 floats, top
// row first: a direction at azimuth a (from +z toward +x) and elevation e at column
// u = a/360°, row v = (90° − e)/180° (the rainbow engine's sky images).  Linear sRGB of
// the radiance in W m⁻² nm⁻¹ sr⁻¹ (Y = 1 for a flat spectrum of 1) under ASTM G173's
// sun, the sun at (sun_zenith, sun_azimuth) radians; below the horizon the horizon's
// (what a ray that misses the ground sees; the ground is the caller's).  The radiance is
// computed on a 61 × 61 grid of elevation (90°·t², dense at the horizon) and azimuth
// from the sun (3° apart: the sky is symmetric about the sun's vertical) and
// interpolated bilinearly in XYZ.
std::vector<float> sky_panorama(const Atmosphere& atmosphere, double sun_zenith, double sun_azimuth, int width,
                                int height);

// The direct sun's colour at the site: linear sRGB of its irradiance in W m⁻² nm⁻¹
// (Y = 1 for a flat spectrum of 1) through the refracted path at apparent zenith angle
// `sun_zenith` (radians, < π/2), as sky_panorama's radiances are.
std::array<double, 3> sun_linear_srgb(const Atmosphere& atmosphere, double sun_zenith);

// What falls on a horizontal ground at the site (W m⁻² nm⁻¹) at each wavelength: the
// direct sun through its refracted path (sun_zenith taken as apparent) times cos z, and
// the sky (multiple scattering included unless asked) over the upper hemisphere weighted by cos θ (16-point
// Gauss–Legendre in cos θ, 24 azimuths over the half the sky is symmetric in).
void ground_irradiance(const Atmosphere& atmosphere, double sun_zenith, const std::vector<double>& wavelengths_nm,
                       double* direct, double* diffuse, bool multiple = true);

// Henyey–Greenstein's phase function per steradian.
double henyey_greenstein(double cos_theta, double g);

}  // namespace arcus::sky
