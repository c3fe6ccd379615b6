// The documented defaults of arcus_advance_params, in one place for the API
// (arcus_advance_params_init) and the scene reader; host-only, no OpenCL.
#pragma once

#include "arcus/arcus_curved.h"

namespace arcus::curved {

// Fills params with the defaults arcus_curved.h documents.
void default_advance_params(arcus_advance_params* params);

}  // namespace arcus::curved
