// The OpenCL headers as arcus uses them (1.2 API, available on PoCL and GPU drivers).
#pragma once

#ifndef CL_TARGET_OPENCL_VERSION
#define CL_TARGET_OPENCL_VERSION 120
#endif
#include <CL/cl.h>

#include <string>

namespace arcus {

// "CL_OUT_OF_RESOURCES (-5)" for an OpenCL error code.
std::string cl_error_name(cl_int code);

// Throws ARCUS_ERROR_OPENCL naming the call unless code is CL_SUCCESS.
void check_cl(cl_int code, const char* call);

// RAII owner of one OpenCL object (mem, kernel, event, ...).
template <class T, cl_int (*Release)(T)>
class ClHandle {
 public:
  ClHandle() = default;
  explicit ClHandle(T h) : h_(h) {}
  ClHandle(const ClHandle&) = delete;
  ClHandle& operator=(const ClHandle&) = delete;
  ClHandle(ClHandle&& o) noexcept : h_(o.h_) { o.h_ = nullptr; }
  ClHandle& operator=(ClHandle&& o) noexcept {
    reset();
    h_ = o.h_;
    o.h_ = nullptr;
    return *this;
  }
  ~ClHandle() { reset(); }
  void reset() {
    if (h_) Release(h_);
    h_ = nullptr;
  }
  T get() const { return h_; }
  explicit operator bool() const { return h_ != nullptr; }

 private:
  T h_ = nullptr;
};

using ClMem = ClHandle<cl_mem, clReleaseMemObject>;
using ClKernel = ClHandle<cl_kernel, clReleaseKernel>;
using ClEvent = ClHandle<cl_event, clReleaseEvent>;
using ClQueue = ClHandle<cl_command_queue, clReleaseCommandQueue>;
using ClContext = ClHandle<cl_context, clReleaseContext>;
using ClProgram = ClHandle<cl_program, clReleaseProgram>;

}  // namespace arcus
