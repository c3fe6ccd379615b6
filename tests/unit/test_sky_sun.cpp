// The sun above the atmosphere (src/sky/sun.h): the embedded tables are data/sky's CSVs;
// band means are the table's integral; the limb darkening of Neckel (2005) against the
// per-wavelength fits of Neckel & Labs (1994, Solar Physics 153, 91, Table 1), written
// here from the paper's table: an independent fit to the same Kitt Peak scans.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "sky/sun.h"
#include "unit_util.h"

namespace {

#include "sky/sky_data.inc"

using arcus_unit::Rows;

Rows read_csv(const std::string& name, const std::string& header) {
  return arcus_unit::read_data_csv("sky", name, header);
}

TEST(SkyData, EmbeddedTablesAreTheCsvs) {
  const Rows solar = read_csv("solar_astm_g173.csv", "wavelength_nm,extraterrestrial_w_per_m2_nm");
  ASSERT_EQ(int(solar.size()), embedded::kSolarRows);
  for (size_t i = 0; i < solar.size(); ++i) {
    EXPECT_EQ(embedded::kSolarNm[i], std::stod(solar[i][0]));
    EXPECT_EQ(embedded::kSolarIrradiance[i], std::stod(solar[i][1]));
  }
  const Rows ozone = read_csv("ozone_serdyuchenko_233k.csv", "bin_start_nm,bin_end_nm,cross_section_m2");
  ASSERT_EQ(int(ozone.size()), embedded::kOzoneBins);
  for (size_t i = 0; i < ozone.size(); ++i) {
    EXPECT_EQ(embedded::kOzoneBinStartNm[i], std::stod(ozone[i][0]));
    EXPECT_EQ(embedded::kOzoneBinEndNm[i], std::stod(ozone[i][1]));
    EXPECT_EQ(embedded::kOzoneCrossSection[i], std::stod(ozone[i][2]));
  }
}

TEST(SkySun, TheIrradianceIsTheTablesAtItsPointsAndABandIsItsMean) {
  for (int i = 0; i < embedded::kSolarRows; i += 37)
    EXPECT_DOUBLE_EQ(arcus::sky::solar_irradiance(embedded::kSolarNm[i]), embedded::kSolarIrradiance[i]);
  // A band's mean against the midpoint rule on 20 000 points of the interpolant (error
  // ~ h²·f''; f'' lives only at the table's points, where the kinks are < 1 W/m²/nm).
  for (const double centre : {400.3, 550.0, 589.0, 700.7}) {
    for (const double width : {1.0, 5.0, 10.0}) {
      const int n = 20000;
      double sum = 0;
      for (int k = 0; k < n; ++k) sum += arcus::sky::solar_irradiance(centre - width / 2 + width * (k + 0.5) / n);
      EXPECT_NEAR(arcus::sky::solar_irradiance_band(centre - width / 2, centre + width / 2), sum / n, 1e-6)
          << centre << " nm, " << width << " nm";
    }
  }
}

TEST(SkySun, LimbDarkeningFollowsNeckelAndLabs1994) {
  // Table 1's fifth-degree coefficients, normalised to 1 at μ = 1, at wavelengths away
  // from the strong lines.  The two fits agree within 2.5 % for μ >= 0.1 (Neckel 2005
  // smooths over wavelength what 1994 fitted per window) and within 5 % at the limb
  // itself, where both extrapolate past the last measured μ ≈ 0.05.
  struct Window {
    double nm, a[6];
  };
  const Window windows[] = {
      {401.970, {0.12323, 1.08648, -0.43974, 0.45912, -0.32759, 0.09850}},
      {443.885, {0.16220, 1.24893, -0.92165, 0.89978, -0.50148, 0.11220}},
      {492.905, {0.20924, 1.30798, -1.20411, 1.21505, -0.67196, 0.14381}},
      {559.950, {0.26892, 1.34319, -1.58427, 1.91271, -1.31350, 0.37295}},
      {640.970, {0.33644, 1.30590, -1.79238, 2.45040, -1.89979, 0.59943}},
      {811.760, {0.42977, 1.25182, -1.85164, 2.31949, -1.59101, 0.44155}},
  };
  for (const Window& w : windows) {
    double total = 0;
    for (double a : w.a) total += a;
    EXPECT_DOUBLE_EQ(arcus::sky::limb_darkening(w.nm, 1.0), 1.0) << w.nm;
    for (int i = 0; i <= 10; ++i) {
      const double mu = 0.1 * i;
      double expected = 0;
      for (int k = 5; k >= 0; --k) expected = expected * mu + w.a[k] / total;
      EXPECT_NEAR(arcus::sky::limb_darkening(w.nm, mu) / expected, 1, i == 0 ? 0.05 : 0.025)
          << w.nm << " nm, mu " << mu;
    }
  }
}

TEST(SkySun, TheDiscsMeanRadianceIsTheAreaWeightedMean) {
  // 2∫I(μ)μ dμ by the midpoint rule on 100 000 points (error ~1e-10) against the
  // library's four-point Gauss–Legendre (exact for the degree-6 integrand).
  for (const double nm : {380.0, 450.0, 550.0, 700.0}) {
    const int n = 100000;
    double sum = 0;
    for (int k = 0; k < n; ++k) {
      const double mu = (k + 0.5) / n;
      sum += arcus::sky::limb_darkening(nm, mu) * mu;
    }
    EXPECT_NEAR(arcus::sky::limb_darkening_mean(nm), 2 * sum / n, 1e-9) << nm;
  }
  // The disc is darker toward the blue: its mean is 0.83–0.86 in the green and red and
  // falls below 0.8 in the violet (Neckel & Labs' Table 1, last column, is this mean).
  EXPECT_NEAR(arcus::sky::limb_darkening_mean(559.95), 0.8061, 0.01);
  EXPECT_NEAR(arcus::sky::limb_darkening_mean(401.97), 0.7303, 0.01);
}

}  // namespace
