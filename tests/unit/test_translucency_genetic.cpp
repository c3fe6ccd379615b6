// The genetic search (src/translucency/genetic.h) on a fitness whose minimum is known:
// the distance to a target point.  The best fitness never rises (the best survives),
// every gene stays within its bounds, a threshold stops it early, it closes in on the
// target, and the same seed gives the same history (a determinism test).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "translucency/genetic.h"

namespace {

using arcus::translucency::genetic_search;
using arcus::translucency::GeneticHistory;
using arcus::translucency::GeneticSettings;

const std::vector<double> kTarget = {0.003, 2.5, -0.4, 1.45};

GeneticSettings settings(uint64_t seed) {
  GeneticSettings s;
  s.seed = seed;
  s.initial = {1, 1, 0, 1.3};       // Table 3.1-like: far from the target
  s.lower = {1e-4, 0.01, -0.9, 1.05};
  s.upper = {5, 10, 0.95, 2};
  return s;
}

double distance(const std::vector<double>& g) {
  // Relative in the scales (a coefficient of 0.003 matters as much as one of 2.5).
  double sum = 0;
  for (size_t i = 0; i < g.size(); ++i) {
    const double d = i == 2 ? g[i] - kTarget[i] : std::log(g[i] / kTarget[i]);
    sum += d * d;
  }
  return std::sqrt(sum);
}

TEST(TranslucencyGenetic, TheBestNeverRisesGenesStayInBoundsAndTheTargetIsApproached) {
  GeneticSettings s = settings(7);
  s.generations = 200;
  const GeneticSettings bounds = s;
  const GeneticHistory h = genetic_search(s, [&](const std::vector<double>& g) {
    for (size_t i = 0; i < g.size(); ++i) {
      EXPECT_GE(g[i], bounds.lower[i]);
      EXPECT_LE(g[i], bounds.upper[i]);
    }
    return distance(g);
  }, nullptr);
  ASSERT_EQ(h.best_fitness.size(), 201u);
  for (size_t k = 1; k < h.best_fitness.size(); ++k) EXPECT_LE(h.best_fitness[k], h.best_fitness[k - 1]) << k;
  EXPECT_GT(h.best_fitness.front(), 5.0);   // ln(1/0.003) alone is 5.8
  EXPECT_LT(h.best_fitness.back(), 0.1);    // within ~10% in every gene
  EXPECT_EQ(h.evaluations, 40u + 200u * 32u);  // 40 seeded, then 80% of 40 replaced each time
}

TEST(TranslucencyGenetic, AThresholdStopsTheSearchEarly) {
  GeneticSettings s = settings(3);
  s.generations = 1000;
  s.threshold = 0.5;
  const GeneticHistory h = genetic_search(s, distance, nullptr);
  EXPECT_LE(h.best_fitness.back(), 0.5);
  EXPECT_LT(h.best_fitness.size(), 1001u);
  EXPECT_GT(h.best_fitness[h.best_fitness.size() - 2], 0.5);  // it went one generation past nothing
}

TEST(TranslucencyGenetic, TheSameSeedGivesTheSameHistoryDeterminism) {
  GeneticSettings s = settings(11);
  s.generations = 30;
  const GeneticHistory a = genetic_search(s, distance, nullptr), b = genetic_search(s, distance, nullptr);
  EXPECT_EQ(a.best_fitness, b.best_fitness);
  EXPECT_EQ(a.mean_fitness, b.mean_fitness);
  EXPECT_EQ(a.best_genes, b.best_genes);
  s.seed = 12;
  EXPECT_NE(genetic_search(s, distance, nullptr).mean_fitness, a.mean_fitness);
}

TEST(TranslucencyGenetic, TheHookSeesEveryGenerationAndCanStopIt) {
  GeneticSettings s = settings(5);
  s.generations = 50;
  std::vector<uint32_t> seen;
  const GeneticHistory h = genetic_search(s, distance, [&](uint32_t generation, double, const double*) {
    seen.push_back(generation);
    return generation == 9;
  });
  EXPECT_TRUE(h.cancelled);
  EXPECT_EQ(seen.size(), 10u);
  EXPECT_EQ(seen.back(), 9u);
  EXPECT_EQ(h.best_fitness.size(), 10u);
}

}  // namespace
