// Refractive indices for the rainbow engine (src/rainbow/refractive_index): IAPWS R9-97
// and SR6-08 against their releases' check values, the thesis' numbers (§4.4.1.1), the
// ice table against data/rainbow/ice_index.csv, and the geometric rainbow angle against
// eq. 4.20 and a brute-force minimum deviation.  Sources: data/rainbow/README.md.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <functional>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "unit_util.h"
#include "core/error.h"
#include "rainbow/refractive_index.h"

#ifndef ARCUS_SOURCE_DIR
#define ARCUS_SOURCE_DIR "."
#endif

namespace {

using namespace arcus::rainbow;

constexpr double kPi = 3.14159265358979323846;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

using arcus_unit::Failure;
using arcus_unit::failure_of;

// Fails unless f throws INVALID_ARGUMENT whose message holds every one of `parts`.
void expect_invalid(const std::function<void()>& f, const std::vector<std::string>& parts) {
  const Failure got = failure_of(f);
  EXPECT_EQ(got.status, ARCUS_ERROR_INVALID_ARGUMENT) << got.message;
  for (const auto& p : parts) EXPECT_NE(got.message.find(p), std::string::npos) << got.message << " lacks " << p;
}

// ---- water: IAPWS R9-97 ----

// The release's table of computed values (as printed, 8 decimals): λ 0.2265 and
// 0.5893 µm at 298.15 K, ρ 997.047435 kg/m³ (liquid, 0.1 MPa), and 0.5893 µm at
// 773.15 K, ρ 30.4758534 kg/m³ (steam).
TEST(RainbowIndex, IapwsReleaseCheckValues) {
  EXPECT_NEAR(water_index_iapws(226.5, 298.15, 997.047435), 1.39277824, 5e-9);
  EXPECT_NEAR(water_index_iapws(589.3, 298.15, 997.047435), 1.33285819, 5e-9);
  EXPECT_NEAR(water_index_iapws(589.3, 773.15, 30.4758534), 1.00949307, 5e-9);
  EXPECT_DOUBLE_EQ(water_index_iapws(589.3, 298.15, 0), 1.0);  // no matter, no refraction
}

// IAPWS SR6-08 Table 8 at 298.15 K, 0.1 MPa: ρ = 997.047013 kg/m³, (∂v/∂p)T =
// −4.53803340e-7 m³ kg⁻¹ MPa⁻¹; water_density() is at 101.325 kPa, 1.325 kPa above.
// (The table's other points, 260 K and 375 K, lie outside −12…100 °C.)
TEST(RainbowIndex, DensityMatchesSr608CheckValue) {
  const double v = 1 / 997.047013 + (-4.53803340e-7) * (0.101325 - 0.1);
  EXPECT_NEAR(water_density(25), 1 / v, 1e-6);
  // IAPWS-95 itself at 298.15 K, 0.1 MPa (the density of R9-97's check table) differs
  // from SR6-08 by less than the latter's uncertainty (1 ppm).
  EXPECT_NEAR(water_density(25), 997.047435, 1e-3);
}

// Tanaka et al. 2001 (CIPM, SMOW at 101.325 kPa, 0–40 °C) agrees within 1.2 ppm, and the
// maximum density is IAPWS-95's 999.975 kg/m³ at 3.98 °C.
TEST(RainbowIndex, DensityMatchesTanakaAndMaximum) {
  const auto tanaka = [](double t) {
    const double a1 = -3.983035, a2 = 301.797, a3 = 522528.9, a4 = 69.34881, a5 = 999.974950;
    return a5 * (1 - (t + a1) * (t + a1) * (t + a2) / (a3 * (t + a4)));
  };
  for (double t = 0; t <= 40; t += 0.5) EXPECT_NEAR(water_density(t), tanaka(t), 2e-3) << t;
  double best = 0, at = 0;
  for (double t = 0; t <= 10; t += 0.001) {
    if (water_density(t) > best) best = water_density(t), at = t;
  }
  EXPECT_NEAR(at, 3.98, 0.01);
  EXPECT_NEAR(best, 999.975, 1e-3);
  // Supercooled and hot ends stay physical: denser than at 100 °C, below the maximum.
  EXPECT_GT(water_density(-12), 997.0);
  EXPECT_LT(water_density(-12), water_density(0));
  EXPECT_NEAR(water_density(100), 958.35, 0.01);
}

// water_index() is R9-97 at the SR6-08 density.
TEST(RainbowIndex, WaterIndexIsIapwsAtNormalPressure) {
  for (double t : {-12.0, 0.0, 20.0, 55.5, 100.0}) {
    for (double nm : {200.0, 400.0, 589.3, 1100.0}) {
      EXPECT_DOUBLE_EQ(water_index(nm, t), water_index_iapws(nm, t + 273.15, water_density(t))) << nm << " " << t;
    }
  }
  EXPECT_DOUBLE_EQ(water_index(500), water_index(500, 20));  // the default is 20 °C
}

// Thesis §4.4.1.1: "1.34451 at 400 nm ... 1.33141 at 700 nm", no temperature given.
// R9-97 reproduces both within 5e-6 at 5 °C (best fit 5.1 °C: 1.8e-6); at 20 °C it is
// ~9e-4 lower, so the thesis' numbers are for cold water, not 20 °C.
TEST(RainbowIndex, ThesisWaterValuesAreFiveDegrees) {
  EXPECT_NEAR(water_index(400, 5), 1.34451, 5e-6);
  EXPECT_NEAR(water_index(700, 5), 1.33141, 5e-6);
  EXPECT_NEAR(water_index(400, 20) - 1.34451, -9.5e-4, 5e-5);
  EXPECT_NEAR(water_index(700, 20) - 1.33141, -8.9e-4, 5e-5);
  // Fig. 4.10's n = 1.33257 is λ = 650 nm at the same 5 °C.
  EXPECT_NEAR(water_index(650, 5), 1.33257, 5e-6);
}

TEST(RainbowIndex, WaterDecreasesWithWavelengthAndTemperature) {
  for (double t : {-12.0, 0.0, 5.0, 20.0, 60.0, 100.0}) {
    for (double nm = 380; nm < 780; nm += 1) EXPECT_GT(water_index(nm, t), water_index(nm + 1, t)) << nm << " " << t;
  }
  for (double t = 4; t < 100; t += 1) EXPECT_GT(water_index(550, t), water_index(550, t + 1)) << t;
  // The visible stays where water's index lives.
  EXPECT_GT(water_index(380, -12), water_index(780, 100));
  EXPECT_LT(water_index(380, -12), 1.35);
  EXPECT_GT(water_index(780, 100), 1.31);
}

TEST(RainbowIndex, WaterRangesAreEnforced) {
  expect_invalid([] { water_index(199.9); }, {"water_index", "wavelength_nm", "199.9", "[200, 1100]"});
  expect_invalid([] { water_index(1100.5); }, {"wavelength_nm", "1100.5", "[200, 1100]"});
  expect_invalid([] { water_index(kNaN); }, {"wavelength_nm", "nan"});
  expect_invalid([] { water_index(500, -12.5); }, {"temperature_c", "-12.5", "[-12, 100]"});
  expect_invalid([] { water_index(500, 100.01); }, {"temperature_c", "100.01", "[-12, 100]"});
  expect_invalid([] { water_index(500, kNaN); }, {"temperature_c", "nan"});
  expect_invalid([] { water_density(-20); }, {"water_density", "temperature_c", "-20"});
  expect_invalid([] { water_index_iapws(500, 260, 1000); }, {"temperature_k", "260", "[261.15, 773.15]"});
  expect_invalid([] { water_index_iapws(500, 300, 1070); }, {"density_kg_m3", "1070", "[0, 1060]"});
  expect_invalid([] { water_index_iapws(500, 300, -1); }, {"density_kg_m3", "-1"});
  expect_invalid([] { water_index_iapws(150, 300, 1000); }, {"wavelength_nm", "150"});
  EXPECT_NO_THROW(water_index(200, -12));
  EXPECT_NO_THROW(water_index(1100, 100));
}

// ---- ice: Warren & Brandt 2008 ----

TEST(RainbowIndex, IceTableEqualsCsv) {
  std::ifstream in(std::string(ARCUS_SOURCE_DIR) + "/data/rainbow/ice_index.csv");
  ASSERT_TRUE(in);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "wavelength_um,n_real");
  std::vector<IceRow> rows;
  while (std::getline(in, line)) {
    std::istringstream s(line);
    std::string a, b;
    std::getline(s, a, ',');
    std::getline(s, b, ',');
    rows.push_back({std::stod(a), std::stod(b)});
  }
  const auto& table = ice_table();
  ASSERT_EQ(rows.size(), table.size());
  for (size_t i = 0; i < rows.size(); ++i) {
    EXPECT_EQ(rows[i].wavelength_um, table[i].wavelength_um) << i;
    EXPECT_EQ(rows[i].n_real, table[i].n_real) << i;
  }
  EXPECT_EQ(table.front().wavelength_um * 1000, kIceMinNm);
  EXPECT_EQ(table.back().wavelength_um * 1000, kIceMaxNm);
}

// The source's printed values at its rows, returned exactly; CRC's n_D = 1.3098 (589 nm).
TEST(RainbowIndex, IceMatchesWarrenBrandt) {
  EXPECT_EQ(ice_index(199), 1.3943);
  EXPECT_EQ(ice_index(250), 1.3509);
  EXPECT_EQ(ice_index(400), 1.3194);
  EXPECT_EQ(ice_index(500), 1.3130);
  EXPECT_EQ(ice_index(600), 1.3094);
  EXPECT_EQ(ice_index(700), 1.3069);
  EXPECT_EQ(ice_index(1000), 1.3015);
  EXPECT_EQ(ice_index(1100), 1.2998);
  for (const auto& r : ice_table()) EXPECT_EQ(ice_index(r.wavelength_um * 1000), r.n_real) << r.wavelength_um;
  EXPECT_NEAR(ice_index(589), 1.3098, 2e-4);
  EXPECT_NEAR(ice_index(589.3), 1.3098, 2e-4);
  // Between rows it stays between them.
  EXPECT_LT(ice_index(275), 1.3509);
  EXPECT_GT(ice_index(275), 1.3339);
}

TEST(RainbowIndex, IceDecreasesWithWavelength) {
  for (double nm = 199; nm < 1100; nm += 0.5) EXPECT_GT(ice_index(nm), ice_index(nm + 0.5)) << nm;
  // Ice refracts less than liquid water across the visible.
  for (double nm = 380; nm <= 780; nm += 10) EXPECT_LT(ice_index(nm), water_index(nm, 0)) << nm;
}

TEST(RainbowIndex, IceRangeIsEnforced) {
  expect_invalid([] { ice_index(198.9); }, {"ice_index", "wavelength_nm", "198.9", "[199, 1100]"});
  expect_invalid([] { ice_index(1101); }, {"wavelength_nm", "1101", "[199, 1100]"});
  expect_invalid([] { ice_index(kNaN); }, {"wavelength_nm", "nan"});
}

// ---- the geometric rainbow ----

// Thesis eq. 4.20 as printed, 2 arcsin((1/n²)((4 − n²)/3)^{3/2}), is 42.14° for
// n = 1.33257: the angle from the antisolar point, i.e. 180° minus the scattering angle
// 137.86° the thesis quotes for it.  rainbow_angle_deg() is the scattering angle.
TEST(RainbowIndex, PrimaryMatchesEq420) {
  for (double n = 1.2; n < 1.99; n += 0.01) {
    const double eq420 = 2 * std::asin(1 / (n * n) * std::pow((4 - n * n) / 3, 1.5)) * 180 / kPi;
    EXPECT_NEAR(rainbow_angle_deg(n, 2), 180 - eq420, 1e-12) << n;
  }
}

TEST(RainbowIndex, ThesisRainbowAngles) {
  EXPECT_NEAR(rainbow_angle_deg(1.33257, 2), 137.86, 0.01);  // Fig. 4.10
  EXPECT_NEAR(rainbow_angle_deg(1.34451, 2), 139.57, 0.01);  // 400 nm
  EXPECT_NEAR(rainbow_angle_deg(1.33141, 2), 137.69, 0.01);  // 700 nm
  // Secondary: "129.5° for red light and 126.1° for violet light".
  EXPECT_NEAR(rainbow_angle_deg(1.33141, 3), 129.5, 0.05);
  EXPECT_NEAR(rainbow_angle_deg(1.34451, 3), 126.1, 0.05);
  // n = 1.3318 (≈ 650 nm): 129.42°, the secondary bow 50.58° from the antisolar point.
  EXPECT_NEAR(rainbow_angle_deg(1.3318, 3), 129.42, 0.01);
  // From the library's own water: the primary bow's red edge lies inside its violet edge.
  EXPECT_LT(rainbow_angle_deg(water_index(700, 5), 2), rainbow_angle_deg(water_index(400, 5), 2));
}

// The closed form is the extremum of the deviation D(i) = 2(i − p r) + (p − 1)·180° over
// the incidence angle: found here by golden-section search, then folded to [0°, 180°].
TEST(RainbowIndex, ClosedFormIsMinimumDeviation) {
  for (int p = 2; p <= 7; ++p) {
    for (double n : {1.31, 1.333, 1.345, 1.5}) {
      if (n >= p) continue;
      const auto deviation = [&](double i) {
        return 2 * (i - p * std::asin(std::sin(i) / n)) * 180 / kPi + (p - 1) * 180.0;
      };
      double a = 0, b = kPi / 2;
      const double g = (std::sqrt(5.0) - 1) / 2;
      for (int k = 0; k < 200; ++k) {
        const double c = b - g * (b - a), d = a + g * (b - a);
        if (deviation(c) < deviation(d)) {
          b = d;
        } else {
          a = c;
        }
      }
      double dmin = std::fmod(deviation((a + b) / 2), 360.0);
      if (dmin < 0) dmin += 360;
      if (dmin > 180) dmin = 360 - dmin;
      EXPECT_NEAR(rainbow_angle_deg(n, p), dmin, 1e-6) << "p " << p << " n " << n;
    }
  }
}

TEST(RainbowIndex, RainbowArgumentsAreChecked) {
  expect_invalid([] { rainbow_angle_deg(1.333, 1); }, {"rainbow_angle_deg", "p", "1"});
  expect_invalid([] { rainbow_angle_deg(1.0, 2); }, {"n", "(1, 2)", "got 1"});
  expect_invalid([] { rainbow_angle_deg(0.75, 2); }, {"n", "0.75"});
  expect_invalid([] { rainbow_angle_deg(2.0, 2); }, {"n", "2"});
  expect_invalid([] { rainbow_angle_deg(kNaN, 2); }, {"n", "nan"});
  EXPECT_NO_THROW(rainbow_angle_deg(2.5, 3));
}

}  // namespace
