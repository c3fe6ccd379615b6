#include "sky/paths.h"

#include <algorithm>
#include <cmath>

#include "common/real.h"
#include "sky/air.h"  // kernels/sky/air.h: Ciddor's index
#include "sky/us1976.h"

namespace arcus::sky {

namespace {

struct Air {
  double density, index;  // molecules per m³, n
};

Air air_at(double h, double refractivity) {
  const double H = geopotential_height(h), p = standard_pressure(H, 101325, 288.15), T = standard_temperature(H, 288.15);
  return {number_density(p, T), 1 + refractivity * p / T};
}

// The columns along a ray whose air has (n − 1)·T/p = refractivity (0: a straight ray).
// In r from the site up: ds = dr/cos θ, sin θ = b/(n r) with b = n0 r0 sin z.  At the
// horizon cos θ → 0 at the site as √(r − r0), so r = r0 + L u² makes the integrand
// finite (dr = 2 L u du); the midpoint rule in u never evaluates u = 0 itself.
void columns(double site_m, double zenith, double refractivity, const Densities& densities, double* out) {
  const double r0 = kEarthRadius + site_m, length = kAtmosphereTop - site_m;
  const double b = air_at(site_m, refractivity).index * r0 * std::sin(zenith);
  const int n = 8000, count = densities ? densities.count : 0;
  double sums[kMaxDensities + 1] = {};
  for (int i = 0; i < n; ++i) {
    const double u = (i + 0.5) / n, r = r0 + length * u * u, h = r - kEarthRadius;
    const Air a = air_at(h, refractivity);
    const double sine = b / (a.index * r);
    const double ds = 2 * length * u / std::sqrt(std::max((1 - sine) * (1 + sine), 0.0));
    sums[0] += a.density * ds;
    double d[kMaxDensities];
    if (count) densities.at(h, d);
    for (int k = 0; k < count; ++k) sums[k + 1] += d[k] * ds;
  }
  for (int k = 0; k <= count; ++k) out[k] = sums[k] / n;
}

double column(double site_m, double zenith, double refractivity) {
  double c;
  columns(site_m, zenith, refractivity, {}, &c);
  return c;
}

}  // namespace

double slant_column(double site_m, double zenith) { return column(site_m, zenith, 0); }

double relative_air_mass(double site_m, double zenith) { return slant_column(site_m, zenith) / slant_column(site_m, 0); }

double refracted_column(double site_m, double zenith, double wavelength_nm) {
  return column(site_m, zenith, ciddor_refractivity(wavelength_nm));
}

void refracted_columns(double site_m, double zenith, double wavelength_nm, const Densities& densities,
                       double* columns_out) {
  columns(site_m, zenith, ciddor_refractivity(wavelength_nm), densities, columns_out);
}

double refracted_air_mass(double site_m, double zenith, double wavelength_nm) {
  return refracted_column(site_m, zenith, wavelength_nm) / refracted_column(site_m, 0, wavelength_nm);
}

}  // namespace arcus::sky
