// Table 3.2's basis families (src/translucency/basis.h) at the fine bins' middles
// against closed forms written here: piecewise-constant bins; Haar's box and wavelets,
// orthogonal over the bins; the zero-mean Gaussians' widths; Hermite's and Legendre's
// polynomials of low degree (each column equals its closed form divided by the
// largest |value|, to rounding).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

#include "arcus/arcus_translucency.h"
#include "translucency/basis.h"

namespace {

using arcus::translucency::basis_matrix;
using arcus::translucency::fine_bins_for;

double middle(uint32_t k, uint32_t bins) { return (k + 0.5) / bins; }

// Column h of W against f(x) / max |f| over the bins' middles.
void expect_column(const std::vector<double>& w, uint32_t m, uint32_t bins, uint32_t h,
                   const std::function<double(double)>& f) {
  double largest = 0;
  for (uint32_t k = 0; k < bins; ++k) largest = std::max(largest, std::fabs(f(middle(k, bins))));
  for (uint32_t k = 0; k < bins; ++k)
    EXPECT_NEAR(w[size_t(k) * m + h], f(middle(k, bins)) / largest, 1e-12) << "h " << h << " bin " << k;
}

TEST(TranslucencyBasis, PiecewiseConstantFunctionsAreTheirBins) {
  const uint32_t m = 24, bins = fine_bins_for(ARCUS_BASIS_PIECEWISE_CONSTANT, m);
  EXPECT_EQ(bins, 192u);  // 8 fine bins inside each function's bin
  const std::vector<double> w = basis_matrix(ARCUS_BASIS_PIECEWISE_CONSTANT, m, bins);
  for (uint32_t k = 0; k < bins; ++k)
    for (uint32_t h = 0; h < m; ++h) EXPECT_EQ(w[size_t(k) * m + h], k / 8 == h ? 1.0 : 0.0);
}

TEST(TranslucencyBasis, HaarWaveletsAreOrthogonalBoxesAndSteps) {
  const uint32_t m = 30, bins = fine_bins_for(ARCUS_BASIS_HAAR, m);
  const std::vector<double> w = basis_matrix(ARCUS_BASIS_HAAR, m, bins);
  expect_column(w, m, bins, 0, [](double) { return 1.0; });
  expect_column(w, m, bins, 1, [](double x) { return x < 0.5 ? 1.0 : -1.0; });
  // h = 2^j + k: +1 on the first half of [k/2^j, (k+1)/2^j), −1 on the second.
  expect_column(w, m, bins, 5, [](double x) { return x < 0.25 || x >= 0.5 ? 0.0 : x < 0.375 ? 1.0 : -1.0; });
  expect_column(w, m, bins, 29, [](double x) {
    return x < 13 / 16.0 || x >= 14 / 16.0 ? 0.0 : x < 13.5 / 16 ? 1.0 : -1.0;
  });
  for (uint32_t a = 0; a < m; ++a)
    for (uint32_t b = a + 1; b < m; ++b) {
      double product = 0;
      for (uint32_t k = 0; k < bins; ++k) product += w[size_t(k) * m + a] * w[size_t(k) * m + b];
      EXPECT_EQ(product, 0.0) << a << " " << b;
    }
}

TEST(TranslucencyBasis, GaussiansAreZeroMeanWithGeometricWidths) {
  const uint32_t m = 10, bins = fine_bins_for(ARCUS_BASIS_GAUSSIAN, m);
  const std::vector<double> w = basis_matrix(ARCUS_BASIS_GAUSSIAN, m, bins);
  for (uint32_t h = 0; h < m; ++h) {
    const double s = std::pow(10.0, double(h) / 9 - 1);  // 1/m to 1, geometric
    expect_column(w, m, bins, h, [s](double x) { return std::exp(-x * x / (2 * s * s)); });
  }
}

TEST(TranslucencyBasis, HermiteAndLegendreAreTheirPolynomials) {
  const uint32_t m = 6, bins = fine_bins_for(ARCUS_BASIS_HERMITE, m);
  const std::vector<double> hermite = basis_matrix(ARCUS_BASIS_HERMITE, m, bins);
  const std::vector<double> legendre = basis_matrix(ARCUS_BASIS_LEGENDRE, m, bins);
  auto t = [](double x) { return 2 * x - 1; };
  expect_column(hermite, m, bins, 0, [](double) { return 1.0; });
  expect_column(hermite, m, bins, 3, [&](double x) { return 8 * std::pow(t(x), 3) - 12 * t(x); });
  expect_column(hermite, m, bins, 5, [&](double x) {
    return 32 * std::pow(t(x), 5) - 160 * std::pow(t(x), 3) + 120 * t(x);
  });
  expect_column(legendre, m, bins, 2, [&](double x) { return (3 * t(x) * t(x) - 1) / 2; });
  expect_column(legendre, m, bins, 5, [&](double x) {
    return (63 * std::pow(t(x), 5) - 70 * std::pow(t(x), 3) + 15 * t(x)) / 8;
  });
}

}  // namespace
