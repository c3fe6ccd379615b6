#include "sky/scattering.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "core/parallel.h"
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

// The colours' spectra: 47 bands of 10 nm over 360–830 nm, each with the sun's band mean
// above the air.
struct Bands {
  std::vector<double> nm, sun;
  Bands() {
    for (double w = kDaylightMinNm + 5; w < kDaylightMaxNm; w += 10) {
      nm.push_back(w);
      sun.push_back(solar_irradiance_band(w - 5, w + 5));
    }
  }
};

// Per wavelength: the air's cross-section, ozone's per molecule-of-column times the
// column's DU, and the aerosol's extinction per unit of its relative density.
struct Coefficients {
  std::vector<double> rayleigh, ozone, aerosol;
  double albedo;
  Coefficients(const Atmosphere& a, const std::vector<double>& nm) : albedo(a.aerosol_albedo) {
    for (const double w : nm) {
      rayleigh.push_back(rayleigh_cross_section(w, a.co2_ppm));
      ozone.push_back(ozone_cross_section(w) * a.ozone_du);
      aerosol.push_back(a.aerosol_depth_500 * std::pow(w / 500.0, -a.angstrom_exponent) / a.aerosol_scale_height_m);
    }
  }
  template <class Column>
  double depth(size_t k, const Column& c) const {
    return rayleigh[k] * c.air + ozone[k] * c.ozone + aerosol[k] * c.aerosol;
  }
  template <class Density>
  double scattering(size_t k, const Density& d) const {
    return rayleigh[k] * d.air + albedo * aerosol[k] * d.aerosol;
  }
};

// Hillaire's table: heights 86 km·t² (dense near the ground), sun cosines −0.2..1 (at
// 86 km the sun sets at μ = −0.16), 64 directions on a Fibonacci sphere, 20 steps a
// direction and 16 for each sample's sun column: ~1 s, and smooth where the sky is.
constexpr int kMsHeights = 16, kMsSunCosines = 24, kMsDirections = 64, kMsSteps = 20, kMsSunSteps = 16;
constexpr double kMsLowestCosine = -0.2;

}  // namespace

double henyey_greenstein(double cos_theta, double g) {
  const double d = 1 + g * g - 2 * g * cos_theta;
  return (1 - g * g) / (4 * M_PI * d * std::sqrt(d));
}

ClearSky::ClearSky(const Atmosphere& atmosphere, double sun_zenith, bool multiple) : atmosphere_(atmosphere) {
  sun_[0] = std::sin(sun_zenith);
  sun_[1] = 0;
  sun_[2] = std::cos(sun_zenith);
  const int n = int(kAtmosphereTop / kGridStep) + 2;
  log_air_.resize(n);
  for (int i = 0; i < n; ++i) {
    const double H = geopotential_height(i * kGridStep);
    log_air_[i] = std::log(number_density(standard_pressure(H, 101325, 288.15), standard_temperature(H, 288.15)));
  }
  if (multiple) tabulate_multiple_scattering();
}

ClearSky::Density ClearSky::density(double h) const {
  const double x = std::clamp(h, 0.0, kAtmosphereTop) / kGridStep;
  const int i = std::min(int(x), int(log_air_.size()) - 2);
  const double t = x - i;
  return {std::exp((1 - t) * log_air_[i] + t * log_air_[i + 1]), ozone_profile(h),
          std::exp(-(h - atmosphere_.site_height_m) / atmosphere_.aerosol_scale_height_m)};
}

// Midpoint rule in u with the distance from the dense end q = length·u² (dq = 2·length·u
// du): exponential profiles are sampled where they hold most of their column.
ClearSky::Column ClearSky::segment(const double start[3], const double dir[3], double length,
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

template <class Visit>
void ClearSky::march(const double start[3], const double dir[3], double length, int steps, Visit&& visit) const {
  Column path;
  for (int i = 0; i < steps; ++i) {
    const double u = (i + 0.5) / steps, s = length * u * u, ds = 2 * length * u / steps;
    const double x[3] = {start[0] + s * dir[0], start[1] + s * dir[1], start[2] + s * dir[2]};
    const double r = std::sqrt(dot(x, x));
    const Density d = density(r - kEarthRadius);
    const Column to_point{path.air + 0.5 * d.air * ds, path.ozone + 0.5 * d.ozone * ds,
                          path.aerosol + 0.5 * d.aerosol * ds};
    path.air += d.air * ds;
    path.ozone += d.ozone * ds;
    path.aerosol += d.aerosol * ds;
    visit(x, r, d, to_point, ds);
  }
}

bool ClearSky::column_to_top(double r, double mu, Column* out, int steps) const {
  const double p[3] = {0, 0, r}, d[3] = {std::sqrt(std::max(1 - mu * mu, 0.0)), 0, mu};
  if (distance_to_ground(p, d) >= 0) return false;
  const double length = distance_to_top(p, d);
  if (mu >= 0) {
    *out = segment(p, d, length, false, steps);
    return true;
  }
  // Down to the tangent point, where the air is densest, and up from it.
  const double to_tangent = -r * mu;
  const double tangent[3] = {p[0] + to_tangent * d[0], p[1] + to_tangent * d[1], p[2] + to_tangent * d[2]};
  const Column a = segment(p, d, to_tangent, true, steps / 2), b = segment(tangent, d, length - to_tangent, false, steps / 2);
  *out = {a.air + b.air, a.ozone + b.ozone, a.aerosol + b.aerosol};
  return true;
}

void ClearSky::tabulate_multiple_scattering() {
  const Bands bands;
  const size_t nb = bands.nm.size();
  const Coefficients co(atmosphere_, bands.nm);
  // Directions on a Fibonacci sphere: equal areas, 4π/N each.
  std::vector<std::array<double, 3>> dirs(kMsDirections);
  for (int n = 0; n < kMsDirections; ++n) {
    const double z = 1 - (2 * n + 1.0) / kMsDirections, rho = std::sqrt(1 - z * z), phi = n * M_PI * (3 - std::sqrt(5.0));
    dirs[n] = {rho * std::cos(phi), rho * std::sin(phi), z};
  }
  ms_.assign(nb * kMsHeights * kMsSunCosines, 0.0);
  parallel_for(size_t(kMsHeights), [&](size_t i) {
    // the air's and the ground's parts of L2 and of f, apart: see the series below
    std::vector<double> second(nb), transfer(nb), second_ground(nb), transfer_ground(nb);
    const double t = double(i) / (kMsHeights - 1), h = std::min(kAtmosphereTop * t * t, kAtmosphereTop - 1.0);
    const double x0[3] = {0, 0, kEarthRadius + h};
    for (int j = 0; j < kMsSunCosines; ++j) {
      const double mu_s = kMsLowestCosine + (1 - kMsLowestCosine) * j / (kMsSunCosines - 1);
      const double sun[3] = {std::sqrt(1 - mu_s * mu_s), 0, mu_s};
      for (auto* v : {&second, &transfer, &second_ground, &transfer_ground}) std::fill(v->begin(), v->end(), 0.0);
      for (const auto& w : dirs) {
        const double ground = distance_to_ground(x0, w.data());
        march(x0, w.data(), ground >= 0 ? ground : distance_to_top(x0, w.data()), kMsSteps,
              [&](const double* y, double r, const Density& d, const Column& to_point, double ds) {
                Column to_sun;
                const bool lit = column_to_top(r, dot(y, sun) / r, &to_sun, kMsSunSteps);
                for (size_t k = 0; k < nb; ++k) {
                  const double seen = std::exp(-co.depth(k, to_point)) * co.scattering(k, d) * ds;
                  transfer[k] += seen;
                  if (lit) second[k] += seen * std::exp(-co.depth(k, to_sun));
                }
              });
        // The ground where the direction meets it, a Lambertian reflector (Hillaire 2020,
        // §5.1).  In L2: its radiance ρ/π·T_sun·μ_g lit by the sun through the air, seen
        // through the air between (T), entered as 4π times it, as the air's terms above
        // are before the isotropic phase's 1/4π.  In the transfer, whose terms are the
        // radiance a direction brings under a uniform field of radiance 1: the ground
        // sends back ρ, seen as ρ·T (Hillaire's f has the air only: over bright ground
        // that leaves out the light the ground and the air pass back and forth).
        if (ground >= 0 && atmosphere_.ground_albedo > 0) {
          const double rho = atmosphere_.ground_albedo;
          const double g[3] = {x0[0] + ground * w[0], x0[1] + ground * w[1], x0[2] + ground * w[2]};
          const double r_g = std::sqrt(dot(g, g)), mu_g = dot(g, sun) / r_g;
          const Column between = segment(x0, w.data(), ground, true, kMsSteps);
          Column to_sun;
          const bool lit = mu_g > 0 && column_to_top(r_g, mu_g, &to_sun, kMsSunSteps);
          for (size_t k = 0; k < nb; ++k) {
            const double seen = std::exp(-co.depth(k, between));
            transfer_ground[k] += rho * seen;
            if (lit) second_ground[k] += 4 * rho * mu_g * seen * std::exp(-co.depth(k, to_sun));
          }
        }
      }
      // Isotropic phase at both ends (1/4π each) over 4π/N per direction: L2 = Σ/(4π N),
      // f = Σ/N; Hillaire's Ψ = L2/(1 − f) sums the orders L2·fⁿ.  With a ground the
      // orders are sequences of air (a) and ground (g) steps in which no two ground
      // steps follow one another (light the ground sends up meets the flat ground again
      // only after the air scatters it) and none follows L2's own ground light: summed,
      // A = 1/(1 − a(1 + g)) over the sequences that do not start with g, (1 + g)·A over
      // all.  Counting g as one more scattering (1/(1 − a − g)) put ground after ground:
      // over snow (ρ = 0.8) the diffuse light at the ground came out up to 32 % above
      // a discrete-ordinates solution (tests/python/test_sky_disort.py).
      for (size_t k = 0; k < nb; ++k) {
        const double a = transfer[k] / kMsDirections, g = transfer_ground[k] / kMsDirections;
        const double air_first = 1 / (1 - a * (1 + g));
        const double l2_air = second[k] / (4 * M_PI * kMsDirections), l2_ground = second_ground[k] / (4 * M_PI * kMsDirections);
        ms_[(k * kMsHeights + i) * kMsSunCosines + j] = l2_air * (1 + g) * air_first + l2_ground * air_first;
      }
    }
  });
}

double ClearSky::multiple_scattering(double wavelength_nm, double height_m, double mu_sun) const {
  const double b = std::clamp((wavelength_nm - (kDaylightMinNm + 5)) / 10, 0.0, double(ms_.size() / (kMsHeights * kMsSunCosines) - 1));
  const double t = std::sqrt(std::clamp(height_m / kAtmosphereTop, 0.0, 1.0)) * (kMsHeights - 1);
  const double c = std::clamp((mu_sun - kMsLowestCosine) / (1 - kMsLowestCosine), 0.0, 1.0) * (kMsSunCosines - 1);
  const int bi = std::min(int(b), int(ms_.size() / (kMsHeights * kMsSunCosines)) - 2), ti = std::min(int(t), kMsHeights - 2),
            ci = std::min(int(c), kMsSunCosines - 2);
  const double fb = b - bi, ft = t - ti, fc = c - ci;
  auto at = [&](int band, int i, int j) { return ms_[(size_t(band) * kMsHeights + i) * kMsSunCosines + j]; };
  auto plane = [&](int band) {
    return (1 - ft) * ((1 - fc) * at(band, ti, ci) + fc * at(band, ti, ci + 1)) +
           ft * ((1 - fc) * at(band, ti + 1, ci) + fc * at(band, ti + 1, ci + 1));
  };
  return (1 - fb) * plane(bi) + fb * plane(bi + 1);
}

void ClearSky::radiance(double view_zenith, double view_azimuth, const std::vector<double>& wavelengths_nm,
                        double* radiance) const {
  const size_t count = wavelengths_nm.size();
  std::fill(radiance, radiance + count, 0.0);
  const double site[3] = {0, 0, kEarthRadius + atmosphere_.site_height_m};
  const double v[3] = {std::sin(view_zenith) * std::cos(view_azimuth), std::sin(view_zenith) * std::sin(view_azimuth),
                       std::cos(view_zenith)};
  const double ground = distance_to_ground(site, v);
  const double length = ground >= 0 ? ground : distance_to_top(site, v);
  if (length <= 0) return;
  const double cos_theta = dot(v, sun_);  // the scattering angle's: light along −sun, out along −v
  const Coefficients co(atmosphere_, wavelengths_nm);
  std::vector<double> phase_r(count);
  for (size_t k = 0; k < count; ++k) phase_r[k] = rayleigh_phase(cos_theta, wavelengths_nm[k], atmosphere_.co2_ppm);
  const double phase_a = henyey_greenstein(cos_theta, atmosphere_.aerosol_asymmetry);
  march(site, v, length, kViewSteps, [&](const double* x, double r, const Density& d, const Column& to_point, double ds) {
    const double mu_sun = dot(x, sun_) / r;
    // Light scattered more than once reaches the shadowed air too.
    if (!ms_.empty())
      for (size_t k = 0; k < count; ++k)
        radiance[k] += std::exp(-co.depth(k, to_point)) * co.scattering(k, d) *
                       multiple_scattering(wavelengths_nm[k], r - kEarthRadius, mu_sun) * ds;
    Column sun;
    if (!column_to_top(r, mu_sun, &sun, kSunSteps)) return;  // in Earth's shadow
    for (size_t k = 0; k < count; ++k) {
      const double single = co.rayleigh[k] * d.air * phase_r[k] + co.albedo * co.aerosol[k] * d.aerosol * phase_a;
      radiance[k] += std::exp(-co.depth(k, to_point) - co.depth(k, sun)) * single * ds;
    }
  });
}

namespace {

std::array<double, 3> xyz_of(const Bands& b, const std::vector<double>& values) {
  double xyz[3];
  spectral::spectrum_to_xyz(b.nm.data(), values.data(), b.nm.size(), xyz);
  return {xyz[0], xyz[1], xyz[2]};
}

}  // namespace

std::array<double, 3> sun_linear_srgb(const Atmosphere& atmosphere, double sun_zenith) {
  const Bands b;
  const SlantPath path(atmosphere, sun_zenith);
  std::vector<double> e(b.nm.size());
  for (size_t k = 0; k < e.size(); ++k) e[k] = b.sun[k] * std::exp(-path.depths(b.nm[k]).total());
  return spectral::xyz_to_linear_srgb(xyz_of(b, e));
}

std::vector<float> sky_panorama(const Atmosphere& atmosphere, double sun_zenith, double sun_azimuth, int width,
                                int height) {
  const Bands bands;
  const std::vector<double>& nm = bands.nm;
  const std::vector<double>& sun = bands.sun;
  const ClearSky sky(atmosphere, sun_zenith);
  // Rows at elevations 90°·t² (t uniform): the sky changes fastest toward the horizon,
  // where the rows are 0.025° apart; columns every 3° of azimuth from the sun's.
  constexpr int rows = 61, columns = 61;
  constexpr double kAzimuthStep = M_PI / (columns - 1);
  auto elevation_of = [](double t) { return 0.5 * M_PI * t * t; };
  std::vector<std::array<double, 3>> grid(size_t(rows) * columns);
  parallel_for(size_t(rows), [&](size_t i) {
    std::vector<double> L(nm.size());
    for (int j = 0; j < columns; ++j) {
      sky.radiance(0.5 * M_PI - elevation_of(double(i) / (rows - 1)), j * kAzimuthStep, nm, L.data());
      for (size_t k = 0; k < nm.size(); ++k) L[k] *= sun[k];
      grid[i * columns + j] = xyz_of(bands, L);
    }
  });
  std::vector<float> rgb(size_t(width) * height * 3, 0.0f);
  for (int py = 0; py < height; ++py) {
    const double elevation = std::max(0.5 * M_PI - (py + 0.5) / height * M_PI, 0.0);  // below: the horizon's
    const double ti = std::sqrt(elevation / (0.5 * M_PI)) * (rows - 1);
    const int i = std::min(int(ti), rows - 2);
    for (int px = 0; px < width; ++px) {
      double relative = std::fabs(std::remainder((px + 0.5) / width * 2 * M_PI - sun_azimuth, 2 * M_PI));
      const double aj = std::min(relative / kAzimuthStep, columns - 1.0);
      const int j = std::min(int(aj), columns - 2);
      const double fz = ti - i, fa = aj - j;
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
                       double* direct, double* diffuse, bool multiple) {
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
  const ClearSky sky(atmosphere, sun_zenith, multiple);
  std::vector<std::vector<double>> per_node(kNodes, std::vector<double>(count, 0.0));
  parallel_for(size_t(kNodes), [&](size_t n) {
    const double x = n < 8 ? -kX[7 - n] : kX[n - 8], w = n < 8 ? kW[7 - n] : kW[n - 8];
    const double mu = 0.5 * (x + 1), weight_mu = 0.5 * w * mu;
    std::vector<double> L(count);
    for (int j = 0; j <= kAzimuths; ++j) {
      const double phi = M_PI * j / kAzimuths, weight_phi = 2 * M_PI / kAzimuths * (j == 0 || j == kAzimuths ? 0.5 : 1);
      sky.radiance(std::acos(mu), phi, wavelengths_nm, L.data());
      for (size_t k = 0; k < count; ++k) per_node[n][k] += weight_mu * weight_phi * L[k] * sun[k];
    }
  });
  std::fill(diffuse, diffuse + count, 0.0);
  for (const auto& node : per_node)  // summed in a fixed order: the same bits on any machine
    for (size_t k = 0; k < count; ++k) diffuse[k] += node[k];
}

}  // namespace arcus::sky
