// The clear sky by single scattering (src/sky/scattering.h) against closed forms:
// Rayleigh-only air seen near the zenith is the plane-parallel single-scattering
// radiance, whose integral over depth is exact for any vertical profile; Earth's
// shadow darkens the zenith once the sun is 10.5° down (its shadow then lies above
// 86 km); Henyey–Greenstein's phase is normalised with mean cosine g; and the zenith
// reddens as the sun sets unless ozone's Chappuis band absorbs the long paths' orange
// (Hulburt 1953, J. Opt. Soc. Am. 43, 113: why the twilight zenith stays blue).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <vector>

#include "sky/atmosphere.h"
#include "sky/rayleigh.h"
#include "sky/scattering.h"
#include "sky/sun.h"
#include "spectral/cie.h"

namespace {

using arcus::sky::Atmosphere;
using arcus::sky::ClearSky;

constexpr double kDeg = M_PI / 180;

Atmosphere rayleigh_only() {
  Atmosphere a;
  a.ozone_du = 0;
  a.aerosol_depth_500 = 0;
  return a;
}

// L/E0 of a plane-parallel layer of optical depth tau seen from its bottom, the sun
// at cosine mu_s, the view at mu_v: p/μv·e^{−τ/μv}·∫0^τ e^{−t(1/μs − 1/μv)} dt.
double plane_parallel(double tau, double mu_s, double mu_v, double phase) {
  const double k = 1 / mu_s - 1 / mu_v;
  const double integral = std::fabs(k) < 1e-12 ? tau : (1 - std::exp(-tau * k)) / k;
  return phase / mu_v * std::exp(-tau / mu_v) * integral;
}

TEST(SkyScattering, RayleighAirNearTheZenithIsThePlaneParallelClosedForm) {
  // The sphere's curvature changes a path's air by ~(H/R)·tan²z: 1.3e-3 at 45°; the
  // quadrature (128 and 64 points) adds < 1e-4.  Bound: 2e-3.
  const Atmosphere a = rayleigh_only();
  const std::vector<double> nm = {400, 550, 800};
  double worst = 0;
  for (const double sun_deg : {0.0, 30.0, 45.0}) {
    const ClearSky sky(a, sun_deg * kDeg, false);
    for (const double view_deg : {0.0, 20.0, 45.0}) {
      for (const double azimuth_deg : {0.0, 90.0, 180.0}) {
        double L[3];
        sky.radiance(view_deg * kDeg, azimuth_deg * kDeg, nm, L);
        const double cos_theta = std::cos(sun_deg * kDeg) * std::cos(view_deg * kDeg) +
                                 std::sin(sun_deg * kDeg) * std::sin(view_deg * kDeg) * std::cos(azimuth_deg * kDeg);
        for (size_t k = 0; k < nm.size(); ++k) {
          const double tau = arcus::sky::vertical_depths(a, nm[k]).rayleigh;
          const double expected = plane_parallel(tau, std::cos(sun_deg * kDeg), std::cos(view_deg * kDeg),
                                                 arcus::sky::rayleigh_phase(cos_theta, nm[k], a.co2_ppm));
          EXPECT_NEAR(L[k] / expected, 1, 2e-3) << sun_deg << " " << view_deg << " " << azimuth_deg << " " << nm[k];
          worst = std::max(worst, std::fabs(L[k] / expected - 1));
        }
      }
    }
  }
  std::printf("largest difference from the plane-parallel closed form: %.2e\n", worst);
}

TEST(SkyScattering, EarthsShadowDarkensTheZenithAtTenAndAHalfDegreesDown) {
  // The shadow's edge above the site lies at R(1/cos δ − 1): 35 km at δ = 6°, 107 km
  // at 10.5°, above the top.
  const Atmosphere a;
  const std::vector<double> nm = {550};
  double six, ten_and_half;
  ClearSky(a, 96 * kDeg, false).radiance(0, 0, nm, &six);
  ClearSky(a, 100.5 * kDeg, false).radiance(0, 0, nm, &ten_and_half);
  EXPECT_GT(six, 0);
  EXPECT_EQ(ten_and_half, 0);
}

TEST(SkyScattering, HenyeyGreensteinIsNormalisedWithMeanCosineG) {
  for (const double g : {0.0, 0.5, 0.8}) {
    const int n = 200000;
    double norm = 0, mean = 0;
    for (int i = 0; i < n; ++i) {
      const double mu = -1 + 2 * (i + 0.5) / n, p = arcus::sky::henyey_greenstein(mu, g) * 2 * M_PI * 2 / n;
      norm += p;
      mean += p * mu;
    }
    EXPECT_NEAR(norm, 1, 1e-6) << g;
    EXPECT_NEAR(mean, g, 1e-6) << g;
  }
}

// The zenith's CIE 1931 chromaticity (x, y) in sunlight above the air (ASTM G173), from
// 10 nm samples over 360–830 nm.
std::array<double, 2> zenith_chromaticity(const Atmosphere& a, double sun_elevation_deg) {
  std::vector<double> nm;
  for (double w = 365; w <= 825; w += 10) nm.push_back(w);
  std::vector<double> L(nm.size());
  ClearSky(a, (90 - sun_elevation_deg) * kDeg, false).radiance(0, 0, nm, L.data());
  for (size_t k = 0; k < nm.size(); ++k) L[k] *= arcus::sky::solar_irradiance_band(nm[k] - 5, nm[k] + 5);
  double xyz[3];
  arcus::spectral::spectrum_to_xyz(nm.data(), L.data(), nm.size(), xyz);
  const double sum = xyz[0] + xyz[1] + xyz[2];
  return {xyz[0] / sum, xyz[1] / sum};
}

TEST(SkyScattering, TheZenithReddensAsTheSunSetsUnlessOzoneKeepsItBlue) {
  // D65 white is (0.3127, 0.3290).  At noon the zenith is well on the blue side; the
  // air alone then turns it yellow through sunset (the light that reaches it crossed
  // ever longer, redder paths); with 300 DU of ozone, whose Chappuis band takes the
  // orange from those paths, it stays blue throughout, as Hulburt computed.
  constexpr double kWhiteX = 0.3127;
  Atmosphere clear = rayleigh_only(), with_ozone = clear;
  with_ozone.ozone_du = 300;
  double previous_x = 0;
  for (const double elevation : {60.0, 20.0, 10.0, 5.0, 2.0, 0.0, -2.0, -4.0, -6.0}) {
    const auto c = zenith_chromaticity(clear, elevation), o = zenith_chromaticity(with_ozone, elevation);
    std::printf("sun %+5.1f deg: zenith x, y = %.4f, %.4f without ozone; %.4f, %.4f with 300 DU\n", elevation, c[0],
                c[1], o[0], o[1]);
    if (elevation >= -2) {
      EXPECT_GT(c[0], previous_x) << elevation;  // reddening down to 2° below
      previous_x = c[0];
    }
    if (elevation == 60) {
      EXPECT_LT(c[0], 0.26);
      EXPECT_LT(c[1], 0.27);
    }
    if (elevation <= 0) {
      EXPECT_GT(c[0], kWhiteX) << elevation;
    }
    EXPECT_LT(o[0], kWhiteX - 0.02) << elevation;
  }
}

}  // namespace

namespace {

TEST(SkyScattering, TheGroundsDiffuseIrradianceIsThePlaneParallelSkysOverTheHemisphere) {
  // The closed form of the first test integrated over the hemisphere by a fine midpoint
  // rule (400 × 180), against the library's Gauss-Legendre over its spherical sky.  Near
  // the horizon the two skies part: a plane-parallel path grows as 1/μ without bound, a
  // round Earth's air mass stops at 38.  Where the air is thick (400, 550 nm) the
  // horizon's light is attenuated away in both and they agree within 1 %; in the thin
  // limit (800 nm, τ = 0.016) the flat sky's horizon adds τ·p·∫(1 − μ·m(μ))dμ ≈ 2.5 % of
  // the total that the round one lacks: there the sphere is below, by less than 3 %.
  const Atmosphere a = rayleigh_only();
  const std::vector<double> nm = {400, 550, 800};
  for (const double sun_deg : {0.0, 30.0}) {
    double direct[3], diffuse[3];
    arcus::sky::ground_irradiance(a, sun_deg * kDeg, nm, direct, diffuse, false);
    const double mu_s = std::cos(sun_deg * kDeg);
    for (size_t k = 0; k < nm.size(); ++k) {
      const double tau = arcus::sky::vertical_depths(a, nm[k]).rayleigh;
      const int n_mu = 400, n_phi = 180;
      double sum = 0;
      for (int i = 0; i < n_mu; ++i) {
        const double mu = (i + 0.5) / n_mu, sin_v = std::sqrt(1 - mu * mu);
        for (int j = 0; j < n_phi; ++j) {
          const double phi = 2 * M_PI * (j + 0.5) / n_phi;
          const double cos_theta = mu_s * mu + std::sqrt(1 - mu_s * mu_s) * sin_v * std::cos(phi);
          sum += plane_parallel(tau, mu_s, mu, arcus::sky::rayleigh_phase(cos_theta, nm[k], a.co2_ppm)) * mu;
        }
      }
      const double expected = sum / n_mu * 2 * M_PI / n_phi * arcus::sky::solar_irradiance(nm[k]);
      std::printf("sun %2.0f deg, %3.0f nm: diffuse %.5f, plane-parallel %.5f (%+.2f%%)\n", sun_deg, nm[k], diffuse[k],
                  expected, 100 * (diffuse[k] / expected - 1));
      if (nm[k] < 600) {
        EXPECT_NEAR(diffuse[k] / expected, 1, 0.01) << sun_deg << " " << nm[k];
      } else {
        EXPECT_LT(diffuse[k], expected);
        EXPECT_GT(diffuse[k], 0.97 * expected);
      }
      // The direct beam: the sun's irradiance above the air through the slant path.
      EXPECT_NEAR(direct[k], arcus::sky::solar_irradiance(nm[k]) * mu_s *
                                 std::exp(-arcus::sky::SlantPath(a, sun_deg * kDeg).depths(nm[k]).total()),
                  1e-12);
    }
  }
}

}  // namespace

namespace {

// ∫ L μ dΩ over the hemisphere below the site, per unit of the sun above the air, at
// each wavelength: Gauss–Legendre in |μ| (16 nodes) and 24 azimuths over [0, 2π).
std::vector<double> upward_flux(const ClearSky& sky, const std::vector<double>& nm) {
  static const double x[8] = {0.0950125098376374, 0.2816035507792589, 0.4580167776572274, 0.6178762444026438,
                              0.7554044083550030, 0.8656312023878318, 0.9445750230732326, 0.9894009349916499};
  static const double w[8] = {0.1894506104550685, 0.1826034150449236, 0.1691565193950025, 0.1495959888165767,
                              0.1246289712555339, 0.0951585116824928, 0.0622535239386479, 0.0271524594117541};
  std::vector<double> flux(nm.size(), 0.0), L(nm.size());
  const int azimuths = 24;
  for (int n = 0; n < 16; ++n) {
    const double xn = n < 8 ? -x[7 - n] : x[n - 8], wn = n < 8 ? w[7 - n] : w[n - 8];
    const double mu = 0.5 * (xn + 1);
    for (int j = 0; j < azimuths; ++j) {
      sky.radiance(M_PI - std::acos(mu), 2 * M_PI * (j + 0.5) / azimuths, nm, L.data());
      for (size_t k = 0; k < nm.size(); ++k) flux[k] += 0.5 * wn * mu * 2 * M_PI / azimuths * L[k];
    }
  }
  return flux;
}

TEST(SkyScattering, AConservativeAtmosphereSendsBackUpWhatDoesNotReachTheGround) {
  // Rayleigh air only (no ozone, no aerosol, a black ground): every photon of the sun's
  // flux μ0 either reaches the ground (direct or diffuse) or leaves at the top (taken
  // at 80 km: the air above holds 1e-5 of the column).  Single scattering alone loses
  // what is scattered twice or more (a third of the diffuse light at 400 nm); with
  // Hillaire's approximation the balance closes within 3 % of the scattered flux
  // (measured: within 2.6 %; his isotropic higher orders and our 64-direction table).
  Atmosphere ground = rayleigh_only(), top = ground;
  top.site_height_m = 80000;
  const std::vector<double> nm = {400, 550};
  for (const double sun_deg : {0.0, 60.0}) {
    const double mu0 = std::cos(sun_deg * kDeg);
    double direct[2], diffuse_single[2], diffuse[2];
    arcus::sky::ground_irradiance(ground, sun_deg * kDeg, nm, direct, diffuse_single, false);
    arcus::sky::ground_irradiance(ground, sun_deg * kDeg, nm, direct, diffuse, true);
    const std::vector<double> up = upward_flux(ClearSky(top, sun_deg * kDeg, true), nm);
    for (size_t k = 0; k < nm.size(); ++k) {
      const double e0 = arcus::sky::solar_irradiance(nm[k]);
      const double scattered = mu0 - direct[k] / e0, down = diffuse[k] / e0;
      std::printf("%3.0f nm, sun %2.0f deg: scattered %.4f; down %.4f (single scattering %.4f) + up %.4f = %.4f\n",
                  nm[k], sun_deg, scattered, down, diffuse_single[k] / e0, up[k], down + up[k]);
      EXPECT_NEAR((down + up[k]) / scattered, 1, 0.03) << nm[k] << " " << sun_deg;
      EXPECT_LT(diffuse_single[k], diffuse[k]);
    }
  }
}

TEST(SkyScattering, OverAReflectingGroundTheAtmosphereStillBalancesItsFlux) {
  // Rayleigh air over a Lambertian ground of albedo ρ: of the sun's flux μ0 the ground
  // absorbs (1 − ρ)·E↓ (E↓ its direct and diffuse light, the latter raised by the
  // ground's own light scattered back: Hillaire's ground term in L2) and the rest leaves
  // at the top, as the air's upward light (lit by the ground too) plus the ground's own
  // light seen through the air, ρ·E↓·2∫T(μ)μdμ with T = exp(−τ/μ) (plane-parallel).  The
  // sky's ground term is what is checked.  The light the air and the ground pass back
  // and forth is Hillaire's isotropic series with ground steps that never follow one
  // another (src/sky/scattering.cpp): measured, the balance closes within 1.9 % over
  // ρ = 0.3 and 4.1 % over snow (ρ = 0.8, 400 nm, the sun 60° down); with the ground in
  // L2 alone, as Hillaire has it, it fell short by up to 4.9 % and 14 %, and with the
  // ground as one more scattering in his series it overshot by 11 % over snow.  Bounds:
  // 2.5 % and 5 %.  (tests/python/test_sky_disort.py checks the same light against a
  // discrete-ordinates solution.)
  Atmosphere ground = rayleigh_only(), top = ground;
  top.site_height_m = 80000;
  const std::vector<double> nm = {400, 550};
  for (const double albedo : {0.3, 0.8}) {
    ground.ground_albedo = top.ground_albedo = albedo;
    for (const double sun_deg : {0.0, 60.0}) {
      const double mu0 = std::cos(sun_deg * kDeg);
      double direct[2], diffuse[2];
      arcus::sky::ground_irradiance(ground, sun_deg * kDeg, nm, direct, diffuse, true);
      const std::vector<double> up = upward_flux(ClearSky(top, sun_deg * kDeg, true), nm);
      for (size_t k = 0; k < nm.size(); ++k) {
        const double e0 = arcus::sky::solar_irradiance(nm[k]);
        const double tau = arcus::sky::rayleigh_optical_depth(nm[k], 101325, 45, 0, ground.co2_ppm);
        double escape = 0;  // 2∫0^1 e^{−τ/μ} μ dμ, midpoint rule in μ
        for (int i = 0; i < 2000; ++i) {
          const double mu = (i + 0.5) / 2000;
          escape += 2 * std::exp(-tau / mu) * mu / 2000;
        }
        const double down = (direct[k] + diffuse[k]) / e0;
        const double out = (1 - albedo) * down + up[k] + albedo * down * escape;
        std::printf("%3.0f nm, sun %2.0f deg, albedo %.1f: absorbed %.4f + air up %.4f + ground up %.4f = %.4f of %.4f\n",
                    nm[k], sun_deg, albedo, (1 - albedo) * down, up[k], albedo * down * escape, out, mu0);
        EXPECT_NEAR(out / mu0, 1, albedo < 0.5 ? 0.025 : 0.05) << nm[k] << " nm, sun " << sun_deg << ", albedo " << albedo;
      }
    }
  }
}

}  // namespace
