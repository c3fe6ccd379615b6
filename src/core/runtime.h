// OpenCL devices and the per-device runtime: one cl_context per device shared by all
// arcus contexts on it, and the cache of built programs keyed by feature set.
#pragma once

#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "arcus/arcus.h"
#include "core/opencl.h"

namespace arcus {

struct DeviceEntry {
  cl_platform_id platform;
  cl_device_id device;
  arcus_device_info info;
};

// Every OpenCL device of every platform, enumerated once per process.
const std::vector<DeviceEntry>& devices();

// Resolves ARCUS_DEVICE_DEFAULT (environment ARCUS_DEVICE, else first GPU, else first
// CPU, else first device) or checks an explicit index; throws DEVICE_NOT_FOUND.
uint32_t resolve_device(int32_t requested);

struct BuiltProgram {
  cl_program program;
  double build_seconds;
  bool cache_hit;
};

class DeviceRuntime {
 public:
  explicit DeviceRuntime(uint32_t device_index);
  ~DeviceRuntime();
  DeviceRuntime(const DeviceRuntime&) = delete;
  DeviceRuntime& operator=(const DeviceRuntime&) = delete;

  const DeviceEntry& entry() const { return entry_; }
  cl_context context() const { return context_.get(); }

  // The advance program built with `options` (its feature set), from the cache when
  // it was built before.  A failed build throws ARCUS_ERROR_KERNEL_BUILD with the log.
  BuiltProgram program(const std::string& options);

 private:
  DeviceEntry entry_;
  ClContext context_;
  std::mutex mutex_;
  std::map<std::string, ClProgram> programs_;
};

// The shared runtime of a device (created on first use, freed with its last user).
std::shared_ptr<DeviceRuntime> runtime_for(uint32_t device_index);

// The embedded kernel sources, concatenated in include order (generated at build).
const std::string& advance_program_source();

}  // namespace arcus
