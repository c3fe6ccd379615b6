#include "sky/paths.h"

#include <cmath>

#include "sky/us1976.h"

namespace arcus::sky {

double slant_column(double site_m, double zenith) {
  // Along the ray s, the height is h(s) = sqrt(r0² + s² + 2 r0 s cos z) − R; the path
  // to the top has length L.  Simpson in u with s = L u², which crowds the steps near
  // the ground, where the air is densest and, at low sun, changes fastest along s.
  const double r0 = kEarthRadius + site_m, top = kEarthRadius + kAtmosphereTop, c = std::cos(zenith);
  const double length = -r0 * c + std::sqrt(r0 * r0 * c * c + top * top - r0 * r0);
  const int n = 4000;
  double sum = 0;
  for (int i = 0; i <= n; ++i) {
    const double u = double(i) / n, s = length * u * u;
    const double h = std::sqrt(r0 * r0 + s * s + 2 * r0 * s * c) - kEarthRadius;
    const double H = geopotential_height(h);
    const double density = number_density(standard_pressure(H, 101325, 288.15), standard_temperature(H, 288.15));
    sum += (i == 0 || i == n ? 1 : i % 2 ? 4 : 2) * density * 2 * length * u;
  }
  return sum / (3.0 * n);
}

double relative_air_mass(double site_m, double zenith) { return slant_column(site_m, zenith) / slant_column(site_m, 0); }

}  // namespace arcus::sky
