// Rainbow skies through the public C API (thesis §4.1.4, §5.5.2): the marched single
// scattering against closed forms of the same integral, the scattering-angle channel,
// the azimuth lookup's side, the AZIMUTH feature compiled only for tables that need it,
// and bad input (a status and a message naming what is wrong).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "arcus/arcus.h"
#include "test_util.h"

using namespace arcus_test;

namespace {

// A table of `count` wavelengths, constant β and σ_e (φ_count azimuths; β_of_phi may
// shape it over φ).
struct Table {
  std::vector<double> nm, beta, ext;
  arcus_rainbow_table t{};
  Table(int count, double beta_value, double sigma, uint32_t phis = 1, double (*beta_of_phi)(double) = nullptr) {
    for (int i = 0; i < count; ++i) nm.push_back(380 + 320.0 * i / std::max(count - 1, 1));
    const uint32_t thetas = 181;
    for (int l = 0; l < count; ++l)
        for (uint32_t j = 0; j < phis; ++j) {
        const double shape = beta_of_phi ? beta_of_phi(360.0 * j / phis) : 1.0;
        for (uint32_t i = 0; i < thetas; ++i) beta.push_back(beta_value * shape);
      }
    ext.assign(count, sigma);
    t.wavelength_count = count;
    t.wavelengths_nm = nm.data();
    t.theta_count = thetas;
    t.theta_first_deg = 0;
    t.theta_last_deg = 180;
    t.phi_count = phis;
    t.scattering = beta.data();
    t.extinction = ext.data();
  }
};

// One pixel looking along +z from (0, 1.7, 0) into a slab of rain z ∈ [100, 1100],
// y ∈ [0, 100], under a flat sun of 1 and a flat sky of `sky`.
struct Sky {
  std::vector<double> sun, sky_l;
  arcus_rainbow_sky s{};
  Sky(int count, double sky_value) : sun(count, 1.0), sky_l(count, sky_value) {
    EXPECT_EQ(arcus_rainbow_sky_init(&s), ARCUS_SUCCESS);
    s.width = s.height = 1;
    s.rain_min[0] = -1e4, s.rain_min[1] = 0, s.rain_min[2] = 100;
    s.rain_max[0] = 1e4, s.rain_max[1] = 100, s.rain_max[2] = 1100;
    s.sun_samples = 1;
    s.sun_irradiance = sun.data();
    s.sky_radiance = sky_l.data();
    s.exposure = 1;
  }
};

std::vector<float> render_y(arcus_context_t* ctx, const Table& t, const Sky& s, float* theta = nullptr,
                            arcus_features* features = nullptr) {
  arcus_job_t* raw = nullptr;
  EXPECT_EQ(arcus_rainbow_render(ctx, &t.t, &s.s, &raw), ARCUS_SUCCESS) << arcus_context_last_error(ctx);
  const JobPtr j(raw);
  const size_t n = size_t(s.s.width) * s.s.height;
  std::vector<float> xyz(3 * n), y(n), th(n);
  EXPECT_EQ(arcus_job_get_rainbow_image(j.get(), nullptr, nullptr, xyz.data(), nullptr, th.data()), ARCUS_SUCCESS);
  for (size_t p = 0; p < n; ++p) y[p] = xyz[3 * p + 1];
  if (theta) *theta = th[0];
  if (features) {
    EXPECT_EQ(arcus_job_get_features(j.get(), features), ARCUS_SUCCESS);
  }
  return y;
}

class RainbowSky : public ArcusTest {};

}  // namespace

// With the sun at the zenith the sun's path out of the slab is the same at every step
// (100 − 1.7 m), so the march integrates a pure exponential:
//   Y = E β e^{−σ·98.3} (1 − e^{−σ·1000})/σ + L_sky e^{−σ·1000}.
// A flat spectrum of 1 has Y = 1 (the band weights), so Y is that radiance.  Midpoint
// rule with 2048 steps: relative error (σ Δt)²/24 ≈ 1e-8; the image is float32 (6e-8),
// so 1e-6 bounds both.
TEST_F(RainbowSky, MarchMatchesTheClosedFormUnderAZenithSun) {
  const double beta = 2e-4, sigma = 1e-3, sky = 0.3;
  Table t(8, beta, sigma);
  Sky s(8, sky);
  s.s.sun_elevation_deg = 90;
  s.s.march_steps = 2048;
  float theta = 0;
  const auto y = render_y(ctx(), t, s, &theta);
  const double expected = beta * std::exp(-sigma * 98.3) * (1 - std::exp(-sigma * 1000)) / sigma +
                          sky * std::exp(-sigma * 1000);
  EXPECT_NEAR(y[0], expected, 1e-6 * expected);
  EXPECT_NEAR(theta, 90.0, 1e-4);  // looking level, the sun straight up
}

// An oblique sun (30° up, behind the camera) leaves the slab through its top far from
// the camera and through its near face (z = 100) close to it: the integrand switches
// form mid-ray, which the kernel's one-exp-per-face sequence must follow.  Reference: the
// same integral by the trapezoid rule on 10⁶ intervals (error ~1e-12), independent of
// the kernel; the march's 4096 midpoints err by ~(σΔt)²/24 ≈ 2e-9 relative.
TEST_F(RainbowSky, MarchFollowsTheSunsExitFaceAlongTheRay) {
  const double beta = 1e-4, sigma = 2e-3;
  Table t(4, beta, sigma);
  Sky s(4, 0.0);
  s.s.sun_elevation_deg = 30;
  s.s.sun_azimuth_deg = 180;
  s.s.march_steps = 4096;
  float theta = 0;
  const auto y = render_y(ctx(), t, s, &theta);
  const double se = 0.5, sz = -std::sqrt(3.0) / 2;
  auto f = [&](double z) {
    const double path = std::min((100 - 1.7) / se, (100 - z) / sz);
    return std::exp(-sigma * (z - 100 + path));
  };
  const int n = 1000000;
  double integral = 0.5 * (f(100) + f(1100));
  for (int i = 1; i < n; ++i) integral += f(100 + 1000.0 * i / n);
  integral *= 1000.0 / n;
  EXPECT_NEAR(y[0], beta * integral, 1e-6 * beta * integral);
  EXPECT_NEAR(theta, 150.0, 1e-4);  // cos θ = d·sun = −cos 30°
}

// β only for φ in [180°, 360°): light leaving downward across the light (φ = 270° is
// straight down).  A drop above the antisolar point sends light down to the camera, so
// the pixel looking above it is lit and the one below is dark.
TEST_F(RainbowSky, AzimuthIsMeasuredFromTheLightFrameWithYUp) {
  Table t(4, 1e-4, 1e-4, 8, [](double phi) { return phi >= 180 ? 1.0 : 0.0; });
  Sky s(4, 0.0);
  s.s.sun_elevation_deg = 0;
  s.s.width = 1;
  s.s.height = 3;
  s.s.fov_deg = 40;
  s.s.camera_position[1] = 50;  // inside the slab: both rows cross rain
  s.s.camera_position[2] = 200;
  arcus_features features = 0;
  const auto y = render_y(ctx(), t, s, nullptr, &features);
  EXPECT_GT(y[0], 0.0f);         // top row: looking up
  EXPECT_EQ(y[2], 0.0f);         // bottom row: looking down
  EXPECT_TRUE(features & ARCUS_FEATURE_RAINBOW_AZIMUTH);
}

TEST_F(RainbowSky, TablesWithoutAzimuthCompileWithoutIt) {
  Table t(4, 1e-4, 1e-4);
  Sky s(4, 0.0);
  arcus_features features = ~arcus_features(0);
  render_y(ctx(), t, s, nullptr, &features);
  EXPECT_EQ(features, arcus_features(0));
}

TEST_F(RainbowSky, BadInputIsRefusedWithAReason) {
  auto refused = [&](const Table& t, const Sky& s, const std::string& words) {
    arcus_job_t* job = nullptr;
    EXPECT_EQ(arcus_rainbow_render(ctx(), &t.t, &s.s, &job), ARCUS_ERROR_INVALID_ARGUMENT) << words;
    EXPECT_NE(std::string(arcus_context_last_error(ctx())).find(words), std::string::npos)
        << arcus_context_last_error(ctx());
    EXPECT_EQ(job, nullptr);
  };
  {
    Table t(4, 1e-4, 1e-4);
    Sky s(4, 0.0);
    s.s.sun_elevation_deg = -3;
    refused(t, s, "below the horizon");
  }
  {
    Table t(4, 1e-4, 1e-4);
    t.ext[2] = -1;
    Sky s(4, 0.0);
    refused(t, s, "table.extinction[2]");
  }
  {
    Table t(4, 1e-4, 1e-4);
    t.nm[1] = t.nm[0];
    Sky s(4, 0.0);
    refused(t, s, "increase strictly");
  }
  {
    Table t(4, 1e-4, 1e-4);
    Sky s(4, 0.0);
    s.s.sun_irradiance = nullptr;
    refused(t, s, "sun_irradiance is NULL");
  }
  {
    Table t(4, 1e-4, 1e-4);
    Sky s(4, 0.0);
    s.s.rain_max[1] = s.s.rain_min[1];
    refused(t, s, "rain_min must lie below rain_max");
  }
  {
    Table t(4, 1e-4, 1e-4);
    Sky s(4, 0.0);
    s.s.camera_up[0] = 0, s.s.camera_up[1] = 0, s.s.camera_up[2] = 2;  // along forward
    refused(t, s, "camera_up");
  }
}
