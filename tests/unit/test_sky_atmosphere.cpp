// The clear atmosphere's optical depths (src/sky/atmosphere.h) against closed forms:
// straight up, the air's depth is Bodhaine's column from pressure and gravity, the
// ozone's the column times the cross-section, the aerosol's the given τ(500) scaled
// by Ångström's law; along a slant path each layer's depth grows as a thin shell's
// air mass at its height; and one path serves every wavelength.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "sky/atmosphere.h"
#include "sky/paths.h"
#include "sky/rayleigh.h"

namespace {

using arcus::sky::Atmosphere;
using arcus::sky::OpticalDepths;

TEST(SkyAtmosphere, StraightUpEachLayersDepthIsItsColumnsClosedForm) {
  Atmosphere a;
  a.co2_ppm = 0;  // Bodhaine's column counts CO2's mass; the standard's density does not
  for (const double nm : {360.0, 450.0, 550.0, 700.0, 830.0}) {
    const OpticalDepths d = arcus::sky::vertical_depths(a, nm);
    // The US 1976 column against Bodhaine's p·N_A/(m_a·g) at 45°: within 4e-4
    // (tests/unit/test_sky_us1976.cpp: the two columns differ by 3.3e-4).
    EXPECT_NEAR(d.rayleigh / arcus::sky::rayleigh_optical_depth(nm, 101325, 45, 0, 0), 1, 4e-4) << nm;
    // The tent holds exactly 1 DU per unit; the midpoint rule's error on its kinks is
    // ~(Δh)² with Δh ≈ 20 m at 25 km: < 1e-5.
    EXPECT_NEAR(d.ozone / (a.ozone_du * arcus::sky::kDobsonUnit * arcus::sky::ozone_cross_section(nm)), 1, 1e-5) << nm;
    EXPECT_NEAR(d.aerosol / (a.aerosol_depth_500 * std::pow(nm / 500, -a.angstrom_exponent)), 1, 1e-5) << nm;
  }
}

TEST(SkyAtmosphere, ASitesAirIsTheColumnAboveIt) {
  // Above 3 km lies the air that presses 70 121 Pa (US 1976, Table I), held up by a
  // gravity 0.07 % weaker than at sea level: Bodhaine's column from pressure and g
  // there, within the two routes' 4e-4.  The aerosol's depth is given above the site,
  // so it does not change; the ozone lies above both.
  Atmosphere sea, mountain;
  sea.co2_ppm = mountain.co2_ppm = 0;
  mountain.site_height_m = 3000;
  const OpticalDepths low = arcus::sky::vertical_depths(sea, 550), high = arcus::sky::vertical_depths(mountain, 550);
  const double bodhaine = arcus::sky::rayleigh_optical_depth(550, 70121, 45, 3000, 0) /
                          arcus::sky::rayleigh_optical_depth(550, 101325, 45, 0, 0);
  EXPECT_NEAR(high.rayleigh / low.rayleigh / bodhaine, 1, 4e-4);
  EXPECT_NEAR(high.aerosol / low.aerosol, 1, 1e-6);
  EXPECT_NEAR(high.ozone / low.ozone, 1, 1e-6);
}

// A thin shell at height h seen at zenith angle z from sea level over a sphere of
// radius R, without refraction: (1 + h/R)/√(cos²z + 2h/R + (h/R)²).
double shell_air_mass(double h, double zenith) {
  const double q = h / arcus::sky::kEarthRadius, c = std::cos(zenith);
  return (1 + q) / std::sqrt(c * c + 2 * q + q * q);
}

TEST(SkyAtmosphere, ASlantPathsLayersGrowAsShellsAtTheirHeights) {
  // Ozone sits near 25 km: its air mass is a shell's there to within the tent's
  // spread (±15 km) — 1 % at 80°, 0.1 % at 60° — and refraction, which bends the
  // ray below the straight line (< 0.3 % by 80°).  The aerosol hugs the ground: within
  // 0.5 % of sec z to 70° (H/R = 2e-4: curvature adds (H/R)·tan²z).
  Atmosphere a;
  for (const double deg : {30.0, 60.0, 70.0, 80.0}) {
    const double z = deg * M_PI / 180;
    const OpticalDepths up = arcus::sky::vertical_depths(a, 600), slant = arcus::sky::SlantPath(a, z).depths(600);
    EXPECT_NEAR(slant.ozone / up.ozone / shell_air_mass(25000, z), 1, deg <= 60 ? 2e-3 : 1.2e-2) << deg;
    if (deg <= 70) {
      EXPECT_NEAR(slant.aerosol / up.aerosol * std::cos(z), 1, 5e-3) << deg;
    }
    EXPECT_NEAR(slant.rayleigh / up.rayleigh, arcus::sky::refracted_air_mass(0, z, 600), 1e-6) << deg;
  }
}

TEST(SkyAtmosphere, OnePathServesEveryWavelength) {
  // The columns interpolated in the air's refractivity between 360 and 830 nm against
  // the path integrated for 550 nm itself, at the horizon where dispersion matters
  // most: the two ends' columns differ by 0.33 %, and what is left after a linear
  // interpolation is second order in it: within 1e-5.
  Atmosphere a;
  const double z = M_PI / 2;
  const OpticalDepths interpolated = arcus::sky::SlantPath(a, z).depths(550);
  arcus::sky::Densities none;
  double air, violet, red;
  arcus::sky::refracted_columns(0, z, 550, none, &air);
  arcus::sky::refracted_columns(0, z, 360, none, &violet);
  arcus::sky::refracted_columns(0, z, 830, none, &red);
  std::printf("horizontal columns: %.6e at 360 nm, %.6e at 550 nm, %.6e at 830 nm\n", violet, air, red);
  EXPECT_NEAR(interpolated.rayleigh / (air * arcus::sky::rayleigh_cross_section(550, a.co2_ppm)), 1, 1e-5);
}

}  // namespace
