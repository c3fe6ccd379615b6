#include "fp64_peak.hpp"

#define CL_TARGET_OPENCL_VERSION 120
#include <CL/cl.h>

#include <algorithm>
#include <stdexcept>
#include <string>

namespace bench {
namespace {

void check(cl_int err, const char* what) {
  if (err != CL_SUCCESS) throw std::runtime_error(std::string("fp64 peak: ") + what + " failed (" + std::to_string(err) + ")");
}

std::string platform_string(cl_platform_id p, cl_platform_info what) {
  char buf[512] = {0};
  clGetPlatformInfo(p, what, sizeof buf - 1, buf, nullptr);
  return buf;
}

std::string device_string(cl_device_id d, cl_device_info what) {
  char buf[512] = {0};
  clGetDeviceInfo(d, what, sizeof buf - 1, buf, nullptr);
  return buf;
}

// arcus names its device by platform and device name; find the same one here.
cl_device_id find_device(const std::string& platform_name, const std::string& device_name, cl_platform_id* platform) {
  cl_uint np = 0;
  check(clGetPlatformIDs(0, nullptr, &np), "clGetPlatformIDs");
  std::vector<cl_platform_id> platforms(np);
  check(clGetPlatformIDs(np, platforms.data(), nullptr), "clGetPlatformIDs");
  for (cl_platform_id p : platforms) {
    if (platform_string(p, CL_PLATFORM_NAME) != platform_name) continue;
    cl_uint nd = 0;
    if (clGetDeviceIDs(p, CL_DEVICE_TYPE_ALL, 0, nullptr, &nd) != CL_SUCCESS) continue;
    std::vector<cl_device_id> devices(nd);
    check(clGetDeviceIDs(p, CL_DEVICE_TYPE_ALL, nd, devices.data(), nullptr), "clGetDeviceIDs");
    for (cl_device_id d : devices)
      if (device_string(d, CL_DEVICE_NAME) == device_name) {
        *platform = p;
        return d;
      }
  }
  throw std::runtime_error("fp64 peak: no OpenCL device named '" + device_name + "' on platform '" + platform_name + "'");
}

enum class Operation { Fma, Division };

// One work-item runs `chains` independent recurrences on doubleN vectors: x = fma(x, a, b)
// (a < 1 keeps x finite and normal, x → b / (1 − a)) or x = a / x (x alternates between
// x0 and a / x0).  Independent chains hide the latency (FMA: ≈4 cycles × 2 pipes needs
// ≥ 8 in flight); a and b are kernel arguments so the compiler cannot fold the loop.  The
// chains are summed and stored so none of them is dead code.
std::string kernel_source(Operation op, int width, int chains) {
  const std::string vec = "double" + std::to_string(width);
  std::string init, body, sum;
  for (int c = 0; c < chains; ++c) {
    const std::string x = "x" + std::to_string(c);
    // 1 + …: a division chain must not start at 0 (a / 0 = inf, a / inf = 0, …).
    init += "  " + vec + " " + x + " = (" + vec + ")(1.0 + seed + " + std::to_string(c) + ".0);\n";
    body += "    " + x + " = " + (op == Operation::Fma ? "fma(" + x + ", a, b)" : "a / " + x) + ";\n";
    sum += (c ? " + " : "") + x;
  }
  return "#pragma OPENCL EXTENSION cl_khr_fp64 : enable\n"
         "__kernel void chains(__global double* out, const int iterations, const double a, const double b) {\n"
         "  const double seed = (double)get_global_id(0) * 1e-6;\n" +
         init + "  for (int i = 0; i < iterations; ++i) {\n" + body + "  }\n" +
         "  vstore" + std::to_string(width) + "(" + sum + ", get_global_id(0), out);\n}\n";
}

struct ClSession {
  cl_context context = nullptr;
  cl_command_queue queue = nullptr;
  cl_device_id device = nullptr;
  cl_uint compute_units = 1;
  ~ClSession() {
    if (queue) clReleaseCommandQueue(queue);
    if (context) clReleaseContext(context);
  }
};

// Device seconds of one launch, from the profiling events.
double launch_seconds(ClSession& s, cl_kernel kernel, size_t global, size_t local, int iterations) {
  check(clSetKernelArg(kernel, 1, sizeof(int), &iterations), "clSetKernelArg");
  cl_event ev;
  check(clEnqueueNDRangeKernel(s.queue, kernel, 1, nullptr, &global, &local, 0, nullptr, &ev), "clEnqueueNDRangeKernel");
  check(clWaitForEvents(1, &ev), "clWaitForEvents");
  cl_ulong t0 = 0, t1 = 0;
  clGetEventProfilingInfo(ev, CL_PROFILING_COMMAND_START, sizeof t0, &t0, nullptr);
  clGetEventProfilingInfo(ev, CL_PROFILING_COMMAND_END, sizeof t1, &t1, nullptr);
  clReleaseEvent(ev);
  return (t1 - t0) * 1e-9;
}

// Operations (FMAs or divisions) per second of one variant.
double measure_variant(ClSession& s, Operation op, int width, int chains, double target_seconds) {
  const std::string src = kernel_source(op, width, chains);
  const char* text = src.c_str();
  cl_int err;
  cl_program program = clCreateProgramWithSource(s.context, 1, &text, nullptr, &err);
  check(err, "clCreateProgramWithSource");
  check(clBuildProgram(program, 1, &s.device, "", nullptr, nullptr), "clBuildProgram");
  cl_kernel kernel = clCreateKernel(program, "chains", &err);
  check(err, "clCreateKernel");

  // Several work-groups per core so every core stays busy to the end (PoCL runs one
  // work-group per core at a time: left to choose, it put all items in one group).
  const size_t local = 1, global = 16 * static_cast<size_t>(s.compute_units);
  cl_mem out = clCreateBuffer(s.context, CL_MEM_WRITE_ONLY, global * width * sizeof(double), nullptr, &err);
  check(err, "clCreateBuffer");
  const double a = 0.999999, b = 1e-6;
  check(clSetKernelArg(kernel, 0, sizeof out, &out), "clSetKernelArg");
  check(clSetKernelArg(kernel, 2, sizeof a, &a), "clSetKernelArg");
  check(clSetKernelArg(kernel, 3, sizeof b, &b), "clSetKernelArg");

  // The first launch pays for code generation; it also calibrates the iteration count.
  const int probe_iterations = 1 << 14;
  launch_seconds(s, kernel, global, local, probe_iterations);
  const double probe = launch_seconds(s, kernel, global, local, probe_iterations);
  const int iterations = static_cast<int>(std::clamp(probe_iterations * target_seconds / std::max(probe, 1e-6),
                                                     double(probe_iterations), 1e9));
  // The best of several launches: the least disturbed by other work on the cores.
  constexpr int kLaunches = 5;
  double best = 1e300;
  for (int r = 0; r < kLaunches; ++r) best = std::min(best, launch_seconds(s, kernel, global, local, iterations));

  clReleaseMemObject(out);
  clReleaseKernel(kernel);
  clReleaseProgram(program);
  return double(global) * width * chains * iterations / best;
}

// A session on arcus' device, by its platform and device names.
void open_session(ClSession& s, const std::string& platform_name, const std::string& device_name) {
  cl_platform_id platform;
  s.device = find_device(platform_name, device_name, &platform);
  clGetDeviceInfo(s.device, CL_DEVICE_MAX_COMPUTE_UNITS, sizeof s.compute_units, &s.compute_units, nullptr);
  cl_int err;
  s.context = clCreateContext(nullptr, 1, &s.device, nullptr, nullptr, &err);
  check(err, "clCreateContext");
  s.queue = clCreateCommandQueue(s.context, s.device, CL_QUEUE_PROFILING_ENABLE, &err);
  check(err, "clCreateCommandQueue");
}

}  // namespace

std::vector<PeakResult> measure_fp64_peak(const std::string& platform_name, const std::string& device_name,
                                          double target_seconds) {
  ClSession s;
  open_session(s, platform_name, device_name);
  // double8 fills one AVX-512 register; double16 two.  16 × double8 or 8 × double16
  // chains use 16 of the 32 vector registers, leaving room for a, b and the loop.
  const struct { int width, chains; } variants[] = {{8, 8}, {8, 16}, {16, 8}};
  std::vector<PeakResult> results;
  for (const auto& v : variants)
    results.push_back({v.width, v.chains, 2e-9 * measure_variant(s, Operation::Fma, v.width, v.chains, target_seconds)});
  return results;
}

std::vector<DivisionResult> measure_fp64_division(const std::string& platform_name, const std::string& device_name,
                                                  double target_seconds) {
  ClSession s;
  open_session(s, platform_name, device_name);
  // The divider is not pipelined like the FMA units (a zmm vdivpd issues every ~16
  // cycles, latency ~23): 4 chains already cover its latency, 8 show it does not grow.
  const struct { int width, chains; } variants[] = {{8, 4}, {8, 8}};
  std::vector<DivisionResult> results;
  for (const auto& v : variants)
    results.push_back({v.width, v.chains, measure_variant(s, Operation::Division, v.width, v.chains, target_seconds)});
  return results;
}

}  // namespace bench
