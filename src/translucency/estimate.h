// Estimating a BSSRDF from one HDR photograph (thesis §3.3.1; Muñoz et al. 2011): the
// photo downscaled, its matte, highlights and minimum; front and back points with their
// irradiance (eq. 3.10–3.11); the distance histograms of eq. 3.16 on the device
// (kernels/translucency/histogram.cl); per channel the least-squares solve
// (least_squares.h) and the dipole fit (fit.h).
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "arcus/arcus_translucency.h"
#include "core/job.h"
#include "geometry/mesh.h"

namespace arcus::translucency {

struct EstimateJob : arcus_job_s {
  explicit EstimateJob(arcus_context_t* ctx) : arcus_job_s(ctx, "translucency estimate") {}
  arcus_translucency_estimate_result result{};
  std::vector<double> edges, weights;  // m + 1; m × 3 (the profile's bin averages)
  // The system, per channel: a (3 × n × m), b (3 × n), x (3 × m); and what it is
  // assembled from: rows (n × 3), sources and their weights (2|𝕆| × 3), near (n × 3).
  std::vector<double> a, b, x, rows, sources, source_weights, near;
  // The front sources' sub-pixel points (3 each) and their E·ΔA (3 each), which stand
  // for the front sources within the refined radius.
  std::vector<double> sub_sources, sub_source_weights;
  // From an uncontrolled photograph (photo_estimate.h): what the photo gave in place of
  // the mesh and lights; empty otherwise.
  bool automatic = false;
  arcus_light_detection lights{};
  std::vector<double> depth, normals;  // per pixel of the photo
  std::vector<uint8_t> mask;
  geometry::Mesh relief;               // the closed mesh the estimate ran on, in pixels
};

// The luminance above which pixels are highlights (thesis §3.3.1 after Khan et al.
// 2006): over a 256-bin histogram of the object's luminances (counts summed over 5
// bins), the steepest fall (the minimum of the derivative) above its peak marks where
// the diffuse pixels end; from there the lowest count so far is the valley's floor, and
// the first count above it by more than counting noise (3 standard deviations) starts a
// highlight's bump: the cut.  INFINITY when none rises (no highlight).
double highlight_cut(const std::vector<double>& luminance);

// Checks every parameter, naming it as the C API does, and estimates.
std::unique_ptr<EstimateJob> estimate(arcus_context_t* ctx, const geometry::Mesh& mesh, uint32_t width,
                                      uint32_t height, const float* photo, const uint8_t* matte,
                                      const std::vector<arcus_directional_light>& lights,
                                      const arcus_translucency_estimate_params& params, bool* cancelled);

}  // namespace arcus::translucency
