#include "translucency/hermite.h"

#include <algorithm>
#include <cmath>

namespace arcus::translucency {
namespace {

// The weighted least-squares non-increasing fit to y (pool adjacent violators).
std::vector<double> non_increasing(const std::vector<double>& y, const std::vector<double>& w) {
  struct Block {
    double value, weight;
    size_t size;
  };
  std::vector<Block> blocks;
  for (size_t i = 0; i < y.size(); ++i) {
    blocks.push_back({y[i], w[i], 1});
    while (blocks.size() > 1 && blocks[blocks.size() - 2].value < blocks.back().value) {
      const Block b = blocks.back();
      blocks.pop_back();
      Block& a = blocks.back();
      a.value = (a.value * a.weight + b.value * b.weight) / (a.weight + b.weight);
      a.weight += b.weight;
      a.size += b.size;
    }
  }
  std::vector<double> out;
  for (const Block& b : blocks) out.insert(out.end(), b.size, b.value);
  return out;
}

}  // namespace

std::vector<double> monotone_hermite_profile(const std::vector<double>& edges, const std::vector<double>& averages,
                                             uint32_t count) {
  const size_t m = averages.size();
  const double r_max = edges.back();
  std::vector<double> area(m), x, y;
  for (size_t h = 0; h < m; ++h) area[h] = M_PI * (edges[h + 1] * edges[h + 1] - edges[h] * edges[h]);
  std::vector<double> bins = non_increasing(averages, area);
  double energy = 0;
  for (size_t h = 0; h < m; ++h) {
    bins[h] = std::max(0.0, bins[h]);
    energy += area[h] * bins[h];
  }
  // Knots: r = 0 (the line through the first two bins continued, never below the
  // first), the bins' middles, r_max at 0.
  const double c0 = 0.5 * (edges[0] + edges[1]), c1 = 0.5 * (edges[1] + edges[2]);
  const double slope0 = m > 1 ? (bins[1] - bins[0]) / (c1 - c0) : 0;
  x.push_back(0);
  y.push_back(std::max(bins[0], bins[0] - slope0 * c0));
  for (size_t h = 0; h < m; ++h) {
    x.push_back(0.5 * (edges[h] + edges[h + 1]));
    y.push_back(bins[h]);
  }
  x.push_back(r_max);
  y.push_back(0);
  // Fritsch–Carlson tangents: the secants' harmonic-style limits keep each piece monotone.
  const size_t n = x.size();
  std::vector<double> secant(n - 1), tangent(n, 0.0);
  for (size_t i = 0; i + 1 < n; ++i) secant[i] = (y[i + 1] - y[i]) / (x[i + 1] - x[i]);
  tangent[0] = secant[0];
  tangent[n - 1] = secant[n - 2];
  for (size_t i = 1; i + 1 < n; ++i) tangent[i] = secant[i - 1] * secant[i] <= 0 ? 0 : 0.5 * (secant[i - 1] + secant[i]);
  for (size_t i = 0; i + 1 < n; ++i) {
    if (secant[i] == 0) {
      tangent[i] = tangent[i + 1] = 0;
      continue;
    }
    const double a = tangent[i] / secant[i], b = tangent[i + 1] / secant[i], norm = a * a + b * b;
    if (norm > 9) {
      const double t = 3 / std::sqrt(norm);
      tangent[i] = t * a * secant[i];
      tangent[i + 1] = t * b * secant[i];
    }
  }
  auto evaluate = [&](double r) {
    if (r >= r_max) return 0.0;
    const size_t i = size_t(std::upper_bound(x.begin(), x.end(), r) - x.begin()) - 1;
    const double h = x[i + 1] - x[i], t = (r - x[i]) / h, t2 = t * t, t3 = t2 * t;
    return (2 * t3 - 3 * t2 + 1) * y[i] + (t3 - 2 * t2 + t) * h * tangent[i] + (-2 * t3 + 3 * t2) * y[i + 1] +
           (t3 - t2) * h * tangent[i + 1];
  };
  std::vector<double> out(count);
  for (uint32_t k = 0; k < count; ++k) {
    const double u = double(k) / (count - 1);
    out[k] = std::max(0.0, evaluate(r_max * u * u));
  }
  // ∫2πr R dr of the curve (Simpson over 64 intervals per bin), then scaled to `energy`.
  double curve = 0;
  const int steps = 64;
  for (size_t h = 0; h < m; ++h) {
    const double lo = edges[h], step = (edges[h + 1] - lo) / steps;
    for (int s = 0; s <= steps; ++s) {
      const double r = lo + s * step;
      curve += (s == 0 || s == steps ? 1 : s % 2 ? 4 : 2) * 2 * M_PI * r * std::max(0.0, evaluate(r)) * step / 3;
    }
  }
  if (curve > 0)
    for (double& v : out) v *= energy / curve;
  return out;
}

}  // namespace arcus::translucency
