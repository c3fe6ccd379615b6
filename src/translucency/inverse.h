// Genetic inverse rendering (thesis §3.2, §5.1): the appearance cache of the target's
// view (appearance.h), a fitness comparing the cache's image for some genes with the
// target (relative RMS difference in YCbCr or RGB), and the genetic search (genetic.h).
#pragma once

#include <memory>
#include <vector>

#include "arcus/arcus_translucency.h"
#include "core/job.h"
#include "geometry/mesh.h"

namespace arcus::translucency {

struct GeneticJob : arcus_job_s {
  explicit GeneticJob(arcus_context_t* ctx) : arcus_job_s(ctx, "translucency genetic search") {}
  arcus_genetic_result result{};
  std::vector<double> best_fitness, mean_fitness, best_genes;
  std::vector<float> image;  // the best individual's, width × height × 3
};

// The model's gene count, its defaults (Table 3.1) and bounds.
uint32_t gene_count(int32_t model);
void genetic_defaults(int32_t model, arcus_genetic_params* params);

// Checks every parameter, naming it as the C API does, and searches.
std::unique_ptr<GeneticJob> genetic_inverse(arcus_context_t* ctx, const geometry::Mesh& mesh, uint32_t width,
                                            uint32_t height, const float* target,
                                            const std::vector<arcus_directional_light>& lights,
                                            const arcus_genetic_params& params, bool* cancelled);

}  // namespace arcus::translucency
