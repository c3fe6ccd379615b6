// How a kernel lays its items out over work-items: `lanes` items side by side in
// vector lanes, `groups` independent lane groups per work-item.  The device decides
// the lanes (its native double vector width on CPUs, 1 on GPUs), the engine the
// groups it prefers; ARCUS_LANES and ARCUS_GROUPS override both for experiments.
#pragma once

#include <cstdint>

#include "core/device.h"

namespace arcus {

struct Layout {
  uint32_t lanes = 1, groups = 1;
  uint32_t per_item() const { return lanes * groups; }
};

// The layout on `device` for an engine that prefers `cpu_groups` groups on CPUs (GPUs
// get one ray per work-item), after the environment's overrides.  A malformed or
// unsupported override ("8abc", "4294967304", "3" lanes) throws INVALID_ARGUMENT.
Layout choose_layout(const DeviceEntry& device, uint32_t cpu_groups);

// Parses a decimal number strictly (digits only, no sign or space, no overflow) and
// checks it against `allowed`; throws INVALID_ARGUMENT naming `variable`.
uint32_t parse_layout_value(const char* variable, const char* text, const uint32_t* allowed, int allowed_count);

}  // namespace arcus
