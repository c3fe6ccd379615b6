// arcus_bench — "what accuracy costs in time".
//
// Reproduces the study of numerical methods of thesis §5.4.1 (Fig. 5.13) on the medium
// n = 1 + 0.1·y, whose ray paths have a closed form (problem.hpp), with arcus' Euler,
// RK2, RK4 and DP45 kernels; sets them against a peer (Boost.Odeint's controlled
// Dormand–Prince on the CPU) and against the device's FP64 peak; and measures the float
// path.  Writes CSV files, results.md and (through plot_bench.py) PNG plots.
//
//   arcus_bench [--out DIR] [--quick] [--no-plot] [--sweep-layout]
//
// Its last two lines are the two ratios the issue sets targets for.
#include <arcus/arcus.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <memory>
#include <numeric>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <tuple>
#include <utility>
#include <vector>

#include "flops.hpp"
#include "fp64_peak.hpp"
#include "native_rk4.hpp"
#include "odeint_peer.hpp"
#include "problem.hpp"

namespace {

namespace fs = std::filesystem;
using bench::RaySet;

// ---- the problem (thesis §5.4.1) --------------------------------------------------
constexpr double kN0 = 1.0;
constexpr double kGradient = 0.1;       // n = 1 + 0.1·y
constexpr double kLength = 1000.0;      // path length of the step, tolerance and gradient studies
constexpr double kDistanceStep = 5e-3;  // fixed step of the distance and gradient studies
constexpr double kDistanceTol = 1e-6;   // DP45 tolerance of the distance and gradient studies
// DP45 and the peer run with rtol = tol and atol = tol·1e-3: positions reach 10⁴ m and
// v is ≈ 1, so the relative part decides and the absolute part only guards v ≈ 0.
constexpr double kAtolPerTol = 1e-3;
constexpr double kHeadlineTol = 1e-9;   // the tolerance of the DP45 target
constexpr double kRk4PeakStep = 0.01;   // RK4 run for the fraction of the FP64 peak

// FLOPs of one RK4 step of the compiled kernel for the linear field (no box, no path),
// per ray (lane), read from kernels/advance.cl and kernels/field.h and checked against
// PoCL's machine code (README.md, "RK4 FLOPs per step").  An FMA counts 2, a mul, add
// or division 1.
//   4 derivatives (ray_derivative + field_eval LINEAR), each: n = n0 + g·r as
//     3 FMAs = 6, inv_n = 1/n = 1, dr/ds = v·inv_n 3 muls = 3; ∇n = g is a constant   4 × 10 = 40
//   stage states ray_step(y, h/2 | h/2 | h, k): 6 FMAs each = 36, less 6: since
//     dv/ds = g in every stage, stage 3's v equals stage 2's and the compiler
//     computes it once                                                                     30
//   combination t = k1 + 2k2 + 2k3 + k4 for r: 2 FMAs + 1 add (ray_fma by 1 is
//     folded to an add) per component = 15; the v part is loop-invariant (all g)
//     and hoisted out of the step loop: 0                                                  15
//   final update ray_step(y, h/6, t): 6 FMAs                                               12
//   step bookkeeping: h/2 and h/6 are scalar, once per step for all lanes and groups:  ≈ 0
//   total                                                                                  97
// (The source, counted naively, holds 120.)  The disassembly of one step-loop iteration
// (8 groups of double8) has 312 vfmadd, 96 vmulpd, 24 vaddpd and 32 vdivpd on zmm: per
// group 39 FMA + 12 mul + 3 add + 4 div = 97 FLOPs per lane.  The divisions count 1
// each but hold the divider far longer than an FMA its pipe.
constexpr double kRk4FlopsPerStep = 97;

// ---- options and sizes -----------------------------------------------------------
struct Options {
  std::string out_dir = "out/bench";
  bool quick = false;
  bool plot = true;
  bool sweep_layout = false;
};

Options parse_options(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--out" && i + 1 < argc) {
      o.out_dir = argv[++i];
    } else if (a == "--quick") {
      o.quick = true;
    } else if (a == "--no-plot") {
      o.plot = false;
    } else if (a == "--sweep-layout") {
      o.sweep_layout = true;
    } else {
      std::cerr << "usage: arcus_bench [--out DIR] [--quick] [--no-plot] [--sweep-layout]\n"
                   "  --out DIR   where the CSVs, results.md and PNGs go (default out/bench)\n"
                   "  --quick     much smaller sweeps (< 30 s) for smoke tests\n"
                   "  --no-plot   do not run plot_bench.py\n"
                   "  --sweep-layout  also time RK4 and DP45 over lanes x groups (ARCUS_LANES,\n"
                   "              ARCUS_GROUPS; about a minute more)\n";
      std::exit(a == "--help" || a == "-h" ? 0 : 2);
    }
  }
  return o;
}

// What one run of the benchmark covers.  Each sweep point aims at `point_seconds` of
// kernel time: the ray count follows from a probe run, so slow settings (Euler at
// step 0.001 over 10 km) stay bounded and fast ones still run long enough to time.
struct Plan {
  std::vector<double> steps, tolerances, lengths, gradients;
  std::vector<double> float_rk4_steps, float_dp45_tols;
  double point_seconds;     // per sweep point
  double headline_seconds;  // per repeat of the two ratio runs
  int headline_launches;    // at least this many launches for each of them
  std::size_t max_rays;
  std::size_t peer_rays;    // rays the peer integrates: a prefix of arcus' rays
  double peak_seconds;      // per FMA-microkernel launch
};

Plan full_plan() {
  Plan p;
  p.steps = {1, 0.5, 0.1, 0.05, 0.01, 0.005, 0.001};
  for (int e = 3; e <= 12; ++e) {  // 1e-3 … 1e-12 in half decades
    p.tolerances.push_back(std::pow(10.0, -e));
    if (e < 12) p.tolerances.push_back(std::pow(10.0, -e) / std::sqrt(10.0));
  }
  std::sort(p.tolerances.rbegin(), p.tolerances.rend());
  p.lengths = {1, 3, 10, 30, 100, 300, 1000, 3000, 10000};
  p.gradients = {0.01, 0.02, 0.05, 0.1, 0.2, 0.5, 1};
  p.float_rk4_steps = {0.1, 0.01};
  p.float_dp45_tols = {1e-4, 1e-6, 1e-8};
  p.point_seconds = 0.4;
  p.headline_seconds = 1.5;
  p.headline_launches = 5;
  p.max_rays = 65536;
  p.peer_rays = 16384;
  p.peak_seconds = 0.3;
  return p;
}

Plan quick_plan() {
  Plan p;
  p.steps = {1, 0.1, 0.01};
  p.tolerances = {1e-3, 1e-6, 1e-9, 1e-10, 1e-11};
  p.lengths = {10, 1000};
  p.gradients = {0.01, 1};
  p.float_rk4_steps = {0.1};
  p.float_dp45_tols = {1e-6};
  p.point_seconds = 0.02;
  p.headline_seconds = 0.1;
  p.headline_launches = 3;
  p.max_rays = 4096;
  p.peer_rays = 1024;
  p.peak_seconds = 0.05;
  return p;
}

// ---- arcus calls ---------------------------------------------------------------------
void check(arcus_status status, arcus_context_t* ctx, const std::string& what) {
  if (status == ARCUS_SUCCESS) return;
  const char* msg = ctx ? arcus_context_last_error(ctx) : arcus_last_error();
  throw std::runtime_error(what + ": " + arcus_status_string(status) + (msg && *msg ? std::string(" — ") + msg : ""));
}

struct ContextDeleter { void operator()(arcus_context_t* c) const { arcus_context_release(c); } };
struct FieldDeleter { void operator()(arcus_field_t* f) const { arcus_field_release(f); } };
struct JobDeleter { void operator()(arcus_job_t* j) const { arcus_job_release(j); } };
using ContextPtr = std::unique_ptr<arcus_context_t, ContextDeleter>;
using FieldPtr = std::unique_ptr<arcus_field_t, FieldDeleter>;
using JobPtr = std::unique_ptr<arcus_job_t, JobDeleter>;

const char* method_name(arcus_method m) {
  switch (m) {
    case ARCUS_METHOD_EULER: return "euler";
    case ARCUS_METHOD_RK2: return "rk2";
    case ARCUS_METHOD_RK4: return "rk4";
    case ARCUS_METHOD_DP45: return "dp45";
  }
  return "?";
}

const char* precision_name(arcus_precision p) { return p == ARCUS_PRECISION_FLOAT ? "float" : "double"; }

// One point of a study: a method with its accuracy knob, over a path length, in a
// medium of a given gradient.
struct Setting {
  arcus_method method;
  arcus_precision precision;
  double step;  // fixed-step methods
  double tol;   // DP45
  double length;
  double gradient;
};

bool adaptive(const Setting& s) { return s.method == ARCUS_METHOD_DP45; }

// The times of repeated launches of one job.  A launch of a few milliseconds is at the
// mercy of scheduling noise (other work on the cores, too): the job is launched at
// least `min_launches` times and until `seconds` are in, at most 25 times.  The median
// is the typical time; the best is the least disturbed one.
struct Timing {
  std::vector<double> samples;
  double median() const {
    std::vector<double> v = samples;
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
    return v[v.size() / 2];
  }
  double best() const { return *std::min_element(samples.begin(), samples.end()); }
};

// `first` is a launch already made (its time counts); `launch` makes another and
// returns its time.
Timing time_launches(double first, const std::function<double()>& launch, double seconds, int min_launches) {
  constexpr std::size_t kMaxLaunches = 25;
  Timing t{{first}};
  auto total = [&] { return std::accumulate(t.samples.begin(), t.samples.end(), 0.0); };
  while (t.samples.size() < static_cast<std::size_t>(min_launches) ||
         (total() < seconds && t.samples.size() < kMaxLaunches))
    t.samples.push_back(launch());
  return t;
}

// One measured point, from arcus or from the peer; a row of every CSV.
struct Row {
  std::string impl;  // "arcus" | "odeint"
  Setting setting;
  unsigned threads = 0;  // peer threads (0 for arcus)
  std::size_t rays = 0;
  std::size_t launches = 1;    // timed runs behind the times below
  double mean_steps = 0;       // accepted steps per ray
  double seconds = 0;          // median launch; arcus: kernel (device) time, peer: wall time
  double best_seconds = 0;     // fastest launch
  double wall_seconds = 0;     // median launch; arcus: all of arcus_advance, peer: = seconds
  double err_max = 0, err_mean = 0;  // end-point error against the catenary, metres
  std::size_t not_done = 0;    // rays that ended other than ARCUS_RAY_DONE
  uint32_t lanes = 0, groups = 0;
  std::vector<double> errors;  // per ray (not written out)

  double time_per_ray() const { return seconds / static_cast<double>(rays); }
  double rays_per_second() const { return static_cast<double>(rays) / seconds; }
  double steps_per_second() const { return mean_steps * static_cast<double>(rays) / seconds; }
  double best_rays_per_second() const { return static_cast<double>(rays) / best_seconds; }
  double best_steps_per_second() const { return mean_steps * static_cast<double>(rays) / best_seconds; }
  void set_timing(const Timing& t) {
    seconds = t.median();
    best_seconds = t.best();
    launches = t.samples.size();
  }
  // Max error over the first `count` rays: the rays the peer also integrated.
  double err_max_over(std::size_t count) const {
    return *std::max_element(errors.begin(), errors.begin() + static_cast<std::ptrdiff_t>(std::min(count, errors.size())));
  }
};

void fill_errors(Row& row, std::vector<double> errors) {
  row.err_max = *std::max_element(errors.begin(), errors.end());
  row.err_mean = std::accumulate(errors.begin(), errors.end(), 0.0) / static_cast<double>(errors.size());
  row.errors = std::move(errors);
}

// Runs settings through arcus: one field per gradient, one untimed warm-up per kernel
// variant (so program build and PoCL's first-launch code generation are not timed),
// then a probe that sizes the measured run.
class ArcusBench {
 public:
  ArcusBench(arcus_context_t* ctx, const RaySet& rays) : ctx_(ctx), rays_(rays) {
    check(arcus_context_get_device(ctx, &device_), ctx, "arcus_context_get_device");
    for (const char* name : kLayoutVariables)
      if (const char* v = std::getenv(name)) user_layout_[name] = v;
  }
  ~ArcusBench() { set_layout(0, 0); }
  ArcusBench(const ArcusBench&) = delete;
  ArcusBench& operator=(const ArcusBench&) = delete;

  // Overrides the library's lanes × groups per work-item through the ARCUS_LANES and
  // ARCUS_GROUPS variables it reads at every arcus_advance; (0, 0) restores what the
  // user had set.  The layout is part of the kernel variant, so it keys the warm-up.
  void set_layout(uint32_t lanes, uint32_t groups) {
    const uint32_t values[] = {lanes, groups};
    for (int i = 0; i < 2; ++i) {
      const char* name = kLayoutVariables[i];
      const auto user = user_layout_.find(name);
      if (values[i]) setenv(name, std::to_string(values[i]).c_str(), 1);
      else if (user != user_layout_.end()) setenv(name, user->second.c_str(), 1);
      else unsetenv(name);
    }
    layout_ = {lanes, groups};
  }

  const arcus_device_info& device() const { return device_; }

  // Measures `s` over about `seconds` of kernel time with at least `min_rays` rays and
  // `min_launches` launches (time_launches).  A probe launch sizes the ray count; when
  // even the most rays make a short kernel, the launches are repeated instead.
  Row measure(const Setting& s, double seconds, std::size_t min_rays, int min_launches) {
    const std::size_t fill = warm_up(s);
    const std::size_t probe_rays = std::min(rays_.count(), round_up(std::max(min_rays, fill), fill));
    Run probe = run(s, probe_rays);
    const double per_ray = std::max(probe.stats.kernel_seconds, 1e-9) / static_cast<double>(probe_rays);
    const std::size_t wanted = static_cast<std::size_t>(seconds / per_ray);
    const std::size_t count = std::clamp(wanted / fill * fill, probe_rays, rays_.count());

    // Launches of the same rays give the same results; only their times differ.
    const Run result = count == probe_rays ? std::move(probe) : run(s, count);
    Timing wall{{result.stats.total_seconds}};
    const Timing kernel = time_launches(
        result.stats.kernel_seconds,
        [&] {
          const Run again = run(s, count);
          wall.samples.push_back(again.stats.total_seconds);
          return again.stats.kernel_seconds;
        },
        seconds, min_launches);
    Row row = summarize(s, result);
    row.set_timing(kernel);
    row.wall_seconds = wall.median();
    return row;
  }

 private:
  struct Run {
    std::size_t count = 0;
    arcus_job_stats stats{};
    std::vector<double> positions;
    std::vector<uint64_t> steps;
    std::vector<int32_t> status;
  };

  static constexpr const char* kLayoutVariables[2] = {"ARCUS_LANES", "ARCUS_GROUPS"};

  static std::size_t round_up(std::size_t n, std::size_t multiple) { return (n + multiple - 1) / multiple * multiple; }

  static arcus_advance_params params_for(const Setting& s) {
    arcus_advance_params p;
    arcus_advance_params_init(&p);
    p.method = s.method;
    p.precision = s.precision;
    p.length = s.length;
    if (adaptive(s)) {
      p.rtol = s.tol;
      p.atol = s.tol * kAtolPerTol;
      p.step = 0;  // the library's initial-step heuristic
    } else {
      p.step = s.step;
    }
    // The step limit must never be what ends a ray: 2·10⁶ fixed steps is this
    // benchmark's longest path.
    p.max_steps = 1000000000ull;
    return p;
  }

  arcus_field_t* field(double gradient) {
    auto it = fields_.find(gradient);
    if (it != fields_.end()) return it->second.get();
    const double g[3] = {0.0, gradient, 0.0};
    arcus_field_t* f = nullptr;
    check(arcus_field_create_linear(ctx_, kN0, g, &f), ctx_, "arcus_field_create_linear");
    return fields_.emplace(gradient, FieldPtr(f)).first->second.get();
  }

  Run run(const Setting& s, std::size_t count) {
    const arcus_advance_params params = params_for(s);
    arcus_job_t* raw = nullptr;
    check(arcus_advance(ctx_, field(s.gradient), &params, count, rays_.origins.data(), rays_.directions.data(), nullptr, &raw),
          ctx_, std::string("arcus_advance (") + method_name(s.method) + ")");
    JobPtr job(raw);
    Run r;
    r.count = count;
    r.positions.resize(3 * count);
    r.steps.resize(count);
    r.status.resize(count);
    check(arcus_job_get_end_states(job.get(), r.positions.data(), nullptr, r.steps.data(), r.status.data(), nullptr),
          ctx_, "arcus_job_get_end_states");
    check(arcus_job_get_stats(job.get(), &r.stats), ctx_, "arcus_job_get_stats");
    return r;
  }

  // Builds and first-launches the kernel variant of `s` on a short path; returns the
  // number of rays one pass of the device holds (lanes × groups × compute units), the
  // granularity of every measured run.
  std::size_t warm_up(const Setting& s) {
    const auto key = std::make_tuple(s.method, s.precision, layout_);
    auto it = fill_.find(key);
    if (it != fill_.end()) return it->second;
    Setting shortened = s;
    shortened.length = adaptive(s) ? 1.0 : std::min(s.length, 16 * s.step);
    const Run r = run(shortened, 256);
    const std::size_t fill = std::max<std::size_t>(
        64, std::size_t(std::max(1u, r.stats.lanes)) * std::max(1u, r.stats.groups) * std::max(1u, device_.compute_units));
    return fill_[key] = fill;
  }

  Row summarize(const Setting& s, const Run& r) const {
    Row row;
    row.impl = "arcus";
    row.setting = s;
    row.rays = r.count;
    row.mean_steps = std::accumulate(r.steps.begin(), r.steps.end(), 0.0) / static_cast<double>(r.count);
    row.not_done = static_cast<std::size_t>(
        std::count_if(r.status.begin(), r.status.end(), [](int32_t st) { return st != ARCUS_RAY_DONE; }));
    row.lanes = r.stats.lanes;
    row.groups = r.stats.groups;
    // Rays that stopped early keep their end points: a setting that fails shows up as
    // a large error (and in not_done), not as a gap.
    fill_errors(row, bench::end_point_errors(rays_, r.count, r.positions.data(), kN0, s.gradient, s.length));
    return row;
  }

  arcus_context_t* ctx_;
  const RaySet& rays_;
  arcus_device_info device_{};
  std::map<double, FieldPtr> fields_;
  std::map<std::string, std::string> user_layout_;
  std::pair<uint32_t, uint32_t> layout_{0, 0};
  std::map<std::tuple<arcus_method, arcus_precision, std::pair<uint32_t, uint32_t>>, std::size_t> fill_;
};

// The peer on the first `count` rays at tolerance `tol`, timed like arcus' launches.
Row measure_peer(const RaySet& rays, std::size_t count, double tol, unsigned threads, double seconds,
                 int min_launches) {
  auto integrate = [&] {
    return bench::run_odeint_dopri5(rays, count, kN0, kGradient, kLength, tol, tol * kAtolPerTol, threads);
  };
  const bench::PeerRun run = integrate();
  const Timing timing = time_launches(run.seconds, [&] { return integrate().seconds; }, seconds, min_launches);
  Row row;
  row.impl = "odeint";
  row.setting = {ARCUS_METHOD_DP45, ARCUS_PRECISION_DOUBLE, 0, tol, kLength, kGradient};
  row.threads = threads;
  row.rays = count;
  row.mean_steps = std::accumulate(run.steps.begin(), run.steps.end(), 0.0) / static_cast<double>(count);
  row.set_timing(timing);
  row.wall_seconds = row.seconds;
  fill_errors(row, bench::end_point_errors(rays, count, run.positions.data(), kN0, kGradient, kLength));
  return row;
}

// The native C++ RK4 peer (native_rk4.hpp) at step h, L = kLength, on `threads`
// threads: a probe launch sizes the ray count to about `seconds` per launch.
Row measure_native_rk4(const RaySet& rays, double h, unsigned threads, double seconds, int min_launches) {
  auto integrate = [&](std::size_t count) {
    return bench::run_native_rk4(rays, count, kN0, kGradient, kLength, h, threads);
  };
  const std::size_t probe = std::min<std::size_t>(256, rays.count());
  const double per_ray = std::max(integrate(probe).seconds, 1e-9) / static_cast<double>(probe);
  const std::size_t count = std::clamp<std::size_t>(static_cast<std::size_t>(seconds / per_ray) / 64 * 64, probe,
                                                    rays.count());
  const bench::PeerRun run = integrate(count);
  const Timing timing = time_launches(run.seconds, [&] { return integrate(count).seconds; }, seconds, min_launches);
  Row row;
  row.impl = "native";
  row.setting = {ARCUS_METHOD_RK4, ARCUS_PRECISION_DOUBLE, h, 0, kLength, kGradient};
  row.threads = threads;
  row.rays = count;
  row.mean_steps = std::accumulate(run.steps.begin(), run.steps.end(), 0.0) / static_cast<double>(count);
  row.set_timing(timing);
  row.wall_seconds = row.seconds;
  fill_errors(row, bench::end_point_errors(rays, count, run.positions.data(), kN0, kGradient, kLength));
  return row;
}

// ---- the studies -------------------------------------------------------------------------
void print_row(const Row& r) {
  const Setting& s = r.setting;
  const std::string layout = r.impl == "arcus" ? std::to_string(r.lanes) + "x" + std::to_string(r.groups)
                                               : std::to_string(r.threads) + " thr";
  std::printf("  %-6s %-5s %-6s %s=%-8.3g L=%-6g g=%-5g %-5s rays=%-5zux%-2zu steps/ray=%-9.4g time/ray=%-9.3g "
              "steps/s=%-9.3g err max=%-9.3g mean=%-9.3g%s\n",
              r.impl.c_str(), method_name(s.method), precision_name(s.precision), adaptive(s) ? "tol " : "step",
              adaptive(s) ? s.tol : s.step, s.length, s.gradient, layout.c_str(), r.rays, r.launches, r.mean_steps,
              r.time_per_ray(), r.steps_per_second(), r.err_max, r.err_mean,
              r.not_done ? (" NOT DONE: " + std::to_string(r.not_done)).c_str() : "");
  std::fflush(stdout);
}

std::vector<Row> measure_all(ArcusBench& arcus, const std::vector<Setting>& settings, double seconds,
                             std::size_t min_rays = 0) {
  std::vector<Row> rows;
  for (const Setting& s : settings) {
    rows.push_back(arcus.measure(s, seconds, min_rays, 1));
    print_row(rows.back());
  }
  return rows;
}

constexpr arcus_method kFixedMethods[] = {ARCUS_METHOD_EULER, ARCUS_METHOD_RK2, ARCUS_METHOD_RK4};
constexpr arcus_method kAllMethods[] = {ARCUS_METHOD_EULER, ARCUS_METHOD_RK2, ARCUS_METHOD_RK4, ARCUS_METHOD_DP45};

// Fig. 5.13 (a, c): fixed-step methods against step size.
std::vector<Setting> step_study(const Plan& p) {
  std::vector<Setting> out;
  for (arcus_method m : kFixedMethods)
    for (double h : p.steps) out.push_back({m, ARCUS_PRECISION_DOUBLE, h, 0, kLength, kGradient});
  return out;
}

// Fig. 5.13 (b, d): DP45 against tolerance.
std::vector<Setting> tolerance_study(const Plan& p) {
  std::vector<Setting> out;
  for (double tol : p.tolerances) out.push_back({ARCUS_METHOD_DP45, ARCUS_PRECISION_DOUBLE, 0, tol, kLength, kGradient});
  return out;
}

// Fig. 5.13 (e–h): every method at the thesis' settings against one varied parameter.
std::vector<Setting> all_methods_over(const std::vector<double>& values, const std::function<Setting(double)>& base) {
  std::vector<Setting> out;
  for (arcus_method m : kAllMethods)
    for (double v : values) {
      Setting s = base(v);
      s.method = m;
      out.push_back(s);
    }
  return out;
}

std::vector<Setting> distance_study(const Plan& p) {
  return all_methods_over(p.lengths, [](double L) {
    return Setting{ARCUS_METHOD_EULER, ARCUS_PRECISION_DOUBLE, kDistanceStep, kDistanceTol, L, kGradient};
  });
}

std::vector<Setting> gradient_study(const Plan& p) {
  return all_methods_over(p.gradients, [](double g) {
    return Setting{ARCUS_METHOD_EULER, ARCUS_PRECISION_DOUBLE, kDistanceStep, kDistanceTol, kLength, g};
  });
}

// The float path against double at the same settings, in pairs (double first).
std::vector<Setting> float_study(const Plan& p) {
  std::vector<Setting> out;
  auto pair = [&](Setting s) {
    for (arcus_precision prec : {ARCUS_PRECISION_DOUBLE, ARCUS_PRECISION_FLOAT}) {
      s.precision = prec;
      out.push_back(s);
    }
  };
  for (double h : p.float_rk4_steps) pair({ARCUS_METHOD_RK4, ARCUS_PRECISION_DOUBLE, h, 0, kLength, kGradient});
  for (double tol : p.float_dp45_tols) pair({ARCUS_METHOD_DP45, ARCUS_PRECISION_DOUBLE, 0, tol, kLength, kGradient});
  return out;
}

// lanes × groups per work-item for the two headline kernels (--sweep-layout): what the
// library's per-device default leaves on the table.
std::vector<Row> layout_study(ArcusBench& arcus, const Plan& p) {
  const Setting kernels[] = {{ARCUS_METHOD_RK4, ARCUS_PRECISION_DOUBLE, kRk4PeakStep, 0, kLength, kGradient},
                             {ARCUS_METHOD_DP45, ARCUS_PRECISION_DOUBLE, 0, kHeadlineTol, kLength, kGradient}};
  std::vector<Row> rows;
  for (const Setting& s : kernels)
    for (uint32_t lanes : {4u, 8u, 16u})
      for (uint32_t groups : {1u, 2u, 4u, 8u}) {
        arcus.set_layout(lanes, groups);
        rows.push_back(arcus.measure(s, p.point_seconds, 0, 1));
        print_row(rows.back());
      }
  arcus.set_layout(0, 0);
  return rows;
}

// ---- the two ratios ----------------------------------------------------------------------
struct DpComparison {
  Row arcus, peer, peer_all_cores;
  double arcus_err = 0;  // arcus' max error over the peer's rays
  bool equal_tolerance = true;
  bool arcus_reaches_peer_error = true;
  // For context, not the target: the loosest sweep tolerance at which arcus' error is
  // still no worse than the peer's (arcus may be doing more work than the peer at 1e-9).
  std::optional<Row> cheapest_equal_error;
  // The headline compares fastest launches: on a shared machine the least disturbed
  // time of each side (arcus needs both cores, the peer one, so other load hurts arcus
  // more).  The ratio of medians is reported beside it.
  double ratio() const { return arcus.best_rays_per_second() / peer.best_rays_per_second(); }
  double ratio_of_medians() const { return arcus.rays_per_second() / peer.rays_per_second(); }
};

// The loosest (cheapest) swept arcus tolerance, no looser than `max_tol`, whose max
// error over the first `rays` rays is no worse than `err`; null if none.
const Row* loosest_tolerance_matching(const std::vector<Row>& tol_rows, double max_tol, double err, std::size_t rays) {
  for (const Row& r : tol_rows)  // loosest first
    if (r.setting.tol <= max_tol * (1 + 1e-9) && r.err_max_over(rays) <= err) return &r;
  return nullptr;
}

// arcus DP45 against the peer at tolerance 1e-9.  "At equal or better error": if arcus'
// max error over the shared rays is worse than the peer's, the comparison moves to the
// loosest tighter tolerance of the sweep at which arcus matches the peer.
DpComparison compare_dp45(ArcusBench& arcus, const RaySet& rays, const Plan& p, const std::vector<Row>& tol_rows) {
  DpComparison c;
  c.peer = measure_peer(rays, p.peer_rays, kHeadlineTol, 1, p.headline_seconds, p.headline_launches);
  c.peer_all_cores = measure_peer(rays, p.peer_rays, kHeadlineTol, std::max(1u, std::thread::hardware_concurrency()),
                                  p.headline_seconds, p.headline_launches);
  const Row* match = loosest_tolerance_matching(tol_rows, kHeadlineTol, c.peer.err_max, p.peer_rays);
  c.arcus_reaches_peer_error = match != nullptr;
  const double tol = match ? match->setting.tol : kHeadlineTol;
  c.equal_tolerance = tol == kHeadlineTol;
  if (const Row* any = loosest_tolerance_matching(tol_rows, HUGE_VAL, c.peer.err_max, p.peer_rays))
    c.cheapest_equal_error = *any;
  const Setting s{ARCUS_METHOD_DP45, ARCUS_PRECISION_DOUBLE, 0, tol, kLength, kGradient};
  c.arcus = arcus.measure(s, p.headline_seconds, p.peer_rays, p.headline_launches);
  c.arcus_err = c.arcus.err_max_over(p.peer_rays);
  return c;
}

struct PeakComparison {
  Row rk4;
  std::vector<bench::PeakResult> variants;
  bench::PeakResult best;
  // Fastest RK4 launch against the best microkernel launch; the median beside it.
  double rk4_gflops() const { return rk4.best_steps_per_second() * kRk4FlopsPerStep * 1e-9; }
  double rk4_gflops_median() const { return rk4.steps_per_second() * kRk4FlopsPerStep * 1e-9; }
  double fraction() const { return rk4_gflops() / best.gflops; }
};

PeakComparison compare_rk4_with_peak(ArcusBench& arcus, const Plan& p) {
  PeakComparison c;
  c.variants = bench::measure_fp64_peak(arcus.device().platform, arcus.device().name, p.peak_seconds);
  c.best = *std::max_element(c.variants.begin(), c.variants.end(),
                             [](const auto& a, const auto& b) { return a.gflops < b.gflops; });
  const Setting s{ARCUS_METHOD_RK4, ARCUS_PRECISION_DOUBLE, kRk4PeakStep, 0, kLength, kGradient};
  c.rk4 = arcus.measure(s, p.headline_seconds, 0, p.headline_launches);
  return c;
}

// ---- output --------------------------------------------------------------------------------
std::string fmt(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

// Two significant digits with a plain exponent: 4.9e-8, as in the ratio lines.
std::string sci(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.1e", v);
  const std::string s = buf;
  const std::size_t e = s.find('e');
  return e == std::string::npos ? s : s.substr(0, e) + "e" + std::to_string(std::stoi(s.substr(e + 1)));
}

void write_csv(const fs::path& path, const std::vector<Row>& rows) {
  std::ofstream out(path);
  out << "impl,method,precision,threads,step,tol,length,gradient,rays,launches,mean_steps,seconds,best_seconds,wall_seconds,"
         "time_per_ray_s,rays_per_s,steps_per_s,err_max_m,err_mean_m,not_done,lanes,groups\n";
  out.precision(9);
  for (const Row& r : rows) {
    const Setting& s = r.setting;
    out << r.impl << ',' << method_name(s.method) << ',' << precision_name(s.precision) << ',' << r.threads << ','
        << (adaptive(s) ? 0.0 : s.step) << ',' << (adaptive(s) ? s.tol : 0.0) << ',' << s.length << ',' << s.gradient
        << ',' << r.rays << ',' << r.launches << ',' << r.mean_steps << ',' << r.seconds << ',' << r.best_seconds << ','
        << r.wall_seconds << ',' << r.time_per_ray() << ',' << r.rays_per_second() << ',' << r.steps_per_second() << ','
        << r.err_max << ',' << r.err_mean << ',' << r.not_done << ',' << r.lanes << ',' << r.groups << '\n';
  }
}

void write_peak_csv(const fs::path& path, const PeakComparison& c) {
  std::ofstream out(path);
  out << "vector_width,chains,gflops\n";
  for (const auto& v : c.variants) out << v.vector_width << ',' << v.chains << ',' << v.gflops << '\n';
}

std::string markdown_table(const std::vector<Row>& rows) {
  std::ostringstream md;
  md << "| impl | method | precision | step / tol | length m | gradient | rays × launches | steps/ray | time/ray s "
        "| best time/ray s | rays/s | steps/s | max err m | mean err m | not done | lanes×groups |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const Row& r : rows) {
    const Setting& s = r.setting;
    const std::string impl = r.impl == "arcus" ? r.impl : r.impl + " ×" + std::to_string(r.threads);
    md << "| " << impl << " | " << method_name(s.method) << " | " << precision_name(s.precision) << " | "
       << (adaptive(s) ? "tol " + fmt("%.3g", s.tol) : "h " + fmt("%.3g", s.step)) << " | " << fmt("%g", s.length)
       << " | " << fmt("%g", s.gradient) << " | " << r.rays << " × " << r.launches << " | " << fmt("%.4g", r.mean_steps) << " | "
       << fmt("%.3e", r.time_per_ray()) << " | " << fmt("%.3e", r.best_seconds / static_cast<double>(r.rays)) << " | "
       << fmt("%.3e", r.rays_per_second()) << " | "
       << fmt("%.3e", r.steps_per_second()) << " | " << fmt("%.2e", r.err_max) << " | " << fmt("%.2e", r.err_mean)
       << " | " << r.not_done << " | "
       << (r.impl == "arcus" ? std::to_string(r.lanes) + "×" + std::to_string(r.groups) : "–") << " |\n";
  }
  return md.str();
}

// Float against double, from the pairs of float_study.
std::string float_summary(const std::vector<Row>& rows) {
  std::ostringstream md;
  md << "| method | step / tol | double rays/s | float rays/s | float speed-up | double max err m | float max err m "
        "| float not done |\n|---|---|---|---|---|---|---|---|\n";
  for (std::size_t i = 0; i + 1 < rows.size(); i += 2) {
    const Row &d = rows[i], &f = rows[i + 1];
    const Setting& s = d.setting;
    md << "| " << method_name(s.method) << " | "
       << (adaptive(s) ? "tol " + fmt("%.3g", s.tol) : "h " + fmt("%.3g", s.step)) << " | "
       << fmt("%.3e", d.rays_per_second()) << " | " << fmt("%.3e", f.rays_per_second()) << " | "
       << fmt("%.2f×", f.rays_per_second() / d.rays_per_second()) << " | " << fmt("%.2e", d.err_max) << " | "
       << fmt("%.2e", f.err_max) << " | " << f.not_done << " |\n";
  }
  return md.str();
}

struct Machine {
  std::string cpu, date, device, platform, device_version, arcus_version;
  std::string load_before, load_after;  // other work on the cores skews every timing
  unsigned cores = 0;
  uint32_t compute_units = 0, lanes = 0;
};

// The 1, 5 and 15 minute load averages.
std::string load_average() {
  std::ifstream in("/proc/loadavg");
  std::string a, b, c;
  in >> a >> b >> c;
  return a + " " + b + " " + c;
}

std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);)
    if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
  return "unknown";
}

Machine describe_machine(const arcus_device_info& dev) {
  Machine m;
  m.cpu = cpu_model();
  m.load_before = load_average();
  m.cores = std::thread::hardware_concurrency();
  char date[64];
  const std::time_t now = std::time(nullptr);
  std::strftime(date, sizeof date, "%Y-%m-%d %H:%M UTC", std::gmtime(&now));
  m.date = date;
  m.device = dev.name;
  m.platform = dev.platform;
  m.device_version = dev.version;
  m.compute_units = dev.compute_units;
  m.lanes = dev.lanes;
  int major = 0, minor = 0, patch = 0;
  arcus_get_version(&major, &minor, &patch);
  m.arcus_version = std::to_string(major) + "." + std::to_string(minor) + "." + std::to_string(patch);
  return m;
}

std::string dp45_line(const DpComparison& c) {
  return "ratio dp45_vs_odeint_1thread = " + fmt("%.1f", c.ratio()) + "x (arcus err " + sci(c.arcus_err) +
         " m, odeint err " + sci(c.peer.err_max) + " m)";
}

std::string dp45_basis(const DpComparison& c, const Plan& p) {
  std::string s = "arcus DP45 at tol " + fmt("%.3g", c.arcus.setting.tol) + " vs odeint dopri5 at tol " +
                  fmt("%.3g", kHeadlineTol) + " (rtol = tol, atol = tol·1e-3), max end-point error over the same " +
                  std::to_string(p.peer_rays) + " rays; ";
  if (!c.arcus_reaches_peer_error)
    s += "arcus' error is WORSE than the peer's at every tolerance down to the sweep's tightest: compared at 1e-9";
  else if (c.equal_tolerance)
    s += "equal tolerance, arcus' error equal or better";
  else
    s += "arcus' error at 1e-9 was worse, so arcus runs at the loosest tighter tolerance that matches the peer";
  return s;
}

std::string rk4_line(const PeakComparison& c) {
  return "ratio rk4_fraction_of_fp64_peak = " + fmt("%.1f", 100 * c.fraction()) + "% (RK4 " + fmt("%.1f", c.rk4_gflops()) +
         " GFLOP/s of peak " + fmt("%.1f", c.best.gflops) + " GFLOP/s)";
}

struct Results {
  std::vector<Row> step, tolerance, peer, distance, gradient, precision, layout;
  DpComparison dp;
  PeakComparison peak;
  std::vector<Row> native;  // native C++ RK4 on 1 thread, then on every core
};

// arcus' RK4 (the peak run) against the native C++ loop: fastest launches, and the
// fraction of the FP64 peak with FLOPs counted from the formulas (flops.hpp).
std::string native_rk4_summary(const Results& r) {
  const double flops = bench::flops_per_step(ARCUS_METHOD_RK4, ARCUS_FIELD_LINEAR);
  const Row& a = r.peak.rk4;
  const std::size_t shared = std::min({a.rays, r.native[0].rays, r.native[1].rays});  // errors over the same rays
  std::ostringstream md;
  md << "**RK4 against native C++** (bench/native_rk4.cpp: OpenMP, -O3 -march=native), h = " << kRk4PeakStep
     << ", L = " << kLength << ", " << flops << " FLOPs per step (flops.hpp; PoCL's compiled kernel executes 97):\n\n"
     << "| impl | steps/s | arcus ÷ it | max err m (first " << shared << " rays) | GFLOP/s | of FP64 peak |\n"
     << "|---|---|---|---|---|---|\n";
  for (const Row* row : {&a, &r.native[0], &r.native[1]}) {
    const double gflops = row->best_steps_per_second() * flops * 1e-9;
    md << "| " << (row->impl == "arcus" ? "arcus" : "native ×" + std::to_string(row->threads)) << " | "
       << fmt("%.3e", row->best_steps_per_second()) << " | "
       << fmt("%.2f×", a.best_steps_per_second() / row->best_steps_per_second()) << " | "
       << fmt("%.2e", row->err_max_over(shared)) << " | " << fmt("%.1f", gflops) << " | "
       << fmt("%.1f%%", 100 * gflops / r.peak.best.gflops) << " |\n";
  }
  return md.str();
}

void write_markdown(const fs::path& path, const Machine& m, const Plan& p, const Results& r, bool quick) {
  std::ofstream md(path);
  md << "# arcus benchmark: what accuracy costs in time\n\n"
     << "Thesis §5.4.1 / Fig. 5.13 on n = 1 + 0.1·y (linear field, gradient along y), errors against the exact "
        "catenary end point.\n\n"
     << "- date: " << m.date << (quick ? " (--quick: reduced sizes, not for reporting)" : "") << "\n"
     << "- CPU: " << m.cpu << ", " << m.cores << " hardware threads\n"
     << "- device: " << m.device << " (" << m.platform << ", " << m.device_version << "), " << m.compute_units
     << " compute units, " << m.lanes << " lanes\n"
     << "- load average (1/5/15 min) before the run: " << m.load_before << ", after: " << m.load_after << "\n"
     << "- arcus " << m.arcus_version << "; time per ray = kernel seconds (arcus_job_stats) / rays, after an untimed "
        "warm-up per kernel variant; peer times are wall clock\n"
     << "- DP45 and the peer use rtol = tol, atol = tol·1e-3; errors are max / mean over the rays of each point\n\n";

  const DpComparison& dp = r.dp;
  const PeakComparison& pk = r.peak;
  md << "## Headline\n\n"
     << "Fastest launch of each side (at least " << p.headline_launches << " launches and " << p.headline_seconds
     << " s each); the same ratios from median launches beside them.\n\n"
     << "| ratio | value | from medians | target | met |\n|---|---|---|---|---|\n"
     << "| arcus DP45 rays/s ÷ odeint 1 thread, tol 1e-9, equal or better error | " << fmt("%.1f×", dp.ratio())
     << " | " << fmt("%.1f×", dp.ratio_of_medians()) << " | ≥ 10× | "
     << (dp.ratio() >= 10 && dp.arcus_reaches_peer_error ? "yes" : "no") << " |\n"
     << "| RK4 kernel GFLOP/s ÷ FP64 peak | " << fmt("%.1f%%", 100 * pk.fraction()) << " | "
     << fmt("%.1f%%", 100 * pk.rk4_gflops_median() / pk.best.gflops) << " | ≥ 40% | "
     << (pk.fraction() >= 0.4 ? "yes" : "no") << " |\n\n";

  md << "**DP45 against the peer.** " << dp45_basis(dp, p) << ". Max error: arcus " << fmt("%.2e", dp.arcus_err)
     << " m, odeint " << fmt("%.2e", dp.peer.err_max) << " m. Rays/s, fastest launch: arcus "
     << fmt("%.3e", dp.arcus.best_rays_per_second()) << ", odeint 1 thread " << fmt("%.3e", dp.peer.best_rays_per_second())
     << ", odeint " << dp.peer_all_cores.threads << " threads " << fmt("%.3e", dp.peer_all_cores.best_rays_per_second())
     << " (arcus " << fmt("%.1f×", dp.arcus.best_rays_per_second() / dp.peer_all_cores.best_rays_per_second())
     << " of it). Counting all of arcus_advance (host copies included, median): "
     << fmt("%.1f×", static_cast<double>(dp.arcus.rays) / dp.arcus.wall_seconds / dp.peer.rays_per_second())
     << " the peer's median.";
  if (dp.cheapest_equal_error)
    md << " At equal error rather than equal tolerance, the loosest swept arcus tolerance whose max error is no worse "
          "than the peer's at 1e-9 is "
       << fmt("%.3g", dp.cheapest_equal_error->setting.tol) << " ("
       << fmt("%.2e", dp.cheapest_equal_error->err_max_over(p.peer_rays)) << " m): "
       << fmt("%.1f×", dp.cheapest_equal_error->best_rays_per_second() / dp.peer.best_rays_per_second())
       << " the peer (sweep timing).";
  md << "\n\n" << markdown_table({dp.arcus, dp.peer, dp.peer_all_cores}) << "\n";

  md << "**RK4 against the FP64 peak.** RK4 h = " << kRk4PeakStep << ", L = " << kLength << ": "
     << fmt("%.3e", pk.rk4.best_steps_per_second()) << " steps/s (median " << fmt("%.3e", pk.rk4.steps_per_second())
     << ") × " << kRk4FlopsPerStep << " FLOPs per step (compiled kernel, see README) = " << fmt("%.1f", pk.rk4_gflops())
     << " GFLOP/s (median " << fmt("%.1f", pk.rk4_gflops_median()) << "). FP64 peak " << fmt("%.1f", pk.best.gflops)
     << " GFLOP/s (double" << pk.best.vector_width << " × " << pk.best.chains
     << " independent FMA chains, best of 5 launches). Microkernel variants:";
  for (const auto& v : pk.variants) md << " double" << v.vector_width << " × " << v.chains << ": " << fmt("%.1f", v.gflops) << ";";
  md << "\n\n" << markdown_table({pk.rk4}) << "\n";
  md << native_rk4_summary(r) << "\n" << markdown_table(r.native) << "\n";

  md << "## (a, c) fixed-step methods against step, L = 1000\n\n" << markdown_table(r.step) << "\n"
     << "## (b, d) DP45 against tolerance, L = 1000, with the peer\n\n" << markdown_table(r.tolerance) << "\n"
     << markdown_table(r.peer) << "\n"
     << "## (e, f) against distance, step 5e-3, tol 1e-6\n\n" << markdown_table(r.distance) << "\n"
     << "## (g, h) against gradient, L = 1000, step 5e-3, tol 1e-6\n\n" << markdown_table(r.gradient) << "\n"
     << "## Float against double, L = 1000\n\n" << float_summary(r.precision) << "\n" << markdown_table(r.precision);
  if (!r.layout.empty())
    md << "\n## lanes × groups per work-item (ARCUS_LANES, ARCUS_GROUPS), RK4 h = " << kRk4PeakStep
       << " and DP45 tol 1e-9\n\n" << markdown_table(r.layout);
}

void run_plot_script(const fs::path& out_dir) {
  const fs::path script = ARCUS_BENCH_PLOT_SCRIPT;
  if (!fs::exists(script)) {
    std::printf("plots skipped: %s not found\n", script.c_str());
    return;
  }
  const std::string cmd = "python3 \"" + script.string() + "\" \"" + out_dir.string() + "\"";
  if (std::system(cmd.c_str()) != 0) std::printf("plots failed: %s\n", cmd.c_str());
}

int run_benchmark(const Options& opt) {
  const Plan plan = opt.quick ? quick_plan() : full_plan();
  const fs::path out_dir = opt.out_dir;
  fs::create_directories(out_dir);

  arcus_context_t* raw_ctx = nullptr;
  check(arcus_context_create(ARCUS_DEVICE_DEFAULT, &raw_ctx), nullptr, "arcus_context_create");
  ContextPtr ctx(raw_ctx);
  const RaySet rays = bench::make_rays(std::max(plan.max_rays, plan.peer_rays));
  ArcusBench arcus(ctx.get(), rays);
  Machine machine = describe_machine(arcus.device());
  std::printf("arcus_bench%s on %s (%s)\n", opt.quick ? " --quick" : "", machine.device.c_str(), machine.cpu.c_str());

  Results r;
  std::printf("(a, c) fixed steps against step size\n");
  r.step = measure_all(arcus, step_study(plan), plan.point_seconds);
  std::printf("(b, d) DP45 against tolerance\n");
  r.tolerance = measure_all(arcus, tolerance_study(plan), plan.point_seconds, plan.peer_rays);
  std::printf("(b, d) peer: Boost.Odeint dopri5 against tolerance\n");
  for (unsigned threads : {1u, std::max(1u, std::thread::hardware_concurrency())})
    for (double tol : plan.tolerances) {
      r.peer.push_back(measure_peer(rays, plan.peer_rays, tol, threads, plan.point_seconds, 1));
      print_row(r.peer.back());
    }
  std::printf("(e, f) against distance\n");
  r.distance = measure_all(arcus, distance_study(plan), plan.point_seconds);
  std::printf("(g, h) against gradient\n");
  r.gradient = measure_all(arcus, gradient_study(plan), plan.point_seconds);
  std::printf("float against double\n");
  r.precision = measure_all(arcus, float_study(plan), plan.point_seconds);
  if (opt.sweep_layout) {
    std::printf("lanes x groups\n");
    r.layout = layout_study(arcus, plan);
  }
  std::printf("DP45 against the peer at tol 1e-9\n");
  r.dp = compare_dp45(arcus, rays, plan, r.tolerance);
  for (const Row* row : {&r.dp.arcus, &r.dp.peer, &r.dp.peer_all_cores}) print_row(*row);
  std::printf("RK4 against the FP64 peak\n");
  r.peak = compare_rk4_with_peak(arcus, plan);
  print_row(r.peak.rk4);
  std::printf("RK4 against native C++\n");
  for (unsigned threads : {1u, std::max(1u, std::thread::hardware_concurrency())}) {
    r.native.push_back(measure_native_rk4(rays, kRk4PeakStep, threads, plan.headline_seconds, 3));
    print_row(r.native.back());
  }

  write_csv(out_dir / "step.csv", r.step);
  std::vector<Row> tol_rows = r.tolerance;
  tol_rows.insert(tol_rows.end(), r.peer.begin(), r.peer.end());
  write_csv(out_dir / "tolerance.csv", tol_rows);
  write_csv(out_dir / "distance.csv", r.distance);
  write_csv(out_dir / "gradient.csv", r.gradient);
  write_csv(out_dir / "float.csv", r.precision);
  write_csv(out_dir / "headline.csv", {r.dp.arcus, r.dp.peer, r.dp.peer_all_cores, r.peak.rk4});
  write_csv(out_dir / "native.csv", r.native);
  write_peak_csv(out_dir / "fp64_peak.csv", r.peak);
  if (!r.layout.empty()) write_csv(out_dir / "layout.csv", r.layout);
  machine.load_after = load_average();
  write_markdown(out_dir / "results.md", machine, plan, r, opt.quick);
  if (opt.plot) run_plot_script(out_dir);

  std::printf("wrote %s/{step,tolerance,distance,gradient,float,headline,native,fp64_peak%s}.csv, results.md%s\n",
              fs::absolute(out_dir).c_str(), r.layout.empty() ? "" : ",layout",
              opt.plot ? ", fig5_13*.png, float.png" : "");
  std::printf("RK4 arcus vs native C++: %.3e vs %.3e (1 thread), %.3e (%u threads) steps/s: %.2fx, %.2fx\n",
              r.peak.rk4.best_steps_per_second(), r.native[0].best_steps_per_second(),
              r.native[1].best_steps_per_second(), r.native[1].threads,
              r.peak.rk4.best_steps_per_second() / r.native[0].best_steps_per_second(),
              r.peak.rk4.best_steps_per_second() / r.native[1].best_steps_per_second());
  std::printf("DP45 basis: %s\n", dp45_basis(r.dp, plan).c_str());
  std::printf("%s\n%s\n", dp45_line(r.dp).c_str(), rk4_line(r.peak).c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run_benchmark(parse_options(argc, argv));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "arcus_bench: %s\n", e.what());
    return 1;
  }
}
