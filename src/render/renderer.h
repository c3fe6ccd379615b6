// Renderers and render jobs: a frame of a render scene through its medium (thesis
// §4.1.6), with the optimizations of §4.3 a caller switches on.
#pragma once

#include <cstdint>
#include <vector>

#include "arcus/arcus_render.h"
#include "core/job.h"
#include "render/photons.h"
#include "render/scene.h"
#include "render/trace.h"

namespace arcus::render {
// Every pixel's path for the path-based techniques: the recorded paths (on the device)
// and, per pixel, which of them it follows (mirrored, interpolated).
struct PathFrame {
  DevicePaths paths;
  std::vector<WalkRay> rays;
  MirrorPlane plane;
  arcus_features features = 0;  // the recording's program
};

// What one light's shadow rays leave to the next frame while the camera and the scene
// rest: the batch (to recognise it: the same origins and directions bit for bit), each
// ray's end step (smart step selection's temporal prediction) and, with PATH_CACHE,
// its recorded path (static lights, thesis §4.3.2.4), which the next frame walks.
struct ShadowMemory {
  std::vector<double> origins, directions;
  std::vector<int32_t> end_step;
  std::unique_ptr<DevicePaths> paths;
  uint64_t steps_p999 = 0;  // the 99.9th percentile of the rays' steps
};
}  // namespace arcus::render

namespace arcus::render {
extern const HandleKind kRendererHandle;  // "renderer"
}  // namespace arcus::render

struct arcus_renderer_s : arcus::Handle {
  arcus_renderer_s(arcus_context_t* ctx, arcus::render::RenderScene* scene);
  ~arcus_renderer_s() override;

  arcus::render::RenderScene* scene;  // a reference
  arcus::render::CameraDesc camera;
  uint32_t techniques = 0;
  arcus_advance_params params{};
  // What the last frame leaves to the next while the camera rests: each pixel's hit
  // step (smart step selection's temporal prediction) and, with PATH_CACHE, every
  // pixel's path (thesis §4.3.2.4; on the host, its size reported as cache_bytes).
  std::vector<int32_t> previous_hit_step;
  uint64_t previous_steps = 0;  // the 99.9th percentile of the primary rays' steps
  std::unique_ptr<arcus::render::PathFrame> cached_paths;
  // The photons' first generation and its end steps (render/photons.h: PATH_CACHE,
  // SMART_STEP's temporal prediction); it checks its own key, and is dropped with the frames.
  std::unique_ptr<arcus::render::PhotonCache> photon_cache;
  std::vector<arcus::render::ShadowMemory> shadow_memory;  // one per light

  void reset_frames() {
    previous_hit_step.clear();
    previous_steps = 0;
    cached_paths.reset();
    photon_cache.reset();
    shadow_memory.clear();
  }
};

namespace arcus::render {

struct RenderJob : arcus_job_s {
  explicit RenderJob(arcus_context_t* ctx) : arcus_job_s(ctx, "render") {}
  uint32_t width = 0, height = 0;
  double exposure = 1;
  std::vector<float> rgb;  // width × height × 3
  std::vector<double> points, distances;
  std::vector<int32_t> objects, primitives;
  std::vector<uint32_t> steps, tests;
  arcus_render_stats render_stats{};
};

// Why `techniques` cannot be used for this renderer's scene and camera ("" if they can).
std::string technique_problem(const arcus_renderer_s& r, uint32_t techniques);

// Renders one frame (throws on errors, ARCUS_ERROR_CANCELLED when cancelled).
std::unique_ptr<RenderJob> render_frame(arcus_renderer_s* r, arcus_progress_callback progress, void* user);

}  // namespace arcus::render
