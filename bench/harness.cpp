#include "harness.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <numeric>
#include <stdexcept>

#include "native_rk4.hpp"
#include "odeint_peer.hpp"

namespace bench {
namespace {

constexpr const char* kLayoutVariables[2] = {"ARCUS_LANES", "ARCUS_GROUPS"};

std::size_t round_up(std::size_t n, std::size_t multiple) { return (n + multiple - 1) / multiple * multiple; }

arcus_advance_params params_for(const Setting& s) {
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

void fill_errors(Row& row, std::vector<double> errors) {
  row.err_max = *std::max_element(errors.begin(), errors.end());
  row.err_mean = std::accumulate(errors.begin(), errors.end(), 0.0) / static_cast<double>(errors.size());
  row.errors = std::move(errors);
}

double mean(const std::vector<uint64_t>& steps) {
  return std::accumulate(steps.begin(), steps.end(), 0.0) / static_cast<double>(steps.size());
}

// A row of a CPU peer's run on the first `count` rays, L = kLength, gradient kGradient.
Row peer_row(const char* impl, const Setting& s, unsigned threads, const PeerRun& run, std::size_t count,
             const RaySet& rays, const Timing& timing) {
  Row row;
  row.impl = impl;
  row.setting = s;
  row.threads = threads;
  row.rays = count;
  row.mean_steps = mean(run.steps);
  row.set_timing(timing);
  row.wall_seconds = row.seconds;
  fill_errors(row, end_point_errors(rays, count, run.positions.data(), kN0, kGradient, kLength));
  return row;
}

}  // namespace

// ---- arcus handles -------------------------------------------------------------------
void check(arcus_status status, arcus_context_t* ctx, const std::string& what) {
  if (status == ARCUS_SUCCESS) return;
  const char* msg = ctx ? arcus_context_last_error(ctx) : arcus_last_error();
  throw std::runtime_error(what + ": " + arcus_status_string(status) + (msg && *msg ? std::string(" — ") + msg : ""));
}

ContextPtr make_context() {
  arcus_context_t* raw = nullptr;
  check(arcus_context_create(ARCUS_DEVICE_DEFAULT, &raw), nullptr, "arcus_context_create");
  return ContextPtr(raw);
}

FieldPtr make_linear_field(arcus_context_t* ctx, double gradient) {
  const double g[3] = {0.0, gradient, 0.0};
  arcus_field_t* f = nullptr;
  check(arcus_field_create_linear(ctx, kN0, g, &f), ctx, "arcus_field_create_linear");
  return FieldPtr(f);
}

// ---- settings ------------------------------------------------------------------------
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

bool adaptive(const Setting& s) { return s.method == ARCUS_METHOD_DP45; }

Setting short_path(const Setting& s) {
  Setting shortened = s;
  shortened.length = adaptive(s) ? 1.0 : std::min(s.length, 16 * s.step);
  return shortened;
}

// ---- timing --------------------------------------------------------------------------
double Timing::median() const {
  std::vector<double> v = samples;
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

double Timing::best() const { return *std::min_element(samples.begin(), samples.end()); }

Timing time_launches(double first, const std::function<double()>& launch, double seconds, int min_launches) {
  constexpr std::size_t kMaxLaunches = 25;
  Timing t{{first}};
  auto total = [&] { return std::accumulate(t.samples.begin(), t.samples.end(), 0.0); };
  while (t.samples.size() < static_cast<std::size_t>(min_launches) ||
         (total() < seconds && t.samples.size() < kMaxLaunches))
    t.samples.push_back(launch());
  return t;
}

// ---- rows ------------------------------------------------------------------------------
void Row::set_timing(const Timing& t) {
  seconds = t.median();
  best_seconds = t.best();
  launches = t.samples.size();
}

double Row::err_max_over(std::size_t count) const {
  return *std::max_element(errors.begin(), errors.begin() + static_cast<std::ptrdiff_t>(std::min(count, errors.size())));
}

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

// ---- running arcus ---------------------------------------------------------------------
AdvanceRun advance(arcus_context_t* ctx, arcus_field_t* field, const Setting& s, const RaySet& rays, std::size_t count) {
  const arcus_advance_params params = params_for(s);
  arcus_job_t* raw = nullptr;
  check(arcus_curved_advance(ctx, field, &params, count, rays.origins.data(), rays.directions.data(), nullptr, &raw), ctx,
                             std::string("arcus_curved_advance (") + method_name(s.method) + ")");
  JobPtr job(raw);
  AdvanceRun r;
  r.count = count;
  r.positions.resize(3 * count);
  r.steps.resize(count);
  r.status.resize(count);
  check(arcus_job_get_curved_end_states(job.get(), r.positions.data(), nullptr, r.steps.data(), r.status.data(), nullptr), ctx,
                                        "arcus_job_get_curved_end_states");
  check(arcus_job_get_stats(job.get(), &r.stats), ctx, "arcus_job_get_stats");
  return r;
}

ArcusBench::ArcusBench(arcus_context_t* ctx, const RaySet& rays) : ctx_(ctx), rays_(rays) {
  check(arcus_context_get_device(ctx, &device_), ctx, "arcus_context_get_device");
  for (const char* name : kLayoutVariables)
    if (const char* v = std::getenv(name)) user_layout_[name] = v;
}

ArcusBench::~ArcusBench() { set_layout(0, 0); }

void ArcusBench::set_layout(uint32_t lanes, uint32_t groups) {
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

Row ArcusBench::measure(const Setting& s, double seconds, std::size_t min_rays, int min_launches) {
  const std::size_t fill = warm_up(s);
  const std::size_t probe_rays = std::min(rays_.count(), round_up(std::max(min_rays, fill), fill));
  AdvanceRun probe = run(s, probe_rays);
  const double per_ray = std::max(probe.stats.kernel_seconds, 1e-9) / static_cast<double>(probe_rays);
  const std::size_t wanted = static_cast<std::size_t>(seconds / per_ray);
  const std::size_t count = std::clamp(wanted / fill * fill, probe_rays, rays_.count());

  // Launches of the same rays give the same results; only their times differ.
  const AdvanceRun result = count == probe_rays ? std::move(probe) : run(s, count);
  Timing wall{{result.stats.total_seconds}};
  const Timing kernel = time_launches(
      result.stats.kernel_seconds,
      [&] {
        const AdvanceRun again = run(s, count);
        wall.samples.push_back(again.stats.total_seconds);
        return again.stats.kernel_seconds;
      },
      seconds, min_launches);
  Row row = summarize(s, result);
  row.set_timing(kernel);
  row.wall_seconds = wall.median();
  return row;
}

arcus_field_t* ArcusBench::field(double gradient) {
  auto it = fields_.find(gradient);
  if (it != fields_.end()) return it->second.get();
  return fields_.emplace(gradient, make_linear_field(ctx_, gradient)).first->second.get();
}

AdvanceRun ArcusBench::run(const Setting& s, std::size_t count) { return advance(ctx_, field(s.gradient), s, rays_, count); }

// Builds and first-launches the kernel variant of `s` on a short path; returns the
// number of rays one pass of the device holds (lanes × groups × compute units), the
// granularity of every measured run.
std::size_t ArcusBench::warm_up(const Setting& s) {
  const auto key = std::make_tuple(s.method, s.precision, layout_);
  auto it = fill_.find(key);
  if (it != fill_.end()) return it->second;
  const AdvanceRun r = run(short_path(s), 256);
  const std::size_t fill = std::max<std::size_t>(
      64, std::size_t(std::max(1u, r.stats.lanes)) * std::max(1u, r.stats.groups) * std::max(1u, device_.compute_units));
  return fill_[key] = fill;
}

Row ArcusBench::summarize(const Setting& s, const AdvanceRun& r) const {
  Row row;
  row.impl = "arcus";
  row.setting = s;
  row.rays = r.count;
  row.mean_steps = mean(r.steps);
  row.not_done = static_cast<std::size_t>(
      std::count_if(r.status.begin(), r.status.end(), [](int32_t st) { return st != ARCUS_RAY_DONE; }));
  row.lanes = r.stats.lanes;
  row.groups = r.stats.groups;
  // Rays that stopped early keep their end points: a setting that fails shows up as
  // a large error (and in not_done), not as a gap.
  fill_errors(row, end_point_errors(rays_, r.count, r.positions.data(), kN0, s.gradient, s.length));
  return row;
}

// ---- running the peers -------------------------------------------------------------------
Row measure_peer(const RaySet& rays, std::size_t count, double tol, unsigned threads, double seconds, int min_launches) {
  auto integrate = [&] { return run_odeint_dopri5(rays, count, kN0, kGradient, kLength, tol, tol * kAtolPerTol, threads); };
  const PeerRun run = integrate();
  const Timing timing = time_launches(run.seconds, [&] { return integrate().seconds; }, seconds, min_launches);
  return peer_row("odeint", {ARCUS_METHOD_DP45, ARCUS_PRECISION_DOUBLE, 0, tol, kLength, kGradient}, threads, run, count,
                  rays, timing);
}

Row measure_native_rk4(const RaySet& rays, double h, unsigned threads, double seconds, int min_launches) {
  auto integrate = [&](std::size_t count) { return run_native_rk4(rays, count, kN0, kGradient, kLength, h, threads); };
  const std::size_t probe = std::min<std::size_t>(256, rays.count());
  const double per_ray = std::max(integrate(probe).seconds, 1e-9) / static_cast<double>(probe);
  const std::size_t count =
      std::clamp<std::size_t>(static_cast<std::size_t>(seconds / per_ray) / 64 * 64, probe, rays.count());
  const PeerRun run = integrate(count);
  const Timing timing = time_launches(run.seconds, [&] { return integrate(count).seconds; }, seconds, min_launches);
  return peer_row("native", {ARCUS_METHOD_RK4, ARCUS_PRECISION_DOUBLE, h, 0, kLength, kGradient}, threads, run, count,
                  rays, timing);
}

}  // namespace bench
