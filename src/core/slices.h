// Long jobs run in slices: each launch does a bounded amount of work (`units`: steps,
// attempts, photons — the engine's choice), sized from the last launch's time to take
// about a quarter second, so a job can report progress, be cancelled, and never hold a
// GPU for long.  One driver for every engine's jobs and for the live preview.
#pragma once

#include <cstdint>
#include <functional>

#include "arcus/arcus_core.h"

namespace arcus {

struct SliceJob {
  double first_units;                                // the first launch's work
  std::function<double(int64_t units, bool first)> launch;  // runs a slice; its device seconds
  std::function<bool()> finished;                    // after a launch: is the job done?
  std::function<double()> fraction;                  // after a launch: how much is done (0..1)
  arcus_progress_callback progress = nullptr;        // the caller's callback, or null
  void* progress_user = nullptr;
};

// Runs the slices; adds the launches and their device time to *stats.  Returns true
// when the progress callback cancelled the job (then the work so far is kept).  On
// completion the callback sees 1.0 (its answer is ignored then).
bool run_in_slices(const SliceJob& job, arcus_job_stats* stats);

namespace testing {
// Every slice does exactly `units` (0: timed slices again).  Results must not depend on
// it (a determinism test checks).
void set_slice_units(int64_t units);
}  // namespace testing

}  // namespace arcus
