#include "translucency/genetic.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

namespace arcus::translucency {
namespace {

struct Individual {
  std::vector<double> genes;
  double fitness = 0;
};

class Random {
 public:
  explicit Random(uint64_t seed) : engine_(seed) {}
  double uniform() { return double(engine_() >> 11) * 0x1.0p-53; }  // [0, 1), the same on every library
  size_t below(size_t n) { return std::min(n - 1, size_t(uniform() * double(n))); }

 private:
  std::mt19937_64 engine_;
};

void mutate(const GeneticSettings& s, Random& random, std::vector<double>* genes) {
  for (size_t g = 0; g < genes->size(); ++g) {
    if (random.uniform() >= s.mutation) continue;
    double& x = (*genes)[g];
    // A gene bounded away from 0 is a scale (coefficients, η, angles): steps relative to
    // itself, the thesis' "±0–30% of their original value", at any magnitude.  A gene
    // that may be 0 (g, k_d, k_s) steps by at least 10% of its range, so it can move.
    const double reach = s.lower[g] > 0 ? x : std::max(std::fabs(x), 0.1 * (s.upper[g] - s.lower[g]));
    x = std::clamp(x + (2 * random.uniform() - 1) * s.mutation_range * reach, s.lower[g], s.upper[g]);
  }
}

// Linear ranking: survivor r (0 the best) of n is drawn with weight n − r.
size_t rank_select(Random& random, size_t n) {
  double pick = random.uniform() * double(n) * double(n + 1) / 2;
  for (size_t r = 0; r < n; ++r) {
    pick -= double(n - r);
    if (pick < 0) return r;
  }
  return n - 1;
}

}  // namespace

GeneticHistory genetic_search(const GeneticSettings& s, const Fitness& fitness, const GenerationHook& hook) {
  Random random(s.seed);
  const size_t genes = s.initial.size();
  GeneticHistory history;
  std::vector<Individual> population(s.population);
  for (size_t i = 0; i < population.size(); ++i) {
    population[i].genes = s.initial;
    for (size_t g = 0; g < genes; ++g) population[i].genes[g] = std::clamp(s.initial[g], s.lower[g], s.upper[g]);
    if (i > 0) mutate(s, random, &population[i].genes);
    population[i].fitness = fitness(population[i].genes);
    ++history.evaluations;
  }
  auto record = [&](uint32_t generation) {
    // Rank: a stable sort keeps equal fitnesses in the order they were made.
    std::stable_sort(population.begin(), population.end(),
                     [](const Individual& a, const Individual& b) { return a.fitness < b.fitness; });
    double mean = 0;
    for (const Individual& i : population) mean += i.fitness / double(population.size());
    history.best_fitness.push_back(population[0].fitness);
    history.mean_fitness.push_back(mean);
    history.best_genes.insert(history.best_genes.end(), population[0].genes.begin(), population[0].genes.end());
    history.cancelled = hook && hook(generation, population[0].fitness, population[0].genes.data());
  };
  record(0);
  const size_t replaced = std::min(population.size() - 1, size_t(std::lround(s.replacement * double(s.population))));
  const size_t survivors = population.size() - replaced;
  for (uint32_t generation = 1; generation <= s.generations && !history.cancelled; ++generation) {
    if (s.threshold > 0 && population[0].fitness <= s.threshold) break;
    for (size_t slot = survivors; slot < population.size(); ++slot) {
      std::vector<double> child = population[rank_select(random, survivors)].genes;
      if (genes > 1 && random.uniform() < s.crossover) {
        const std::vector<double>& other = population[rank_select(random, survivors)].genes;
        const size_t point = 1 + random.below(genes - 1);  // genes [point, end) from the other parent
        std::copy(other.begin() + long(point), other.end(), child.begin() + long(point));
      }
      mutate(s, random, &child);
      population[slot].genes = child;
      population[slot].fitness = fitness(child);
      ++history.evaluations;
    }
    record(generation);
  }
  for (const Individual& i : population) history.last.push_back(i.genes);
  return history;
}

namespace {

double norm2(const std::vector<double>& r) {
  double sum = 0;
  for (double v : r) sum += v * v;
  return sum;
}

// Solves the symmetric positive definite n × n system m x = b by Cholesky; false when
// m is not positive definite.
bool cholesky_solve(std::vector<double> m, size_t n, std::vector<double>* b) {
  for (size_t j = 0; j < n; ++j) {
    double d = m[j * n + j];
    for (size_t k = 0; k < j; ++k) d -= m[j * n + k] * m[j * n + k];
    if (!(d > 0)) return false;
    m[j * n + j] = std::sqrt(d);
    for (size_t i = j + 1; i < n; ++i) {
      double v = m[i * n + j];
      for (size_t k = 0; k < j; ++k) v -= m[i * n + k] * m[j * n + k];
      m[i * n + j] = v / m[j * n + j];
    }
  }
  std::vector<double>& x = *b;
  for (size_t i = 0; i < n; ++i) {
    for (size_t k = 0; k < i; ++k) x[i] -= m[i * n + k] * x[k];
    x[i] /= m[i * n + i];
  }
  for (size_t i = n; i-- > 0;) {
    for (size_t k = i + 1; k < n; ++k) x[i] -= m[k * n + i] * x[k];
    x[i] /= m[i * n + i];
  }
  return true;
}

}  // namespace

PolishReport polish(const Residuals& residuals, const std::vector<double>& lower, const std::vector<double>& upper,
                    uint32_t max_steps, std::vector<double>* genes) {
  const size_t n = genes->size();
  auto is_scale = [&](size_t g) { return lower[g] > 0; };
  auto to_u = [&](const std::vector<double>& x) {
    std::vector<double> u(n);
    for (size_t g = 0; g < n; ++g) u[g] = is_scale(g) ? std::log(x[g]) : x[g];
    return u;
  };
  auto to_x = [&](const std::vector<double>& u) {
    std::vector<double> x(n);
    for (size_t g = 0; g < n; ++g) x[g] = std::clamp(is_scale(g) ? std::exp(u[g]) : u[g], lower[g], upper[g]);
    return x;
  };
  PolishReport report;
  std::vector<double> u = to_u(*genes), r = residuals(*genes);
  ++report.evaluations;
  double cost = norm2(r), lambda = 1e-3;
  for (uint32_t step = 0; step < max_steps; ++step) {
    // J (rows × n, column by column) by forward differences in u.
    const size_t rows = r.size();
    std::vector<std::vector<double>> jacobian(n);
    for (size_t g = 0; g < n; ++g) {
      const double h = is_scale(g) ? 1e-4 : 1e-4 * (upper[g] - lower[g]);
      std::vector<double> moved = u;
      moved[g] += h;
      const std::vector<double> shifted = residuals(to_x(moved));
      ++report.evaluations;
      jacobian[g].resize(rows);
      for (size_t i = 0; i < rows; ++i) jacobian[g][i] = (shifted[i] - r[i]) / h;
    }
    std::vector<double> jtj(n * n), jtr(n);
    double largest = 0;
    for (size_t a = 0; a < n; ++a) {
      for (size_t b = 0; b <= a; ++b) {
        double sum = 0;
        for (size_t i = 0; i < rows; ++i) sum += jacobian[a][i] * jacobian[b][i];
        jtj[a * n + b] = jtj[b * n + a] = sum;
      }
      double sum = 0;
      for (size_t i = 0; i < rows; ++i) sum += jacobian[a][i] * r[i];
      jtr[a] = sum;
      largest = std::max(largest, jtj[a * n + a]);
    }
    bool improved = false;
    for (int tries = 0; tries < 12 && !improved; ++tries, lambda *= 10) {
      // Marquardt's scaling, with a floor for genes the image does not see (σ_s and g
      // move σ′_s together: one direction of the dipole's genes has no effect).
      std::vector<double> m = jtj, delta(n);
      for (size_t g = 0; g < n; ++g) {
        m[g * n + g] += lambda * std::max(jtj[g * n + g], 1e-12 * largest);
        delta[g] = -jtr[g];
      }
      if (!cholesky_solve(m, n, &delta)) continue;
      std::vector<double> next = u;
      for (size_t g = 0; g < n; ++g) next[g] += delta[g];
      const std::vector<double> x = to_x(next), rx = residuals(x);
      ++report.evaluations;
      const double c = norm2(rx);
      if (std::isfinite(c) && c < cost) {
        improved = true;
        const bool settled = cost - c <= 1e-12 * cost;
        u = to_u(x);
        r = rx;
        cost = c;
        *genes = x;
        ++report.steps;
        lambda = std::max(lambda / 100, 1e-12);  // the loop's ×10 follows
        if (settled) step = max_steps;
      }
    }
    if (!improved) break;
  }
  report.fitness = std::sqrt(cost);
  return report;
}

}  // namespace arcus::translucency
