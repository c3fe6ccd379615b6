// Kernel launches: arguments bound by name, and a job run in slices.
//
// Each kernel's arguments are listed once, in its engine's kernels/<engine>/*_desc.h
// (shared by host and kernel), as an X-macro of X(type, name):
//   #define ARCUS_OCEAN_TRACE_ARGS(X) X(__global const REAL*, water) X(const ocean_desc, d) ...
// The kernel's signature is made from it (ARCUS_PARAMS, common/real.h) and the host's
// indices and names from it (ARCUS_KERNEL_ARGS below), so the two cannot disagree.  No
// clGetKernelArgInfo: cached program binaries and some GPU drivers do not keep names.
#pragma once

#include <algorithm>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

#include "core/buffer.h"
#include "core/slices.h"

// struct NAME { enum Index {...the arguments..., kCount}; kernel; names[] }.
#define ARCUS_ARG_INDEX_(type, name) name,
#define ARCUS_ARG_NAME_(type, name) #name,
#define ARCUS_KERNEL_ARGS(NAME, KERNEL, LIST)                        \
  struct NAME {                                                      \
    enum Index : unsigned { LIST(ARCUS_ARG_INDEX_) kCount };         \
    static constexpr const char* kernel = KERNEL;                    \
    static constexpr const char* names[] = {LIST(ARCUS_ARG_NAME_)}; \
  }

namespace arcus {

// A job over units [0, total) in order, each launch a slice [first, end) of them.
struct SliceRange {
  uint64_t total = 0;
  double first_units = 1;                       // the first launch's units
  uint64_t most_units = UINT64_MAX;             // a launch's units at most (a scratch buffer's size)
  arcus_progress_callback progress = nullptr;  // the caller's callback, or null
  void* progress_user = nullptr;
  uint64_t done = 0;  // after the run: the units run (all, unless cancelled)
};

// The untyped part of Launch (launch.cpp).
class KernelLaunch {
 public:
  // Runs `items` work-items and waits; returns their device seconds.  Throws
  // INVALID_ARGUMENT naming the first argument of the kernel left unbound.
  double run(size_t items);
  // Runs `range` in slices (run_in_slices): slice(first, end) binds the slice's bounds
  // (in the kernel's description) and returns the work-items it needs.  Adds to
  // *stats; returns true when the progress callback cancelled.
  bool run_slices(SliceRange& range, const std::function<size_t(uint64_t, uint64_t)>& slice, arcus_job_stats* stats);
  // By index: for code that binds the same arguments of several kernels, each caller
  // naming them (Launch binds by name).
  void bind_buffer(unsigned arg, const DeviceBuffer* buffer);
  void bind_bytes(unsigned arg, size_t size, const void* value);
  void upload_bytes(unsigned arg, const void* data, size_t bytes, const std::string& what);

 protected:
  KernelLaunch(arcus_context_t* ctx, cl_program program, const char* kernel, const char* const* names, unsigned count);

 private:
  arcus_context_t* ctx_;
  KernelCall call_;
  std::vector<std::unique_ptr<DeviceBuffer>> inputs_;  // upload()'s
  const char* kernel_;
  const char* const* names_;
  unsigned args_;      // the kernel's (fewer than listed where a feature leaves some out)
  uint64_t bound_ = 0;  // a bit per argument
};

// A kernel of `program` whose arguments `Args` lists (ARCUS_KERNEL_ARGS), run on ctx.
template <class Args>
class Launch : public KernelLaunch {
 public:
  Launch(arcus_context_t* ctx, cl_program program) : KernelLaunch(ctx, program, Args::kernel, Args::names, Args::kCount) {}
  // A buffer; null: a NULL buffer argument.
  void bind(typename Args::Index arg, const DeviceBuffer* buffer) { bind_buffer(arg, buffer); }
  // A copy of `count` values on the device, kept by the launch: an input the kernel
  // only reads.  `what` names it in errors (DeviceBuffer).
  template <class T>
  void upload(typename Args::Index arg, const T* data, size_t count, const std::string& what) {
    upload_bytes(arg, data, count * sizeof(T), what);
  }
  template <class T>
  void upload(typename Args::Index arg, const std::vector<T>& data, const std::string& what) {
    upload(arg, data.data(), data.size(), what);
  }
  // A value: a scalar or a description struct passed by value.
  template <class T>
  void bind_value(typename Args::Index arg, const T& value) {
    static_assert(std::is_trivially_copyable_v<T> && !std::is_pointer_v<T>, "values only: buffers go through bind");
    bind_bytes(arg, sizeof value, &value);
  }
};

}  // namespace arcus
