// Columns of air along straight paths through the standard atmosphere (src/sky/
// us1976.h) over a spherical Earth: what a ray's optical depth is made of before
// refraction bends it.  Host code; metres, radians.
#pragma once

#include <functional>

namespace arcus::sky {

constexpr double kEarthRadius = 6371000.0;  // m, the mean radius (as the curved engine's ARCUS_EARTH_RADIUS)
constexpr double kAtmosphereTop = 86000.0;  // m geometric: the standard's table ends here

// Molecules per m² along the straight ray from geometric height `site_m` at zenith
// angle `zenith` (0 = up, < π/2) to the top of the atmosphere.
double slant_column(double site_m, double zenith);

// The relative air mass: the slant column over the vertical one.
double relative_air_mass(double site_m, double zenith);

// Molecules per m² along the ray that leaves the site at apparent zenith angle
// `zenith` (<= π/2) and bends as the air's index falls with height (at
// `wavelength_nm`): in air whose index depends on r alone, n·r·sin θ is constant along
// a ray (Bouguer), so ds = dr/cos θ(r).
double refracted_column(double site_m, double zenith, double wavelength_nm);

// Other gases and particles along the same path: `count` number densities (per m³, or
// any per-metre quantity) as functions of geometric height, all filled by one call.
constexpr int kMaxDensities = 4;
struct Densities {
  int count = 0;
  std::function<void(double height_m, double* densities)> at;
  explicit operator bool() const { return count > 0; }
};

// columns[0] = refracted_column, columns[1 + k] = ∫ density k ds along that same path.
void refracted_columns(double site_m, double zenith, double wavelength_nm, const Densities& densities,
                       double* columns);

// The refracted path's relative air mass.
double refracted_air_mass(double site_m, double zenith, double wavelength_nm);

}  // namespace arcus::sky
