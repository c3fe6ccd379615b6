// Rainbow skies through the public C API (thesis §4.1.4, §5.5.2): the marched single
// scattering against closed forms of the same integral, the scattering-angle channel,
// the azimuth lookup's side, the AZIMUTH feature compiled only for tables that need it,
// sky images (through empty air exactly as they went in, through rain dimmed by its
// extinction), reading images, and bad input (a status and a message naming what is
// wrong).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "arcus/arcus.h"
#include "scoped_env.h"
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

// An equirectangular sky of w × h pixels whose channel c is linear in the pixel
// centres' (u, v): a_c + b_c·u + c_c·v.  Bilinear reading returns a linear function
// exactly, so away from the seam (u within half a pixel of 0 or 1) and the poles the
// image's value in any direction is known in closed form.
struct LinearSkyImage {
  static constexpr double a[3] = {0.2, 0.5, 0.1}, b[3] = {0.6, -0.3, 0.4}, c[3] = {0.3, 0.2, 0.9};
  uint32_t w, h;
  std::vector<float> rgb;
  LinearSkyImage(uint32_t width, uint32_t height) : w(width), h(height), rgb(size_t(width) * height * 3) {
    for (uint32_t j = 0; j < h; ++j)
      for (uint32_t i = 0; i < w; ++i)
        for (int k = 0; k < 3; ++k) rgb[(size_t(j) * w + i) * 3 + k] = float(at(k, (i + 0.5) / w, (j + 0.5) / h));
  }
  static double at(int k, double u, double v) { return a[k] + b[k] * u + c[k] * v; }
};

// The linear sRGB image of a render.
std::vector<float> render_rgb(arcus_context_t* ctx, const Table& t, const Sky& s) {
  arcus_job_t* raw = nullptr;
  EXPECT_EQ(arcus_rainbow_render(ctx, &t.t, &s.s, &raw), ARCUS_SUCCESS) << arcus_context_last_error(ctx);
  const JobPtr j(raw);
  std::vector<float> rgb(size_t(s.s.width) * s.s.height * 3);
  EXPECT_EQ(arcus_job_get_rainbow_image(j.get(), nullptr, nullptr, nullptr, rgb.data(), nullptr), ARCUS_SUCCESS);
  return rgb;
}

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

// The kernel's march (the midpoint rule over the ray's part in the box) summed here term
// by term, each term its own exp, in double: independent of the kernel's shortcut of a
// geometric sequence while the sun leaves through one face.  Sun of 1, β = 1, no sky:
// the Y this returns is what a flat-spectrum render gives.
double march_sum(const double cam[3], const double d[3], const double sun[3], const double lo[3], const double hi[3],
                 double sigma, int steps) {
  double t0 = 0, t1 = INFINITY;
  for (int a = 0; a < 3; ++a) {
    const double ta = (lo[a] - cam[a]) / d[a], tb = (hi[a] - cam[a]) / d[a];
    t0 = std::max(t0, std::min(ta, tb));
    t1 = std::min(t1, std::max(ta, tb));
  }
  if (d[1] < 0 && cam[1] > 0) t1 = std::min(t1, -cam[1] / d[1]);
  if (t1 <= t0) return 0;
  const double dt = (t1 - t0) / steps;
  double sum = 0;
  for (int k = 0; k < steps; ++k) {
    const double t = t0 + (k + 0.5) * dt;
    double path = INFINITY;
    for (int a = 0; a < 3; ++a)
      if (sun[a] != 0) path = std::min(path, ((sun[a] > 0 ? hi[a] : lo[a]) - cam[a] - t * d[a]) / sun[a]);
    sum += std::exp(-sigma * (t - t0 + std::max(path, 0.0)));
  }
  return sum * dt;
}

std::array<double, 3> direction(double elevation_deg, double azimuth_deg) {
  const double e = elevation_deg * M_PI / 180, a = azimuth_deg * M_PI / 180;
  return {std::cos(e) * std::sin(a), std::sin(e), std::cos(e) * std::cos(a)};
}

// Optically thick rain.  Looking into it where the sun's path out of the box shortens
// faster than the view ray lengthens, the kernel's sequence of terms multiplied a term
// that had underflowed to 0 by a ratio that had overflowed: NaN pixels reported as
// success (σ_e ≳ 15/m, a low sun behind the camera).  And a term underflowed to 0 stayed
// 0 under a finite ratio above 1, though later terms are not small: a camera inside a
// layer of rain looking up, a low sun ahead (σ_e = 0.2/m), rendered black.  Reference:
// march_sum.  The image is float32: 1e-5 relative, and values below 1e-30 as 0.
TEST_F(RainbowSky, ThickRainGivesTheMarchsSumNotNanNorZero) {
  struct Case {
    double sigma, sun_elevation, sun_azimuth, look_elevation, camera_y, lo_z, hi_y, hi_z;
    int steps;
  };
  const Case cases[] = {
      {15, 0.5, 180, 10, 1.7, 100, 100, 1100, 32},    // was NaN
      {20, 10, 180, 60, 1.7, 100, 100, 1100, 32},     // was NaN
      {5, 5, 180, 60, 1.7, 100, 100, 1100, 32},       // was NaN
      {0.2, 0.5, 0, 30, 50, -1e4, 100, 1e4, 32},      // was 0, is ~1e-16
      {0.2, 0.5, 0, 60, 50, -1e4, 100, 1e4, 128},     // was 0, is ~5e-8
      {0.2, 0.5, 0, 85, 50, -1e4, 100, 1e4, 128},     // was 0, is ~2e-7
  };
  Table t(4, 1.0, 0.0);
  for (const Case& c : cases) {
    t.ext.assign(4, c.sigma);
    t.t.extinction = t.ext.data();
    Sky s(4, 0.0);
    s.s.sun_elevation_deg = c.sun_elevation;
    s.s.sun_azimuth_deg = c.sun_azimuth;
    s.s.march_steps = static_cast<uint32_t>(c.steps);
    s.s.camera_position[1] = c.camera_y;
    s.s.rain_min[2] = c.lo_z;
    s.s.rain_max[1] = c.hi_y;
    s.s.rain_max[2] = c.hi_z;
    const auto f = direction(c.look_elevation, 0);
    std::copy(f.begin(), f.end(), s.s.camera_forward);
    const auto y = render_y(ctx(), t, s);
    const double cam[3] = {0, c.camera_y, 0};
    const auto sun = direction(c.sun_elevation, c.sun_azimuth);
    const double expected = march_sum(cam, f.data(), sun.data(), s.s.rain_min, s.s.rain_max, c.sigma, c.steps);
    ASSERT_EQ(y.size(), 1u);
    EXPECT_TRUE(std::isfinite(y[0])) << "sigma " << c.sigma;
    EXPECT_NEAR(y[0], expected, 1e-5 * expected + 1e-30)
        << "sigma " << c.sigma << ", looking up " << c.look_elevation << "°: expected " << expected;
  }
  // The probe's picture: a whole image of thick rain renders, every pixel finite.
  t.ext.assign(4, 15.0);
  t.t.extinction = t.ext.data();
  Sky s(4, 0.2);
  s.s.width = 16;
  s.s.height = 12;
  s.s.fov_deg = 90;
  s.s.sun_elevation_deg = 2;
  const auto f = direction(30, 0);
  std::copy(f.begin(), f.end(), s.s.camera_forward);
  for (float v : render_y(ctx(), t, s)) EXPECT_TRUE(std::isfinite(v));
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

// With no rain in view the image sky must come out as it went in, times its scale, at
// any wavelength grid: the header's mapping (azimuth from +z toward +x → u = a/360°,
// elevation → v = (90° − e)/180°) and its pinhole camera (+x to the right looking along
// +z) recomputed here.  The spectra r·S_r + g·S_g + b·S_b have the pixel's colour exactly
// (double sums); what is left is float32 storage, 1e-6 relative, so 1e-5 bounds it.
TEST_F(RainbowSky, SkyImageComesOutAsItWentInWhereNoRainIsInTheWay) {
  const LinearSkyImage image(64, 32);
  for (int count : {8, 33, 66}) {
    Table t(count, 0.0, 1e-3);
    Sky s(count, 0.0);
    s.s.width = 16;
    s.s.height = 12;
    s.s.fov_deg = 60;
    const double look_a = 200 * M_PI / 180, look_e = 30 * M_PI / 180;  // every row above the horizon
    const double f[3] = {std::cos(look_e) * std::sin(look_a), std::sin(look_e), std::cos(look_e) * std::cos(look_a)};
    std::copy(f, f + 3, s.s.camera_forward);
    s.s.rain_min[2] = 100, s.s.rain_max[2] = 1100;  // behind the camera (β is 0 anyway)
    s.s.sky_image = image.rgb.data();
    s.s.sky_image_width = image.w;
    s.s.sky_image_height = image.h;
    s.s.sky_image_scale = 1.5;
    const auto rgb = render_rgb(ctx(), t, s);
    // right = up × forward, up' = forward × right; image plane at distance 1.
    const double right[3] = {f[2], 0, -f[0]};
    const double rn = std::hypot(right[0], right[2]);
    const double r[3] = {right[0] / rn, 0, right[2] / rn};
    const double u_[3] = {f[1] * r[2] - f[2] * r[1], f[2] * r[0] - f[0] * r[2], f[0] * r[1] - f[1] * r[0]};
    const double half_w = std::tan(30 * M_PI / 180), half_h = half_w * 12 / 16;
    for (uint32_t py = 0; py < 12; ++py)
      for (uint32_t px = 0; px < 16; ++px) {
        const double x = (2 * (px + 0.5) / 16 - 1) * half_w, y = (1 - 2 * (py + 0.5) / 12) * half_h;
        double d[3], n = 0;
        for (int a = 0; a < 3; ++a) {
          d[a] = f[a] + x * r[a] + y * u_[a];
          n += d[a] * d[a];
        }
        for (double& da : d) da /= std::sqrt(n);
        double azimuth = std::atan2(d[0], d[2]);
        if (azimuth < 0) azimuth += 2 * M_PI;
        const double u = azimuth / (2 * M_PI), v = std::acos(d[1]) / M_PI;
        for (int k = 0; k < 3; ++k) {
          const double expected = 1.5 * LinearSkyImage::at(k, u, v);
          EXPECT_NEAR(rgb[(py * 16 + px) * 3 + k], expected, 1e-5 * std::fabs(expected) + 1e-7)
              << count << " wavelengths, pixel " << px << ", " << py << " channel " << k;
        }
      }
  }
}

// Through rain the sky is dimmed by exp(−σ_e·ℓ) over the rain's length ℓ along the ray.
// A uniform image behind a grey slab (σ_e the same at every λ, β = 0): looking level
// along +z through z ∈ [100, 1100] the image must come out times exp(−σ·1000), to
// float precision (1e-5).
TEST_F(RainbowSky, SkyImageIsDimmedByTheRainsExtinction) {
  const double sigma = 1.2e-3, colour[3] = {0.25, 0.5, 0.8};
  std::vector<float> uniform;
  for (int p = 0; p < 8 * 4; ++p) uniform.insert(uniform.end(), {float(colour[0]), float(colour[1]), float(colour[2])});
  Table t(33, 0.0, sigma);
  Sky s(33, 0.0);
  s.s.sky_image = uniform.data();
  s.s.sky_image_width = 8;
  s.s.sky_image_height = 4;
  s.s.camera_position[1] = 50;  // inside the slab's height, so the level ray crosses all of it
  const auto rgb = render_rgb(ctx(), t, s);
  for (int k = 0; k < 3; ++k) {
    const double expected = colour[k] * std::exp(-sigma * 1000);
    EXPECT_NEAR(rgb[k], expected, 1e-5 * expected) << "channel " << k;
  }
}

// arcus_image_read against a file written here: a PFM (float, rows stored bottom-up),
// which must come back exactly and top row first; a missing file is an I/O error that
// names it.
TEST(ImageRead, ReadsFloatImagesExactlyTopRowFirst) {
  const std::string path = (std::filesystem::temp_directory_path() / "arcus_test_image_read.pfm").string();
  const uint32_t w = 3, h = 2;
  const float top[9] = {0.5f, 1, 2, 3, 4, 5, 6, 7, 8.25f}, bottom[9] = {9, 10, 11, 12, 13, 14, 15, 16, 0.125f};
  {
    FILE* f = std::fopen(path.c_str(), "wb");
    ASSERT_NE(f, nullptr);
    std::fprintf(f, "PF\n%u %u\n-1.0\n", w, h);  // negative scale: little-endian
    std::fwrite(bottom, sizeof(float), 9, f);
    std::fwrite(top, sizeof(float), 9, f);
    std::fclose(f);
  }
  uint32_t width = 0, height = 0;
  ASSERT_EQ(arcus_image_read(path.c_str(), &width, &height, nullptr, 0), ARCUS_SUCCESS) << arcus_last_error();
  ASSERT_EQ(width, w);
  ASSERT_EQ(height, h);
  std::vector<float> rgb(w * h * 3);
  ASSERT_EQ(arcus_image_read(path.c_str(), nullptr, nullptr, rgb.data(), rgb.size()), ARCUS_SUCCESS);
  for (int i = 0; i < 9; ++i) {
    EXPECT_EQ(rgb[i], top[i]);
    EXPECT_EQ(rgb[9 + i], bottom[i]);
  }
  std::filesystem::remove(path);
  EXPECT_EQ(arcus_image_read(path.c_str(), &width, &height, nullptr, 0), ARCUS_ERROR_IO);
  EXPECT_NE(std::string(arcus_last_error()).find("arcus_test_image_read.pfm"), std::string::npos);
  EXPECT_EQ(arcus_image_read(nullptr, &width, &height, nullptr, 0), ARCUS_ERROR_INVALID_ARGUMENT);
}

// arcus_image_write picks the format from the extension; read back, each keeps what its
// format can: EXR the floats exactly, Radiance HDR 8 bits of mantissa per pixel (RGBE:
// relative error below 2^-7 of the largest channel), PNG the 8-bit sRGB quantisation
// (half a step of the encoded value, at most 1/255 · 0.0045 near black and 2 % near 1),
// JPEG only approximately (lossy: a few code values).  Unknown extensions are refused.
TEST(ImageWrite, TheFormatFollowsTheExtension) {
  const auto dir = std::filesystem::temp_directory_path();
  const uint32_t w = 4, h = 2;
  std::vector<float> rgb(w * h * 3);
  for (size_t i = 0; i < rgb.size(); ++i) rgb[i] = 0.05f + 0.9f * float(i) / float(rgb.size());
  struct Case { const char* name; double tolerance; };
  for (const Case c : {Case{"a.exr", 0.0}, Case{"a.hdr", 1.0 / 128}, Case{"a.PNG", 0.02}, Case{"a.jpg", 0.1}}) {
    const std::string path = (dir / (std::string("arcus_test_write_") + c.name)).string();
    ASSERT_EQ(arcus_image_write(path.c_str(), w, h, rgb.data()), ARCUS_SUCCESS) << arcus_last_error();
    std::vector<float> back(rgb.size());
    uint32_t bw = 0, bh = 0;
    ASSERT_EQ(arcus_image_read(path.c_str(), &bw, &bh, back.data(), back.size()), ARCUS_SUCCESS) << arcus_last_error();
    EXPECT_EQ(bw, w);
    EXPECT_EQ(bh, h);
    for (size_t i = 0; i < rgb.size(); ++i) EXPECT_NEAR(back[i], rgb[i], c.tolerance) << c.name << " value " << i;
    std::filesystem::remove(path);
  }
  const std::string bad = (dir / "arcus_test_write.gif").string();
  EXPECT_EQ(arcus_image_write(bad.c_str(), w, h, rgb.data()), ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(std::string(arcus_last_error()).find("arcus_test_write.gif"), std::string::npos);
  rgb[5] = std::nanf("");
  EXPECT_EQ(arcus_image_write((dir / "arcus_test_write_nan.png").string().c_str(), w, h, rgb.data()),
            ARCUS_ERROR_NOT_FINITE);
}

TEST_F(RainbowSky, ASkyBeyondTheHostsMemoryIsRefusedBeforeAllocating) {
  // 16384 x 16384 pixels: 11 GiB of images on the host, held to the memory available
  // (a bound of 1 GiB here) before anything is allocated.
  Table t(4, 1e-4, 1e-4);
  Sky s(4, 0.0);
  s.s.width = s.s.height = 16384;
  ScopedEnv limit("ARCUS_MEMORY_LIMIT", "1G");
  arcus_job_t* job = nullptr;
  EXPECT_EQ(arcus_rainbow_render(ctx(), &t.t, &s.s, &job), ARCUS_ERROR_OUT_OF_MEMORY);
  EXPECT_EQ(job, nullptr);
  EXPECT_NE(std::string(arcus_context_last_error(ctx())).find("a 16384 x 16384 sky needs 11 GiB"), std::string::npos)
      << arcus_context_last_error(ctx());
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
  {
    const std::vector<float> image(4 * 2 * 3, 0.5f);
    auto with_image = [&](int count, auto change, const std::string& words) {
      Table t(count, 1e-4, 1e-4);
      Sky s(count, 0.0);
      std::vector<float> pixels = image;
      s.s.sky_image = pixels.data();
      s.s.sky_image_width = 4;
      s.s.sky_image_height = 2;
      change(s.s, pixels);
      refused(t, s, words);
    };
    with_image(4, [](arcus_rainbow_sky& s, std::vector<float>&) { s.sky_image_width = 0; }, "sky_image must be 1-65536");
    with_image(4, [](arcus_rainbow_sky& s, std::vector<float>&) { s.sky_image_scale = -1; }, "sky_image_scale");
    with_image(4, [](arcus_rainbow_sky&, std::vector<float>& p) { p[3 * 5 + 1] = -0.25f; }, "pixel (1, 1) channel 1");
    with_image(4, [](arcus_rainbow_sky&, std::vector<float>& p) { p[0] = NAN; }, "pixel (0, 0) channel 0");
    // Two wavelengths cannot mix three primaries.
    with_image(2, [](arcus_rainbow_sky&, std::vector<float>&) {}, "at least 3 wavelengths");
  }
}
