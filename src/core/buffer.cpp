#include "core/buffer.h"

#include <algorithm>
#include <cstring>

#include "core/error.h"
#include "core/format.h"

namespace arcus {
namespace {

std::string gib(double bytes) { return number(bytes / 1073741824.0) + " GiB"; }

}  // namespace

void check_device_allocation(const arcus_context_t* ctx, double bytes, double total, const std::string& what) {
  const DeviceEntry& d = ctx->runtime->entry();
  if (bytes > static_cast<double>(d.max_alloc))
    fail(ARCUS_ERROR_OUT_OF_MEMORY, what + " needs " + gib(bytes) + " in one buffer; the device allows at most " +
                                        gib(static_cast<double>(d.max_alloc)));
  const double used = static_cast<double>(ctx->device_bytes->load());
  const double memory = static_cast<double>(d.info.global_memory);
  if (used + total > memory)
    fail(ARCUS_ERROR_OUT_OF_MEMORY, what + " needs " + gib(total) + " of device memory; the device has " +
                                        gib(memory) + ", of which this context holds " + gib(used));
}

DeviceBuffer::DeviceBuffer(arcus_context_t* ctx, size_t bytes, const std::string& what, const void* host)
    : runtime_(ctx->runtime), account_(ctx->device_bytes), bytes_(bytes) {
  check_device_allocation(ctx, static_cast<double>(bytes), static_cast<double>(bytes), what);
  cl_int err = CL_SUCCESS;
  // OpenCL refuses empty buffers; a tiny one stands in for "no data".  The copy is read
  // over the whole (padded) size, so a short source goes through a padded copy.
  constexpr size_t kSmallest = 8;
  unsigned char padded[kSmallest] = {};
  if (host && bytes < kSmallest) {
    std::memcpy(padded, host, bytes);
    host = padded;
  }
  mem_ = ClMem(clCreateBuffer(runtime_->context(), CL_MEM_READ_WRITE | (host ? CL_MEM_COPY_HOST_PTR : 0),
                              std::max<size_t>(bytes, kSmallest), const_cast<void*>(host), &err));
  if (err == CL_MEM_OBJECT_ALLOCATION_FAILURE || err == CL_OUT_OF_HOST_MEMORY || err == CL_OUT_OF_RESOURCES ||
      err == CL_INVALID_BUFFER_SIZE)
    fail(ARCUS_ERROR_OUT_OF_MEMORY, what + ": the device could not allocate " + gib(static_cast<double>(bytes)) +
                                        " (" + cl_error_name(err) + ")");
  check_cl(err, "clCreateBuffer");
  account_->fetch_add(bytes_);
}

DeviceBuffer::~DeviceBuffer() { account_->fetch_sub(bytes_); }

void DeviceBuffer::read(arcus_context_t* ctx, size_t offset, size_t bytes, void* out) const {
  if (bytes)
    check_cl(clEnqueueReadBuffer(ctx->queue.get(), mem_.get(), CL_TRUE, offset, bytes, out, 0, nullptr, nullptr),
             "clEnqueueReadBuffer");
}

void DeviceBuffer::write(arcus_context_t* ctx, size_t offset, size_t bytes, const void* in) {
  if (bytes)
    check_cl(clEnqueueWriteBuffer(ctx->queue.get(), mem_.get(), CL_TRUE, offset, bytes, in, 0, nullptr, nullptr),
             "clEnqueueWriteBuffer");
}

KernelCall::KernelCall(cl_program program, const char* name) : name_(name) {
  cl_int err = CL_SUCCESS;
  kernel_ = ClKernel(clCreateKernel(program, name, &err));
  check_cl(err, "clCreateKernel");
}

void KernelCall::set(unsigned index, const DeviceBuffer* buffer) {
  cl_mem m = buffer ? buffer->get() : nullptr;
  set_raw(index, sizeof(cl_mem), buffer ? &m : nullptr);
}

void KernelCall::set_raw(unsigned index, size_t size, const void* value) {
  check_cl(clSetKernelArg(kernel_.get(), index, size, value), "clSetKernelArg");
}

unsigned KernelCall::arg_count() const {
  cl_uint n = 0;
  check_cl(clGetKernelInfo(kernel_.get(), CL_KERNEL_NUM_ARGS, sizeof n, &n, nullptr), "clGetKernelInfo");
  return n;
}

double KernelCall::run(arcus_context_t* ctx, size_t items) {
  const size_t local = local_work_size(ctx);
  cl_event raw = nullptr;
  check_cl(clEnqueueNDRangeKernel(ctx->queue.get(), kernel_.get(), 1, nullptr, &items, local ? &local : nullptr, 0,
                                  nullptr, &raw),
           "clEnqueueNDRangeKernel");
  ClEvent event(raw);
  check_cl(clWaitForEvents(1, &raw), "clWaitForEvents");
  cl_ulong t0 = 0, t1 = 0;
  if (clGetEventProfilingInfo(raw, CL_PROFILING_COMMAND_START, sizeof t0, &t0, nullptr) == CL_SUCCESS &&
      clGetEventProfilingInfo(raw, CL_PROFILING_COMMAND_END, sizeof t1, &t1, nullptr) == CL_SUCCESS)
    return (t1 - t0) * 1e-9;
  return 0.0;
}

}  // namespace arcus
