// arcus_bench — "what accuracy costs in time".
//
// Reproduces the study of numerical methods of thesis §5.4.1 (Fig. 5.13) on the medium
// n = 1 + 0.1·y, whose ray paths have a closed form (problem.hpp), with arcus' Euler,
// RK2, RK4 and DP45 kernels; sets them against two peers (Boost.Odeint's controlled
// Dormand–Prince, a native C++ RK4 loop) and against the device's FP64 rates; measures
// the float path, a new process's first job and a large grid's creation.  Writes CSV
// files, results.md and (through plot_bench.py) PNG plots.
//
//   arcus_bench [--out DIR] [--quick] [--no-plot] [--sweep-layout]
//
// Its last two lines are the two ratios the issue sets targets for.  This file holds the
// options, the plan and the order of the run; harness.* runs things, studies.* says what
// is swept and compared, fresh_process.* measures in child processes, report.* writes.
#include <arcus/arcus.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <stdexcept>
#include <string>

#include "fresh_process.hpp"
#include "harness.hpp"
#include "problem.hpp"
#include "report.hpp"
#include "studies.hpp"

namespace {

namespace fs = std::filesystem;
using namespace bench;

// ---- options ---------------------------------------------------------------------------
struct Options {
  std::string out_dir = "out/bench";
  bool quick = false;
  bool plot = true;
  bool sweep_layout = false;
  // The child-process modes the benchmark runs itself in (fresh_process.hpp).
  bool first_job_child = false;
  std::string grid_child_file;
  bool grid_from_memory = false;
};

[[noreturn]] void usage(int status) {
  std::cerr << "usage: arcus_bench [--out DIR] [--quick] [--no-plot] [--sweep-layout]\n"
               "  --out DIR   where the CSVs, results.md and PNGs go (default out/bench)\n"
               "  --quick     much smaller sweeps (< 60 s) for smoke tests\n"
               "  --no-plot   do not run plot_bench.py\n"
               "  --sweep-layout  also time RK4 and DP45 over lanes x groups (ARCUS_LANES,\n"
               "              ARCUS_GROUPS; about a minute more)\n"
               "run by the benchmark itself in child processes:\n"
               "  --first-job                     context + first RK4 and DP45 advance\n"
               "  --grid-child FILE [--from-memory]  create a grid from a float32 cube file\n";
  std::exit(status);
}

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
    } else if (a == "--first-job") {
      o.first_job_child = true;
    } else if (a == "--grid-child" && i + 1 < argc) {
      o.grid_child_file = argv[++i];
    } else if (a == "--from-memory") {
      o.grid_from_memory = true;
    } else {
      usage(a == "--help" || a == "-h" ? 0 : 2);
    }
  }
  return o;
}

// ---- the plan ------------------------------------------------------------------------------
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

// ---- the run ---------------------------------------------------------------------------------
int run_benchmark(const Options& opt) {
  const Plan plan = opt.quick ? quick_plan() : full_plan();
  const fs::path out_dir = opt.out_dir;
  fs::create_directories(out_dir);

  const ContextPtr ctx = make_context();
  const RaySet rays = make_rays(std::max(plan.max_rays, plan.peer_rays));
  ArcusBench arcus(ctx.get(), rays);
  Machine machine = describe_machine(arcus.device());
  std::printf("arcus_bench%s on %s (%s)\n", opt.quick ? " --quick" : "", machine.device.c_str(), machine.cpu.c_str());

  Results r;
  std::printf("(a, c) fixed steps against step size\n");
  r.step = measure_all(arcus, step_study(plan), plan.point_seconds);
  std::printf("(b, d) DP45 against tolerance\n");
  r.tolerance = measure_all(arcus, tolerance_study(plan), plan.point_seconds, plan.peer_rays);
  std::printf("(b, d) peer: Boost.Odeint dopri5 against tolerance\n");
  r.peer = peer_tolerance_study(rays, plan);
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
  std::printf("RK4 against the FP64 peak and division rate\n");
  r.peak = compare_rk4_with_peak(arcus, plan);
  print_row(r.peak.rk4);
  std::printf("RK4 against native C++\n");
  r.native = native_rk4_study(rays, plan);
  std::printf("first job of a new process (child processes, fresh cache dirs)\n");
  r.first_job = measure_first_jobs();
  std::printf("grid creation (child processes)\n");
  r.grid = measure_grid_creation(kProbeGridSide);

  machine.load_after = load_average();
  write_outputs(out_dir, machine, plan, r, opt.quick);
  if (opt.plot) run_plot_script(out_dir);
  print_summary(out_dir, plan, r, opt.plot);
  return 0;
}

int run(const Options& opt) {
  if (opt.first_job_child) return first_job_child();
  if (!opt.grid_child_file.empty()) return grid_child(opt.grid_child_file, opt.grid_from_memory);
  return run_benchmark(opt);
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(parse_options(argc, argv));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "arcus_bench: %s\n", e.what());
    return 1;
  }
}
