// A genetic search for the genes that minimise a fitness (thesis §3.2, after Winter et
// al. 1995): a population seeded with one individual at the initial genes and the rest
// mutated from it; each generation ranks by fitness, replaces the worst fraction
// (`replacement`, never the best) by children of rank-selected survivors — one-point
// crossover with probability `crossover`, else a copy — each gene of a child mutated
// with probability `mutation` by ±0–`mutation_range` of itself when its lower bound is
// above 0 (a scale: σ_a spans decades, and the thesis mutates "±0–30% of their original
// value"), else of max(|x|, 10% of its range) (so a gene at 0 can move), clamped to its
// bounds.  It stops after `generations`, or
// once the best fitness is at most `threshold`.  The same settings and fitness give the
// same history bit for bit (its own random numbers: mt19937-64, 53-bit uniforms).
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

namespace arcus::translucency {

struct GeneticSettings {
  uint32_t population = 40, generations = 50;
  double replacement = 0.8, crossover = 0.8, mutation = 0.8, mutation_range = 0.3;
  double threshold = 0;  // stop once the best fitness is at most this (0: never)
  uint64_t seed = 0;
  std::vector<double> initial, lower, upper;  // one per gene
};

struct GeneticHistory {
  std::vector<double> best_fitness, mean_fitness;  // per generation, the first the seeded one
  std::vector<double> best_genes;                  // per generation, genes.size() each
  std::vector<std::vector<double>> last;           // the last population, best first
  uint64_t evaluations = 0;
  bool cancelled = false;
};

using Fitness = std::function<double(const std::vector<double>& genes)>;
// After each generation (0 the seeded population): true stops the search (cancelled).
using GenerationHook = std::function<bool(uint32_t generation, double best_fitness, const double* best_genes)>;

GeneticHistory genetic_search(const GeneticSettings& settings, const Fitness& fitness, const GenerationHook& hook);

// After the search (not in the thesis): Levenberg–Marquardt from `genes` on the residual
// vector whose norm is the fitness, in ln x for genes bounded above 0 (scales) and x for
// the others, the Jacobian by forward differences, clamped to the bounds; a step is kept
// only when the fitness falls, so it never rises.  The search finds the valley; its
// floor, long and shallow (a denser medium of the same albedo fits nearly as well), is
// what 40 × 50 random steps do not walk and a Gauss–Newton step does.
using Residuals = std::function<std::vector<double>(const std::vector<double>& genes)>;
struct PolishReport {
  uint32_t steps = 0;        // accepted
  uint64_t evaluations = 0;  // residual vectors computed
  double fitness = 0;        // |r| at the end
};
PolishReport polish(const Residuals& residuals, const std::vector<double>& lower, const std::vector<double>& upper,
                    uint32_t max_steps, std::vector<double>* genes);

}  // namespace arcus::translucency
