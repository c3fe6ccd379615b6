#include "translucency/basis.h"

#include <algorithm>
#include <cmath>

#include "arcus/arcus_translucency.h"
#include "translucency/translucency_desc.h"

namespace arcus::translucency {
namespace {

// B_h(x), before scaling.
double value(int32_t family, uint32_t h, uint32_t m, double x) {
  const double t = 2 * x - 1;
  switch (family) {
    case ARCUS_BASIS_PIECEWISE_CONSTANT:
      return uint32_t(x * m) == h ? 1 : 0;
    case ARCUS_BASIS_HAAR: {
      if (h == 0) return 1;
      uint32_t level = 0;
      while ((2u << level) <= h) ++level;
      const double width = std::ldexp(1.0, -int(level)), from = (h - (1u << level)) * width;
      if (x < from || x >= from + width) return 0;
      return x < from + width / 2 ? 1 : -1;
    }
    case ARCUS_BASIS_GAUSSIAN: {
      const double s = m > 1 ? std::pow(double(m), double(h) / (m - 1) - 1) : 1;
      return std::exp(-x * x / (2 * s * s));
    }
    case ARCUS_BASIS_HERMITE: {  // H_0 = 1, H_1 = 2t, H_{n+1} = 2t H_n − 2n H_{n−1}
      double previous = 1, current = 2 * t;
      if (h == 0) return previous;
      for (uint32_t n = 1; n < h; ++n) {
        const double next = 2 * t * current - 2 * n * previous;
        previous = current;
        current = next;
      }
      return current;
    }
    default: {  // Legendre: (n+1) P_{n+1} = (2n+1) t P_n − n P_{n−1}
      double previous = 1, current = t;
      if (h == 0) return previous;
      for (uint32_t n = 1; n < h; ++n) {
        const double next = ((2 * n + 1) * t * current - n * previous) / (n + 1);
        previous = current;
        current = next;
      }
      return current;
    }
  }
}

}  // namespace

const char* basis_name(int32_t family) {
  switch (family) {
    case ARCUS_BASIS_PIECEWISE_CONSTANT: return "piecewise constant";
    case ARCUS_BASIS_HAAR: return "Haar";
    case ARCUS_BASIS_GAUSSIAN: return "zero-mean Gaussian";
    case ARCUS_BASIS_HERMITE: return "Hermite";
    case ARCUS_BASIS_LEGENDRE: return "Legendre";
    default: return "unknown";
  }
}

uint32_t fine_bins_for(int32_t family, uint32_t m) {
  if (family == ARCUS_BASIS_PIECEWISE_CONSTANT) return m * std::min<uint32_t>(8, ARCUS_MAX_HISTOGRAM_BINS / m);
  return ARCUS_MAX_HISTOGRAM_BINS;
}

std::vector<double> basis_matrix(int32_t family, uint32_t m, uint32_t bins) {
  std::vector<double> w(size_t(bins) * m);
  for (uint32_t h = 0; h < m; ++h) {
    double largest = 0;
    for (uint32_t k = 0; k < bins; ++k) {
      w[size_t(k) * m + h] = value(family, h, m, (k + 0.5) / bins);
      largest = std::max(largest, std::fabs(w[size_t(k) * m + h]));
    }
    for (uint32_t k = 0; k < bins; ++k) w[size_t(k) * m + h] /= largest > 0 ? largest : 1;
  }
  return w;
}

}  // namespace arcus::translucency
