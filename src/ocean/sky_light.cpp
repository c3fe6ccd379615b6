#include "ocean/sky_light.h"

#include <algorithm>
#include <cmath>

#include "core/quadrature.h"

// Fresnel at the surface: the scalar code the kernels share.
#include "common/real.h"
#include "common/fresnel.h"

namespace arcus::ocean {
namespace {

constexpr double kPi = 3.14159265358979323846;
// Depth rows and view cosines (render.cl: bilinear between).
constexpr int kSkyRows = 256, kSkyCosines = 129;

}  // namespace

SkyTables sky_tables(const WaterTables& w, const std::vector<Light>& lights, const Medium& medium,
                     const std::vector<double>& st, const std::vector<double>& M, double d_max) {
  SkyTables t;
  const size_t n = w.grid.count;
  std::vector<double> radiance(n, 0.0);  // L_s per sample [W/m²/sr/nm]
  bool any = false;
  for (const Light& L : lights)
    if (L.kind == Light::sky) {
      any = true;
      for (size_t m = 0; m < n; ++m) radiance[m] += light_spectrum(L, w.grid.nm(int(m))) / kPi;
    }
  if (!any) return t;
  const double nw = medium.n_water, mu_c = std::sqrt(std::max(0.0, 1 - 1 / (nw * nw)));
  t.rows = kSkyRows;
  t.cosines = kSkyCosines;
  t.d_step = std::max(d_max, 1e-9) / (t.rows - 1);
  // Gauss–Legendre in μ over [μ_c, 1] and a midpoint rule in the azimuth.
  constexpr int kMu = 32, kPhi = 64;
  std::vector<double> x(kMu), wq(kMu);
  gauss_legendre(kMu, mu_c, 1.0, x.data(), wq.data());
  std::vector<double> through(kMu);  // n² T(μ) times μ's quadrature weight
  for (int k = 0; k < kMu; ++k) {
    const double mu_a = std::sqrt(std::max(0.0, 1 - nw * nw * (1 - x[k] * x[k])));
    through[k] = nw * nw * (1 - arcus_fresnel_reflectance(mu_a, 1.0, nw)) * wq[k];
  }
  // P[s][c][k] = ∫ p_s dφ between the sky's downward direction at μ_k and −view.
  std::vector<double> P(size_t(kScattererCount) * t.cosines * kMu, 0.0);
  for (int c = 0; c < t.cosines; ++c) {
    const double v = -1 + 2.0 * c / (t.cosines - 1), sv = std::sqrt(std::max(0.0, 1 - v * v));
    for (int k = 0; k < kMu; ++k) {
      const double sk = std::sqrt(std::max(0.0, 1 - x[k] * x[k]));
      for (int s = 0; s < kScattererCount; ++s) {
        double sum = 0;
        for (int j = 0; j < kPhi; ++j)
          sum += phase_value(w.phase[s], x[k] * v - sk * sv * std::cos(2 * kPi * (j + 0.5) / kPhi));
        P[(size_t(s) * t.cosines + c) * kMu + k] = sum * 2 * kPi / kPhi;
      }
    }
  }
  t.data.assign(n + t.cosines + size_t(t.rows) * t.cosines * n + size_t(t.rows) * n, 0.0);
  for (size_t m = 0; m < n; ++m) t.data[m] = radiance[m];
  for (int c = 0; c < t.cosines; ++c) {  // n² T(v) looking up at cos v through the surface
    const double v = -1 + 2.0 * c / (t.cosines - 1);
    if (v <= mu_c) continue;  // beyond Snell's window: total internal reflection
    const double mu_a = std::sqrt(std::max(0.0, 1 - nw * nw * (1 - v * v)));
    t.data[n + c] = nw * nw * (1 - arcus_fresnel_reflectance(mu_a, 1.0, nw));
  }
  double* elastic = &t.data[n + t.cosines];
  double* inelastic = elastic + size_t(t.rows) * t.cosines * n;
  std::vector<double> e0(n), att(kMu);
  for (int r = 0; r < t.rows; ++r) {
    const double d = r * t.d_step;
    for (size_t m = 0; m < n; ++m) {
      for (int k = 0; k < kMu; ++k) att[k] = through[k] * radiance[m] * std::exp(-st[m] * d / x[k]);
      e0[m] = 0;
      for (int k = 0; k < kMu; ++k) e0[m] += 2 * kPi * att[k];
      for (int c = 0; c < t.cosines; ++c) {
        double sum = 0;
        for (int s = 0; s < kScattererCount; ++s) {
          const double sigma = w.event[kScatterWater + s][m];
          if (sigma <= 0) continue;
          const double* Ps = &P[(size_t(s) * t.cosines + c) * kMu];
          double acc = 0;
          for (int k = 0; k < kMu; ++k) acc += Ps[k] * att[k];
          sum += sigma * acc;
        }
        elastic[(size_t(r) * t.cosines + c) * n + m] = sum;
      }
    }
    if (M.empty()) continue;
    for (size_t m = 0; m < n; ++m) {
      double sum = 0;
      for (size_t i = 0; i < n; ++i) sum += M[m * n + i] * e0[i];
      inelastic[size_t(r) * n + m] = sum;
    }
  }
  return t;
}

}  // namespace arcus::ocean
