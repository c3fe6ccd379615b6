#include "core/job.h"

#include "core/context.h"
#include "core/kernel_source.h"

namespace arcus {

BuiltProgram build_job_program(arcus_context_t* ctx, arcus_job_s& job, const KernelSource& source,
                               const Layout& layout) {
  const BuiltProgram built = ctx->runtime->program(source, job.features, layout);
  job.stats.build_seconds = built.seconds;
  job.stats.program_origin = built.origin;
  job.stats.lanes = layout.lanes;
  job.stats.groups = layout.groups;
  return built;
}

}  // namespace arcus
