#include "core/runtime.h"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <optional>
#include <vector>

#include "core/cache_dir.h"
#include "core/error.h"
#include "core/features.h"

namespace arcus {
namespace {

namespace fs = std::filesystem;

std::mutex g_extra_mutex;
std::string g_extra_options;

std::string extra_options() {
  std::lock_guard<std::mutex> lock(g_extra_mutex);
  return g_extra_options;
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::string build_log(cl_program program, cl_device_id device) {
  size_t size = 0;
  clGetProgramBuildInfo(program, device, CL_PROGRAM_BUILD_LOG, 0, nullptr, &size);
  std::string log(size, '\0');
  if (size) clGetProgramBuildInfo(program, device, CL_PROGRAM_BUILD_LOG, size, &log[0], nullptr);
  log.resize(std::strlen(log.c_str()));
  return log;
}

// ---- the program cache on disk --------------------------------------------------------
// A file holds: the magic line, the key it was stored under (compared in full, so a
// hash collision cannot hand back another program), the binary, and a checksum of the
// binary.  Anything that does not match is rebuilt.  The checksum only catches damage:
// what keeps out a planted program is that entries are read only from a directory and
// files of this user's own that nobody else can write (CacheDir).
constexpr char kMagic[] = "arcus program cache 1\n";

std::string cache_key(const DeviceEntry& d, const std::string& options, const std::string& text) {
  const uint64_t source_hash = fnv1a64(text.data(), text.size());
  char hash[32];
  std::snprintf(hash, sizeof hash, "%016llx", static_cast<unsigned long long>(source_hash));
  return std::string("device=") + d.info.name + "\nplatform=" + d.info.platform + " " + d.platform_version +
         "\ndriver=" + d.driver_version + "\ndevice_version=" + d.info.version + "\noptions=" + options +
         "\nsource=" + hash + "\n";
}

// The file name of `key` in the cache directory.
std::string cache_file(const std::string& key) {
  char name[40];
  std::snprintf(name, sizeof name, "%016llx.clbin", static_cast<unsigned long long>(fnv1a64(key.data(), key.size())));
  return name;
}

// The largest entry read back: PoCL's binaries are a few hundred kB, a GPU driver's a few
// MB; a bigger file is nothing arcus wrote and is not read into memory.
constexpr size_t kMaxEntryBytes = size_t(256) << 20;

void put_u64(std::string* out, uint64_t v) { out->append(reinterpret_cast<const char*>(&v), sizeof v); }

bool get_u64(const std::string& in, size_t* pos, uint64_t* v) {
  if (in.size() - *pos < sizeof *v) return false;
  std::memcpy(v, in.data() + *pos, sizeof *v);
  *pos += sizeof *v;
  return true;
}

// The binary stored under `key`, or "" if the entry is missing, not this user's own
// (CacheDir::read) or not intact.
std::string load_binary(const CacheDir& dir, const std::string& file, const std::string& key) {
  const std::optional<std::string> entry = dir.read(file, kMaxEntryBytes);
  if (!entry) return "";
  const std::string& data = *entry;
  const size_t magic = sizeof kMagic - 1;
  if (data.compare(0, magic, kMagic) != 0) return "";
  size_t pos = magic;
  uint64_t key_size = 0, size = 0, sum = 0;
  if (!get_u64(data, &pos, &key_size) || key_size != key.size() || data.size() - pos < key_size) return "";
  if (data.compare(pos, key_size, key) != 0) return "";
  pos += key_size;
  if (!get_u64(data, &pos, &size) || size == 0 || data.size() - pos < size) return "";
  std::string binary = data.substr(pos, size);
  pos += size;
  if (!get_u64(data, &pos, &sum) || sum != fnv1a64(binary.data(), binary.size()) || pos != data.size()) return "";
  return binary;
}

// Best effort: a cache that cannot be written only costs the next process a build.
void store_binary(const CacheDir& dir, const std::string& file, const std::string& key, const std::string& binary) {
  std::string data(kMagic);
  put_u64(&data, key.size());
  data += key;
  put_u64(&data, binary.size());
  data += binary;
  put_u64(&data, fnv1a64(binary.data(), binary.size()));
  dir.write(file, data);
}

std::string program_binary(cl_program program) {
  size_t size = 0;
  if (clGetProgramInfo(program, CL_PROGRAM_BINARY_SIZES, sizeof size, &size, nullptr) != CL_SUCCESS || size == 0)
    return "";
  std::string binary(size, '\0');
  unsigned char* ptr = reinterpret_cast<unsigned char*>(&binary[0]);
  if (clGetProgramInfo(program, CL_PROGRAM_BINARIES, sizeof ptr, &ptr, nullptr) != CL_SUCCESS) return "";
  return binary;
}

// A program from a cached binary, or an empty handle if the driver refuses it.
ClProgram program_from_binary(cl_context context, cl_device_id device, const std::string& binary,
                              const std::string& options) {
  const unsigned char* ptr = reinterpret_cast<const unsigned char*>(binary.data());
  const size_t size = binary.size();
  cl_int status = CL_SUCCESS, err = CL_SUCCESS;
  ClProgram program(clCreateProgramWithBinary(context, 1, &device, &size, &ptr, &status, &err));
  if (err != CL_SUCCESS || status != CL_SUCCESS) return ClProgram();
  if (clBuildProgram(program.get(), 1, &device, options.c_str(), nullptr, nullptr) != CL_SUCCESS) return ClProgram();
  return program;
}

}  // namespace

namespace testing {
void set_extra_build_options(const std::string& options) {
  std::lock_guard<std::mutex> lock(g_extra_mutex);
  g_extra_options = options;
}
}  // namespace testing

std::string program_cache_dir() {
  const char* env = std::getenv("ARCUS_CACHE_DIR");
  if (env && *env) return std::string(env) == "off" ? "" : env;
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) return (fs::path(xdg) / "arcus").string();
  if (const char* home = std::getenv("HOME"); home && *home) return (fs::path(home) / ".cache" / "arcus").string();
  return "";
}

DeviceRuntime::DeviceRuntime(uint32_t device_index) : entry_(devices().at(device_index)) {
  cl_int err = CL_SUCCESS;
  cl_context_properties props[] = {CL_CONTEXT_PLATFORM, reinterpret_cast<cl_context_properties>(entry_.platform), 0};
  context_ = ClContext(clCreateContext(props, 1, &entry_.device, nullptr, nullptr, &err));
  check_cl(err, "clCreateContext");
}

std::string DeviceRuntime::build_options(arcus_features features, Layout layout) const {
  std::string options = "-cl-std=CL1.2 -D ARCUS_LANES=" + std::to_string(layout.lanes) +
                        " -D ARCUS_GROUPS=" + std::to_string(layout.groups);
  const std::string f = feature_options(features);
  if (!f.empty()) options += " " + f;
  const std::string extra = extra_options();
  if (!extra.empty()) options += " " + extra;
  return options;
}

BuiltProgram DeviceRuntime::program(const KernelSource& source, arcus_features features, Layout layout) {
  const std::string extra = extra_options();
  const Key key{source.name, features, layout.lanes, layout.groups, extra};
  std::lock_guard<std::mutex> lock(mutex_);
  auto it = programs_.find(key);
  if (it != programs_.end()) return {it->second.get(), 0.0, ARCUS_PROGRAM_MEMORY_CACHE};

  const auto start = std::chrono::steady_clock::now();
  const std::string options = build_options(features, layout);
  const std::string text = kernel_text(source);
  const CacheDir dir(program_cache_dir(), "program cache");
  const std::string disk_key = cache_key(entry_, options, text);
  const std::string file = cache_file(disk_key);

  if (dir.usable()) {
    const std::string binary = load_binary(dir, file, disk_key);
    if (!binary.empty()) {
      ClProgram p = program_from_binary(context_.get(), entry_.device, binary, options);
      if (p) {
        cl_program raw = p.get();
        programs_.emplace(key, std::move(p));
        return {raw, seconds_since(start), ARCUS_PROGRAM_DISK_CACHE};
      }
    }
  }

  const char* ptr = text.c_str();
  const size_t length = text.size();
  cl_int err = CL_SUCCESS;
  ClProgram program(clCreateProgramWithSource(context_.get(), 1, &ptr, &length, &err));
  check_cl(err, "clCreateProgramWithSource");
  err = clBuildProgram(program.get(), 1, &entry_.device, options.c_str(), nullptr, nullptr);
  if (err != CL_SUCCESS)
    fail(ARCUS_ERROR_KERNEL_BUILD, "building kernel " + std::string(source.name) + " failed (" + cl_error_name(err) +
                                       ") with options '" + options + "':\n" + build_log(program.get(), entry_.device));
  if (dir.usable()) {
    const std::string binary = program_binary(program.get());
    if (!binary.empty()) store_binary(dir, file, disk_key, binary);
  }
  cl_program raw = program.get();
  programs_.emplace(key, std::move(program));
  return {raw, seconds_since(start), ARCUS_PROGRAM_BUILT};
}

std::shared_ptr<DeviceRuntime> runtime_for(uint32_t device_index) {
  static std::mutex mutex;
  static std::map<uint32_t, std::weak_ptr<DeviceRuntime>> runtimes;
  std::lock_guard<std::mutex> lock(mutex);
  if (auto rt = runtimes[device_index].lock()) return rt;
  auto rt = std::make_shared<DeviceRuntime>(device_index);
  runtimes[device_index] = rt;
  return rt;
}

}  // namespace arcus
