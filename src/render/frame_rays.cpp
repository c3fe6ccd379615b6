#include "render/frame_rays.h"

#include <algorithm>
#include <cmath>

namespace arcus::render {

uint64_t percentile999(std::vector<uint64_t> steps) {
  if (steps.empty()) return 0;
  const size_t at = steps.size() * 999 / 1000;
  std::nth_element(steps.begin(), steps.begin() + static_cast<std::ptrdiff_t>(at), steps.end());
  return steps[at];
}

Frame camera_frame(const CameraDesc& c) {
  Frame f;
  f.origin = c.position;
  f.forward = normalized(c.look_at - f.origin);
  f.right = normalized(cross(f.forward, c.up));
  f.up = cross(f.right, f.forward);
  f.tan_half = std::tan(0.5 * c.vfov_deg * M_PI / 180.0);
  f.aspect = static_cast<double>(c.width) / c.height;
  return f;
}

Vec3 pixel_direction(const Frame& f, const CameraDesc& c, uint32_t i, uint32_t j) {
  const double px = (2.0 * (i + 0.5) / c.width - 1.0) * f.tan_half * f.aspect;
  const double py = (1.0 - 2.0 * (j + 0.5) / c.height) * f.tan_half;
  return f.forward + px * f.right + py * f.up;
}

uint64_t probe_steps(arcus_context_t* ctx, RenderScene* scene, const arcus_advance_params& params, const Batch& probe,
                     double* seconds) {
  const TraceOutput t = trace(ctx, scene, params, probe.input(false));
  *seconds += t.stats.total_seconds;
  return percentile999(t.steps);
}

int32_t end_step_of(int32_t status, int32_t hit_step) {
  if (status == ARCUS_STATUS_HIT) return hit_step;
  return status == ARCUS_STATUS_LEFT_BOX || status == ARCUS_STATUS_DONE ? kNoHit : -1;
}

uint32_t path_room(uint64_t steps) {
  return static_cast<uint32_t>(std::min<uint64_t>(steps + steps / 4 + 4, 1u << 20));
}

}  // namespace arcus::render
