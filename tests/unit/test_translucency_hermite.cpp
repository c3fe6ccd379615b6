// §3.4's plausible profile (src/translucency/hermite.h) against what it promises, with
// closed forms written here: bins on one line falling to 0 at r_max give that line
// (Fritsch–Carlson keeps the tangents of collinear knots, so the cubic pieces are the
// line); the curve's ∫2πr R dr is the bins' Σ area·R; a bump against the grain is
// pooled, never reproduced: the curve never rises and is never negative.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "translucency/hermite.h"

namespace {

using arcus::translucency::monotone_hermite_profile;

constexpr uint32_t kCount = 4097;

double radius(uint32_t k, double r_max) {
  const double u = double(k) / (kCount - 1);
  return r_max * u * u;
}

// ∫2πr R dr of a table on the √r grid, by the trapezoid rule in r.
double energy(const std::vector<double>& t, double r_max) {
  double sum = 0;
  for (uint32_t k = 0; k + 1 < kCount; ++k) {
    const double r0 = radius(k, r_max), r1 = radius(k + 1, r_max);
    sum += 0.5 * (2 * M_PI * r0 * t[k] + 2 * M_PI * r1 * t[k + 1]) * (r1 - r0);
  }
  return sum;
}

std::vector<double> uniform_edges(size_t m, double r_max) {
  std::vector<double> e(m + 1);
  for (size_t h = 0; h <= m; ++h) e[h] = r_max * double(h) / double(m);
  return e;
}

double bins_energy(const std::vector<double>& edges, const std::vector<double>& bins) {
  double sum = 0;
  for (size_t h = 0; h < bins.size(); ++h) sum += M_PI * (edges[h + 1] * edges[h + 1] - edges[h] * edges[h]) * bins[h];
  return sum;
}

TEST(TranslucencyHermite, CollinearBinsGiveTheirLineWithTheirEnergy) {
  const double r_max = 40;
  const std::vector<double> edges = uniform_edges(20, r_max);
  std::vector<double> bins(20);
  for (size_t h = 0; h < 20; ++h) bins[h] = 0.002 * (r_max - 0.5 * (edges[h] + edges[h + 1]));
  const std::vector<double> t = monotone_hermite_profile(edges, bins, kCount);
  // The shape: the line through the bins' middles, up to one scale factor.
  for (uint32_t k = 0; k < kCount; k += 64)
    EXPECT_NEAR(t[k] / t[0], (r_max - radius(k, r_max)) / r_max, 1e-12) << k;
  // The scale: ∫2πr R dr = Σ area·R of the bins (to the trapezoid rule's 1e-6).
  EXPECT_NEAR(energy(t, r_max), bins_energy(edges, bins), 1e-6 * bins_energy(edges, bins));
}

TEST(TranslucencyHermite, ABumpIsPooledAndTheCurveNeverRisesNorGoesNegative) {
  const double r_max = 30;
  const std::vector<double> edges = uniform_edges(12, r_max);
  // A falling profile with a bump at bins 4–5 and a negative tail (as a solve gives).
  const std::vector<double> bins = {0.08, 0.05, 0.03, 0.01, 0.02, 0.015, 0.004, 0.002, 0.001, -0.0005, 0.0002, -0.001};
  const std::vector<double> t = monotone_hermite_profile(edges, bins, kCount);
  for (uint32_t k = 0; k + 1 < kCount; ++k) {
    EXPECT_GE(t[k], 0.0) << k;
    EXPECT_LE(t[k + 1], t[k] * (1 + 1e-12)) << k;
  }
  // Bins 3–5 pool to their area-weighted mean (rings of area ∝ 2h + 1: 7, 9, 11); bins
  // 9–10 pool to a negative mean, clamped at 0 as bin 11 is: the energy is of those bins.
  std::vector<double> monotone = bins;
  const double pooled = (7 * 0.01 + 9 * 0.02 + 11 * 0.015) / 27;
  monotone[3] = monotone[4] = monotone[5] = pooled;
  const double tail = (19 * -0.0005 + 21 * 0.0002) / 40;
  ASSERT_LT(tail, 0.0);
  monotone[9] = monotone[10] = monotone[11] = 0;
  EXPECT_NEAR(energy(t, r_max), bins_energy(edges, monotone), 1e-6 * bins_energy(edges, monotone));
}

}  // namespace
