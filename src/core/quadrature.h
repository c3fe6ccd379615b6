// Gauss–Legendre quadrature: nodes and weights of order n on [a, b], by Newton's method
// on the Legendre polynomial P_n from Chebyshev guesses.
#pragma once

#include <cmath>

namespace arcus {

inline void gauss_legendre(int n, double a, double b, double* x, double* w) {
  constexpr double kPi = 3.14159265358979323846;
  for (int i = 0; i < n; ++i) {
    double z = std::cos(kPi * (i + 0.75) / (n + 0.5)), dp = 1;
    for (int it = 0; it < 100; ++it) {
      double p0 = 1, p1 = z;  // P_0, P_1, then up to P_n by the recurrence
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2.0 * k - 1) * z * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      dp = n * (z * p1 - p0) / (z * z - 1);
      const double step = p1 / dp;
      z -= step;
      if (std::abs(step) < 1e-16) break;
    }
    x[i] = 0.5 * (a + b) + 0.5 * (b - a) * z;
    w[i] = (b - a) / ((1 - z * z) * dp * dp);
  }
}

}  // namespace arcus
