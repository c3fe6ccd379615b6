#include "fresh_process.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

#include "harness.hpp"
#include "studies.hpp"

extern char** environ;

namespace bench {
namespace {

namespace fs = std::filesystem;

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// A fresh directory under the system's temp dir, removed with everything in it.
class TempDir {
 public:
  TempDir() {
    std::string pattern = (fs::temp_directory_path() / "arcus_bench.XXXXXX").string();
    if (!::mkdtemp(pattern.data())) throw std::runtime_error("mkdtemp: " + std::string(std::strerror(errno)));
    path_ = pattern;
  }
  ~TempDir() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

// A child's "key value" lines, and the wall time from spawn to exit.
struct ChildRun {
  double seconds = 0;
  std::map<std::string, double> values;
  double at(const std::string& key) const {
    const auto it = values.find(key);
    if (it == values.end()) throw std::runtime_error("child process did not report " + key);
    return it->second;
  }
};

// Runs this executable with `args` and the environment with `env` set (replacing what
// the parent had), its stdout read back through a pipe; stderr passes through.
ChildRun run_child(const std::vector<std::string>& args, const std::map<std::string, std::string>& env) {
  const std::string exe = fs::read_symlink("/proc/self/exe").string();
  std::vector<std::string> envs;
  for (char** e = environ; *e; ++e) {
    const std::string entry = *e;
    if (!env.count(entry.substr(0, entry.find('=')))) envs.push_back(entry);
  }
  for (const auto& [name, value] : env) envs.push_back(name + "=" + value);
  std::vector<char*> argv{const_cast<char*>(exe.c_str())}, envp;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  for (const std::string& e : envs) envp.push_back(const_cast<char*>(e.c_str()));
  argv.push_back(nullptr);
  envp.push_back(nullptr);

  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0) throw std::runtime_error("pipe2: " + std::string(std::strerror(errno)));
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, fds[1], STDOUT_FILENO);  // dup2 clears O_CLOEXEC
  std::fflush(stdout);
  const auto start = std::chrono::steady_clock::now();
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, exe.c_str(), &actions, nullptr, argv.data(), envp.data());
  posix_spawn_file_actions_destroy(&actions);
  ::close(fds[1]);
  if (spawned != 0) {
    ::close(fds[0]);
    throw std::runtime_error("posix_spawn " + exe + ": " + std::strerror(spawned));
  }
  std::string output;
  char buf[4096];
  for (ssize_t got; (got = ::read(fds[0], buf, sizeof buf)) != 0;) {
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) break;
    output.append(buf, static_cast<std::size_t>(got));
  }
  ::close(fds[0]);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  ChildRun run;
  run.seconds = seconds_since(start);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw std::runtime_error("child '" + args.front() + "' failed (status " + std::to_string(status) + "): " + output);
  std::istringstream lines(output);
  for (std::string key; lines >> key;) {
    double value = 0;
    if (lines >> value) run.values[key] = value;
    else lines.clear();
  }
  return run;
}

// ---- peak memory ---------------------------------------------------------------------------
// VmRSS or VmHWM (the peak) of this process, bytes.  getrusage's ru_maxrss would be the
// same peak, but after posix_spawn it starts at the parent's peak (the child shares the
// parent's memory until exec) and cannot be reset, so a growth read from it can be 0.
double status_bytes(const char* field) {
  std::ifstream in("/proc/self/status");
  for (std::string line; std::getline(in, line);)
    if (line.rfind(field, 0) == 0) return std::stod(line.substr(line.find(':') + 1)) * 1024.0;
  return 0;
}

// Starts a measurement: resets the peak to the current RSS (Linux ≥ 4.0, "5" to
// clear_refs) and returns the RSS to measure the growth from.  Without the reset the
// baseline is the earlier peak, and the growth can only read low.
double start_peak_window() {
  std::ofstream("/proc/self/clear_refs") << "5";
  return std::max(status_bytes("VmRSS:"), 0.0);
}

double peak_growth_since(double baseline) { return std::max(0.0, status_bytes("VmHWM:") - baseline); }

// ---- first job --------------------------------------------------------------------------------
constexpr std::size_t kFirstJobRays = 256;
const char* const kFirstJobMethods[] = {"rk4", "dp45"};

FirstJob first_job_from(const ChildRun& child, const char* scenario, const char* arcus_cache, const char* pocl_cache) {
  FirstJob j;
  j.scenario = scenario;
  j.arcus_cache = arcus_cache;
  j.pocl_cache = pocl_cache;
  j.process_seconds = child.seconds;
  j.context_seconds = child.at("context_s");
  j.first_job_seconds = child.at("first_job_s");
  for (const char* m : kFirstJobMethods) {
    const std::string k = m;
    j.kernels.push_back({k, child.at(k + "_advance_s"), child.at(k + "_build_s"), child.at(k + "_kernel_s"),
                         static_cast<int>(child.at(k + "_origin"))});
  }
  return j;
}

void print_first_job(const FirstJob& j) {
  std::printf("  %-17s process %.3f s, context %.3f s, first jobs %.3f s:", j.scenario.c_str(), j.process_seconds,
              j.context_seconds, j.first_job_seconds);
  for (const FirstKernel& k : j.kernels)
    std::printf(" %s %.3f s (build %.3f s, %s)", k.method.c_str(), k.advance_seconds, k.build_seconds,
                program_origin_name(k.origin));
  std::printf("\n");
  std::fflush(stdout);
}

// ---- grid --------------------------------------------------------------------------------------
// n = 1 + 1e-4·(sin + sin + sin)/3 over the grid: smooth, positive, and not constant, so
// no step of the check or the read can be skipped.
void write_grid_file(const fs::path& path, uint32_t side) {
  std::vector<double> wave(side);
  for (uint32_t i = 0; i < side; ++i) wave[i] = std::sin(6.283185307179586 * i / side);
  std::vector<float> slice(std::size_t(side) * side);  // one k at a time: the parent stays small
  std::ofstream out(path, std::ios::binary);
  for (uint32_t k = 0; k < side; ++k) {
    for (uint32_t j = 0; j < side; ++j)
      for (uint32_t i = 0; i < side; ++i)
        slice[std::size_t(j) * side + i] = static_cast<float>(1.0 + 1e-4 * (wave[i] + wave[j] + wave[k]) / 3.0);
    out.write(reinterpret_cast<const char*>(slice.data()), static_cast<std::streamsize>(slice.size() * sizeof(float)));
  }
  if (!out) throw std::runtime_error("writing " + path.string() + " failed");
}

// The grid's placement: it spans the rays' starting points, y0 ∈ [0, 1].
void grid_geometry(uint32_t side, uint32_t dims[3], double origin[3], double spacing[3]) {
  for (int a = 0; a < 3; ++a) {
    dims[a] = side;
    origin[a] = -0.5;
    spacing[a] = 2.0 / (side - 1);
  }
}

FieldPtr make_grid(arcus_context_t* ctx, const double* values, uint32_t side) {
  uint32_t dims[3];
  double origin[3], spacing[3];
  grid_geometry(side, dims, origin, spacing);
  arcus_field_t* f = nullptr;
  check(arcus_field_create_grid(ctx, values, dims, origin, spacing, &f), ctx, "arcus_field_create_grid");
  return FieldPtr(f);
}

}  // namespace

const char* program_origin_name(int origin) {
  switch (origin) {
    case ARCUS_PROGRAM_BUILT: return "built";
    case ARCUS_PROGRAM_MEMORY_CACHE: return "memory cache";
    case ARCUS_PROGRAM_DISK_CACHE: return "disk cache";
  }
  return "?";
}

// ---- first job --------------------------------------------------------------------------------
FirstJobStudy measure_first_jobs() {
  FirstJobStudy study;
  try {
    const TempDir arcus_dir, pocl_dir, pocl_fresh;
    const std::string a = arcus_dir.path().string(), p = pocl_dir.path().string(), fresh = pocl_fresh.path().string();
    const struct {
      const char *name, *arcus_cache, *pocl_cache;  // as reported
      std::string arcus_env, pocl_env;              // ARCUS_CACHE_DIR, POCL_CACHE_DIR
    } scenarios[] = {  // in this order: each finds the dirs the ones before it filled
        {"cold", "empty", "empty", a, p},
        {"warm", "warm", "warm", a, p},
        // What arcus' own cache adds: the same process without it, PoCL's cache warm.
        {"PoCL cache only", "off", "warm", "off", p},
        // And arcus' cache alone: PoCL still generates each kernel's launch code.
        {"arcus cache only", "warm", "empty", a, fresh},
    };
    for (const auto& sc : scenarios) {
      const ChildRun child = run_child({"--first-job"}, {{"ARCUS_CACHE_DIR", sc.arcus_env}, {"POCL_CACHE_DIR", sc.pocl_env}});
      study.runs.push_back(first_job_from(child, sc.name, sc.arcus_cache, sc.pocl_cache));
      print_first_job(study.runs.back());
    }
  } catch (const std::exception& e) {
    study.error = e.what();
    std::printf("  first job: not measured: %s\n", e.what());
  }
  return study;
}

int first_job_child() {
  const auto start = std::chrono::steady_clock::now();
  const ContextPtr ctx = make_context();
  const double context_seconds = seconds_since(start);
  const FieldPtr field = make_linear_field(ctx.get(), kGradient);
  const RaySet rays = make_rays(kFirstJobRays);
  std::ostringstream report;
  const Setting settings[] = {rk4_headline_setting(), dp45_headline_setting()};
  for (const Setting& s : settings) {
    const AdvanceRun run = advance(ctx.get(), field.get(), short_path(s), rays, kFirstJobRays);
    const std::string m = method_name(s.method);
    report << m << "_advance_s " << run.stats.total_seconds << '\n'
           << m << "_build_s " << run.stats.build_seconds << '\n'
           << m << "_kernel_s " << run.stats.kernel_seconds << '\n'
           << m << "_origin " << run.stats.program_origin << '\n';
  }
  std::printf("context_s %.9g\nfirst_job_s %.9g\n%s", context_seconds, seconds_since(start), report.str().c_str());
  return 0;
}

// ---- grid --------------------------------------------------------------------------------------
GridStudy measure_grid_creation(uint32_t side) {
  GridStudy study;
  study.side = side;
  study.file_bytes = 4.0 * side * side * side;
  try {
    const TempDir dir;
    const fs::path file = dir.path() / ("grid" + std::to_string(side) + ".f32");
    write_grid_file(file, side);
    for (const bool from_memory : {false, true}) {
      std::vector<std::string> args{"--grid-child", file.string()};
      if (from_memory) args.push_back("--from-memory");
      const ChildRun child = run_child(args, {});
      GridCreation g;
      g.source = from_memory ? "memory, double" : "file, float32";
      g.create_seconds = child.at("create_s");
      g.create_peak_bytes = child.at("create_peak_bytes");
      g.job_seconds = child.at("job_advance_s");
      g.job_kernel_seconds = child.at("job_kernel_s");
      g.job_peak_bytes = child.at("job_peak_bytes");
      study.rows.push_back(g);
      char before[64] = "";  // the probe's figures, at its size only
      if (side == kProbeGridSide)
        std::snprintf(before, sizeof before, from_memory ? " [before: %.1f s]" : " [before: %.1f s, %.1f×]",
                      kProbeSecondsBefore, kProbePeakPerFileBefore);
      std::printf("  %s³ grid from %-14s create %.3f s, peak +%.0f MiB (%.2f× the file)%s; first RK4 job %.3f s "
                  "(kernel %.3f s), peak +%.0f MiB\n",
                  std::to_string(side).c_str(), g.source.c_str(), g.create_seconds, g.create_peak_bytes / 1048576.0,
                  g.create_peak_bytes / study.file_bytes, before, g.job_seconds, g.job_kernel_seconds, g.job_peak_bytes / 1048576.0);
      std::fflush(stdout);
    }
  } catch (const std::exception& e) {
    study.error = e.what();
    std::printf("  grid: not measured: %s\n", e.what());
  }
  return study;
}

int grid_child(const std::string& path, bool from_memory) {
  const double file_bytes = static_cast<double>(fs::file_size(path));
  const uint32_t side = static_cast<uint32_t>(std::lround(std::cbrt(file_bytes / 4)));
  if (4.0 * side * side * side != file_bytes) throw std::runtime_error(path + " is not a cube of float32 values");
  const ContextPtr ctx = make_context();
  const RaySet rays = make_rays(256);
  const Setting rk4 = short_path(rk4_headline_setting());
  {
    // The grid RK4 program, from a 2³ grid: the job below then times the upload, not a build.
    const std::vector<double> ones(8, 1.0);
    const FieldPtr tiny = make_grid(ctx.get(), ones.data(), 2);
    advance(ctx.get(), tiny.get(), rk4, rays, rays.count());
  }
  std::vector<double> values;
  if (from_memory) {  // the caller's array exists before the call: not part of its cost
    std::vector<float> f(std::size_t(side) * side * side);
    std::ifstream(path, std::ios::binary).read(reinterpret_cast<char*>(f.data()), static_cast<std::streamsize>(file_bytes));
    values.assign(f.begin(), f.end());
  }
  uint32_t dims[3];
  double origin[3], spacing[3];
  grid_geometry(side, dims, origin, spacing);

  double baseline = start_peak_window();
  auto start = std::chrono::steady_clock::now();
  FieldPtr grid;
  if (from_memory) {
    grid = make_grid(ctx.get(), values.data(), side);
  } else {
    arcus_field_t* f = nullptr;
    check(arcus_field_create_grid_from_file(ctx.get(), path.c_str(), ARCUS_FLOAT32, dims, origin, spacing, &f),
          ctx.get(), "arcus_field_create_grid_from_file");
    grid.reset(f);
  }
  const double create_seconds = seconds_since(start);
  const double create_peak = peak_growth_since(baseline);

  baseline = start_peak_window();
  const AdvanceRun job = advance(ctx.get(), grid.get(), rk4, rays, rays.count());
  std::printf("create_s %.9g\ncreate_peak_bytes %.0f\njob_advance_s %.9g\njob_kernel_s %.9g\njob_peak_bytes %.0f\n",
              create_seconds, create_peak, job.stats.total_seconds, job.stats.kernel_seconds, peak_growth_since(baseline));
  return 0;
}

}  // namespace bench
