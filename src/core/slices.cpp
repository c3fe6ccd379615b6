#include "core/slices.h"

#include <algorithm>
#include <atomic>

namespace arcus {
namespace {

constexpr double kSliceSeconds = 0.25;  // progress four times a second; short GPU launches
std::atomic<int64_t> g_slice_units{0};

}  // namespace

namespace testing {
void set_slice_units(int64_t units) { g_slice_units = units; }
}  // namespace testing

bool run_in_slices(const SliceJob& job, arcus_job_stats* stats) {
  const int64_t fixed = g_slice_units.load();
  double units = fixed ? static_cast<double>(fixed) : std::max(1.0, job.first_units);
  double reported = 0;
  for (bool first = true;; first = false) {
    const double seconds = job.launch(static_cast<int64_t>(units), first);
    stats->kernel_seconds += seconds;
    stats->launches += 1;
    // Towards kSliceSeconds, but never more than 8× or less than half at once: one
    // launch's time is a noisy guide.
    if (!fixed) units = std::clamp(units * kSliceSeconds / std::max(seconds, 1e-6), std::max(1.0, units / 2), units * 8);
    if (job.finished()) break;
    if (job.progress) {
      reported = std::max(reported, std::min(job.fraction(), 1.0));
      if (job.progress(job.progress_user, reported) != 0) return true;
    }
  }
  if (job.progress) job.progress(job.progress_user, 1.0);
  return false;
}

}  // namespace arcus
