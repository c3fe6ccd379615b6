// The harness: the benchmark's problem constants, one measured point (Row), the timing
// of repeated launches, and running arcus and the two CPU peers on the benchmark's rays.
#pragma once

#include <arcus/arcus.h>

#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "problem.hpp"

namespace bench {

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

// ---- arcus handles -------------------------------------------------------------------
// Throws a runtime_error naming `what`, the status and arcus' message.
void check(arcus_status status, arcus_context_t* ctx, const std::string& what);

struct ContextDeleter { void operator()(arcus_context_t* c) const { arcus_context_release(c); } };
struct FieldDeleter { void operator()(arcus_field_t* f) const { arcus_field_release(f); } };
struct JobDeleter { void operator()(arcus_job_t* j) const { arcus_job_release(j); } };
using ContextPtr = std::unique_ptr<arcus_context_t, ContextDeleter>;
using FieldPtr = std::unique_ptr<arcus_field_t, FieldDeleter>;
using JobPtr = std::unique_ptr<arcus_job_t, JobDeleter>;

ContextPtr make_context();  // on arcus' default device
FieldPtr make_linear_field(arcus_context_t* ctx, double gradient);  // n = kN0 + gradient·y

// ---- settings ------------------------------------------------------------------------
const char* method_name(arcus_method m);
const char* precision_name(arcus_precision p);

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

bool adaptive(const Setting& s);
// The same kernel variant on a short path: builds and first-launches it cheaply.
Setting short_path(const Setting& s);

// ---- timing --------------------------------------------------------------------------
// The times of repeated launches of one job.  A launch of a few milliseconds is at the
// mercy of scheduling noise (other work on the cores, too): the job is launched at
// least `min_launches` times and until `seconds` are in, at most 25 times.  The median
// is the typical time; the best is the least disturbed one.
struct Timing {
  std::vector<double> samples;
  double median() const;
  double best() const;
};

// `first` is a launch already made (its time counts); `launch` makes another and
// returns its time.
Timing time_launches(double first, const std::function<double()>& launch, double seconds, int min_launches);

// ---- rows ------------------------------------------------------------------------------
// One measured point, from arcus or from a peer; a row of every CSV.
struct Row {
  std::string impl;  // "arcus" | "odeint" | "native"
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
  void set_timing(const Timing& t);
  // Max error over the first `count` rays: the rays the peer also integrated.
  double err_max_over(std::size_t count) const;
};

// One line per row on stdout, as the run goes.
void print_row(const Row& r);

// ---- running arcus ---------------------------------------------------------------------
// One arcus_advance of the first `count` rays through `field` with `s`'s method,
// precision, length and accuracy (s.gradient is the caller's business).
struct AdvanceRun {
  std::size_t count = 0;
  arcus_job_stats stats{};
  std::vector<double> positions;
  std::vector<uint64_t> steps;
  std::vector<int32_t> status;
};
AdvanceRun advance(arcus_context_t* ctx, arcus_field_t* field, const Setting& s, const RaySet& rays, std::size_t count);

// Runs settings through arcus: one field per gradient, one untimed warm-up per kernel
// variant (so program build and PoCL's first-launch code generation are not timed),
// then a probe that sizes the measured run.
class ArcusBench {
 public:
  ArcusBench(arcus_context_t* ctx, const RaySet& rays);
  ~ArcusBench();
  ArcusBench(const ArcusBench&) = delete;
  ArcusBench& operator=(const ArcusBench&) = delete;

  // Overrides the library's lanes × groups per work-item through the ARCUS_LANES and
  // ARCUS_GROUPS variables it reads at every arcus_advance; (0, 0) restores what the
  // user had set.  The layout is part of the kernel variant, so it keys the warm-up.
  void set_layout(uint32_t lanes, uint32_t groups);

  const arcus_device_info& device() const { return device_; }

  // Measures `s` over about `seconds` of kernel time with at least `min_rays` rays and
  // `min_launches` launches (time_launches).  A probe launch sizes the ray count; when
  // even the most rays make a short kernel, the launches are repeated instead.
  Row measure(const Setting& s, double seconds, std::size_t min_rays, int min_launches);

 private:
  arcus_field_t* field(double gradient);
  AdvanceRun run(const Setting& s, std::size_t count);
  std::size_t warm_up(const Setting& s);
  Row summarize(const Setting& s, const AdvanceRun& r) const;

  arcus_context_t* ctx_;
  const RaySet& rays_;
  arcus_device_info device_{};
  std::map<double, FieldPtr> fields_;
  std::map<std::string, std::string> user_layout_;
  std::pair<uint32_t, uint32_t> layout_{0, 0};
  std::map<std::tuple<arcus_method, arcus_precision, std::pair<uint32_t, uint32_t>>, std::size_t> fill_;
};

// ---- running the peers -------------------------------------------------------------------
// Boost.Odeint's dopri5 on the first `count` rays at tolerance `tol`, L = kLength, timed
// like arcus' launches.
Row measure_peer(const RaySet& rays, std::size_t count, double tol, unsigned threads, double seconds, int min_launches);

// The native C++ RK4 (native_rk4.hpp) at step h, L = kLength, on `threads` threads: a
// probe launch sizes the ray count to about `seconds` per launch.
Row measure_native_rk4(const RaySet& rays, double h, unsigned threads, double seconds, int min_launches);

}  // namespace bench
