#include "studies.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <thread>

#include "flops.hpp"

namespace bench {
namespace {

constexpr arcus_method kFixedMethods[] = {ARCUS_METHOD_EULER, ARCUS_METHOD_RK2, ARCUS_METHOD_RK4};
constexpr arcus_method kAllMethods[] = {ARCUS_METHOD_EULER, ARCUS_METHOD_RK2, ARCUS_METHOD_RK4, ARCUS_METHOD_DP45};

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

// The loosest (cheapest) swept arcus tolerance, no looser than `max_tol`, whose max
// error over the first `rays` rays is no worse than `err`; null if none.
const Row* loosest_tolerance_matching(const std::vector<Row>& tol_rows, double max_tol, double err, std::size_t rays) {
  for (const Row& r : tol_rows)  // loosest first
    if (r.setting.tol <= max_tol * (1 + 1e-9) && r.err_max_over(rays) <= err) return &r;
  return nullptr;
}

template <typename T, typename Key>
T best_of(const std::vector<T>& v, Key key) {
  return *std::max_element(v.begin(), v.end(), [&](const T& a, const T& b) { return key(a) < key(b); });
}

}  // namespace

unsigned all_cores() { return std::max(1u, std::thread::hardware_concurrency()); }

Setting rk4_headline_setting() { return {ARCUS_METHOD_RK4, ARCUS_PRECISION_DOUBLE, kRk4PeakStep, 0, kLength, kGradient}; }

Setting dp45_headline_setting(double tol) { return {ARCUS_METHOD_DP45, ARCUS_PRECISION_DOUBLE, 0, tol, kLength, kGradient}; }

// ---- the sweeps (arcus) ------------------------------------------------------------------
std::vector<Setting> step_study(const Plan& p) {
  std::vector<Setting> out;
  for (arcus_method m : kFixedMethods)
    for (double h : p.steps) out.push_back({m, ARCUS_PRECISION_DOUBLE, h, 0, kLength, kGradient});
  return out;
}

std::vector<Setting> tolerance_study(const Plan& p) {
  std::vector<Setting> out;
  for (double tol : p.tolerances) out.push_back(dp45_headline_setting(tol));
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
  for (double tol : p.float_dp45_tols) pair(dp45_headline_setting(tol));
  return out;
}

std::vector<Row> measure_all(ArcusBench& arcus, const std::vector<Setting>& settings, double seconds,
                             std::size_t min_rays) {
  std::vector<Row> rows;
  for (const Setting& s : settings) {
    rows.push_back(arcus.measure(s, seconds, min_rays, 1));
    print_row(rows.back());
  }
  return rows;
}

// What the library's per-device default layout leaves on the table.
std::vector<Row> layout_study(ArcusBench& arcus, const Plan& p) {
  std::vector<Row> rows;
  for (const Setting& s : {rk4_headline_setting(), dp45_headline_setting()})
    for (uint32_t lanes : {4u, 8u, 16u})
      for (uint32_t groups : {1u, 2u, 4u, 8u}) {
        arcus.set_layout(lanes, groups);
        rows.push_back(arcus.measure(s, p.point_seconds, 0, 1));
        print_row(rows.back());
      }
  arcus.set_layout(0, 0);
  return rows;
}

// ---- the peers -------------------------------------------------------------------------
std::vector<Row> peer_tolerance_study(const RaySet& rays, const Plan& p) {
  std::vector<Row> rows;
  for (unsigned threads : {1u, all_cores()})
    for (double tol : p.tolerances) {
      rows.push_back(measure_peer(rays, p.peer_rays, tol, threads, p.point_seconds, 1));
      print_row(rows.back());
    }
  return rows;
}

std::vector<Row> native_rk4_study(const RaySet& rays, const Plan& p) {
  std::vector<Row> rows;
  for (unsigned threads : {1u, all_cores()}) {
    rows.push_back(measure_native_rk4(rays, kRk4PeakStep, threads, p.headline_seconds, 3));
    print_row(rows.back());
  }
  return rows;
}

// ---- DP45 against the peer ------------------------------------------------------------------
DpComparison compare_dp45(ArcusBench& arcus, const RaySet& rays, const Plan& p, const std::vector<Row>& tol_rows) {
  DpComparison c;
  c.compute_units = std::max(1u, arcus.device().compute_units);
  c.peer = measure_peer(rays, p.peer_rays, kHeadlineTol, 1, p.headline_seconds, p.headline_launches);
  c.peer_all_cores = measure_peer(rays, p.peer_rays, kHeadlineTol, all_cores(), p.headline_seconds, p.headline_launches);
  const Row* match = loosest_tolerance_matching(tol_rows, kHeadlineTol, c.peer.err_max, p.peer_rays);
  c.arcus_reaches_peer_error = match != nullptr;
  const double tol = match ? match->setting.tol : kHeadlineTol;
  c.equal_tolerance = tol == kHeadlineTol;
  if (const Row* any = loosest_tolerance_matching(tol_rows, HUGE_VAL, c.peer.err_max, p.peer_rays))
    c.cheapest_equal_error = *any;
  c.arcus = arcus.measure(dp45_headline_setting(tol), p.headline_seconds, p.peer_rays, p.headline_launches);
  c.arcus_err = c.arcus.err_max_over(p.peer_rays);
  return c;
}

// ---- RK4 against the hardware ----------------------------------------------------------------
double rk4_counted_flops() { return flops_per_step(ARCUS_METHOD_RK4, ARCUS_FIELD_LINEAR); }

double PeakComparison::division_ceiling() const { return best_division.per_second / kRk4DivisionsPerStep; }

PeakComparison compare_rk4_with_peak(ArcusBench& arcus, const Plan& p) {
  PeakComparison c;
  const arcus_device_info& dev = arcus.device();
  c.variants = measure_fp64_peak(dev.platform, dev.name, p.peak_seconds);
  c.best = best_of(c.variants, [](const PeakResult& r) { return r.gflops; });
  c.divisions = measure_fp64_division(dev.platform, dev.name, p.peak_seconds);
  c.best_division = best_of(c.divisions, [](const DivisionResult& r) { return r.per_second; });
  c.rk4 = arcus.measure(rk4_headline_setting(), p.headline_seconds, 0, p.headline_launches);
  return c;
}

}  // namespace bench
