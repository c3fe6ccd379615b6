// The US Standard Atmosphere 1976 (src/sky/us1976.h) against the standard's own
// figures (NOAA-S/T 76-1562): the temperature and pressure at its layers' bases, the
// density and number density at sea level, the geopotential conversion's round trip;
// and its column of air against Bodhaine et al.'s (src/sky/rayleigh.h), another route.  The standard computed its pressures with the same g0·M/R* in the same closed
// form, and prints them to 7 digits: they agree to the print.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "sky/rayleigh.h"
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

TEST(SkyUs1976, ItsColumnOfAirIsBodhainesColumn) {
  // Two routes to the molecules over a square metre at sea level: Simpson over the
  // standard's number density, 0 to 86 km in geometric height (the 1.5·10⁻⁵ of the
  // column above is left out), against p·N_A/(m_a·g) with g at the column's centre of
  // mass (Bodhaine et al. 1999, src/sky/rayleigh.h).  The standard holds g0·M/R* fixed
  // in geopotential height; Bodhaine's g at 45° and 5.5 km stands for the same fall of
  // gravity: they agree within 5·10⁻⁴.
  const int n = 20000;
  const double top = 86000, step = top / n;
  double column = 0;
  for (int i = 0; i <= n; ++i) {
    const double H = geopotential_height(i * step);
    const double density = number_density(standard_pressure(H, 101325, 288.15), standard_temperature(H, 288.15));
    column += (i == 0 || i == n ? 1 : i % 2 ? 4 : 2) * density;
  }
  column *= step / 3;
  const double bodhaine = arcus::sky::rayleigh_optical_depth(550, 101325, 45, 0, 0) /
                          arcus::sky::rayleigh_cross_section(550, 0);
  std::printf("molecules over a square metre: %.6e by the standard, %.6e by Bodhaine's column\n", column, bodhaine);
  EXPECT_NEAR(column / bodhaine, 1, 5e-4);
}

}  // namespace
