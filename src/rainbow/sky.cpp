#include "rainbow/sky.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <string>

#include "core/buffer.h"
#include "core/context.h"
#include "core/error.h"
#include "core/limits.h"
#include "core/format.h"
#include "core/job.h"
#include "core/kernel_source.h"
#include "core/runtime.h"
#include "core/launch.h"
#include "geometry/vec3.h"
#include "image/image_io.h"
#include "rainbow/rainbow_desc.h"
#include "spectral/cie.h"
#include "spectral/srgb.h"

namespace arcus::rainbow {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180;
constexpr double kGoldenAngle = 2.39996322972865332;  // π(3 − √5): the sunflower's turn

ARCUS_KERNEL_ARGS(SkyArg, "arcus_rainbow_sky", ARCUS_RAINBOW_SKY_ARGS);

const KernelSource kSky{"rainbow/sky", {"common/real.h", "rainbow/rainbow_desc.h", "rainbow/sky.cl"}, ""};

bool finite3(const double* v) { return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]); }

// Each of `count` values finite and ≥ 0; NULL allowed when `optional`.
void require_spectrum(const double* values, size_t count, const char* name, bool optional) {
  if (!values) {
    require(optional, std::string(name) + " is NULL");
    return;
  }
  for (size_t i = 0; i < count; ++i)  // `if`, not require(): no message built per value
    if (!(std::isfinite(values[i]) && values[i] >= 0))
      fail(ARCUS_ERROR_INVALID_ARGUMENT,
           std::string(name) + "[" + std::to_string(i) + "] must be finite and ≥ 0, got " + number(values[i]));
}

// The table's β at (φ, θ) of wavelength l, as the kernel reads it: linear in θ and φ
// (periodic), 0 outside the θ samples.
double beta_at(const arcus_rainbow_table& t, uint32_t l, double phi_deg, double theta_deg) {
  const double step = (t.theta_last_deg - t.theta_first_deg) / (t.theta_count - 1);
  const double u = (theta_deg - t.theta_first_deg) / step;
  if (!(u >= 0) || u > t.theta_count - 1) return 0;
  const uint32_t i = std::min<uint32_t>(static_cast<uint32_t>(u), t.theta_count - 2);
  const double fu = u - i;
  auto row = [&](uint32_t j) {
    const double* r = t.scattering + (size_t(l) * t.phi_count + j) * t.theta_count + i;
    return (1 - fu) * r[0] + fu * r[1];
  };
  if (t.phi_count == 1) return row(0);
  double v = phi_deg / 360 * t.phi_count;
  v -= std::floor(v / t.phi_count) * t.phi_count;
  const uint32_t j0 = std::min<uint32_t>(static_cast<uint32_t>(v), t.phi_count - 1);
  const double fv = v - j0;
  return (1 - fv) * row(j0) + fv * row((j0 + 1) % t.phi_count);
}

// The sky image behind every pixel, times its scale (linear sRGB, 3 floats a pixel): the
// kernel's view rays (sky.cl) sampled on the host, so that one bilinear sampler and one
// equirectangular convention (image_io.h) serve every engine.
std::vector<float> sky_behind_pixels(const arcus_rainbow_sky& s, const rainbow_sky_desc& d) {
  image::Image sky;
  sky.width = static_cast<int>(s.sky_image_width);
  sky.height = static_cast<int>(s.sky_image_height);
  sky.channels = {"R", "G", "B"};
  sky.pixels.assign(s.sky_image, s.sky_image + size_t(sky.width) * sky.height * 3);
  std::vector<float> out(size_t(s.width) * s.height * 3);
  for (uint32_t py = 0; py < s.height; ++py)
    for (uint32_t px = 0; px < s.width; ++px) {
      const double u = (2 * (px + 0.5) / s.width - 1) * d.half_width, v = (1 - 2 * (py + 0.5) / s.height) * d.half_height;
      Vec3 ray;
      for (int a = 0; a < 3; ++a) ray[a] = d.forward[a] + u * d.right[a] + v * d.up[a];
      ray = normalized(ray);
      // This engine's +x lies to the right of a camera looking along +z, the renderer's
      // to its left: x mirrored, a panorama reads the same way round in both.
      const auto uv = image::equirect_uv(-ray[0], ray[1], ray[2]);
      const auto rgb = image::sample_bilinear(sky, uv[0], uv[1], true);
      for (int c = 0; c < 3; ++c)
        out[(size_t(py) * s.width + px) * 3 + c] = static_cast<float>(rgb[c] * s.sky_image_scale);
    }
  return out;
}

}  // namespace

void check_sky(const arcus_rainbow_table& t, const arcus_rainbow_sky& s) {
  // ---- the table
  require(t.wavelength_count >= 1 && t.wavelength_count <= 4096,
          "table.wavelength_count must be 1-4096, got " + std::to_string(t.wavelength_count));
  require(t.wavelengths_nm, "table.wavelengths_nm is NULL");
  for (uint32_t l = 0; l < t.wavelength_count; ++l) {
    require(std::isfinite(t.wavelengths_nm[l]) && t.wavelengths_nm[l] > 0,
            "table.wavelengths_nm[" + std::to_string(l) + "] must be positive, got " + number(t.wavelengths_nm[l]));
    require(l == 0 || t.wavelengths_nm[l] > t.wavelengths_nm[l - 1],
            "table.wavelengths_nm must increase strictly (entry " + std::to_string(l) + ")");
  }
  require(t.theta_count >= 2 && t.theta_count <= (1u << 20),
          "table.theta_count must be 2-2^20, got " + std::to_string(t.theta_count));
  require(std::isfinite(t.theta_first_deg) && std::isfinite(t.theta_last_deg) && t.theta_first_deg >= 0 &&
              t.theta_last_deg <= 180 && t.theta_first_deg < t.theta_last_deg,
          "table θ must run from theta_first_deg to a larger theta_last_deg within [0, 180], got " +
              number(t.theta_first_deg) + " to " + number(t.theta_last_deg));
  require(t.phi_count >= 1 && t.phi_count <= 3600, "table.phi_count must be 1-3600, got " + std::to_string(t.phi_count));
  const size_t size = size_t(t.wavelength_count) * t.phi_count * t.theta_count;
  require(size <= (size_t(1) << 28), "the table holds " + std::to_string(size) + " values, more than 2^28");
  require_spectrum(t.scattering, size, "table.scattering", false);
  require_spectrum(t.extinction, t.wavelength_count, "table.extinction", false);
  // ---- the sky
  require(s.width >= 1 && s.height >= 1 && s.width <= 16384 && s.height <= 16384 &&
              size_t(s.width) * s.height <= (size_t(1) << 28),
          "sky width and height must be 1-16384, got " + std::to_string(s.width) + " × " + std::to_string(s.height));
  require(finite3(s.camera_position), "sky.camera_position must be finite");
  require(finite3(s.camera_forward) && dot(vec3(s.camera_forward), vec3(s.camera_forward)) > 0,
          "sky.camera_forward must be a finite non-zero vector");
  require(finite3(s.camera_up) && dot(cross(vec3(s.camera_forward), vec3(s.camera_up)),
                                      cross(vec3(s.camera_forward), vec3(s.camera_up))) > 1e-12 *
                                      dot(vec3(s.camera_forward), vec3(s.camera_forward)) * dot(vec3(s.camera_up), vec3(s.camera_up)),
          "sky.camera_up must be finite and not parallel to camera_forward");
  require(std::isfinite(s.fov_deg) && s.fov_deg > 0 && s.fov_deg < 180,
          "sky.fov_deg must lie in (0, 180), got " + number(s.fov_deg));
  require(std::isfinite(s.sun_elevation_deg) && s.sun_elevation_deg <= 90,
          "sky.sun_elevation_deg must be finite and at most 90, got " + number(s.sun_elevation_deg));
  require(s.sun_elevation_deg >= 0,
          "the sun is below the horizon (sun_elevation_deg " + number(s.sun_elevation_deg) +
              "): it lights no rain in front of the camera, so no rainbow forms; raise it to 0 or above");
  require(std::isfinite(s.sun_azimuth_deg), "sky.sun_azimuth_deg must be finite");
  require(std::isfinite(s.sun_diameter_deg) && s.sun_diameter_deg >= 0 && s.sun_diameter_deg <= 20,
          "sky.sun_diameter_deg must lie in [0, 20], got " + number(s.sun_diameter_deg));
  require(s.sun_samples >= 1 && s.sun_samples <= 4096, "sky.sun_samples must be 1-4096, got " + std::to_string(s.sun_samples));
  require_spectrum(s.sun_irradiance, t.wavelength_count, "sky.sun_irradiance", false);
  require_spectrum(s.sky_radiance, t.wavelength_count, "sky.sky_radiance", true);
  require_spectrum(s.ground_radiance, t.wavelength_count, "sky.ground_radiance", true);
  if (s.sky_image) {
    require(s.sky_image_width >= 1 && s.sky_image_height >= 1 && s.sky_image_width <= 65536 &&
                s.sky_image_height <= 65536 && size_t(s.sky_image_width) * s.sky_image_height <= (size_t(1) << 28),
            "sky.sky_image must be 1-65536 pixels on a side, got " + std::to_string(s.sky_image_width) + " × " +
                std::to_string(s.sky_image_height));
    require(std::isfinite(s.sky_image_scale) && s.sky_image_scale >= 0,
            "sky.sky_image_scale must be finite and ≥ 0, got " + number(s.sky_image_scale));
    const size_t values = size_t(s.sky_image_width) * s.sky_image_height * 3;
    for (size_t i = 0; i < values; ++i)  // `if`, not require(): no message built per value
      if (!(std::isfinite(s.sky_image[i]) && s.sky_image[i] >= 0))
        fail(ARCUS_ERROR_INVALID_ARGUMENT,
             "sky.sky_image pixel (" + std::to_string(i / 3 % s.sky_image_width) + ", " +
                 std::to_string(i / 3 / s.sky_image_width) + ") channel " + std::to_string(i % 3) + " is " +
                 number(s.sky_image[i]) + ": a sky's radiance must be finite and ≥ 0 (clip the image first)");
  }
  for (int a = 0; a < 3; ++a)
    require(std::isfinite(s.rain_min[a]) && std::isfinite(s.rain_max[a]) && s.rain_min[a] < s.rain_max[a],
            "sky.rain_min must lie below rain_max on every axis (axis " + std::to_string(a) + ": " +
                number(s.rain_min[a]) + " to " + number(s.rain_max[a]) + ")");
  require(s.march_steps >= 1 && s.march_steps <= 100000,
          "sky.march_steps must be 1-100000, got " + std::to_string(s.march_steps));
  require(std::isfinite(s.exposure) && s.exposure >= 0, "sky.exposure must be finite and ≥ 0 (0: automatic), got " +
                                                            number(s.exposure));
}

std::vector<double> disc_average(const arcus_rainbow_table& t, double diameter_deg, uint32_t samples) {
  const size_t size = size_t(t.wavelength_count) * t.phi_count * t.theta_count;
  if (samples <= 1 || diameter_deg == 0) return std::vector<double>(t.scattering, t.scattering + size);
  // The sunflower: n-th point at radius R·√((n + ½)/N), turned by the golden angle.
  const double radius = diameter_deg / 2 * kDeg;
  std::vector<double> cos_d(samples), sin_d(samples), cos_psi(samples), sin_psi(samples);
  for (uint32_t n = 0; n < samples; ++n) {
    const double delta = radius * std::sqrt((n + 0.5) / samples), psi = n * kGoldenAngle;
    cos_d[n] = std::cos(delta);
    sin_d[n] = std::sin(delta);
    cos_psi[n] = std::cos(psi);
    sin_psi[n] = std::sin(psi);
  }
  const double step = (t.theta_last_deg - t.theta_first_deg) / (t.theta_count - 1);
  std::vector<double> out(size);
  for (uint32_t l = 0; l < t.wavelength_count; ++l)
    for (uint32_t j = 0; j < t.phi_count; ++j)
      for (uint32_t i = 0; i < t.theta_count; ++i) {
        const double theta = (t.theta_first_deg + i * step) * kDeg, phi = 360.0 * j / t.phi_count;
        const double ct = std::cos(theta), st = std::sin(theta);
        double sum = 0;
        for (uint32_t n = 0; n < samples; ++n) {
          const double c = std::clamp(ct * cos_d[n] + st * sin_d[n] * cos_psi[n], -1.0, 1.0);
          const double dphi = st > 1e-9 ? sin_d[n] * sin_psi[n] / st / kDeg : 0;
          sum += beta_at(t, l, phi + dphi, std::acos(c) / kDeg);
        }
        out[(size_t(l) * t.phi_count + j) * t.theta_count + i] = sum / samples;
      }
  return out;
}

arcus_features sky_features(const arcus_rainbow_table& table) {
  return table.phi_count > 1 ? ARCUS_FEATURE_RAINBOW_AZIMUTH : 0;
}

std::unique_ptr<SkyJob> render_sky(arcus_context_t* ctx, const arcus_rainbow_table& t, const arcus_rainbow_sky& s,
                                   bool* cancelled) {
  check_sky(t, s);
  const auto t_start = std::chrono::steady_clock::now();
  auto job = std::make_unique<SkyJob>(ctx);
  job->width = s.width;
  job->height = s.height;
  job->features = sky_features(t);
  const size_t pixels = size_t(s.width) * s.height, L = t.wavelength_count;
  job->count = pixels;

  // ---- the camera, the sun and its light frame (the table's: light along −sun, +y the
  // world's up across the light, +x = y × z)
  rainbow_sky_desc d{};
  const Vec3 f = normalized(vec3(s.camera_forward));
  const Vec3 right = normalized(cross(vec3(s.camera_up), f));
  const Vec3 up = cross(f, right);
  const double e = s.sun_elevation_deg * kDeg, a = s.sun_azimuth_deg * kDeg;
  const Vec3 sun{std::cos(e) * std::sin(a), std::sin(e), std::cos(e) * std::cos(a)};
  const Vec3 light{-sun[0], -sun[1], -sun[2]};
  const Vec3 world_up{0, 1, 0};
  const double uk = dot(world_up, light);
  // A sun at the zenith leaves "up across the light" undefined: any horizontal will do.
  const Vec3 y_light = std::fabs(uk) > 1 - 1e-12 ? Vec3{0, 0, 1}
                                                 : normalized({-uk * light[0], 1 - uk * light[1], -uk * light[2]});
  const Vec3 x_light = cross(y_light, light);
  for (int c = 0; c < 3; ++c) {
    d.camera[c] = s.camera_position[c];
    d.forward[c] = f[c];
    d.right[c] = right[c];
    d.up[c] = up[c];
    d.sun[c] = sun[c];
    d.x_light[c] = x_light[c];
    d.y_light[c] = y_light[c];
    d.box_min[c] = s.rain_min[c];
    d.box_max[c] = s.rain_max[c];
  }
  d.half_width = std::tan(s.fov_deg / 2 * kDeg);
  d.half_height = d.half_width * s.height / s.width;
  d.theta_first = t.theta_first_deg;
  d.theta_step = (t.theta_last_deg - t.theta_first_deg) / (t.theta_count - 1);
  d.width = static_cast<int32_t>(s.width);
  d.height = static_cast<int32_t>(s.height);
  d.steps = static_cast<int32_t>(s.march_steps);
  d.wavelengths = static_cast<int32_t>(L);
  d.thetas = static_cast<int32_t>(t.theta_count);
  d.phis = static_cast<int32_t>(t.phi_count);

  // On the host: per pixel the XYZ, RGB, θ and luminance images and the sky image
  // behind it (44 bytes), and the disc-averaged table.
  limits::require_host_memory(44.0 * pixels + 8.0 * L * t.phi_count * t.theta_count,
                              "a " + std::to_string(s.width) + " x " + std::to_string(s.height) + " sky");
  // ---- the inputs: β over the sun's disc, spectra, colour weights
  const std::vector<double> beta = disc_average(t, s.sun_diameter_deg, s.sun_samples);
  const std::vector<double> zeros(L, 0.0);
  std::vector<double> weights(3 * L);
  const auto bands = spectral::band_weights(std::vector<double>(t.wavelengths_nm, t.wavelengths_nm + L));
  for (size_t l = 0; l < L; ++l)
    for (int c = 0; c < 3; ++c) weights[3 * l + c] = bands[l][c];
  const Layout layout{1, 1};  // scalar: a pixel per work-item (sky.cl)
  const BuiltProgram built = build_job_program(ctx, *job, kSky, layout);
  Launch<SkyArg> launch(ctx, built.program);
  launch.upload(SkyArg::beta, beta, "the disc-averaged table");
  launch.upload(SkyArg::extinction, t.extinction, L, "the extinction");
  launch.upload(SkyArg::sun, s.sun_irradiance, L, "the sun's irradiance");
  launch.upload(SkyArg::sky, s.sky_radiance ? s.sky_radiance : zeros.data(), L, "the sky's radiance");
  launch.upload(SkyArg::ground, s.ground_radiance ? s.ground_radiance : zeros.data(), L, "the ground's radiance");
  launch.upload(SkyArg::weights, weights, "the colour weights");
  // The sky image (if any): its colour behind each pixel and the spectra that colour mixes.
  d.sky_image = s.sky_image != nullptr;
  std::vector<float> sky_rgb(3, 0.0f);
  std::vector<double> sky_basis(3, 0.0);
  if (d.sky_image) {
    const auto basis = spectral::srgb_basis_spectra(std::vector<double>(t.wavelengths_nm, t.wavelengths_nm + L));
    sky_basis.resize(3 * L);
    for (size_t l = 0; l < L; ++l)
      for (int c = 0; c < 3; ++c) sky_basis[3 * l + c] = basis[l][c];
    sky_rgb = sky_behind_pixels(s, d);
  }
  launch.upload(SkyArg::sky_rgb, sky_rgb, "the sky image behind the pixels");
  launch.upload(SkyArg::sky_basis, sky_basis, "the sky image's spectra");
  DeviceBuffer xyz_dev(ctx, pixels * 3 * sizeof(float), "the XYZ image");
  DeviceBuffer theta_dev(ctx, pixels * sizeof(float), "the scattering angles");
  launch.bind(SkyArg::xyz, &xyz_dev);
  launch.bind(SkyArg::theta_out, &theta_dev);
  // A slice: pixels [first, end), one a work-item.
  SliceRange slices{pixels, 4096};
  slices.progress = s.progress;
  slices.progress_user = s.progress_user;
  *cancelled = launch.run_slices(slices, [&](uint64_t first, uint64_t end) {
    d.first = static_cast<int32_t>(first);
    d.count = static_cast<int32_t>(end - first);
    launch.bind_value(SkyArg::s, d);
    return size_t(d.count);
  }, &job->stats);

  job->xyz.resize(pixels * 3);
  job->theta.resize(pixels);
  xyz_dev.read(ctx, 0, job->xyz.size() * sizeof(float), job->xyz.data());
  theta_dev.read(ctx, 0, job->theta.size() * sizeof(float), job->theta.data());
  image::require_finite_pixels(job->xyz, s.width, "XYZ", "arcus_rainbow_render");
  job->rgb.resize(pixels * 3);
  std::vector<float> luminance(pixels);
  for (size_t p = 0; p < pixels; ++p) {
    const auto rgb = spectral::xyz_to_linear_srgb({job->xyz[3 * p], job->xyz[3 * p + 1], job->xyz[3 * p + 2]});
    for (int c = 0; c < 3; ++c) job->rgb[3 * p + c] = static_cast<float>(rgb[c]);
    luminance[p] = job->xyz[3 * p + 1];
  }
  // Automatic exposure: the 99.5th percentile of Y to 0.9, so a bright bow is not clipped
  // by a few pixels and a dark scene is not blown up by noise-free black.
  job->exposure = s.exposure;
  if (job->exposure == 0) {
    auto nth = luminance.begin() + static_cast<std::ptrdiff_t>(0.995 * (pixels - 1));
    std::nth_element(luminance.begin(), nth, luminance.end());
    job->exposure = *nth > 0 ? 0.9 / *nth : 1.0;
  }
  job->stats.total_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
  return job;
}

}  // namespace arcus::rainbow
