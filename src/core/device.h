// OpenCL devices as arcus sees them: enumerated once per process over all platforms,
// and the rule that picks the default one.
#pragma once

#include <string>
#include <vector>

#include "arcus/arcus_core.h"
#include "core/opencl.h"

namespace arcus {

struct DeviceEntry {
  cl_platform_id platform;
  cl_device_id device;
  arcus_device_info info;
  std::string driver_version;   // CL_DRIVER_VERSION (keys the program cache on disk)
  std::string platform_version; // CL_PLATFORM_VERSION
  uint64_t max_alloc = 0;       // CL_DEVICE_MAX_MEM_ALLOC_SIZE, bytes
};

// Every OpenCL device of every platform, enumerated once per process.
const std::vector<DeviceEntry>& devices();

// Resolves ARCUS_DEVICE_DEFAULT (environment ARCUS_DEVICE, else first GPU, else first
// CPU, else first device) or checks an explicit index; throws DEVICE_NOT_FOUND.
uint32_t resolve_device(int32_t requested);

}  // namespace arcus
