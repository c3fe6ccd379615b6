#include "translucency/fit.h"

#include <algorithm>
#include <cmath>
#include <limits>

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

namespace {

double norm2(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x * x;
  return s;
}

// σ within physical reach (1e-8 to 1e4 mm⁻¹), as logarithms.
double clamp_log(double x) { return std::clamp(x, std::log(1e-8), std::log(1e4)); }

Channel channel_of(const double p[2], double eta) { return Channel{std::exp(p[0]), std::exp(p[1]), eta}; }

}  // namespace

DipoleFit fit_dipole(const Residuals& residuals, double data_norm, double eta, double reach) {
  // The start: the best of 1 − α′ in 1e-4..0.5 and ℓ_d in reach/1000..reach (log grids).
  double p[2] = {0, 0}, cost = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 14; ++i)
    for (int j = 0; j < 16; ++j) {
      const double albedo = 1 - 1e-4 * std::pow(5000.0, i / 13.0), length = reach * std::pow(1e-3, 1 - j / 15.0);
      const double sigma_t = 1 / (length * std::sqrt(3 * (1 - albedo)));
      const double q[2] = {clamp_log(std::log(sigma_t * (1 - albedo))), clamp_log(std::log(sigma_t * albedo))};
      const double c = norm2(residuals(channel_of(q, eta)));
      if (std::isfinite(c) && c < cost) {
        cost = c;
        p[0] = q[0];
        p[1] = q[1];
      }
    }
  std::vector<double> r = residuals(channel_of(p, eta));
  double lambda = 1e-3;
  DipoleFit fit;
  for (int it = 0; it < 100; ++it) {
    fit.iterations = it + 1;
    // The Jacobian by central differences in the log parameters.
    std::vector<double> jac[2];
    for (int k = 0; k < 2; ++k) {
      double up[2] = {p[0], p[1]}, down[2] = {p[0], p[1]};
      up[k] += 1e-5;
      down[k] -= 1e-5;
      const std::vector<double> ru = residuals(channel_of(up, eta)), rd = residuals(channel_of(down, eta));
      jac[k].resize(r.size());
      for (size_t i = 0; i < r.size(); ++i) jac[k][i] = (ru[i] - rd[i]) / 2e-5;
    }
    double jtj[3] = {0, 0, 0}, jtr[2] = {0, 0};
    for (size_t i = 0; i < r.size(); ++i) {
      jtj[0] += jac[0][i] * jac[0][i];
      jtj[1] += jac[0][i] * jac[1][i];
      jtj[2] += jac[1][i] * jac[1][i];
      jtr[0] += jac[0][i] * r[i];
      jtr[1] += jac[1][i] * r[i];
    }
    bool improved = false, converged = false;
    for (int tries = 0; tries < 30 && !improved; ++tries) {
      const double a = jtj[0] * (1 + lambda), b = jtj[1], d = jtj[2] * (1 + lambda), det = a * d - b * b;
      if (!(std::fabs(det) > 0)) {
        lambda *= 10;
        continue;
      }
      const double q[2] = {clamp_log(p[0] - (d * jtr[0] - b * jtr[1]) / det),
                           clamp_log(p[1] - (a * jtr[1] - b * jtr[0]) / det)};
      const std::vector<double> rq = residuals(channel_of(q, eta));
      const double c = norm2(rq);
      if (std::isfinite(c) && c < cost) {
        converged = cost - c <= 1e-12 * cost;
        p[0] = q[0];
        p[1] = q[1];
        r = rq;
        cost = c;
        lambda = std::max(lambda / 10, 1e-12);
        improved = true;
      } else {
        lambda *= 10;
      }
    }
    if (!improved || converged) break;
  }
  fit.channel = channel_of(p, eta);
  fit.error = data_norm > 0 ? std::sqrt(cost) / data_norm : 0;
  return fit;
}

DipoleFit fit_to_profile(const std::vector<double>& edges, const std::vector<double>& weights, double eta) {
  const size_t m = weights.size();
  double data = 0;
  for (size_t h = 0; h < m; ++h) data += std::pow(0.5 * (edges[h] + edges[h + 1]) * weights[h], 2);
  auto residuals = [&](const Channel& c) {
    const Terms t = terms(c);
    std::vector<double> out(m);
    for (size_t h = 0; h < m; ++h)
      out[h] = 0.5 * (edges[h] + edges[h + 1]) * (bin_average(t, edges[h], edges[h + 1]) - weights[h]);
    return out;
  };
  return fit_dipole(residuals, std::sqrt(data), eta, edges.back());
}

DipoleFit fit_to_image(const std::vector<double>& edges, const std::vector<double>& histograms, size_t first_bin,
                       const std::vector<double>& near_irradiance, double radius, const std::vector<double>& pixels,
                       double eta) {
  const size_t bins = edges.size() - 1, rows = pixels.size();
  auto residuals = [&](const Channel& c) {
    const Terms t = terms(c);
    std::vector<double> average(bins), out(rows);
    for (size_t f = first_bin; f < bins; ++f) average[f] = bin_average(t, edges[f], edges[f + 1]);
    const double disc = reflectance_within(t, radius);
    for (size_t i = 0; i < rows; ++i) {
      double predicted = near_irradiance[i] * disc;
      for (size_t f = first_bin; f < bins; ++f) predicted += histograms[i * bins + f] * average[f];
      out[i] = predicted - pixels[i];
    }
    return out;
  };
  return fit_dipole(residuals, std::sqrt(norm2(pixels)), eta, edges.back());
}

}  // namespace arcus::translucency
