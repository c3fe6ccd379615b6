// The US Standard Atmosphere 1976 (src/sky/us1976.h) against the standard's own
// figures (NOAA-S/T 76-1562): the temperature and pressure at its layers' bases, the
// density and number density at sea level, and the geopotential conversion's round
// trip.  The standard computed its pressures with the same g0·M/R* in the same closed
// form, and prints them to 7 digits: they agree to the print.
#include <gtest/gtest.h>

#include <cmath>

#include "sky/us1976.h"

namespace {

using namespace arcus::sky;

TEST(SkyUs1976, TheLayersBasesMeetTheStandardsTable) {
  struct Row {
    double H, T, p;
  };
  const Row table[] = {{0, 288.15, 101325.0},     {11000, 216.65, 22632.06}, {20000, 216.65, 5474.889},
                       {32000, 228.65, 868.0187}, {47000, 270.65, 110.9063}, {51000, 270.65, 66.93887},
                       {71000, 214.65, 3.956420}};
  for (const Row& r : table) {
    EXPECT_NEAR(standard_temperature(r.H, 288.15), r.T, 1e-9) << r.H;
    EXPECT_NEAR(standard_pressure(r.H, 101325, 288.15), r.p, 1e-6 * r.p) << r.H;  // 7 printed digits
  }
}

TEST(SkyUs1976, SeaLevelAirHasTheStandardsDensity) {
  // ρ = 1.2250 kg/m³ (M = 28.9644 g/mol) and N = 2.5470e25 m⁻³ (the standard's N_A and
  // R*; with today's exact k_B the same to 4 digits).
  const double n = number_density(101325, 288.15);
  EXPECT_NEAR(n * 28.9644e-3 / 6.02214076e23, 1.2250, 5e-5);
  EXPECT_NEAR(n, 2.5470e25, 2e-4 * 2.5470e25);
}

TEST(SkyUs1976, GeopotentialAndGeometricHeightsAreInverse) {
  for (const double h : {0.0, 1000.0, 11019.1, 86000.0}) EXPECT_NEAR(geometric_height(geopotential_height(h)), h, 1e-8);
  // The standard's 86 km geometric is 84.852 km geopotential.
  EXPECT_NEAR(geopotential_height(86000), 84852.0, 0.5);
}

TEST(SkyUs1976, AnIsothermalLayerThinsExponentially) {
  // dp/p = −(g0 M/R*) dH/T: over 5 km at 216.65 K, exp(−0.034163·5000/216.65).
  EXPECT_NEAR(pressure_ratio(5000, 216.65, 0), std::exp(-0.034163194736310366 * 5000 / 216.65), 1e-15);
}

}  // namespace
