// What every engine's job shares: the handle, its item count, the features it compiled
// and how it ran.  Engines derive their own job (curved: AdvanceJob) with the results;
// nothing here assumes a job copies its results to the host or frees its buffers.
#pragma once

#include "arcus/arcus_core.h"
#include "core/handle.h"
#include "core/layout.h"
#include "core/runtime.h"

struct arcus_job_s : arcus::Handle {
  arcus_job_s(arcus_context_t* ctx, const char* kind) : Handle(arcus::kJobHandle, ctx), kind(kind) {}
  const char* kind;  // "advance", ...: which engine's getters apply
  size_t count = 0;
  arcus_features features = 0;
  arcus_job_stats stats{};
};

namespace arcus {
struct KernelSource;

// The job's program for its features in `layout`, built or found in the caches, with
// how it came (build seconds, origin) and the layout recorded in the job's stats.
BuiltProgram build_job_program(arcus_context_t* ctx, arcus_job_s& job, const KernelSource& source,
                               const Layout& layout);
}  // namespace arcus
