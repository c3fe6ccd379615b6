// The studies: which settings each one sweeps (thesis Fig. 5.13 a–h, float, layout),
// the sizes a run gives them (Plan), and the comparisons behind the two headline ratios:
// DP45 against Boost.Odeint, RK4 against the FP64 peak and the native C++ loop.
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include "fp64_peak.hpp"
#include "harness.hpp"

namespace bench {

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
  double peak_seconds;      // per FMA- or division-microkernel launch
};

unsigned all_cores();  // threads of the "all cores" peer runs

// The two headline kernels: RK4 at h = kRk4PeakStep and DP45 at `tol`, L = kLength.
Setting rk4_headline_setting();
Setting dp45_headline_setting(double tol = kHeadlineTol);

// ---- the sweeps (arcus) ------------------------------------------------------------------
std::vector<Setting> step_study(const Plan& p);       // Fig. 5.13 (a, c)
std::vector<Setting> tolerance_study(const Plan& p);  // (b, d)
std::vector<Setting> distance_study(const Plan& p);   // (e, f)
std::vector<Setting> gradient_study(const Plan& p);   // (g, h)
std::vector<Setting> float_study(const Plan& p);      // float against double, in pairs

// Measures each setting for about `seconds` (one line each on stdout).
std::vector<Row> measure_all(ArcusBench& arcus, const std::vector<Setting>& settings, double seconds,
                             std::size_t min_rays = 0);
// lanes × groups per work-item for the two headline kernels (--sweep-layout).
std::vector<Row> layout_study(ArcusBench& arcus, const Plan& p);

// ---- the peers -------------------------------------------------------------------------
// Boost.Odeint over the plan's tolerances, on 1 thread, then on all cores.
std::vector<Row> peer_tolerance_study(const RaySet& rays, const Plan& p);
// The native C++ RK4 at the headline step, on 1 thread, then on all cores.
std::vector<Row> native_rk4_study(const RaySet& rays, const Plan& p);

// ---- DP45 against the peer ------------------------------------------------------------------
struct DpComparison {
  Row arcus, peer, peer_all_cores;
  double arcus_err = 0;  // arcus' max error over the peer's rays
  bool equal_tolerance = true;
  bool arcus_reaches_peer_error = true;
  uint32_t compute_units = 1;  // the device's, for the per-core ratio
  // For context, not the target: the loosest sweep tolerance at which arcus' error is
  // still no worse than the peer's (arcus may be doing more work than the peer at 1e-9).
  std::optional<Row> cheapest_equal_error;
  // The headline compares fastest launches: on a shared machine the least disturbed
  // time of each side (arcus needs both cores, the peer one, so other load hurts arcus
  // more).  The ratio of medians is reported beside it.
  double ratio() const { return arcus.best_rays_per_second() / peer.best_rays_per_second(); }
  double ratio_of_medians() const { return arcus.rays_per_second() / peer.rays_per_second(); }
  // The same per core: arcus' rays/s over the device's compute units against the peer on
  // one thread, so machines with different core counts compare.
  double per_core_ratio() const { return ratio() / compute_units; }
  double per_core_ratio_of_medians() const { return ratio_of_medians() / compute_units; }
};

// arcus DP45 against the peer at tolerance 1e-9.  "At equal or better error": if arcus'
// max error over the shared rays is worse than the peer's, the comparison moves to the
// loosest tighter tolerance of the sweep at which arcus matches the peer.
DpComparison compare_dp45(ArcusBench& arcus, const RaySet& rays, const Plan& p, const std::vector<Row>& tol_rows);

// ---- RK4 against the hardware ----------------------------------------------------------------
struct PeakComparison {
  Row rk4;
  std::vector<PeakResult> variants;
  PeakResult best;
  std::vector<DivisionResult> divisions;
  DivisionResult best_division;
  // GFLOP/s of the fastest RK4 launch (the median beside it) at `flops` per step, and
  // its fraction of the best microkernel launch.  The headline counts flops.hpp's 118.
  double rk4_gflops(double flops) const { return rk4.best_steps_per_second() * flops * 1e-9; }
  double rk4_gflops_median(double flops) const { return rk4.steps_per_second() * flops * 1e-9; }
  double fraction(double flops) const { return rk4_gflops(flops) / best.gflops; }
  // The step rate the divisions alone allow (kRk4DivisionsPerStep per step).
  double division_ceiling() const;
};

// FLOPs of an RK4 step counted from the method and the linear field (flops.hpp): 118.
double rk4_counted_flops();

PeakComparison compare_rk4_with_peak(ArcusBench& arcus, const Plan& p);

}  // namespace bench
