#include "translucency/fit.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace arcus::translucency {

double bin_average(const Terms& t, double r0, double r1) {
  const int n = 32;
  const double h = (r1 - r0) / n;
  double sum = 0;
  for (int i = 0; i <= n; ++i) {
    const double r = r0 + i * h;
    sum += (i == 0 || i == n ? 1 : i % 2 ? 4 : 2) * r * diffuse_reflectance(t, r);
  }
  return (sum * h / 3) * 2 / (r1 * r1 - r0 * r0);
}

QuadraticForm QuadraticForm::of(const std::vector<double>& l, size_t rows, size_t k, const std::vector<double>& y) {
  QuadraticForm f;
  f.k = k;
  f.q.assign(k * k, 0.0);
  f.g.assign(k, 0.0);
  for (size_t i = 0; i < rows; ++i) {
    const double* row = &l[i * k];
    for (size_t a = 0; a < k; ++a) {
      if (row[a] == 0) continue;
      f.g[a] += row[a] * y[i];
      for (size_t b = a; b < k; ++b) f.q[a * k + b] += row[a] * row[b];
    }
    f.c += y[i] * y[i];
  }
  for (size_t a = 0; a < k; ++a)
    for (size_t b = 0; b < a; ++b) f.q[a * k + b] = f.q[b * k + a];
  return f;
}

double QuadraticForm::cost(const std::vector<double>& a) const {
  double quadratic = 0, linear = 0;
  for (size_t i = 0; i < k; ++i) {
    double qa = 0;
    for (size_t j = 0; j < k; ++j) qa += q[i * k + j] * a[j];
    quadratic += a[i] * qa;
    linear += a[i] * g[i];
  }
  return std::max(0.0, quadratic - 2 * linear + c);
}

namespace {

// σ within physical reach (1e-8 to 1e4 mm⁻¹), as logarithms.
double clamp_log(double x) { return std::clamp(x, std::log(1e-8), std::log(1e4)); }

Channel channel_of(const double p[2], double eta) { return Channel{std::exp(p[0]), std::exp(p[1]), eta}; }

struct Run {
  double p[2];
  double cost;
  int iterations;
};

// Levenberg–Marquardt from p: the Jacobian of a by central differences in the log
// parameters, JᵀJ = J_aᵀ Q J_a and Jᵀr = J_aᵀ(Q a − g) in the form's k dimensions.
Run descend(const Model& model, const QuadraticForm& f, double eta, const double start[2]) {
  Run run{{start[0], start[1]}, 0, 0};
  std::vector<double> a = model(channel_of(run.p, eta));
  run.cost = f.cost(a);
  double lambda = 1e-3;
  for (int it = 0; it < 100; ++it) {
    run.iterations = it + 1;
    std::vector<double> ja[2];
    for (int m = 0; m < 2; ++m) {
      double up[2] = {run.p[0], run.p[1]}, down[2] = {run.p[0], run.p[1]};
      up[m] += 1e-5;
      down[m] -= 1e-5;
      const std::vector<double> au = model(channel_of(up, eta)), ad = model(channel_of(down, eta));
      ja[m].resize(f.k);
      for (size_t i = 0; i < f.k; ++i) ja[m][i] = (au[i] - ad[i]) / 2e-5;
    }
    std::vector<double> qj[2], residual(f.k);
    for (int m = 0; m < 2; ++m) qj[m].assign(f.k, 0.0);
    for (size_t i = 0; i < f.k; ++i) {
      double qa = 0;
      for (size_t j = 0; j < f.k; ++j) {
        const double qij = f.q[i * f.k + j];
        qa += qij * a[j];
        qj[0][i] += qij * ja[0][j];
        qj[1][i] += qij * ja[1][j];
      }
      residual[i] = qa - f.g[i];
    }
    double jtj[3] = {0, 0, 0}, jtr[2] = {0, 0};
    for (size_t i = 0; i < f.k; ++i) {
      jtj[0] += ja[0][i] * qj[0][i];
      jtj[1] += ja[0][i] * qj[1][i];
      jtj[2] += ja[1][i] * qj[1][i];
      jtr[0] += ja[0][i] * residual[i];
      jtr[1] += ja[1][i] * residual[i];
    }
    bool improved = false, converged = false;
    for (int tries = 0; tries < 30 && !improved; ++tries) {
      const double d0 = jtj[0] * (1 + lambda), b = jtj[1], d1 = jtj[2] * (1 + lambda), det = d0 * d1 - b * b;
      if (!(std::fabs(det) > 0)) {
        lambda *= 10;
        continue;
      }
      const double q[2] = {clamp_log(run.p[0] - (d1 * jtr[0] - b * jtr[1]) / det),
                           clamp_log(run.p[1] - (d0 * jtr[1] - b * jtr[0]) / det)};
      const std::vector<double> aq = model(channel_of(q, eta));
      const double c = f.cost(aq);
      if (std::isfinite(c) && c < run.cost) {
        converged = run.cost - c <= 1e-12 * run.cost;
        run.p[0] = q[0];
        run.p[1] = q[1];
        a = aq;
        run.cost = c;
        lambda = std::max(lambda / 10, 1e-12);
        improved = true;
      } else {
        lambda *= 10;
      }
    }
    if (!improved || converged) break;
  }
  return run;
}

}  // namespace

DipoleFit fit_dipole(const Model& model, const QuadraticForm& form, double eta, double reach) {
  // The grid: 1 − α′ from 1e-5 to 0.5 and ℓ_d from reach/1000 to reach, log-spaced.
  std::vector<std::pair<double, std::pair<double, double>>> starts;
  for (int i = 0; i < 24; ++i)
    for (int j = 0; j < 32; ++j) {
      const double albedo = 1 - 1e-5 * std::pow(5e4, i / 23.0), length = reach * std::pow(1e-3, 1 - j / 31.0);
      const double sigma_t = 1 / (length * std::sqrt(3 * (1 - albedo)));
      const double p[2] = {clamp_log(std::log(sigma_t * (1 - albedo))), clamp_log(std::log(sigma_t * albedo))};
      const double c = form.cost(model(channel_of(p, eta)));
      if (std::isfinite(c)) starts.push_back({c, {p[0], p[1]}});
    }
  // Descend from the best few (the cost has long, shallow valleys: a dense medium whose
  // light leaves where it enters can fit a smooth image nearly as well), keep the best.
  std::sort(starts.begin(), starts.end());
  Run best{{0, 0}, std::numeric_limits<double>::infinity(), 0};
  for (size_t s = 0; s < std::min<size_t>(4, starts.size()); ++s) {
    const double p[2] = {starts[s].second.first, starts[s].second.second};
    const Run run = descend(model, form, eta, p);
    if (run.cost < best.cost) best = run;
  }
  DipoleFit fit;
  fit.channel = channel_of(best.p, eta);
  fit.iterations = best.iterations;
  fit.error = form.c > 0 ? std::sqrt(best.cost / form.c) : 0;
  return fit;
}

DipoleFit fit_to_profile(const std::vector<double>& edges, const std::vector<double>& weights, double eta) {
  const size_t m = weights.size();
  std::vector<double> identity(m * m, 0.0), y(m);
  for (size_t h = 0; h < m; ++h) {
    identity[h * m + h] = 1;
    y[h] = 0.5 * (edges[h] + edges[h + 1]) * weights[h];
  }
  auto model = [&](const Channel& c) {
    const Terms t = terms(c);
    std::vector<double> a(m);
    for (size_t h = 0; h < m; ++h) a[h] = 0.5 * (edges[h] + edges[h + 1]) * bin_average(t, edges[h], edges[h + 1]);
    return a;
  };
  return fit_dipole(model, QuadraticForm::of(identity, m, m, y), eta, edges.back());
}

DipoleFit fit_to_image(const std::vector<double>& edges, const std::vector<double>& histograms, size_t first_bin,
                       const std::vector<double>& near_irradiance, double radius, const std::vector<double>& pixels,
                       double eta) {
  const size_t bins = edges.size() - 1, rows = pixels.size(), k = bins - first_bin + 1;
  // L: per row its own irradiance (the disc), then the counted bins.
  std::vector<double> l(rows * k);
  for (size_t i = 0; i < rows; ++i) {
    l[i * k] = near_irradiance[i];
    for (size_t f = first_bin; f < bins; ++f) l[i * k + 1 + f - first_bin] = histograms[i * bins + f];
  }
  auto model = [&](const Channel& c) {
    const Terms t = terms(c);
    std::vector<double> a(k);
    a[0] = reflectance_within(t, radius);
    for (size_t f = first_bin; f < bins; ++f) a[1 + f - first_bin] = bin_average(t, edges[f], edges[f + 1]);
    return a;
  };
  return fit_dipole(model, QuadraticForm::of(l, rows, k, pixels), eta, edges.back());
}

}  // namespace arcus::translucency
