// Rayleigh scattering by dry air (src/sky/rayleigh.h) against Bodhaine, Wood, Dutton &
// Slusser (1999, J. Atmos. Oceanic Technol. 16, 1854): their fits to their own
// calculation — eq. 29, the cross-section of a molecule of air with 360 ppm of CO2,
// and eq. 30, the optical depth at sea level, 1013.25 hPa, 45° latitude — written here
// from the paper.  They took the refractive index of Peck & Reeder (1972), arcus takes
// Ciddor's (1996); the two differ by a few parts in 10⁵ in n − 1 over the visible.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "sky/rayleigh.h"

namespace {

// The rational function both fits share, λ in µm.
double bodhaine_shape(double um) {
  return (1.0455996 - 341.29061 / (um * um) - 0.90230850 * um * um) / (1 + 0.0027059889 / (um * um) - 85.968563 * um * um);
}

TEST(SkyRayleigh, TheCrossSectionMeetsBodhainesFit) {
  // Eq. 29: σ in units of 1e-28 cm² = 1e-32 m².  Their fit is within 0.01% of their
  // calculation from 250 to 850 nm, and σ goes as (n − 1)², so Peck & Reeder against
  // Ciddor (a few 10⁻⁵) and the fit together stay within 3·10⁻⁴.
  double largest = 0;
  for (double nm = 300; nm <= 850; nm += 10) {
    const double expected = 1e-32 * bodhaine_shape(nm / 1000), got = arcus::sky::rayleigh_cross_section(nm, 360);
    EXPECT_NEAR(got, expected, 3e-4 * expected) << nm << " nm";
    largest = std::max(largest, std::fabs(got / expected - 1));
  }
  std::printf("the cross-section's largest difference from eq. 29, 300-850 nm: %.2e\n", largest);
}

TEST(SkyRayleigh, TheOpticalDepthMeetsBodhainesFit) {
  // Eq. 30, τ_R = 0.0021520 × the same shape: the cross-section's 3·10⁻⁴ and nothing
  // more (the column's mass is the same arithmetic).
  double largest = 0;
  for (double nm = 300; nm <= 850; nm += 10) {
    const double expected = 0.0021520 * bodhaine_shape(nm / 1000);
    const double got = arcus::sky::rayleigh_optical_depth(nm, 101325, 45, 0, 360);
    EXPECT_NEAR(got, expected, 3e-4 * expected) << nm << " nm";
    largest = std::max(largest, std::fabs(got / expected - 1));
  }
  std::printf("the optical depth's largest difference from eq. 30, 300-850 nm: %.2e\n", largest);
}

TEST(SkyRayleigh, TheKingFactorIsTheVolumeWeightedMean) {
  // At long wavelengths N2 → 1.034 and O2 → 1.096; with no CO2 the mean is their
  // volume-weighted one with argon's 1.
  const double far = arcus::sky::king_factor(1e7, 0);
  EXPECT_NEAR(far, (78.084 * 1.034 + 20.946 * 1.096 + 0.934) / 99.964, 1e-9);
  // It rises toward the blue.
  EXPECT_GT(arcus::sky::king_factor(400, 360), arcus::sky::king_factor(700, 360));
}

TEST(SkyRayleigh, ThePhaseFunctionIsNormalisedAndKeepsTheKingFactor) {
  for (const double nm : {400.0, 550.0, 700.0}) {
    // ∫ p dΩ = 2π ∫_{-1}^{1} p dμ: p is a quadratic in μ, which Simpson integrates exactly.
    const double integral = 2 * M_PI * (2.0 / 6) *
                            (arcus::sky::rayleigh_phase(-1, nm, 360) + 4 * arcus::sky::rayleigh_phase(0, nm, 360) +
                             arcus::sky::rayleigh_phase(1, nm, 360));
    EXPECT_NEAR(integral, 1, 1e-14) << nm;
    // The depolarisation ratio gives back the King factor it came from.
    const double rho = arcus::sky::depolarisation_ratio(nm, 360);
    EXPECT_NEAR((6 + 3 * rho) / (6 - 7 * rho), arcus::sky::king_factor(nm, 360), 1e-14) << nm;
    // Anisotropic molecules scatter more to the side than the classical 1 + cos²θ: the
    // ratio of side to forward, (1 + 3γ)/2(1 + γ), lies between 1/2 and 1.
    const double side = arcus::sky::rayleigh_phase(0, nm, 360) / arcus::sky::rayleigh_phase(1, nm, 360);
    EXPECT_GT(side, 0.5);
    EXPECT_LT(side, 0.52);  // ρ_n ≈ 0.03 for air: γ ≈ 0.015
  }
  // Air's depolarisation ratio in the visible: Young's (1980) 0.0279, long the value
  // used, against Bates' wavelength-dependent one (0.0282 here at 550 nm).
  EXPECT_NEAR(arcus::sky::depolarisation_ratio(550, 360), 0.0279, 0.001);
}

TEST(SkyRayleigh, ThinnerAirAboveAHighSiteScattersLess) {
  // The column's molecules go as the pressure over gravity at its centre of mass, which
  // rises by 0.73737 of the site's height: half the pressure 2 km up, half the depth
  // times g's fall over 1475 m at the free-air gradient, 3.0855·10⁻⁶ s⁻² (of 9.789 m/s²).
  const double sea = arcus::sky::rayleigh_optical_depth(550, 101325, 45, 0, 360);
  const double high = arcus::sky::rayleigh_optical_depth(550, 101325 / 2.0, 45, 2000, 360);
  const double expected = 0.5 / (1 - 3.0855e-6 * 0.73737 * 2000 / 9.789);
  EXPECT_NEAR(high / sea, expected, 1e-6);  // the gradient's higher terms: ~1e-8
}

}  // namespace
