#include "core/launch.h"

#include <string>

#include "core/error.h"

namespace arcus {

KernelLaunch::KernelLaunch(arcus_context_t* ctx, cl_program program, const char* kernel, const char* const* names,
                           unsigned count)
    : ctx_(ctx),
      call_(program, kernel), kernel_(kernel), names_(names), args_(call_.arg_count()) {
  if (args_ > count || args_ > 64)
    fail(ARCUS_ERROR_INVALID_ARGUMENT, std::string(kernel) + " takes " + std::to_string(args_) +
                                           " arguments; its list names " + std::to_string(count));
}

void KernelLaunch::bind_buffer(unsigned arg, const DeviceBuffer* buffer) {
  call_.set(arg, buffer);
  bound_ |= uint64_t(1) << arg;
}

void KernelLaunch::bind_bytes(unsigned arg, size_t size, const void* value) {
  call_.set_raw(arg, size, value);
  bound_ |= uint64_t(1) << arg;
}

void KernelLaunch::upload_bytes(unsigned arg, const void* data, size_t bytes, const std::string& what) {
  inputs_.push_back(std::make_unique<DeviceBuffer>(ctx_, bytes, what, data));
  bind_buffer(arg, inputs_.back().get());
}

double KernelLaunch::run(size_t items) {
  for (unsigned a = 0; a < args_; ++a)
    if (!(bound_ >> a & 1))
      fail(ARCUS_ERROR_INVALID_ARGUMENT, std::string(kernel_) + ": argument " + names_[a] + " is not bound");
  return call_.run(ctx_, items);
}

bool KernelLaunch::run_slices(SliceRange& range, const std::function<size_t(uint64_t, uint64_t)>& slice,
                              arcus_job_stats* stats) {
  SliceJob job;
  job.first_units = range.first_units;
  job.launch = [&](int64_t units, bool) {
    const uint64_t n = std::min<uint64_t>(static_cast<uint64_t>(std::max<int64_t>(units, 1)), range.most_units);
    const uint64_t first = range.done, end = std::min(range.total, first + n);
    const double seconds = run(slice(first, end));
    range.done = end;
    return seconds;
  };
  job.finished = [&] { return range.done >= range.total; };
  job.fraction = [&] { return static_cast<double>(range.done) / static_cast<double>(range.total); };
  job.progress = range.progress;
  job.progress_user = range.progress_user;
  return run_in_slices(job, stats);
}

}  // namespace arcus
