// The per-device runtime: one cl_context per device, shared by every arcus context on
// it, and its programs, cached in memory and on disk.  A program is addressed by
// (kernel source, feature set, layout); the runtime owns everything that turns that
// address into build options (-cl-std, the layout defines, the features' options).
#pragma once

#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <tuple>

#include "arcus/arcus_core.h"
#include "core/device.h"
#include "core/kernel_source.h"
#include "core/layout.h"
#include "core/opencl.h"

namespace arcus {

struct BuiltProgram {
  cl_program program;
  double seconds;              // build, or load from disk; 0 from memory
  arcus_program_origin origin;
};

class DeviceRuntime {
 public:
  explicit DeviceRuntime(uint32_t device_index);
  DeviceRuntime(const DeviceRuntime&) = delete;
  DeviceRuntime& operator=(const DeviceRuntime&) = delete;

  const DeviceEntry& entry() const { return entry_; }
  cl_context context() const { return context_.get(); }

  // The program of `source` with `features` and `layout`: from memory, else from the
  // disk cache (ARCUS_CACHE_DIR), else built (and stored on disk).  A failed build
  // throws ARCUS_ERROR_KERNEL_BUILD with the compiler's log.
  BuiltProgram program(const KernelSource& source, arcus_features features, Layout layout);

  // The full build options of that program.
  std::string build_options(arcus_features features, Layout layout) const;

 private:
  using Key = std::tuple<std::string, arcus_features, uint32_t, uint32_t, std::string>;
  DeviceEntry entry_;
  ClContext context_;
  std::mutex mutex_;
  std::map<Key, ClProgram> programs_;
};

// The shared runtime of a device (created on first use, freed with its last user).
std::shared_ptr<DeviceRuntime> runtime_for(uint32_t device_index);

// The directory of the on-disk program cache ("" when ARCUS_CACHE_DIR=off or no home).
std::string program_cache_dir();

namespace testing {
// Options appended to every build from now on (to force ARCUS_ERROR_KERNEL_BUILD in
// tests); "" restores normal builds.  Not part of the C API.
void set_extra_build_options(const std::string& options);
}  // namespace testing

}  // namespace arcus
