#include "report.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <sstream>
#include <thread>

#include "flops.hpp"

namespace bench {
namespace {

namespace fs = std::filesystem;

constexpr double kMiB = 1048576.0;
// At this share of its division-bound ceiling RK4 is called bound by its divisions.
constexpr double kBoundShare = 0.8;

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

std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);)
    if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
  return "unknown";
}

std::string step_or_tol(const Setting& s) {
  return adaptive(s) ? "tol " + fmt("%.3g", s.tol) : "h " + fmt("%.3g", s.step);
}

// ---- CSV ---------------------------------------------------------------------------------------
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

void write_peak_csvs(const fs::path& out_dir, const PeakComparison& c) {
  std::ofstream peak(out_dir / "fp64_peak.csv");
  peak << "vector_width,chains,gflops\n";
  for (const auto& v : c.variants) peak << v.vector_width << ',' << v.chains << ',' << v.gflops << '\n';
  std::ofstream div(out_dir / "fp64_division.csv");
  div << "vector_width,chains,divisions_per_s\n";
  for (const auto& v : c.divisions) div << v.vector_width << ',' << v.chains << ',' << v.per_second << '\n';
}

void write_first_job_csv(const fs::path& path, const FirstJobStudy& s) {
  std::ofstream out(path);
  out << "scenario,arcus_cache,pocl_cache,process_s,context_s,first_job_s";
  for (const char* m : {"rk4", "dp45"})
    for (const char* c : {"_advance_s", "_build_s", "_kernel_s", "_origin"}) out << ',' << m << c;
  out << '\n';
  out.precision(6);
  for (const FirstJob& j : s.runs) {
    out << j.scenario << ',' << j.arcus_cache << ',' << j.pocl_cache << ',' << j.process_seconds << ','
        << j.context_seconds << ',' << j.first_job_seconds;
    for (const FirstKernel& k : j.kernels)
      out << ',' << k.advance_seconds << ',' << k.build_seconds << ',' << k.kernel_seconds << ','
          << program_origin_name(k.origin);
    out << '\n';
  }
}

void write_grid_csv(const fs::path& path, const GridStudy& s) {
  std::ofstream out(path);
  out << "source,side,file_bytes,create_s,create_peak_bytes,create_peak_per_file,job_advance_s,job_kernel_s,"
         "job_peak_bytes\n";
  out.precision(6);
  for (const GridCreation& g : s.rows)
    out << '"' << g.source << "\"," << s.side << ',' << s.file_bytes << ',' << g.create_seconds << ','
        << g.create_peak_bytes << ',' << g.create_peak_bytes / s.file_bytes << ',' << g.job_seconds << ','
        << g.job_kernel_seconds << ',' << g.job_peak_bytes << '\n';
}

// ---- results.md --------------------------------------------------------------------------------
std::string markdown_table(const std::vector<Row>& rows) {
  std::ostringstream md;
  md << "| impl | method | precision | step / tol | length m | gradient | rays × launches | steps/ray | time/ray s "
        "| best time/ray s | rays/s | steps/s | max err m | mean err m | not done | lanes×groups |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const Row& r : rows) {
    const Setting& s = r.setting;
    const std::string impl = r.impl == "arcus" ? r.impl : r.impl + " ×" + std::to_string(r.threads);
    md << "| " << impl << " | " << method_name(s.method) << " | " << precision_name(s.precision) << " | "
       << step_or_tol(s) << " | " << fmt("%g", s.length) << " | " << fmt("%g", s.gradient) << " | " << r.rays << " × "
       << r.launches << " | " << fmt("%.4g", r.mean_steps) << " | " << fmt("%.3e", r.time_per_ray()) << " | "
       << fmt("%.3e", r.best_seconds / static_cast<double>(r.rays)) << " | " << fmt("%.3e", r.rays_per_second()) << " | "
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
    md << "| " << method_name(d.setting.method) << " | " << step_or_tol(d.setting) << " | "
       << fmt("%.3e", d.rays_per_second()) << " | " << fmt("%.3e", f.rays_per_second()) << " | "
       << fmt("%.2f×", f.rays_per_second() / d.rays_per_second()) << " | " << fmt("%.2e", d.err_max) << " | "
       << fmt("%.2e", f.err_max) << " | " << f.not_done << " |\n";
  }
  return md.str();
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

std::string headline_section(const Plan& p, const Results& r) {
  const DpComparison& dp = r.dp;
  const PeakComparison& pk = r.peak;
  const double flops = rk4_counted_flops();
  std::ostringstream md;
  md << "## Headline\n\n"
     << "Fastest launch of each side (at least " << p.headline_launches << " launches and " << p.headline_seconds
     << " s each); the same ratios from median launches beside them.\n\n"
     << "| ratio | value | from medians | target | met |\n|---|---|---|---|---|\n"
     << "| arcus DP45 rays/s ÷ odeint 1 thread, tol 1e-9, equal or better error | " << fmt("%.1f×", dp.ratio()) << " | "
     << fmt("%.1f×", dp.ratio_of_medians()) << " | ≥ 10× | "
     << (dp.ratio() >= 10 && dp.arcus_reaches_peer_error ? "yes" : "no") << " |\n"
     << "| the same per core: arcus rays/s ÷ " << dp.compute_units << " compute units ÷ odeint 1 thread | "
     << fmt("%.2f×", dp.per_core_ratio()) << " | " << fmt("%.2f×", dp.per_core_ratio_of_medians()) << " | – | – |\n"
     << "| RK4 kernel GFLOP/s (" << flops << " FLOPs per step, flops.hpp) ÷ FP64 peak | "
     << fmt("%.1f%%", 100 * pk.fraction(flops)) << " | "
     << fmt("%.1f%%", 100 * pk.rk4_gflops_median(flops) / pk.best.gflops) << " | ≥ 40% | "
     << (pk.fraction(flops) >= 0.4 ? "yes" : "no") << " |\n\n";
  return md.str();
}

std::string dp45_section(const Plan& p, const DpComparison& dp) {
  std::ostringstream md;
  md << "**DP45 against the peer.** " << dp45_basis(dp, p) << ". Max error: arcus " << fmt("%.2e", dp.arcus_err)
     << " m, odeint " << fmt("%.2e", dp.peer.err_max) << " m. Rays/s, fastest launch: arcus "
     << fmt("%.3e", dp.arcus.best_rays_per_second()) << " (" << fmt("%.3e", dp.arcus.best_rays_per_second() / dp.compute_units)
     << " per compute unit), odeint 1 thread " << fmt("%.3e", dp.peer.best_rays_per_second()) << ", odeint "
     << dp.peer_all_cores.threads << " threads " << fmt("%.3e", dp.peer_all_cores.best_rays_per_second()) << " (arcus "
     << fmt("%.1f×", dp.arcus.best_rays_per_second() / dp.peer_all_cores.best_rays_per_second())
     << " of it). Per core, arcus does " << fmt("%.2f×", dp.per_core_ratio())
     << " the peer's single-thread rays/s (median " << fmt("%.2f×", dp.per_core_ratio_of_medians())
     << "). Counting all of arcus_curved_advance (host copies included, median): "
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
  return md.str();
}

std::string rk4_peak_section(const PeakComparison& pk) {
  const double counted = rk4_counted_flops(), executed = kRk4LinearExecutedFlops;
  const double rate = pk.rk4.best_steps_per_second(), ceiling = pk.division_ceiling();
  std::ostringstream md;
  md << "**RK4 against the FP64 peak.** RK4 h = " << kRk4PeakStep << ", L = " << kLength << " runs at **"
     << fmt("%.3e", rate) << " steps/s** (fastest launch; median " << fmt("%.3e", pk.rk4.steps_per_second())
     << "): the physical rate, the figure to compare between versions (GFLOP/s depend on how the FLOPs are counted). "
     << "flops.hpp counts " << counted << " FLOPs per step from the method and the field; the compiled kernel executes "
     << executed << " of them for the linear field (∇n is constant, so the compiler removes the loop-invariant v part "
        "of the stage sum and computes stage 3's v, equal to stage 2's, once). FP64 peak "
     << fmt("%.1f", pk.best.gflops) << " GFLOP/s (double" << pk.best.vector_width << " × " << pk.best.chains
     << " independent FMA chains, best of 5 launches). Microkernel variants:";
  for (const auto& v : pk.variants) md << " double" << v.vector_width << " × " << v.chains << ": " << fmt("%.1f", v.gflops) << ";";
  md << "\n\n| FLOPs per step | count | GFLOP/s | median | of FP64 peak | median |\n|---|---|---|---|---|---|\n";
  const struct { const char* what; double flops; } counts[] = {
      {"from the method and the field (flops.hpp; the headline)", counted}, {"executed by the compiled kernel", executed}};
  for (const auto& c : counts)
    md << "| " << c.what << " | " << c.flops << " | " << fmt("%.1f", pk.rk4_gflops(c.flops)) << " | "
       << fmt("%.1f", pk.rk4_gflops_median(c.flops)) << " | " << fmt("%.1f%%", 100 * pk.fraction(c.flops)) << " | "
       << fmt("%.1f%%", 100 * pk.rk4_gflops_median(c.flops) / pk.best.gflops) << " |\n";

  md << "\n**" << (rate >= kBoundShare * ceiling ? "RK4 is bound by its divisions." : "RK4 and its divisions.")
     << "** Each step divides " << kRk4DivisionsPerStep << " times per ray (1/n in each derivative). The division "
     << "microkernel (x = a / x on independent doubleN chains, every compute unit, best of 5 launches) does "
     << fmt("%.3e", pk.best_division.per_second) << " divisions/s (";
  for (std::size_t i = 0; i < pk.divisions.size(); ++i)
    md << (i ? "; " : "") << "double" << pk.divisions[i].vector_width << " × " << pk.divisions[i].chains << ": "
       << fmt("%.3e", pk.divisions[i].per_second);
  md << "), so the divisions alone allow at most " << fmt("%.3e", ceiling) << " steps/s. RK4 runs at "
     << fmt("%.3e", rate) << " steps/s, " << fmt("%.0f%%", 100 * rate / ceiling) << " of that ceiling, while its "
     << executed << " executed FLOPs use " << fmt("%.0f%%", 100 * pk.fraction(executed)) << " of the FP64 peak.\n\n"
     << markdown_table({pk.rk4}) << "\n";
  return md.str();
}

// arcus' RK4 (the peak run) against the native C++ loop: fastest launches, and the
// fraction of the FP64 peak with FLOPs counted from the formulas (flops.hpp).
std::string native_rk4_section(const Results& r) {
  const double flops = rk4_counted_flops();
  const Row& a = r.peak.rk4;
  const std::size_t shared = std::min({a.rays, r.native[0].rays, r.native[1].rays});  // errors over the same rays
  std::ostringstream md;
  md << "**RK4 against native C++** (bench/native_rk4.cpp: OpenMP, -O3 -march=native), h = " << kRk4PeakStep
     << ", L = " << kLength << ", " << flops << " FLOPs per step (flops.hpp; PoCL's compiled kernel executes "
     << kRk4LinearExecutedFlops << "):\n\n"
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
  md << "\n" << markdown_table(r.native) << "\n";
  return md.str();
}

const FirstJob* find_run(const FirstJobStudy& s, const std::string& scenario) {
  for (const FirstJob& j : s.runs)
    if (j.scenario == scenario) return &j;
  return nullptr;
}

std::string first_job_section(const FirstJobStudy& s) {
  std::ostringstream md;
  md << "## First job of a new process\n\n"
     << "Context creation + the first arcus_curved_advance of the RK4 (h " << kRk4PeakStep << ") and DP45 (tol "
     << fmt("%.3g", kHeadlineTol) << ") kernels above (double, linear field, 256 rays, short paths), in a child "
        "process (`arcus_bench --first-job`) with ARCUS_CACHE_DIR and POCL_CACHE_DIR in fresh temp dirs (removed "
        "afterwards). cold: both caches empty; warm: a second process on the same dirs (arcus' disk cache hit); PoCL "
        "cache only: ARCUS_CACHE_DIR=off, PoCL's cache warm; arcus cache only: arcus' cache warm, a fresh "
        "POCL_CACHE_DIR. process: spawn to exit as the parent sees it (loading the libraries and the OpenCL "
        "platform included); advance: all of arcus_curved_advance, build: getting the program, program: where it came "
        "from (arcus_job_stats.program_origin). Advance time beyond build is mostly PoCL generating the kernel's "
        "launch code at its first launch, which PoCL's cache keeps. One process per scenario: single samples.\n\n";
  if (!s.error.empty()) return md.str() + "Not measured: " + s.error + "\n\n";
  md << "| scenario | arcus cache | PoCL cache | process s | context s | context + first jobs s | RK4 advance s "
        "| RK4 build s | RK4 program | DP45 advance s | DP45 build s | DP45 program |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const FirstJob& j : s.runs) {
    md << "| " << j.scenario << " | " << j.arcus_cache << " | " << j.pocl_cache << " | "
       << fmt("%.3f", j.process_seconds) << " | " << fmt("%.3f", j.context_seconds) << " | "
       << fmt("%.3f", j.first_job_seconds);
    for (const FirstKernel& k : j.kernels)
      md << " | " << fmt("%.3f", k.advance_seconds) << " | " << fmt("%.3f", k.build_seconds) << " | "
         << program_origin_name(k.origin);
    md << " |\n";
  }
  const FirstJob *cold = find_run(s, "cold"), *warm = find_run(s, "warm"), *pocl = find_run(s, "PoCL cache only");
  if (cold && warm && pocl)
    md << "\nA new process's first jobs take " << fmt("%.3f", cold->first_job_seconds) << " s cold and "
       << fmt("%.3f", warm->first_job_seconds) << " s warm; with PoCL's cache alone "
       << fmt("%.3f", pocl->first_job_seconds) << " s, so arcus' own cache saves "
       << fmt("%.3f", pocl->first_job_seconds - warm->first_job_seconds) << " s of it.\n";
  return md.str() + "\n";
}

std::string grid_section(const GridStudy& s) {
  std::ostringstream md;
  md << "## Grid creation, " << s.side << "³\n\n"
     << "A " << s.side << "³ float32 grid file (" << fmt("%.0f", s.file_bytes / kMiB)
     << " MiB, n = 1 + 1e-4·(sin + sin + sin)/3) in a temp dir (removed afterwards); each source is created in its own "
        "child process (`arcus_bench --grid-child FILE [--from-memory]`): arcus_field_create_grid_from_file from the "
        "file, arcus_field_create_grid from an array of doubles the child read beforehand. create: wall time of the "
        "call; peak RSS growth: the process's peak RSS during the call (VmHWM, reset just before it) less its RSS "
        "before, also as a multiple of the file's size (the values as doubles are 2×). Then one small RK4 job on the "
        "grid (256 rays, its program built beforehand on a 2³ grid), so the grid's upload to the device is counted, "
        "separately. before: a reliability probe before the fixes (a message formatted for every valid value; "
        "float32 files peaked at 5.3× the file).\n\n";
  if (!s.error.empty()) return md.str() + "Not measured: " + s.error + "\n\n";
  const bool probe_size = s.side == kProbeGridSide;
  md << "| source | create s | before s | peak RSS growth MiB | × file | before × | first RK4 job s | its kernel s "
        "| its peak RSS growth MiB |\n|---|---|---|---|---|---|---|---|---|\n";
  for (const GridCreation& g : s.rows) {
    const bool file = g.source.rfind("file", 0) == 0;
    md << "| " << g.source << " | " << fmt("%.3f", g.create_seconds) << " | "
       << (probe_size ? fmt("%.1f", kProbeSecondsBefore) : "–") << " | " << fmt("%.0f", g.create_peak_bytes / kMiB)
       << " | " << fmt("%.2f×", g.create_peak_bytes / s.file_bytes) << " | "
       << (probe_size && file ? fmt("%.1f×", kProbePeakPerFileBefore) : "–") << " | " << fmt("%.3f", g.job_seconds)
       << " | " << fmt("%.2e", g.job_kernel_seconds) << " | " << fmt("%.0f", g.job_peak_bytes / kMiB) << " |\n";
  }
  return md.str() + "\n";
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
  md << headline_section(p, r) << dp45_section(p, r.dp) << rk4_peak_section(r.peak) << native_rk4_section(r);
  md << "## (a, c) fixed-step methods against step, L = 1000\n\n" << markdown_table(r.step) << "\n"
     << "## (b, d) DP45 against tolerance, L = 1000, with the peer\n\n" << markdown_table(r.tolerance) << "\n"
     << markdown_table(r.peer) << "\n"
     << "## (e, f) against distance, step 5e-3, tol 1e-6\n\n" << markdown_table(r.distance) << "\n"
     << "## (g, h) against gradient, L = 1000, step 5e-3, tol 1e-6\n\n" << markdown_table(r.gradient) << "\n"
     << "## Float against double, L = 1000\n\n" << float_summary(r.precision) << "\n" << markdown_table(r.precision);
  if (!r.layout.empty())
    md << "\n## lanes × groups per work-item (ARCUS_LANES, ARCUS_GROUPS), RK4 h = " << kRk4PeakStep
       << " and DP45 tol 1e-9\n\n" << markdown_table(r.layout);
  md << "\n" << first_job_section(r.first_job) << grid_section(r.grid);
}

}  // namespace

std::string load_average() {
  std::ifstream in("/proc/loadavg");
  std::string a, b, c;
  in >> a >> b >> c;
  return a + " " + b + " " + c;
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

void write_outputs(const fs::path& out_dir, const Machine& m, const Plan& p, const Results& r, bool quick) {
  write_csv(out_dir / "step.csv", r.step);
  std::vector<Row> tol_rows = r.tolerance;
  tol_rows.insert(tol_rows.end(), r.peer.begin(), r.peer.end());
  write_csv(out_dir / "tolerance.csv", tol_rows);
  write_csv(out_dir / "distance.csv", r.distance);
  write_csv(out_dir / "gradient.csv", r.gradient);
  write_csv(out_dir / "float.csv", r.precision);
  write_csv(out_dir / "headline.csv", {r.dp.arcus, r.dp.peer, r.dp.peer_all_cores, r.peak.rk4});
  write_csv(out_dir / "native.csv", r.native);
  write_peak_csvs(out_dir, r.peak);
  if (!r.layout.empty()) write_csv(out_dir / "layout.csv", r.layout);
  write_first_job_csv(out_dir / "first_job.csv", r.first_job);
  write_grid_csv(out_dir / "grid.csv", r.grid);
  write_markdown(out_dir / "results.md", m, p, r, quick);
}

void run_plot_script(const fs::path& out_dir) {
  // An installed copy (pip install .) is told where its plotting script went.
  const char* installed = std::getenv("ARCUS_BENCH_PLOT_SCRIPT");
  const fs::path script = installed && *installed ? installed : ARCUS_BENCH_PLOT_SCRIPT;
  if (!fs::exists(script)) {
    std::printf("plots skipped: %s not found\n", script.c_str());
    return;
  }
  const std::string cmd = "python3 \"" + script.string() + "\" \"" + out_dir.string() + "\"";
  if (std::system(cmd.c_str()) != 0) std::printf("plots failed: %s\n", cmd.c_str());
}

void print_summary(const fs::path& out_dir, const Plan& p, const Results& r, bool plotted) {
  const double flops = rk4_counted_flops();
  const Row &rk4 = r.peak.rk4, &native1 = r.native[0], &native_all = r.native[1];
  std::printf("wrote %s/{step,tolerance,distance,gradient,float,headline,native,fp64_peak,fp64_division%s,first_job,"
              "grid}.csv, results.md%s\n",
              fs::absolute(out_dir).c_str(), r.layout.empty() ? "" : ",layout",
              plotted ? ", fig5_13*.png, float.png" : "");
  std::printf("RK4 arcus vs native C++: %.3e vs %.3e (1 thread), %.3e (%u threads) steps/s: %.2fx, %.2fx\n",
              rk4.best_steps_per_second(), native1.best_steps_per_second(), native_all.best_steps_per_second(),
              native_all.threads, rk4.best_steps_per_second() / native1.best_steps_per_second(),
              rk4.best_steps_per_second() / native_all.best_steps_per_second());
  std::printf("RK4 %.3e steps/s = %.0f%% of its division-bound ceiling %.3e steps/s (%.3e divisions/s / %g per "
              "step); executed %g FLOPs/step: %.1f%% of the FP64 peak\n",
              rk4.best_steps_per_second(), 100 * rk4.best_steps_per_second() / r.peak.division_ceiling(),
              r.peak.division_ceiling(), r.peak.best_division.per_second, kRk4DivisionsPerStep,
              kRk4LinearExecutedFlops, 100 * r.peak.fraction(kRk4LinearExecutedFlops));
  std::printf("DP45 per core: arcus %.3e rays/s / %u compute units vs odeint 1 thread %.3e rays/s = %.2fx\n",
              r.dp.arcus.best_rays_per_second(), r.dp.compute_units, r.dp.peer.best_rays_per_second(),
              r.dp.per_core_ratio());
  std::printf("DP45 basis: %s\n", dp45_basis(r.dp, p).c_str());
  std::printf("ratio dp45_vs_odeint_1thread = %.1fx (arcus err %s m, odeint err %s m)\n", r.dp.ratio(),
              sci(r.dp.arcus_err).c_str(), sci(r.dp.peer.err_max).c_str());
  std::printf("ratio rk4_fraction_of_fp64_peak = %.1f%% (RK4 %.1f GFLOP/s of peak %.1f GFLOP/s)\n",
              100 * r.peak.fraction(flops), r.peak.rk4_gflops(flops), r.peak.best.gflops);
}

}  // namespace bench
