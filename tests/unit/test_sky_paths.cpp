// Straight paths through the standard atmosphere (src/sky/paths.h) against closed forms
// and a published air-mass formula: up, the column is the vertical one; near the zenith
// the air mass is sec z (a flat Earth's); toward the horizon it follows Kasten & Young's
// (1989, Appl. Opt. 28, 4735) fit to the ISO standard atmosphere, which includes
// refraction, within what refraction adds; and the refracted path follows it to the
// horizon.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "sky/paths.h"

namespace {

double kasten_young(double zenith) {
  const double degrees = zenith * 180 / M_PI;
  return 1 / (std::cos(zenith) + 0.50572 * std::pow(96.07995 - degrees, -1.6364));
}

TEST(SkyPaths, NearTheZenithTheAirMassIsTheSecant) {
  // Curvature adds ~ (H/R) tan²z: 8 km / 6371 km × 3 = 0.4% at 60°, 1e-4 at 15°.
  EXPECT_NEAR(arcus::sky::relative_air_mass(0, 0), 1, 1e-12);
  for (const double deg : {5.0, 15.0}) {
    const double z = deg * M_PI / 180;
    EXPECT_NEAR(arcus::sky::relative_air_mass(0, z), 1 / std::cos(z), 2e-4 / std::cos(z)) << deg;
  }
}

TEST(SkyPaths, TowardTheHorizonTheAirMassFollowsKastenAndYoung) {
  // Refraction lengthens a low path (it bends the ray into denser air), which a straight
  // path leaves out: ~0.1% at 70°, ~1% at 85°, 7% at the horizon.  Asserted to 85°.
  for (const double deg : {30.0, 60.0, 70.0, 80.0, 85.0}) {
    const double z = deg * M_PI / 180, ours = arcus::sky::relative_air_mass(0, z), theirs = kasten_young(z);
    std::printf("zenith %.0f deg: air mass %.4f, Kasten & Young %.4f (%+.2f%%)\n", deg, ours, theirs,
                100 * (ours / theirs - 1));
    EXPECT_NEAR(ours / theirs, 1, deg <= 70 ? 2e-3 : 1.5e-2) << deg;
    if (deg >= 60) EXPECT_LT(ours, theirs) << deg;  // refraction only adds air
  }
}

TEST(SkyPaths, ARefractedPathFollowsKastenAndYoungToTheHorizon) {
  // Kasten & Young fitted their formula to ray-traced air masses through the ISO
  // standard atmosphere (which is the 1976 standard below 50 km) with refraction, to
  // about 0.1% down to 86° and ~0.5% at the horizon (their paper's stated accuracy; the
  // index of their air differs from Ciddor's at 700 nm by a part in 10⁴ of n − 1).
  for (const double deg : {0.0, 60.0, 80.0, 85.0, 88.0, 90.0}) {
    const double z = deg * M_PI / 180, ours = arcus::sky::refracted_air_mass(0, z, 700), theirs = kasten_young(z);
    std::printf("apparent zenith %.0f deg: refracted air mass %.4f, Kasten & Young %.4f (%+.2f%%)\n", deg, ours,
                theirs, 100 * (ours / theirs - 1));
    EXPECT_NEAR(ours / theirs, 1, deg <= 86 ? 2e-3 : 1e-2) << deg;
  }
}

}  // namespace
