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
