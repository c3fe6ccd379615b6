#include "sky/us1976.h"

#include <algorithm>
#include <cmath>

#include "common/real.h"
#include "sky/air.h"  // kernels/sky/air.h: g0·M/R*

namespace arcus::sky {

double geopotential_height(double h) { return kGeopotentialRadius * h / (kGeopotentialRadius + h); }

double geometric_height(double H) { return kGeopotentialRadius * H / (kGeopotentialRadius - H); }

double standard_temperature(double H, double t0) {
  double T = t0;
  for (int i = 0; i < kStandardLayers; ++i) {
    const double top = i + 1 < kStandardLayers ? kStandardBase[i + 1] : INFINITY;
    double span = std::min(std::max(H, kStandardBase[i]), top) - kStandardBase[i];
    if (i == 0 && H < 0) span = H;  // below sea level the first lapse rate continues
    T += kStandardLapse[i] * span;
    if (H < top) break;
  }
  return T;
}

double pressure_ratio(double dH, double T0, double lapse) {
  const double x = lapse * dH / T0;
  const double integral = std::fabs(x) < 1e-12 ? dH / T0 : std::log1p(x) / lapse;
  return std::exp(-ARCUS_ATM_G_M_OVER_R * integral);
}

double standard_pressure(double H, double p0, double t0) {
  double p = p0;
  for (int i = 0; i < kStandardLayers; ++i) {
    const double base = kStandardBase[i], top = i + 1 < kStandardLayers ? kStandardBase[i + 1] : INFINITY;
    p *= pressure_ratio(std::min(H, top) - base, standard_temperature(base, t0), kStandardLapse[i]);
    if (H <= top) break;
  }
  return p;
}

double number_density(double pressure_pa, double temperature_k) {
  return pressure_pa / (1.380649e-23 * temperature_k);  // k_B, SI 2019 (exact)
}

}  // namespace arcus::sky
