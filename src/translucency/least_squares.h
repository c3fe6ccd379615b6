// The linear solve of the BSSRDF estimate (thesis §3.3.1): basis weights x that best
// fit A x ≈ b, through the normal equations AᵀA x = Aᵀb formed in double, with the
// columns that carry (almost) nothing dropped, a Jacobi preconditioner and QMR (Freund &
// Nachtigal 1991, in the form of Barrett et al., "Templates for the Solution of Linear
// Systems", 1994, §2.3.5).  Host code: the systems are small (tens of unknowns); the
// assembly of A, the heavy part, runs elsewhere.
#pragma once

#include <cstddef>
#include <vector>

namespace arcus::translucency {

struct LeastSquaresReport {
  int iterations = 0;           // QMR iterations taken (summed over the active-set steps)
  bool converged = false;       // the relative residual fell below the tolerance
  double residual = 0;          // |Aᵀb − AᵀA x| / |Aᵀb| on the kept columns
  double condition_a = 0;       // 2-norm condition number of A's kept columns, sqrt(λmax/λmin)
  double condition_normal = 0;  // of the normal matrix solved, λmax/λmin (condition_a² without Tikhonov)
  std::vector<size_t> dropped;  // columns left out (their weight is 0)
};

struct LeastSquaresOptions {
  double tolerance = 1e-12;        // on the relative residual of the normal equations
  int max_iterations = 1000;
  double column_threshold = 1e-12; // a column whose norm is below this × the largest is dropped
  double tikhonov = 0;             // λ: AᵀA + λ·mean(diag AᵀA)·I (0: off, as the thesis)
  bool nonnegative = false;        // x >= 0 by Lawson–Hanson's active set (off, as the thesis)
};

// x (cols values) for the row-major rows × cols matrix `a` and `b` (rows values).
std::vector<double> solve_least_squares(const std::vector<double>& a, size_t rows, size_t cols,
                                        const std::vector<double>& b, const LeastSquaresOptions& options,
                                        LeastSquaresReport* report);

// The eigenvalues of the symmetric n × n matrix `m` (row-major), ascending, by the
// cyclic Jacobi method: for the condition numbers of small normal matrices.
std::vector<double> symmetric_eigenvalues(std::vector<double> m, size_t n);

}  // namespace arcus::translucency
