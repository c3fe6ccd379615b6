#include "sky/scattering.h"

#include <algorithm>
#include <cmath>

#include "sky/paths.h"
#include "sky/rayleigh.h"
#include "sky/us1976.h"

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

}  // namespace arcus::sky
