#include "translucency/inverse.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <string>

#include "core/error.h"
#include "core/format.h"
#include "translucency/appearance.h"
#include "translucency/genetic.h"
#include "translucency/surface.h"

namespace arcus::translucency {
namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The genes' names for messages, in order.
const char* gene_name(int32_t model, size_t g) {
  static const char* dipole[] = {"sigma_a R", "sigma_a G", "sigma_a B", "sigma_s R", "sigma_s G",
                                 "sigma_s B", "g",         "eta",       "b"};
  static const char* phong[] = {"k_d R", "k_d G", "k_d B", "k_s", "b"};
  return model == ARCUS_GENETIC_DIPOLE ? dipole[g] : phong[g];
}

// Bounds the models need whatever the caller asks: positive coefficients, g < 1 (σ_s′ >
// 0), η within F_dr's fit, a highlight angle in (0, 90).
void check_bounds(const arcus_genetic_params& p) {
  const uint32_t n = gene_count(p.model);
  for (uint32_t g = 0; g < n; ++g) {
    const std::string at = "[" + std::to_string(g) + "] (" + gene_name(p.model, g) + ")";
    require(std::isfinite(p.lower[g]) && std::isfinite(p.upper[g]) && p.lower[g] <= p.upper[g],
            "params->lower" + at + " = " + number(p.lower[g]) + " and params->upper" + at + " = " +
                number(p.upper[g]) + " are not finite bounds, lower <= upper");
    require(std::isfinite(p.initial[g]), "params->initial" + at + " = " + number(p.initial[g]) + " is not finite");
    double low = 0, high = INFINITY;  // what the model allows
    bool open_low = false;
    if (p.model == ARCUS_GENETIC_DIPOLE) {
      if (g >= 3 && g < 6) open_low = true;                    // σ_s > 0
      if (g == 6) low = -1, high = 1, open_low = true;         // |g| < 1
      if (g == 7) low = 1, high = 3;                           // η
      if (g == 8) low = 0, high = 90, open_low = true;         // b
    } else {
      if (g == 4) low = 0, high = 90, open_low = true;         // b
    }
    const bool ok = (open_low ? p.lower[g] > low : p.lower[g] >= low) &&
                    (g == 6 && p.model == ARCUS_GENETIC_DIPOLE ? p.upper[g] < high : p.upper[g] <= high);
    require(ok, "params->lower" + at + ".." + "upper = " + number(p.lower[g]) + ".." + number(p.upper[g]) +
                    " leaves the model's range (" + number(low) + ", " + number(high) + ")");
  }
}

void check_params(const arcus_genetic_params& p, uint32_t width, uint32_t height) {
  check_view(p.camera, p.ortho_height, p.mm_per_unit, ARCUS_EXIT_THESIS);
  require(p.model == ARCUS_GENETIC_DIPOLE || p.model == ARCUS_GENETIC_PHONG,
          "params->model = " + std::to_string(p.model) + " is not ARCUS_GENETIC_DIPOLE (0) or ARCUS_GENETIC_PHONG (1)");
  require(p.population >= 2 && p.population <= 10000,
          "params->population = " + std::to_string(p.population) + " is not 2..10000");
  require(p.generations <= 100000, "params->generations = " + std::to_string(p.generations) + " is not 0..100000");
  require(p.polish_steps <= 1000, "params->polish_steps = " + std::to_string(p.polish_steps) + " is not 0..1000");
  for (auto [value, name] : {std::pair{p.replacement, "replacement"}, std::pair{p.crossover, "crossover"},
                             std::pair{p.mutation, "mutation"}})
    require(std::isfinite(value) && value >= 0 && value <= 1,
            std::string("params->") + name + " = " + number(value) + " is not a probability in [0, 1]");
  require(std::isfinite(p.mutation_range) && p.mutation_range > 0 && p.mutation_range <= 10,
          "params->mutation_range = " + number(p.mutation_range) + " is not in (0, 10]");
  require(std::isfinite(p.fitness_threshold) && p.fitness_threshold >= 0,
          "params->fitness_threshold = " + number(p.fitness_threshold) + " is not a finite value >= 0");
  require(p.fitness_space == ARCUS_FITNESS_YCBCR || p.fitness_space == ARCUS_FITNESS_RGB,
          "params->fitness_space = " + std::to_string(p.fitness_space) +
              " is not ARCUS_FITNESS_YCBCR (0) or ARCUS_FITNESS_RGB (1)");
  check_bounds(p);
  require(width == p.camera.width && height == p.camera.height,
          "the target's " + std::to_string(width) + " × " + std::to_string(height) + " is not params->camera's " +
              std::to_string(p.camera.width) + " × " + std::to_string(p.camera.height));
}

// BT.601's YCbCr from (linear) RGB: the thesis' "perceptual" space (Poynton 1996).
void to_space(int32_t space, const double rgb[3], double out[3]) {
  if (space == ARCUS_FITNESS_RGB) {
    for (int c = 0; c < 3; ++c) out[c] = rgb[c];
    return;
  }
  out[0] = 0.299 * rgb[0] + 0.587 * rgb[1] + 0.114 * rgb[2];
  out[1] = -0.168736 * rgb[0] - 0.331264 * rgb[1] + 0.5 * rgb[2];
  out[2] = 0.5 * rgb[0] - 0.418688 * rgb[1] - 0.081312 * rgb[2];
}

// The caller's progress over a part [from, to] of the job: the cache's slices report
// into its first fifth, the generations into the rest (a non-decreasing fraction).
struct ProgressPart {
  arcus_progress_callback progress;
  void* user;
  double from, to;
  static int32_t report(void* self, double fraction) {
    const auto* part = static_cast<const ProgressPart*>(self);
    return part->progress(part->user, part->from + fraction * (part->to - part->from));
  }
};
constexpr double kCacheShare = 0.2;

std::vector<double> image_of(const AppearanceCache& cache, int32_t model, const double* genes) {
  if (model == ARCUS_GENETIC_PHONG) return phong_image(cache, genes, genes[3], genes[4]);
  arcus_dipole d{};
  for (int c = 0; c < 3; ++c) {
    d.sigma_a[c] = genes[c];
    d.sigma_s_prime[c] = (1 - genes[6]) * genes[3 + c];
  }
  d.eta = genes[7];
  return dipole_image(cache, d, genes[8]);
}

// Levenberg–Marquardt (genetic.h's polish) from each of the last population's best
// kPolishStarts distinct individuals (the valley has more than one low point: from one
// start a channel can slide to its dense end, a short ℓ_d against σ′_s's bound); the best
// result replaces *best_genes when it beats res->best_fitness.  The dipole is polished in
// what the image determines: σ_a, σ′_s, η, b, with g held at the individual's (σ_s and g
// alone only move σ′_s: free, the pair would drift along that direction into σ_s's
// bound).  Phong's genes are all seen.
void polish_best(const std::vector<std::vector<double>>& last, const GeneticSettings& s, bool dipole, uint32_t steps,
                 const std::function<std::vector<double>(const std::vector<double>&)>& residuals,
                 arcus_genetic_result* res, std::vector<double>* best_genes) {
  constexpr size_t kPolishStarts = 4;
  const auto polish_start = std::chrono::steady_clock::now();
  std::vector<std::vector<double>> starts;
  for (const std::vector<double>& genes_of : last)
    if (starts.size() < kPolishStarts && std::find(starts.begin(), starts.end(), genes_of) == starts.end())
      starts.push_back(genes_of);
  for (const std::vector<double>& from : starts) {
    // The dipole's polish variables: σ_a (3), σ′_s = (1 − g)σ_s (3), η, b.
    const double g = dipole ? from[6] : 0;
    auto to_genes = [&](const std::vector<double>& q) {
      if (!dipole) return q;
      return std::vector<double>{q[0], q[1], q[2], q[3] / (1 - g), q[4] / (1 - g), q[5] / (1 - g), g, q[6], q[7]};
    };
    auto to_polish = [&](const std::vector<double>& genes) {
      if (!dipole) return genes;
      return std::vector<double>{genes[0],           genes[1],           genes[2], (1 - g) * genes[3],
                                 (1 - g) * genes[4], (1 - g) * genes[5], genes[7], genes[8]};
    };
    std::vector<double> q = to_polish(from);
    const PolishReport polished = polish([&](const std::vector<double>& x) { return residuals(to_genes(x)); },
                                         to_polish(s.lower), to_polish(s.upper), steps, &q);
    res->polish_evaluations += polished.evaluations;
    if (polished.fitness < res->best_fitness) {
      res->best_fitness = polished.fitness;
      res->polish_steps = polished.steps;
      *best_genes = to_genes(q);
    }
  }
  res->polish_seconds = seconds_since(polish_start);
}

}  // namespace

uint32_t gene_count(int32_t model) { return model == ARCUS_GENETIC_PHONG ? 5 : 9; }

void genetic_defaults(int32_t model, arcus_genetic_params* p) {
  const double dipole_initial[] = {1, 1, 1, 1, 1, 1, 0, 1.3, 10};  // Table 3.1
  const double dipole_lower[] = {1e-4, 1e-4, 1e-4, 0.01, 0.01, 0.01, -0.9, 1.05, 1};
  const double dipole_upper[] = {5, 5, 5, 10, 10, 10, 0.95, 2, 45};
  const double phong_initial[] = {0.5, 0.5, 0.5, 0.5, 10};
  const double phong_lower[] = {0, 0, 0, 0, 1};
  const double phong_upper[] = {1, 1, 1, 1, 45};
  const bool phong = model == ARCUS_GENETIC_PHONG;
  for (uint32_t g = 0; g < gene_count(model); ++g) {
    p->initial[g] = phong ? phong_initial[g] : dipole_initial[g];
    p->lower[g] = phong ? phong_lower[g] : dipole_lower[g];
    p->upper[g] = phong ? phong_upper[g] : dipole_upper[g];
  }
}

std::unique_ptr<GeneticJob> genetic_inverse(arcus_context_t* ctx, const geometry::Mesh& mesh, uint32_t width,
                                            uint32_t height, const float* target,
                                            const std::vector<arcus_directional_light>& lights,
                                            const arcus_genetic_params& p, bool* cancelled) {
  const auto start = std::chrono::steady_clock::now();
  check_params(p, width, height);
  const std::vector<Light> light_list = lights_of(lights);
  const size_t full = size_t(width) * height;
  check_radiance(target, width, height, "target");
  *cancelled = false;
  auto job = std::make_unique<GeneticJob>(ctx);
  arcus_genetic_result& res = job->result;
  const uint32_t genes = gene_count(p.model);
  // η's nodes span its bounds (a Phong search has no η: any range serves).
  const double eta_low = p.model == ARCUS_GENETIC_DIPOLE ? p.lower[7] : 1.3;
  const double eta_high = p.model == ARCUS_GENETIC_DIPOLE ? std::max(p.upper[7], p.lower[7] + 1e-3) : 1.4;
  ProgressPart cache_part{p.progress, p.progress_user, 0, kCacheShare};
  const AppearanceCache cache =
      appearance_cache(ctx, *job, mesh, p.camera, p.ortho_height, p.mm_per_unit, light_list, eta_low, eta_high,
                       p.progress ? &ProgressPart::report : nullptr, &cache_part, cancelled);
  res.cache_seconds = seconds_since(start);
  res.pixels = static_cast<uint32_t>(cache.pixels.size());
  res.samples = cache.samples;
  if (*cancelled) return job;

  // The target in the fitness' space, and its energy there.
  const size_t n = cache.pixels.size();
  std::vector<double> wanted(3 * n);
  double energy = 0;
  for (size_t k = 0; k < n; ++k) {
    const double rgb[3] = {target[3 * cache.pixels[k]], target[3 * cache.pixels[k] + 1], target[3 * cache.pixels[k] + 2]};
    to_space(p.fitness_space, rgb, &wanted[3 * k]);
    for (int c = 0; c < 3; ++c) energy += wanted[3 * k + size_t(c)] * wanted[3 * k + size_t(c)];
  }
  require(energy > 0, "target: every pixel where the mesh is seen is black");
  // Per pixel and channel of the fitness' space, (image − target)/sqrt(energy): the
  // fitness is their norm, the relative RMS difference.
  auto residuals = [&](const std::vector<double>& g) {
    const std::vector<double> image = image_of(cache, p.model, g.data());
    std::vector<double> r(3 * n);
    const double scale = 1 / std::sqrt(energy);
    for (size_t k = 0; k < n; ++k) {
      double v[3];
      to_space(p.fitness_space, &image[3 * k], v);
      for (size_t c = 0; c < 3; ++c) r[3 * k + c] = (v[c] - wanted[3 * k + c]) * scale;
    }
    return r;
  };
  auto fitness = [&](const std::vector<double>& g) {
    double cost = 0;
    for (double v : residuals(g)) cost += v * v;
    return std::sqrt(cost);
  };

  const auto search_start = std::chrono::steady_clock::now();
  GeneticSettings s;
  s.population = p.population;
  s.generations = p.generations;
  s.replacement = p.replacement;
  s.crossover = p.crossover;
  s.mutation = p.mutation;
  s.mutation_range = p.mutation_range;
  s.threshold = p.fitness_threshold;
  s.seed = p.seed;
  s.initial.assign(p.initial, p.initial + genes);
  s.lower.assign(p.lower, p.lower + genes);
  s.upper.assign(p.upper, p.upper + genes);
  auto hook = [&](uint32_t generation, double best, const double* best_genes) {
    bool stop = false;
    if (p.on_generation) stop = p.on_generation(p.generation_user, generation, best, best_genes) != 0;
    if (p.progress && p.generations > 0)
      stop = p.progress(p.progress_user, kCacheShare + (1 - kCacheShare) * generation / p.generations) != 0 || stop;
    return stop;
  };
  const GeneticHistory history = genetic_search(s, fitness, hook);
  *cancelled = history.cancelled;
  res.search_seconds = seconds_since(search_start);
  res.model = p.model;
  res.gene_count = genes;
  res.generations_run = static_cast<uint32_t>(history.best_fitness.size() - 1);
  res.evaluations = history.evaluations;
  std::vector<double> best_genes(history.best_genes.end() - genes, history.best_genes.end());
  res.search_fitness = res.best_fitness = history.best_fitness.back();
  if (p.polish_steps > 0 && !*cancelled)
    polish_best(history.last, s, p.model == ARCUS_GENETIC_DIPOLE, p.polish_steps, residuals, &res, &best_genes);
  const double* best = best_genes.data();
  std::copy(best, best + genes, res.best);
  if (p.model == ARCUS_GENETIC_DIPOLE)
    for (int c = 0; c < 3; ++c) res.sigma_s_prime[c] = (1 - best[6]) * best[3 + c];
  job->best_fitness = history.best_fitness;
  job->mean_fitness = history.mean_fitness;
  job->best_genes = history.best_genes;
  const std::vector<double> image = image_of(cache, p.model, best);
  job->image.assign(3 * full, 0.0f);
  for (size_t k = 0; k < n; ++k)
    for (int c = 0; c < 3; ++c) job->image[3 * cache.pixels[k] + size_t(c)] = static_cast<float>(image[3 * k + size_t(c)]);
  job->count = n;
  job->stats.total_seconds = seconds_since(start);
  return job;
}

}  // namespace arcus::translucency
