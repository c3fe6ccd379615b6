// Device-resident buffers: memory on the context's device that outlives a single job
// (a field's data, a job's ray state, later photon maps and BVHs), so one job can hand
// it to the next without a round trip through the host.  Owned by whatever object
// holds it (shared), counted against the context, released with its last owner.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <string>

#include "core/context.h"

namespace arcus {

class DeviceBuffer {
 public:
  // `bytes` on ctx's device, uninitialised (a kernel fills it) or copied from `host`.
  // `what` names the buffer in errors: one larger than the device allows, or than the
  // memory it has left, is ARCUS_ERROR_OUT_OF_MEMORY, checked before allocating.
  DeviceBuffer(arcus_context_t* ctx, size_t bytes, const std::string& what, const void* host = nullptr);
  ~DeviceBuffer();
  DeviceBuffer(const DeviceBuffer&) = delete;
  DeviceBuffer& operator=(const DeviceBuffer&) = delete;

  cl_mem get() const { return mem_.get(); }
  size_t bytes() const { return bytes_; }
  // Blocking copies on ctx's queue.
  void read(arcus_context_t* ctx, size_t offset, size_t bytes, void* out) const;
  void write(arcus_context_t* ctx, size_t offset, size_t bytes, const void* in);

 private:
  std::shared_ptr<DeviceRuntime> runtime_;  // keeps the cl_context alive
  std::shared_ptr<std::atomic<uint64_t>> account_;
  ClMem mem_;
  size_t bytes_;
};

// Throws ARCUS_ERROR_OUT_OF_MEMORY naming `what` unless one buffer of `bytes` fits the
// device; `total` bytes (several buffers of one job) must fit what the device has left.
void check_device_allocation(const arcus_context_t* ctx, double bytes, double total, const std::string& what);

// One kernel of a program with its arguments, launched on a context's queue.  Engines
// set arguments and launch through it: no OpenCL calls in their job code.
class KernelCall {
 public:
  KernelCall(cl_program program, const char* name);
  void set(unsigned index, const DeviceBuffer* buffer);  // null: a NULL buffer argument
  template <class T>
  void set_value(unsigned index, const T& value) {
    set_raw(index, sizeof value, &value);
  }
  void set_raw(unsigned index, size_t size, const void* value);
  unsigned arg_count() const;  // CL_KERNEL_NUM_ARGS: kept in program binaries too
  // Runs `items` work-items (local size: local_work_size) and waits; returns the device
  // time from the profiling events.
  double run(arcus_context_t* ctx, size_t items);

 private:
  ClKernel kernel_;
  std::string name_;
};

}  // namespace arcus
