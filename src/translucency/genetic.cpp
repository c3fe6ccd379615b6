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
  return history;
}

}  // namespace arcus::translucency
