// Advancing a batch of rays through a field on the context's device.
#pragma once

#include <string>

#include "arcus/arcus.h"

namespace arcus {

// The body of arcus_advance: validates, builds (or reuses) the kernel for the job's
// feature set, runs it and fills a new job.  Returns SUCCESS or a partial status
// (INVALID_RAYS, PATH_OVERFLOW) with *message set; throws on other errors.
arcus_status advance(arcus_context_t* ctx, arcus_field_t* field, const arcus_advance_params& params, size_t count,
                     const double* origins, const double* directions, arcus_job_t** job, std::string* message);

// Fills params with the documented defaults.
void default_advance_params(arcus_advance_params* params);

// Names of the feature bits, space separated.
std::string feature_names(uint32_t features);

}  // namespace arcus
