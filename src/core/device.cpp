#include "core/device.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "core/error.h"

namespace arcus {
namespace {

std::string device_string(cl_device_id d, cl_device_info what) {
  size_t size = 0;
  if (clGetDeviceInfo(d, what, 0, nullptr, &size) != CL_SUCCESS || size == 0) return "";
  std::string s(size, '\0');
  clGetDeviceInfo(d, what, size, &s[0], nullptr);
  s.resize(std::strlen(s.c_str()));
  return s;
}

template <class T>
T device_value(cl_device_id d, cl_device_info what) {
  T v{};
  clGetDeviceInfo(d, what, sizeof v, &v, nullptr);
  return v;
}

void copy_string(char* dst, size_t size, const std::string& src) {
  std::snprintf(dst, size, "%s", src.c_str());
}

// A power of two in 2..16 from the device's native double vector width.
uint32_t cpu_lanes(cl_uint native_width) {
  uint32_t lanes = 2;
  while (lanes < 16 && lanes * 2 <= native_width) lanes *= 2;
  return lanes;
}

std::vector<DeviceEntry> enumerate() {
  std::vector<DeviceEntry> out;
  cl_uint np = 0;
  if (clGetPlatformIDs(0, nullptr, &np) != CL_SUCCESS || np == 0) return out;
  std::vector<cl_platform_id> platforms(np);
  clGetPlatformIDs(np, platforms.data(), nullptr);
  for (cl_platform_id p : platforms) {
    cl_uint nd = 0;
    if (clGetDeviceIDs(p, CL_DEVICE_TYPE_ALL, 0, nullptr, &nd) != CL_SUCCESS || nd == 0) continue;
    std::vector<cl_device_id> ids(nd);
    clGetDeviceIDs(p, CL_DEVICE_TYPE_ALL, nd, ids.data(), nullptr);
    size_t psize = 0;
    clGetPlatformInfo(p, CL_PLATFORM_NAME, 0, nullptr, &psize);
    std::string pname(psize, '\0');
    clGetPlatformInfo(p, CL_PLATFORM_NAME, psize, &pname[0], nullptr);
    pname.resize(std::strlen(pname.c_str()));
    size_t vsize = 0;
    clGetPlatformInfo(p, CL_PLATFORM_VERSION, 0, nullptr, &vsize);
    std::string platform_version(vsize, '\0');
    clGetPlatformInfo(p, CL_PLATFORM_VERSION, vsize, &platform_version[0], nullptr);
    platform_version.resize(std::strlen(platform_version.c_str()));
    for (cl_device_id d : ids) {
      DeviceEntry e{p, d, {}, "", "", 0};
      e.info.index = static_cast<uint32_t>(out.size());
      copy_string(e.info.name, sizeof e.info.name, device_string(d, CL_DEVICE_NAME));
      copy_string(e.info.platform, sizeof e.info.platform, pname);
      copy_string(e.info.version, sizeof e.info.version, device_string(d, CL_DEVICE_VERSION));
      e.info.is_gpu = (device_value<cl_device_type>(d, CL_DEVICE_TYPE) & CL_DEVICE_TYPE_GPU) ? 1 : 0;
      e.info.fp64 = device_string(d, CL_DEVICE_EXTENSIONS).find("cl_khr_fp64") != std::string::npos ? 1 : 0;
      e.info.compute_units = device_value<cl_uint>(d, CL_DEVICE_MAX_COMPUTE_UNITS);
      e.info.global_memory = device_value<cl_ulong>(d, CL_DEVICE_GLOBAL_MEM_SIZE);
      // CPUs (PoCL) want explicit vector lanes, one SIMD register of doubles wide
      // (8 with AVX-512, 4 with AVX2); GPUs one ray per work-item.
      e.info.lanes = e.info.is_gpu ? 1 : cpu_lanes(device_value<cl_uint>(d, CL_DEVICE_NATIVE_VECTOR_WIDTH_DOUBLE));
      e.driver_version = device_string(d, CL_DRIVER_VERSION);
      e.platform_version = platform_version;
      e.max_alloc = device_value<cl_ulong>(d, CL_DEVICE_MAX_MEM_ALLOC_SIZE);
      out.push_back(e);
    }
  }
  return out;
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

std::string device_list() {
  std::string s;
  for (const DeviceEntry& e : devices())
    s += "\n  " + std::to_string(e.info.index) + ": " + e.info.name + " (" + e.info.platform + ")";
  return s.empty() ? " none (is an OpenCL ICD such as pocl-opencl-icd installed?)" : s;
}

}  // namespace

const std::vector<DeviceEntry>& devices() {
  static const std::vector<DeviceEntry> all = enumerate();
  return all;
}

uint32_t resolve_device(int32_t requested) {
  const auto& all = devices();
  if (all.empty())
    fail(ARCUS_ERROR_DEVICE_NOT_FOUND, "no OpenCL device found (is an OpenCL ICD such as pocl-opencl-icd installed?)");
  if (requested >= 0) {
    if (static_cast<size_t>(requested) >= all.size())
      fail(ARCUS_ERROR_DEVICE_NOT_FOUND, "device: index " + std::to_string(requested) + " does not exist; devices:" +
                                             device_list());
    return static_cast<uint32_t>(requested);
  }
  if (requested != ARCUS_DEVICE_DEFAULT)
    fail(ARCUS_ERROR_DEVICE_NOT_FOUND, "device: " + std::to_string(requested) +
                                           " is neither an index nor ARCUS_DEVICE_DEFAULT (-1)");
  if (const char* env = std::getenv("ARCUS_DEVICE"); env && *env) {
    std::string want(env);
    const bool digits = std::all_of(want.begin(), want.end(), [](unsigned char c) { return std::isdigit(c); });
    if (digits) {
      const unsigned long long index = want.size() > 9 ? ~0ull : std::stoull(want);
      if (index >= all.size())
        fail(ARCUS_ERROR_DEVICE_NOT_FOUND,
             "ARCUS_DEVICE=" + want + ": no device with that index; devices:" + device_list());
      return static_cast<uint32_t>(index);
    }
    for (const DeviceEntry& e : all)
      if (lower(std::string(e.info.name) + " " + e.info.platform).find(lower(want)) != std::string::npos)
        return e.info.index;
    fail(ARCUS_ERROR_DEVICE_NOT_FOUND, "ARCUS_DEVICE=" + want + ": no device name matches; devices:" + device_list());
  }
  for (const DeviceEntry& e : all)
    if (e.info.is_gpu) return e.info.index;
  for (const DeviceEntry& e : all)
    if (device_value<cl_device_type>(e.device, CL_DEVICE_TYPE) & CL_DEVICE_TYPE_CPU) return e.info.index;
  return 0;
}

}  // namespace arcus
