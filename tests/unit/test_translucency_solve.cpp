// The estimate's linear solve (src/translucency/least_squares.h) against dense
// references written here: an exactly consistent system gives back its x; a noisy one
// the least-squares x of a dense Cholesky solve of the normal equations; empty columns
// are dropped; badly scaled columns still converge (the Jacobi preconditioner); the
// condition numbers meet closed forms and the Hilbert matrix's tabulated value;
// Tikhonov's option is the dense ridge solve; the non-negative one meets the
// Karush–Kuhn–Tucker conditions.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "translucency/least_squares.h"

namespace {

using arcus::translucency::LeastSquaresOptions;
using arcus::translucency::LeastSquaresReport;
using arcus::translucency::solve_least_squares;
using arcus::translucency::symmetric_eigenvalues;

std::vector<double> random_matrix(size_t rows, size_t cols, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<double> a(rows * cols);
  for (double& v : a) v = normal(rng);
  return a;
}

std::vector<double> times(const std::vector<double>& a, size_t rows, size_t cols, const std::vector<double>& x) {
  std::vector<double> b(rows, 0.0);
  for (size_t i = 0; i < rows; ++i)
    for (size_t j = 0; j < cols; ++j) b[i] += a[i * cols + j] * x[j];
  return b;
}

// The least-squares x by Cholesky on (AᵀA + ridge·I) x = Aᵀb: the dense reference.
std::vector<double> dense_least_squares(const std::vector<double>& a, size_t rows, size_t cols,
                                        const std::vector<double>& b, double ridge = 0) {
  std::vector<double> m(cols * cols, 0.0), f(cols, 0.0), l(cols * cols, 0.0);
  for (size_t i = 0; i < rows; ++i)
    for (size_t p = 0; p < cols; ++p) {
      f[p] += a[i * cols + p] * b[i];
      for (size_t q = 0; q < cols; ++q) m[p * cols + q] += a[i * cols + p] * a[i * cols + q];
    }
  for (size_t p = 0; p < cols; ++p) m[p * cols + p] += ridge;
  for (size_t j = 0; j < cols; ++j) {
    double s = m[j * cols + j];
    for (size_t k = 0; k < j; ++k) s -= l[j * cols + k] * l[j * cols + k];
    l[j * cols + j] = std::sqrt(s);
    for (size_t i = j + 1; i < cols; ++i) {
      double t = m[i * cols + j];
      for (size_t k = 0; k < j; ++k) t -= l[i * cols + k] * l[j * cols + k];
      l[i * cols + j] = t / l[j * cols + j];
    }
  }
  std::vector<double> y(cols), x(cols);
  for (size_t i = 0; i < cols; ++i) {
    double t = f[i];
    for (size_t k = 0; k < i; ++k) t -= l[i * cols + k] * y[k];
    y[i] = t / l[i * cols + i];
  }
  for (size_t i = cols; i-- > 0;) {
    double t = y[i];
    for (size_t k = i + 1; k < cols; ++k) t -= l[k * cols + i] * x[k];
    x[i] = t / l[i * cols + i];
  }
  return x;
}

TEST(TranslucencySolve, AConsistentSystemGivesBackItsSolution) {
  const size_t rows = 400, cols = 24;  // the thesis' default basis count
  const std::vector<double> a = random_matrix(rows, cols, 1);
  std::vector<double> truth(cols);
  for (size_t j = 0; j < cols; ++j) truth[j] = std::sin(0.3 * j) + 0.1 * j;
  LeastSquaresReport report;
  const std::vector<double> x = solve_least_squares(a, rows, cols, times(a, rows, cols, truth), {}, &report);
  EXPECT_TRUE(report.converged);
  EXPECT_LT(report.residual, 1e-12);
  EXPECT_LE(report.iterations, 100);
  for (size_t j = 0; j < cols; ++j) EXPECT_NEAR(x[j], truth[j], 1e-9) << j;
}

TEST(TranslucencySolve, ANoisySystemGivesTheDenseLeastSquaresSolution) {
  const size_t rows = 300, cols = 30;
  const std::vector<double> a = random_matrix(rows, cols, 2);
  const std::vector<double> b = random_matrix(rows, 1, 3);  // no exact solution
  LeastSquaresReport report;
  const std::vector<double> x = solve_least_squares(a, rows, cols, b, {}, &report);
  const std::vector<double> reference = dense_least_squares(a, rows, cols, b);
  EXPECT_TRUE(report.converged);
  for (size_t j = 0; j < cols; ++j) EXPECT_NEAR(x[j], reference[j], 1e-10) << j;
}

// Columns scaled from 1e-4 to 1e4 (basis functions of very different reach): the
// Jacobi preconditioner lets QMR converge, to the dense solution.
TEST(TranslucencySolve, BadlyScaledColumnsStillConverge) {
  const size_t rows = 200, cols = 16;
  std::vector<double> a = random_matrix(rows, cols, 4);
  for (size_t i = 0; i < rows; ++i)
    for (size_t j = 0; j < cols; ++j) a[i * cols + j] *= std::pow(10.0, -4.0 + 8.0 * j / (cols - 1));
  const std::vector<double> b = random_matrix(rows, 1, 5);
  LeastSquaresReport report;
  const std::vector<double> x = solve_least_squares(a, rows, cols, b, {}, &report);
  const std::vector<double> reference = dense_least_squares(a, rows, cols, b);
  EXPECT_TRUE(report.converged) << report.iterations << " iterations, residual " << report.residual;
  for (size_t j = 0; j < cols; ++j) EXPECT_NEAR(x[j], reference[j], 1e-8 * std::fabs(reference[j]) + 1e-14) << j;
}

// A basis function no pair of pixels reaches is a zero column: dropped, weight 0, and
// the rest solved as if it were not there.
TEST(TranslucencySolve, EmptyColumnsAreDroppedAndReported) {
  const size_t rows = 100, cols = 8;
  std::vector<double> a = random_matrix(rows, cols, 6);
  for (size_t i = 0; i < rows; ++i) a[i * cols + 3] = a[i * cols + 6] = 0;
  std::vector<double> truth = {1, 2, 3, 0, 5, 6, 0, 8};
  LeastSquaresReport report;
  const std::vector<double> x = solve_least_squares(a, rows, cols, times(a, rows, cols, truth), {}, &report);
  EXPECT_EQ(report.dropped, (std::vector<size_t>{3, 6}));
  for (size_t j = 0; j < cols; ++j) EXPECT_NEAR(x[j], truth[j], 1e-9) << j;
  EXPECT_TRUE(std::isfinite(report.condition_a));
}

// Orthogonal columns of norms s_j: cond(A) = max s / min s, cond(AᵀA) its square.  The
// 6 × 6 Hilbert matrix H (symmetric positive definite): cond₂(H) = 1.495105864e7
// (Todd 1954; the usual tabulated value), so A = H gives cond(AᵀA) = cond(H)².
TEST(TranslucencySolve, ConditionNumbersMeetClosedForms) {
  const size_t n = 5;
  std::vector<double> diag(n * n, 0.0);
  const double norms[n] = {3, 0.5, 7, 2, 1};
  for (size_t j = 0; j < n; ++j) diag[j * n + j] = norms[j];
  LeastSquaresReport report;
  solve_least_squares(diag, n, n, std::vector<double>(n, 1.0), {}, &report);
  EXPECT_NEAR(report.condition_a, 14.0, 1e-10);
  EXPECT_NEAR(report.condition_normal, 196.0, 1e-8);

  const size_t h = 6;
  std::vector<double> hilbert(h * h);
  for (size_t i = 0; i < h; ++i)
    for (size_t j = 0; j < h; ++j) hilbert[i * h + j] = 1.0 / (i + j + 1);
  const std::vector<double> eigen = symmetric_eigenvalues(hilbert, h);
  EXPECT_NEAR(eigen.back() / eigen.front(), 1.495105864e7, 1e-3 * 1.495105864e7);
  solve_least_squares(hilbert, h, h, std::vector<double>(h, 1.0), {}, &report);
  EXPECT_NEAR(report.condition_a, 1.495105864e7, 1e-3 * 1.495105864e7);
}

// λ adds λ × the mean diagonal of AᵀA to its diagonal: the dense ridge solve.
TEST(TranslucencySolve, TikhonovIsTheDenseRidgeSolution) {
  const size_t rows = 200, cols = 20;
  const std::vector<double> a = random_matrix(rows, cols, 7), b = random_matrix(rows, 1, 8);
  double mean_diagonal = 0;
  for (size_t j = 0; j < cols; ++j)
    for (size_t i = 0; i < rows; ++i) mean_diagonal += a[i * cols + j] * a[i * cols + j] / cols;
  LeastSquaresOptions options;
  options.tikhonov = 0.05;
  LeastSquaresReport report;
  const std::vector<double> x = solve_least_squares(a, rows, cols, b, options, &report);
  const std::vector<double> reference = dense_least_squares(a, rows, cols, b, 0.05 * mean_diagonal);
  for (size_t j = 0; j < cols; ++j) EXPECT_NEAR(x[j], reference[j], 1e-10) << j;
  const std::vector<double> plain = dense_least_squares(a, rows, cols, b);
  double shrunk = 0, unshrunk = 0;
  for (size_t j = 0; j < cols; ++j) {
    shrunk += x[j] * x[j];
    unshrunk += plain[j] * plain[j];
  }
  EXPECT_LT(shrunk, unshrunk);  // the ridge shrinks the weights
}

// min |Ax − b|² over x >= 0 is the x where (Karush–Kuhn–Tucker) the gradient
// g = Aᵀ(b − Ax) vanishes on the positive weights and is <= 0 on the zero ones.  A
// truth with negative entries and noise makes several constraints bind.
TEST(TranslucencySolve, NonNegativeWeightsMeetTheOptimalityConditions) {
  const size_t rows = 300, cols = 24;
  const std::vector<double> a = random_matrix(rows, cols, 9), noise = random_matrix(rows, 1, 10);
  std::vector<double> truth(cols);
  for (size_t j = 0; j < cols; ++j) truth[j] = std::sin(0.7 * j);
  std::vector<double> b = times(a, rows, cols, truth);
  for (size_t i = 0; i < rows; ++i) b[i] += 0.1 * noise[i];
  LeastSquaresOptions options;
  options.nonnegative = true;
  LeastSquaresReport report;
  const std::vector<double> x = solve_least_squares(a, rows, cols, b, options, &report);
  const std::vector<double> fitted = times(a, rows, cols, x);
  size_t zeros = 0;
  double scale = 0;
  for (size_t j = 0; j < cols; ++j)
    for (size_t i = 0; i < rows; ++i) scale = std::max(scale, std::fabs(a[i * cols + j] * b[i]));
  for (size_t j = 0; j < cols; ++j) {
    double g = 0;
    for (size_t i = 0; i < rows; ++i) g += a[i * cols + j] * (b[i] - fitted[i]);
    EXPECT_GE(x[j], 0.0) << j;
    // 1e-9 of the largest term of Aᵀb: QMR's residual (1e-12) times the condition
    // number of these random 300 × 24 systems (a few).
    if (x[j] > 0) EXPECT_NEAR(g, 0.0, 1e-9 * scale) << j;
    else EXPECT_LE(g, 1e-9 * scale) << j;
    zeros += x[j] == 0;
  }
  EXPECT_GE(zeros, 6u);  // sin(0.7 j) is negative for about half of them
  EXPECT_LT(zeros, cols);
}

}  // namespace
