#include "translucency/least_squares.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace arcus::translucency {
namespace {

using Vec = std::vector<double>;

double dot(const Vec& a, const Vec& b) {
  double s = 0;
  for (size_t i = 0; i < a.size(); ++i) s += a[i] * b[i];
  return s;
}

double norm(const Vec& a) { return std::sqrt(dot(a, a)); }

// y = M x for the symmetric n × n matrix M (so Mᵀx is the same product).
Vec multiply(const Vec& m, const Vec& x) {
  const size_t n = x.size();
  Vec y(n, 0.0);
  for (size_t i = 0; i < n; ++i)
    for (size_t j = 0; j < n; ++j) y[i] += m[i * n + j] * x[j];
  return y;
}

// QMR without look-ahead on M x = f with the left (Jacobi) preconditioner D = diag(M)
// and no right one: Templates, Fig. 2.11, with M1 = D and M2 = I.  M is symmetric here,
// so the transpose products are the same products.  Returns x; fills iterations,
// converged.
Vec qmr(const Vec& m, const Vec& f, const Vec& diagonal, const LeastSquaresOptions& o, LeastSquaresReport* rep) {
  const size_t n = f.size();
  Vec x(n, 0.0), r = f;
  const double f_norm = norm(f);
  if (f_norm == 0) {
    rep->converged = true;
    return x;
  }
  auto precondition = [&](const Vec& v) {
    Vec out(n);
    for (size_t i = 0; i < n; ++i) out[i] = v[i] / diagonal[i];
    return out;
  };
  Vec v_tilde = r, y = precondition(v_tilde);
  double rho = norm(y);
  Vec w_tilde = r, z = w_tilde;  // M2ᵀ = I
  double xi = norm(z);
  double gamma_prev = 1, eta = -1, theta_prev = 0, epsilon = 1;
  Vec p(n), q(n), d(n), s(n), v(n), w(n);
  for (int i = 1; i <= o.max_iterations; ++i) {
    if (rho == 0 || xi == 0) break;  // breakdown: the residual is as small as it gets
    for (size_t k = 0; k < n; ++k) {
      v[k] = v_tilde[k] / rho;
      y[k] /= rho;
      w[k] = w_tilde[k] / xi;
      z[k] /= xi;
    }
    const double delta = dot(z, y);
    if (delta == 0) break;
    const Vec y_tilde = y;                 // M2 ỹ = y
    const Vec z_tilde = precondition(z);   // M1ᵀ z̃ = z
    if (i == 1) {
      p = y_tilde;
      q = z_tilde;
    } else {
      for (size_t k = 0; k < n; ++k) {
        p[k] = y_tilde[k] - (xi * delta / epsilon) * p[k];
        q[k] = z_tilde[k] - (rho * delta / epsilon) * q[k];
      }
    }
    const Vec p_tilde = multiply(m, p);
    epsilon = dot(q, p_tilde);
    if (epsilon == 0) break;
    const double beta = epsilon / delta;
    if (beta == 0) break;
    for (size_t k = 0; k < n; ++k) v_tilde[k] = p_tilde[k] - beta * v[k];
    y = precondition(v_tilde);
    const double rho_next = norm(y);
    const Vec mq = multiply(m, q);  // Mᵀq
    for (size_t k = 0; k < n; ++k) w_tilde[k] = mq[k] - beta * w[k];
    z = w_tilde;
    const double xi_next = norm(z);
    const double theta = rho_next / (gamma_prev * std::fabs(beta));
    const double gamma = 1 / std::sqrt(1 + theta * theta);
    if (gamma == 0) break;
    eta = -eta * rho * gamma * gamma / (beta * gamma_prev * gamma_prev);
    const double carry = (theta_prev * gamma) * (theta_prev * gamma);
    for (size_t k = 0; k < n; ++k) {
      d[k] = i == 1 ? eta * p[k] : eta * p[k] + carry * d[k];
      s[k] = i == 1 ? eta * p_tilde[k] : eta * p_tilde[k] + carry * s[k];
      x[k] += d[k];
      r[k] -= s[k];
    }
    rep->iterations = i;
    if (norm(r) <= o.tolerance * f_norm) {
      rep->converged = true;
      break;
    }
    rho = rho_next;
    xi = xi_next;
    gamma_prev = gamma;
    theta_prev = theta;
  }
  return x;
}

// M x = f by Jacobi-preconditioned QMR, iterations added to the report's.
Vec solve_system(const Vec& m, const Vec& f, const LeastSquaresOptions& o, LeastSquaresReport* rep) {
  const size_t n = f.size();
  Vec diagonal(n);
  for (size_t p = 0; p < n; ++p) diagonal[p] = m[p * n + p];
  LeastSquaresReport step;
  const Vec x = qmr(m, f, diagonal, o, &step);
  rep->iterations += step.iterations;
  rep->converged = step.converged;
  return x;
}

// min |A x − b|² subject to x >= 0, from the normal equations M = AᵀA, f = Aᵀb: Lawson
// & Hanson's active set ("Solving Least Squares Problems", 1974, ch. 23), each passive
// set's unconstrained solve by QMR on its rows and columns of M.
Vec nonnegative_solve(const Vec& m, const Vec& f, const LeastSquaresOptions& o, LeastSquaresReport* rep) {
  const size_t n = f.size();
  Vec x(n, 0.0);
  std::vector<bool> passive(n, false);
  double scale = 0;
  for (double v : f) scale = std::max(scale, std::fabs(v));
  const double tolerance = 1e-12 * scale;
  auto gradient = [&] {  // f − M x: the descent direction of the cost
    Vec g = f;
    const Vec mx = multiply(m, x);
    for (size_t p = 0; p < n; ++p) g[p] -= mx[p];
    return g;
  };
  for (size_t outer = 0; outer < 3 * n; ++outer) {
    const Vec g = gradient();
    size_t best = n;
    for (size_t p = 0; p < n; ++p)
      if (!passive[p] && g[p] > tolerance && (best == n || g[p] > g[best])) best = p;
    if (best == n) break;  // the Karush–Kuhn–Tucker conditions hold
    passive[best] = true;
    for (size_t inner = 0; inner < 3 * n; ++inner) {
      std::vector<size_t> set;
      for (size_t p = 0; p < n; ++p)
        if (passive[p]) set.push_back(p);
      const size_t k = set.size();
      Vec sub(k * k), rhs(k);
      for (size_t a = 0; a < k; ++a) {
        rhs[a] = f[set[a]];
        for (size_t b = 0; b < k; ++b) sub[a * k + b] = m[set[a] * n + set[b]];
      }
      const Vec z = solve_system(sub, rhs, o, rep);
      // Step from x toward z as far as every weight stays >= 0.
      double step = 1;
      size_t blocking = k;
      for (size_t a = 0; a < k; ++a)
        if (z[a] <= 0 && x[set[a]] / (x[set[a]] - z[a]) < step) {
          step = x[set[a]] / (x[set[a]] - z[a]);
          blocking = a;
        }
      for (size_t a = 0; a < k; ++a) x[set[a]] += step * (z[a] - x[set[a]]);
      if (blocking == k) break;
      x[set[blocking]] = 0;  // the weight that reached 0 first leaves the passive set
      for (size_t a = 0; a < k; ++a)
        if (x[set[a]] <= 0) {
          x[set[a]] = 0;
          passive[set[a]] = false;
        }
    }
  }
  return x;
}

}  // namespace

std::vector<double> symmetric_eigenvalues(std::vector<double> m, size_t n) {
  // Cyclic Jacobi rotations until the off-diagonal part is negligible against the
  // diagonal (quadratic convergence: a few sweeps for the sizes here).
  for (int sweep = 0; sweep < 100; ++sweep) {
    double off = 0, diag = 0;
    for (size_t i = 0; i < n; ++i)
      for (size_t j = 0; j < n; ++j) (i == j ? diag : off) += m[i * n + j] * m[i * n + j];
    if (off <= 1e-30 * diag || off == 0) break;
    for (size_t p = 0; p < n; ++p)
      for (size_t q = p + 1; q < n; ++q) {
        const double apq = m[p * n + q];
        if (apq == 0) continue;
        const double tau = (m[q * n + q] - m[p * n + p]) / (2 * apq);
        const double t = (tau >= 0 ? 1 : -1) / (std::fabs(tau) + std::sqrt(1 + tau * tau));
        const double c = 1 / std::sqrt(1 + t * t), s = t * c;
        for (size_t k = 0; k < n; ++k) {  // columns p, q
          const double kp = m[k * n + p], kq = m[k * n + q];
          m[k * n + p] = c * kp - s * kq;
          m[k * n + q] = s * kp + c * kq;
        }
        for (size_t k = 0; k < n; ++k) {  // rows p, q
          const double pk = m[p * n + k], qk = m[q * n + k];
          m[p * n + k] = c * pk - s * qk;
          m[q * n + k] = s * pk + c * qk;
        }
      }
  }
  std::vector<double> values(n);
  for (size_t i = 0; i < n; ++i) values[i] = m[i * n + i];
  std::sort(values.begin(), values.end());
  return values;
}

std::vector<double> solve_least_squares(const std::vector<double>& a, size_t rows, size_t cols,
                                        const std::vector<double>& b, const LeastSquaresOptions& options,
                                        LeastSquaresReport* report) {
  require(a.size() == rows * cols && b.size() == rows && cols > 0, "solve_least_squares: sizes do not match");
  LeastSquaresReport rep;
  // Which columns carry anything: a basis function no pixel pair reaches is dropped
  // rather than left to make AᵀA singular.
  Vec column_norm(cols, 0.0);
  for (size_t i = 0; i < rows; ++i)
    for (size_t j = 0; j < cols; ++j) column_norm[j] += a[i * cols + j] * a[i * cols + j];
  const double largest = std::sqrt(*std::max_element(column_norm.begin(), column_norm.end()));
  std::vector<size_t> kept;
  for (size_t j = 0; j < cols; ++j)
    (std::sqrt(column_norm[j]) > options.column_threshold * largest ? kept : rep.dropped).push_back(j);
  Vec x(cols, 0.0);
  if (kept.empty()) {
    if (report) *report = rep;
    return x;
  }
  // The normal equations on the kept columns, in double.
  const size_t n = kept.size();
  Vec normal(n * n, 0.0), rhs(n, 0.0);
  for (size_t i = 0; i < rows; ++i) {
    const double* row = &a[i * cols];
    for (size_t p = 0; p < n; ++p) {
      rhs[p] += row[kept[p]] * b[i];
      for (size_t q = 0; q < n; ++q) normal[p * n + q] += row[kept[p]] * row[kept[q]];
    }
  }
  const Vec plain_eigen = symmetric_eigenvalues(normal, n);
  rep.condition_a = plain_eigen.front() > 0 ? std::sqrt(plain_eigen.back() / plain_eigen.front()) : INFINITY;
  if (options.tikhonov > 0) {
    double mean = 0;
    for (size_t p = 0; p < n; ++p) mean += normal[p * n + p] / double(n);
    for (size_t p = 0; p < n; ++p) normal[p * n + p] += options.tikhonov * mean;
  }
  const Vec solution = options.nonnegative ? nonnegative_solve(normal, rhs, options, &rep)
                                           : solve_system(normal, rhs, options, &rep);
  const Vec fitted = multiply(normal, solution);
  Vec residual(n);
  for (size_t p = 0; p < n; ++p) residual[p] = rhs[p] - fitted[p];
  const double rhs_norm = norm(rhs);
  if (options.nonnegative) {
    // The constrained optimum leaves a gradient on the clamped weights: measure the
    // residual on the free ones (the equations that still hold).
    for (size_t p = 0; p < n; ++p)
      if (solution[p] == 0) residual[p] = 0;
  }
  rep.residual = rhs_norm > 0 ? norm(residual) / rhs_norm : 0;
  const Vec eigen = options.tikhonov > 0 ? symmetric_eigenvalues(normal, n) : plain_eigen;
  rep.condition_normal = eigen.front() > 0 ? eigen.back() / eigen.front() : INFINITY;
  for (size_t p = 0; p < n; ++p) x[kept[p]] = solution[p];
  if (report) *report = rep;
  return x;
}

}  // namespace arcus::translucency
