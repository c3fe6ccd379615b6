// Tracing a batch of rays through a render scene: the curved engine's advance with the
// renderer's per-step hook (kernels/render/hits.h), so each ray stops on the first
// primitive its integrated path crosses.  One pass serves primary rays, retries of
// smart step selection, shadow rays and photons.
#pragma once

#include <cstdint>
#include <memory>
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
  // Any hit ends a ray where its chord hit, not moved onto the integrated path: for
  // rays that only ask whether they are blocked (shadow rays toward a sun).
  bool occlusion = false;
  // The rays leave a surface (shadow rays): smart step selection intersects their first
  // chord alone before proving the steps after it empty.
  bool from_surface = false;
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
  arcus_features features = 0;  // what the programs it ran compiled
  // Ray k of `from` as ray `to` of this one (the same size already).
  void copy_ray(size_t to, const TraceOutput& from, size_t k);
};

// Traces `in` through the scene with `params` (the box is the scene's bounds): each ray
// stops on the first primitive its path crosses.  Throws on errors; a cancelled trace
// is ARCUS_ERROR_CANCELLED.
TraceOutput trace(arcus_context_t* ctx, RenderScene* scene, arcus_advance_params params, const TraceInput& in);

// Recorded paths, kept on the device in the kernels' precision: path r's net points,
// each the whole state x y z vx vy vz s, are the first counts[r] of its `capacity`
// slots, point k at k·stride + r (step by step: a lane group's rays are neighbours);
// end_status[r] says how it ended.
struct DevicePaths {
  static constexpr int kReals = 7;
  std::shared_ptr<DeviceBuffer> points;
  uint32_t capacity = 0;
  size_t stride = 0;  // paths per step (the recording's padded count)
  std::vector<int32_t> counts, end_status;
  // Path caching's proofs (prove_chunks; none before): per path, `chunks` radii of the
  // capsules around its chunks of ARCUS_SMART_CHUNK chords (kernels/render/walk.cl).
  std::shared_ptr<DeviceBuffer> capsules;
  uint32_t chunks = 0;
  bool from_surface = false;  // recorded from TraceInput::from_surface rays
  size_t count() const { return counts.size(); }
  size_t bytes() const { return points ? points->bytes() : 0; }
};

// trace(), recording every ray's net points up to its hit as well (symmetry,
// undersampling and the path cache walk them again): the traced rays' results, and
// the paths in *paths.  `capacity`: points kept per path; a longer path keeps its
// first ones and counts as cut short (walks that run past its end are traced).
TraceOutput record_paths(arcus_context_t* ctx, RenderScene* scene, arcus_advance_params params, const TraceInput& in,
                         uint32_t capacity, DevicePaths* paths);

// Proves every chunk of every path's chords once (paths->capsules; the last chunk may
// be shorter; not for paths leaving a surface, whose first capsule meets it), so that
// walks predicting a later hit (path caching with smart step selection) prove the
// chunks before it with a test each instead of reading their points.
void prove_chunks(arcus_context_t* ctx, RenderScene* scene, const arcus_advance_params& params, DevicePaths* paths);

// A walked ray follows recorded path a; or, with b >= 0, the path interpolated between
// paths a and b at equal arc length along a's net points, as far as both reach
// (undersampling); either one mirrored in `plane` when `mirror` (symmetry).
struct WalkRay {
  int32_t a = 0, b = -1, mirror = 0;
};

// A mirror plane: points p with normal·p = offset (normal a unit vector).
struct MirrorPlane {
  double normal[3] = {1, 0, 0};
  double offset = 0;
};

// Intersects the walked rays' paths chord by chord, as trace() does while integrating:
// a recorded path gives the trace's hit exactly.  A walked ray that comes to the end of
// a path which ended on a hit without hitting anything itself (a mirrored or
// interpolated path, or a cached one after the scene moved) is UNRESOLVED: the path
// stops short of where this ray goes, so it must be traced.
TraceOutput walk(arcus_context_t* ctx, RenderScene* scene, arcus_advance_params params, const DevicePaths& paths,
                 const std::vector<WalkRay>& rays, const MirrorPlane& plane, const int32_t* predictions,
                 bool occlusion = false);  // as TraceInput::occlusion

// The render engine's feature table and its kernel source (features.cpp).
const KernelSource& trace_source();

}  // namespace arcus::render
