// Tracing a batch of rays through a render scene: the curved engine's advance with the
// renderer's per-step hook (kernels/render/hits.h), so each ray stops on the first
// primitive its integrated path crosses.  One pass serves primary rays, retries of
// smart step selection, shadow rays and photons.
#pragma once

#include <cstdint>
#include <vector>

#include "arcus/arcus_render.h"
#include "render/scene.h"

namespace arcus::render {

struct TraceInput {
  size_t count = 0;
  const double* origins = nullptr;     // count × 3
  const double* directions = nullptr;  // count × 3
  const double* wavelengths = nullptr; // count, or null
  const int32_t* predictions = nullptr; // count predicted hit steps (-1: none), or null
};

struct TraceOutput {
  std::vector<double> positions, directions, lengths;  // the hit, or where the ray stopped
  std::vector<uint64_t> steps;
  std::vector<int32_t> status;    // ARCUS_STATUS_* (render_desc.h: HIT, RETRY)
  std::vector<int32_t> object;    // the scene object hit, -1 for none
  std::vector<int32_t> primitive; // its triangle (mesh) or 0 (shape), -1 for none
  std::vector<int32_t> hit_kind;  // ARCUS_HIT_* (render_desc.h)
  std::vector<int32_t> hit_index; // triangle index over all meshes, or shape index
  std::vector<int32_t> hit_step;  // the step that hit, -1 for none
  std::vector<int32_t> tests;
  arcus_job_stats stats{};
};

// Traces `in` through the scene with `params` (the box is the scene's bounds).
// Throws on errors; a cancelled trace is ARCUS_ERROR_CANCELLED.
TraceOutput trace(arcus_context_t* ctx, RenderScene* scene, arcus_advance_params params, const TraceInput& in);

// The render engine's feature table and its kernel source (features.cpp).
const KernelSource& trace_source();

}  // namespace arcus::render
