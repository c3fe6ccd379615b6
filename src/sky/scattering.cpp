#include "sky/scattering.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "sky/paths.h"
#include "sky/rayleigh.h"
#include "sky/sun.h"
#include "sky/us1976.h"
#include "spectral/cie.h"
#include "spectral/srgb.h"

namespace arcus::sky {
namespace {

constexpr double kGridStep = 50.0;  // m: ln N is linear between points to ~1e-6
constexpr int kViewSteps = 128, kSunSteps = 64;
constexpr double kTopRadius = kEarthRadius + kAtmosphereTop;

double dot(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// Distance along d from p (inside the top sphere) to the top; and to the ground, or
// −1 when the ray misses it (a ray that only grazes it, b = 0, misses).
double distance_to_top(const double p[3], const double d[3]) {
  const double b = dot(p, d), c = dot(p, p) - kTopRadius * kTopRadius;
  return -b + std::sqrt(std::max(b * b - c, 0.0));
}
double distance_to_ground(const double p[3], const double d[3]) {
  const double b = dot(p, d), disc = b * b - (dot(p, p) - kEarthRadius * kEarthRadius);
  if (b >= 0 || disc < 0) return -1;
  return std::max(-b - std::sqrt(disc), 0.0);
}

}  // namespace

double henyey_greenstein(double cos_theta, double g) {
  const double d = 1 + g * g - 2 * g * cos_theta;
  return (1 - g * g) / (4 * M_PI * d * std::sqrt(d));
}

SingleScatteringSky::SingleScatteringSky(const Atmosphere& atmosphere, double sun_zenith) : atmosphere_(atmosphere) {
  sun_[0] = std::sin(sun_zenith);
  sun_[1] = 0;
  sun_[2] = std::cos(sun_zenith);
  const int n = int(kAtmosphereTop / kGridStep) + 2;
  log_air_.resize(n);
  for (int i = 0; i < n; ++i) {
    const double H = geopotential_height(i * kGridStep);
    log_air_[i] = std::log(number_density(standard_pressure(H, 101325, 288.15), standard_temperature(H, 288.15)));
  }
}

SingleScatteringSky::Density SingleScatteringSky::density(double h) const {
  const double x = std::clamp(h, 0.0, kAtmosphereTop) / kGridStep;
  const int i = std::min(int(x), int(log_air_.size()) - 2);
  const double t = x - i;
  return {std::exp((1 - t) * log_air_[i] + t * log_air_[i + 1]), ozone_profile(h),
          std::exp(-(h - atmosphere_.site_height_m) / atmosphere_.aerosol_scale_height_m)};
}

// Midpoint rule in u with the distance from the dense end q = length·u² (dq = 2·length·u
// du): exponential profiles are sampled where they hold most of their column.
SingleScatteringSky::Column SingleScatteringSky::segment(const double start[3], const double dir[3], double length,
                                                         bool dense_at_end, int steps) const {
  Column c;
  for (int i = 0; i < steps; ++i) {
    const double u = (i + 0.5) / steps, q = length * u * u, s = dense_at_end ? length - q : q;
    const double p[3] = {start[0] + s * dir[0], start[1] + s * dir[1], start[2] + s * dir[2]};
    const Density d = density(std::sqrt(dot(p, p)) - kEarthRadius);
    const double ds = 2 * length * u / steps;
    c.air += d.air * ds;
    c.ozone += d.ozone * ds;
    c.aerosol += d.aerosol * ds;
  }
  return c;
}

bool SingleScatteringSky::column_to_top(double r, double mu, Column* out) const {
  const double p[3] = {0, 0, r}, d[3] = {std::sqrt(std::max(1 - mu * mu, 0.0)), 0, mu};
  if (distance_to_ground(p, d) >= 0) return false;
  const double length = distance_to_top(p, d);
  if (mu >= 0) {
    *out = segment(p, d, length, false, kSunSteps);
    return true;
  }
  // Down to the tangent point, where the air is densest, and up from it.
  const double to_tangent = -r * mu;
  const double tangent[3] = {p[0] + to_tangent * d[0], p[1] + to_tangent * d[1], p[2] + to_tangent * d[2]};
  const Column a = segment(p, d, to_tangent, true, kSunSteps / 2), b = segment(tangent, d, length - to_tangent, false, kSunSteps / 2);
  *out = {a.air + b.air, a.ozone + b.ozone, a.aerosol + b.aerosol};
  return true;
}

void SingleScatteringSky::radiance(double view_zenith, double view_azimuth, const std::vector<double>& wavelengths_nm,
                                   double* radiance) const {
  const Atmosphere& a = atmosphere_;
  const size_t count = wavelengths_nm.size();
  std::fill(radiance, radiance + count, 0.0);
  const double site[3] = {0, 0, kEarthRadius + a.site_height_m};
  const double v[3] = {std::sin(view_zenith) * std::cos(view_azimuth), std::sin(view_zenith) * std::sin(view_azimuth),
                       std::cos(view_zenith)};
  const double ground = distance_to_ground(site, v);
  const double length = ground >= 0 ? ground : distance_to_top(site, v);
  if (length <= 0) return;
  const double cos_theta = dot(v, sun_);  // the scattering angle's: light along −sun, out along −v
  // Per wavelength: cross-sections, the aerosol's extinction per unit relative density,
  // and the phase functions at this angle.
  std::vector<double> rayleigh(count), ozone(count), aerosol(count), phase_r(count);
  for (size_t k = 0; k < count; ++k) {
    const double nm = wavelengths_nm[k];
    rayleigh[k] = rayleigh_cross_section(nm, a.co2_ppm);
    ozone[k] = ozone_cross_section(nm) * a.ozone_du;
    aerosol[k] = a.aerosol_depth_500 * std::pow(nm / 500.0, -a.angstrom_exponent) / a.aerosol_scale_height_m;
    phase_r[k] = rayleigh_phase(cos_theta, nm, a.co2_ppm);
  }
  const double phase_a = henyey_greenstein(cos_theta, a.aerosol_asymmetry);
  Column view;  // from the site to the sample's start
  for (int i = 0; i < kViewSteps; ++i) {
    const double u = (i + 0.5) / kViewSteps, s = length * u * u, ds = 2 * length * u / kViewSteps;
    const double x[3] = {site[0] + s * v[0], site[1] + s * v[1], site[2] + s * v[2]};
    const double r = std::sqrt(dot(x, x));
    const Density d = density(r - kEarthRadius);
    const Column to_sample{view.air + 0.5 * d.air * ds, view.ozone + 0.5 * d.ozone * ds,
                           view.aerosol + 0.5 * d.aerosol * ds};
    view.air += d.air * ds;
    view.ozone += d.ozone * ds;
    view.aerosol += d.aerosol * ds;
    Column sun;
    if (!column_to_top(r, dot(x, sun_) / r, &sun)) continue;  // in Earth's shadow
    for (size_t k = 0; k < count; ++k) {
      const double tau = rayleigh[k] * (to_sample.air + sun.air) + ozone[k] * (to_sample.ozone + sun.ozone) +
                         aerosol[k] * (to_sample.aerosol + sun.aerosol);
      const double scattering = rayleigh[k] * d.air * phase_r[k] + a.aerosol_albedo * aerosol[k] * d.aerosol * phase_a;
      radiance[k] += std::exp(-tau) * scattering * ds;
    }
  }
}

std::vector<float> sky_panorama(const Atmosphere& atmosphere, double sun_zenith, double sun_azimuth, int width,
                                int height) {
  // 47 bands of 10 nm over 360–830 nm, each the sun's band mean above the air.
  std::vector<double> nm, sun;
  for (double w = kDaylightMinNm + 5; w < kDaylightMaxNm; w += 10) {
    nm.push_back(w);
    sun.push_back(solar_irradiance_band(w - 5, w + 5));
  }
  const SingleScatteringSky sky(atmosphere, sun_zenith);
  constexpr double kZenithStep = 1.5 * M_PI / 180, kAzimuthStep = 3.0 * M_PI / 180;
  const int rows = int(std::lround(0.5 * M_PI / kZenithStep)) + 1, columns = int(std::lround(M_PI / kAzimuthStep)) + 1;
  std::vector<std::array<double, 3>> grid(size_t(rows) * columns);
  std::vector<double> L(nm.size());
  for (int i = 0; i < rows; ++i) {
    for (int j = 0; j < columns; ++j) {
      sky.radiance(std::min(i * kZenithStep, 0.5 * M_PI), j * kAzimuthStep, nm, L.data());
      for (size_t k = 0; k < nm.size(); ++k) L[k] *= sun[k];
      double xyz[3];
      spectral::spectrum_to_xyz(nm.data(), L.data(), nm.size(), xyz);
      grid[size_t(i) * columns + j] = {xyz[0], xyz[1], xyz[2]};
    }
  }
  std::vector<float> rgb(size_t(width) * height * 3, 0.0f);
  for (int py = 0; py < height; ++py) {
    const double elevation = 0.5 * M_PI - (py + 0.5) / height * M_PI;
    if (elevation < 0) continue;
    const double zi = std::min((0.5 * M_PI - elevation) / kZenithStep, rows - 1.0);
    const int i = std::min(int(zi), rows - 2);
    for (int px = 0; px < width; ++px) {
      double relative = std::fabs(std::remainder((px + 0.5) / width * 2 * M_PI - sun_azimuth, 2 * M_PI));
      const double aj = std::min(relative / kAzimuthStep, columns - 1.0);
      const int j = std::min(int(aj), columns - 2);
      const double fz = zi - i, fa = aj - j;
      std::array<double, 3> xyz;
      for (int c = 0; c < 3; ++c)
        xyz[c] = (1 - fz) * ((1 - fa) * grid[size_t(i) * columns + j][c] + fa * grid[size_t(i) * columns + j + 1][c]) +
                 fz * ((1 - fa) * grid[size_t(i + 1) * columns + j][c] + fa * grid[size_t(i + 1) * columns + j + 1][c]);
      const std::array<double, 3> linear = spectral::xyz_to_linear_srgb(xyz);
      for (int c = 0; c < 3; ++c) rgb[(size_t(py) * width + px) * 3 + c] = float(std::max(linear[c], 0.0));
    }
  }
  return rgb;
}

void ground_irradiance(const Atmosphere& atmosphere, double sun_zenith, const std::vector<double>& wavelengths_nm,
                       double* direct, double* diffuse) {
  const size_t count = wavelengths_nm.size();
  std::vector<double> sun(count);
  for (size_t k = 0; k < count; ++k) sun[k] = solar_irradiance(wavelengths_nm[k]);
  if (sun_zenith < 0.5 * M_PI) {
    const SlantPath path(atmosphere, sun_zenith);
    for (size_t k = 0; k < count; ++k)
      direct[k] = sun[k] * std::exp(-path.depths(wavelengths_nm[k]).total()) * std::cos(sun_zenith);
  } else {
    std::fill(direct, direct + count, 0.0);
  }
  // ∫∫ L cos θ sin θ dθ dφ = ∫0^1 μ dμ ∫0^2π L dφ: Gauss–Legendre in μ, and the
  // trapezoid rule in φ over [0, π] (its ends weighted half) doubled by the symmetry.
  constexpr int kNodes = 16, kAzimuths = 24;
  static const double kX[8] = {0.0950125098376374, 0.2816035507792589, 0.4580167776572274, 0.6178762444026438,
                               0.7554044083550030, 0.8656312023878318, 0.9445750230732326, 0.9894009349916499};
  static const double kW[8] = {0.1894506104550685, 0.1826034150449236, 0.1691565193950025, 0.1495959888165767,
                               0.1246289712555339, 0.0951585116824928, 0.0622535239386479, 0.0271524594117541};
  const SingleScatteringSky sky(atmosphere, sun_zenith);
  std::fill(diffuse, diffuse + count, 0.0);
  std::vector<double> L(count);
  for (int n = 0; n < kNodes; ++n) {
    const double x = n < 8 ? -kX[7 - n] : kX[n - 8], w = n < 8 ? kW[7 - n] : kW[n - 8];
    const double mu = 0.5 * (x + 1), weight_mu = 0.5 * w * mu;
    for (int j = 0; j <= kAzimuths; ++j) {
      const double phi = M_PI * j / kAzimuths, weight_phi = 2 * M_PI / kAzimuths * (j == 0 || j == kAzimuths ? 0.5 : 1);
      sky.radiance(std::acos(mu), phi, wavelengths_nm, L.data());
      for (size_t k = 0; k < count; ++k) diffuse[k] += weight_mu * weight_phi * L[k] * sun[k];
    }
  }
}

}  // namespace arcus::sky
