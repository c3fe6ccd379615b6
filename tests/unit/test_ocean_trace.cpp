// The ocean photon tracer on hand-made water tables, against closed forms and
// conservation laws: Beer–Lambert in a purely absorbing column, nothing absorbed in a
// scattering-only medium, the mean squared distance of absorption in an infinite
// isotropically scattering medium (2/(σ_t σ_a)), the roulette's event frequencies (χ²),
// exact energy bookkeeping, determinism, and the features a trace compiles.
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <vector>

#include <algorithm>

#include "core/buffer.h"
#include "core/context.h"
#include "core/error.h"
#include "core/slices.h"
#include "ocean/trace.h"
#include "ocean/water.h"
#include "unit_util.h"

namespace {

using arcus::ocean::Grid;
using arcus::ocean::Light;
using arcus::ocean::Medium;
using arcus::ocean::TraceParams;
using arcus::ocean::WaterTables;
using arcus_unit::Context;

constexpr double kPi = 3.14159265358979323846;

// Water with constant coefficients per event on `grid` (scatterers isotropic), and
// inelastic emission spread uniformly over the grid.
WaterTables constant_water(const Grid& grid, const std::array<double, 10>& events) {
  WaterTables w;
  w.grid = grid;
  const size_t n = grid.count;
  for (int e = 0; e < 10; ++e) w.event[e].assign(n, events[e]);
  for (int p = 0; p < 3; ++p) {
    w.emission[p].assign(n * n, 0.0);
    w.cdf[p].assign(n * n, 0.0);
    if (n < 2) continue;
    const double width = grid.step_nm * (n - 1);
    for (size_t k = 0; k < n; ++k)
      for (size_t m = 0; m < n; ++m) {
        w.emission[p][k * n + m] = 1 / width;
        w.cdf[p][k * n + m] = double(m) / double(n - 1);
      }
  }
  return w;
}

// Water with all ten events, 400–700 nm at 10 nm (the determinism tests').
WaterTables every_event_water() {
  return constant_water(Grid{400, 10, 31}, {0.05, 0.02, 0.02, 0.03, 0.02, 0.01, 0.02, 0.1, 0.3, 0.05});
}

TraceParams stored_trace(uint64_t photons) {
  TraceParams p;
  p.photons = photons;
  p.store = true;
  return p;
}

Light point_light(double nm) {
  Light L;
  L.kind = Light::point;
  L.spectrum = {{nm - 1, nm, nm + 1}, {0, 1.0, 0}};  // a line at nm: one grid sample
  return L;
}

std::unique_ptr<arcus::ocean::TraceJob> run(arcus_context_t* ctx, const WaterTables& w, const std::vector<Light>& L,
                                            const Medium& m, const TraceParams& p) {
  bool cancelled = false;
  std::lock_guard<std::mutex> lock(ctx->lock);
  return arcus::ocean::trace(ctx, w, L, m, p, nullptr, nullptr, &cancelled);
}

// Every run: emitted = absorbed + escaped + carried past the limit + taken by the
// bottom, to rounding (each photon's power is booked once, wherever it ends).
void expect_balanced(const arcus::ocean::Tallies& t) {
  const double booked = t.absorbed_total() + t.escaped() + t.past_limit + t.bottom;
  EXPECT_NEAR(booked, t.emitted, 1e-9 * t.emitted);
}

TEST(OceanTrace, PurelyAbsorbingColumnFollowsBeerLambert) {
  Context ctx;
  const double a = 0.5;  // 1/m
  Grid g{550, 5, 1};
  WaterTables w = constant_water(g, {a, 0, 0, 0, 0, 0, 0, 0, 0, 0});
  for (double zenith_deg : {0.0, 40.0}) {
    const double mu = std::cos(zenith_deg * kPi / 180);
    Light L;
    L.kind = Light::directional;
    L.direction[0] = std::sin(zenith_deg * kPi / 180);
    L.direction[2] = -mu;
    L.spectrum = {{550}, {1.0}};
    Medium m;
    m.box_hi[2] = 0;  // a free top, no interface
    TraceParams p;
    p.photons = 200000;
    p.depths = {0, 1, 2, 4};
    p.layer = 0.2;
    const auto job = run(ctx, w, {L}, m, p);
    const auto& ir = job->irradiance;
    for (size_t j = 0; j < p.depths.size(); ++j) {
      const double z = p.depths[j], expect = std::exp(-a * z / mu);
      // Binomial: the share of N photons flying past z has σ = sqrt(P(1−P)/N) ≤ 1.2e-3;
      // 5σ bounds a false failure at 6e-7.
      EXPECT_NEAR(ir.ed[j], expect, 5 * std::sqrt(expect * (1 - expect) / p.photons) + 1e-12) << "z " << z;
      EXPECT_EQ(ir.eu[j], 0.0);
      // E_0 is the track length in the layer [z − h/2, z + h/2] (clipped at 0) per
      // thickness: (1/μ)·(mean of e^(−a z'/μ) over the layer), exactly.
      const double lo = std::max(0.0, z - p.layer / 2), hi = z + p.layer / 2;
      const double e0 = (std::exp(-a * lo / mu) - std::exp(-a * hi / mu)) / (a * (hi - lo));
      EXPECT_NEAR(ir.e0[j], e0, 0.02 * e0) << "z " << z;  // track lengths: ~0.3 % noise here
    }
    expect_balanced(job->tallies);
  }
}

TEST(OceanTrace, ScatteringOnlyInfiniteMediumAbsorbsNothing) {
  Context ctx;
  Grid g{500, 10, 3};
  WaterTables w = constant_water(g, {0, 0, 0, 0, 0, 0, 0, 0.3, 0.2, 0.1});
  w.phase[0].kind = arcus::ocean::Phase::rayleigh_like;
  w.phase[0].a = 0.835;
  w.phase[1].kind = arcus::ocean::Phase::two_term_hg;
  w.phase[1].g_forward = 0.9;
  w.phase[1].g_backward = -0.3;
  w.phase[1].forward_weight = 0.95;
  TraceParams p;
  p.photons = 20000;
  p.max_interactions = 7;
  const auto job = run(ctx, w, {point_light(510)}, Medium{}, p);
  const auto& t = job->tallies;
  EXPECT_EQ(t.absorbed_total(), 0.0);
  EXPECT_EQ(t.escaped(), 0.0);
  EXPECT_NEAR(t.past_limit, t.emitted, 1e-12 * t.emitted);  // every photon reaches the limit
  EXPECT_EQ(t.interactions, p.photons * 7);
}

TEST(OceanTrace, IsotropicScatteringMeanSquaredAbsorptionDistance) {
  Context ctx;
  // σ_t = 1, σ_a = 0.25: a photon makes K flights (geometric, mean σ_t/σ_a = 4), each of
  // mean squared length 2/σ_t² with independent isotropic directions, so
  // E[r²] = E[K]·2/σ_t² = 2/(σ_t σ_a) = 8 m².
  const double sa = 0.25, ss = 0.75;
  Grid g{550, 5, 1};
  WaterTables w = constant_water(g, {sa, 0, 0, 0, 0, 0, 0, 0, 0, ss});
  TraceParams p;
  p.photons = 200000;
  p.max_interactions = 64;  // P(K > 64) = 0.75^64 ≈ 1e-8
  const auto job = run(ctx, w, {point_light(550)}, Medium{}, p);
  const auto& t = job->tallies;
  const double mean_r2 = t.absorbed_r2 / t.absorbed_total();
  // r² at absorption has a relative standard deviation of about 1.6 (a sum of K
  // exponential flights); over 2e5 photons the mean's is 0.36 %: 2 % is > 5σ.
  EXPECT_NEAR(mean_r2, 2 / ((sa + ss) * sa), 0.02 * 8);
  EXPECT_NEAR(t.past_limit, 0.0, 1e-6 * t.emitted);
  expect_balanced(t);
}

TEST(OceanTrace, RouletteFrequenciesMatchTheAlbedos) {
  Context ctx;
  // Ten events with distinct coefficients at each of three wavelengths (their albedos
  // change with λ); one interaction per photon, 10⁶ photons per wavelength.
  Grid g{450, 50, 3};
  WaterTables w;
  w.grid = g;
  const double base[10] = {0.05, 0.01, 0.03, 0.04, 0.02, 0.06, 0.015, 0.2, 0.3, 0.1};
  for (int e = 0; e < 10; ++e) w.event[e] = {base[e], base[e] * (1 + 0.1 * e), base[e] * (2 - 0.1 * e)};
  for (int q = 0; q < 3; ++q) {
    w.emission[q].assign(9, 0.0);
    w.cdf[q] = {0, 0.5, 1, 0, 0.5, 1, 0, 0.5, 1};
    w.emission[q] = {0.01, 0.01, 0.01, 0.01, 0.01, 0.01, 0.01, 0.01, 0.01};
  }
  for (int k = 0; k < 3; ++k) {
    TraceParams p;
    p.photons = 1000000;
    p.max_interactions = 1;
    p.seed = 7 + k;
    const auto job = run(ctx, w, {point_light(g.nm(k))}, Medium{}, p);
    double st = 0;
    for (int e = 0; e < 10; ++e) st += w.event[e][k];
    double chi2 = 0;
    for (int e = 0; e < 10; ++e) {
      const double expect = p.photons * w.event[e][k] / st;
      chi2 += std::pow(job->tallies.count[e] - expect, 2) / expect;
    }
    // 9 degrees of freedom: P(χ² > 33.7) = 1e-4.  The seed is fixed, so the test is
    // deterministic; the bound says the frequencies are the albedos' (eq. 4.3–4.4).
    EXPECT_LT(chi2, 33.7) << "wavelength " << g.nm(k);
    EXPECT_EQ(job->tallies.interactions, p.photons);
  }
}

TEST(OceanTrace, BookkeepingBalancesWithSurfaceBottomAndInelasticEvents) {
  Context ctx;
  Grid g{400, 10, 31};
  WaterTables w = constant_water(g, {0.05, 0.02, 0.02, 0.03, 0.02, 0.01, 0.02, 0.1, 0.3, 0.05});
  w.phase[1].kind = arcus::ocean::Phase::hg;
  w.phase[1].g_forward = 0.9;
  Light sun;
  sun.kind = Light::directional;
  sun.direction[0] = 0.5;
  sun.direction[2] = -0.8;
  sun.spectrum = {{400, 700}, {1, 2}};
  Light sky;
  sky.kind = Light::sky;
  sky.spectrum = {{550}, {0.3}};
  Medium m;
  m.surface = true;
  m.bottom_depth = 5;
  m.bottom_albedo = 0.3;
  TraceParams p;
  p.photons = 100000;
  p.depths = {0, 1, 2.5};
  const auto job = run(ctx, w, {sun, sky}, m, p);
  const auto& t = job->tallies;
  expect_balanced(t);
  EXPECT_GT(t.bottom, 0);
  EXPECT_GT(t.escaped(), 0);
  EXPECT_GT(t.count[1] + t.count[4] + t.count[6], 0);
  EXPECT_EQ(job->features, ARCUS_FEATURE_OCEAN_INELASTIC | ARCUS_FEATURE_OCEAN_BOUNDARIES | ARCUS_FEATURE_OCEAN_DEPTHS);
}

TEST(OceanTrace, DeterminismSameSeedSameTalliesBitForBit) {
  Context ctx;
  const WaterTables w = every_event_water();
  const TraceParams p = stored_trace(30000);
  const auto a = run(ctx, w, {point_light(500)}, Medium{}, p);
  const auto b = run(ctx, w, {point_light(500)}, Medium{}, p);
  EXPECT_EQ(a->tallies.absorbed_by_interaction, b->tallies.absorbed_by_interaction);
  EXPECT_EQ(a->tallies.count, b->tallies.count);
  EXPECT_EQ(a->photons.positions, b->photons.positions);
  EXPECT_EQ(a->photons.wavelengths, b->photons.wavelengths);
  EXPECT_GT(a->photons.size(), 0u);
}

TEST(OceanTrace, DeterminismLaunchSizesDoNotChangeTheTallies) {
  // Work-item r traces photons r, r + rows, ... into its own row whatever the slices,
  // and the host sums the rows in order: slices of 1000 photons give the very tallies.
  Context ctx;
  const WaterTables w = every_event_water();
  const TraceParams p = stored_trace(30000);
  const auto whole = run(ctx, w, {point_light(500)}, Medium{}, p);
  arcus::testing::set_slice_units(1000);
  const auto sliced = run(ctx, w, {point_light(500)}, Medium{}, p);
  arcus::testing::set_slice_units(0);
  EXPECT_GT(sliced->stats.launches, whole->stats.launches);
  EXPECT_EQ(whole->tallies.absorbed_by_interaction, sliced->tallies.absorbed_by_interaction);
  EXPECT_EQ(whole->tallies.arriving, sliced->tallies.arriving);
  EXPECT_EQ(whole->photons.positions, sliced->photons.positions);
}

TEST(OceanTrace, WaterWithoutInelasticEventsCompilesNoInelasticCode) {
  Context ctx;
  Grid g{400, 10, 31};
  WaterTables w = constant_water(g, {0.05, 0, 0.02, 0.03, 0, 0.01, 0, 0.1, 0.3, 0.05});
  TraceParams p;
  p.photons = 50000;
  const auto plain = run(ctx, w, {point_light(500)}, Medium{}, p);
  EXPECT_EQ(plain->features, 0u);
  p.force_inelastic = true;
  const auto full = run(ctx, w, {point_light(500)}, Medium{}, p);
  EXPECT_EQ(full->features, ARCUS_FEATURE_OCEAN_INELASTIC);
  // No inelastic event has a coefficient, so the full kernel makes the same random
  // choices: the same tallies.
  EXPECT_EQ(plain->tallies.count, full->tallies.count);
  EXPECT_EQ(plain->tallies.absorbed_by_interaction, full->tallies.absorbed_by_interaction);
}

TEST(OceanTrace, BadInputIsRefusedNamingTheParameter) {
  Context ctx;
  Grid g{400, 10, 31};
  WaterTables w = constant_water(g, {0.05, 0, 0, 0, 0, 0, 0, 0.1, 0, 0});
  auto message = [&](const std::vector<Light>& L, const Medium& m, const TraceParams& p) -> std::string {
    try {
      run(ctx, w, L, m, p);
    } catch (const arcus::Error& e) {
      EXPECT_EQ(e.status(), ARCUS_ERROR_INVALID_ARGUMENT);
      return e.what();
    }
    return "";
  };
  TraceParams p;
  p.photons = 100;
  Light bad = point_light(500);
  bad.spectrum.values = {0, -1, 0};
  EXPECT_NE(message({bad}, Medium{}, p).find("lights[0].spectrum.values[1]"), std::string::npos);
  EXPECT_NE(message({}, Medium{}, p).find("lights"), std::string::npos);
  Medium m;
  m.bottom_albedo = 2;
  EXPECT_NE(message({point_light(500)}, m, p).find("bottom_albedo"), std::string::npos);
  TraceParams q = p;
  q.max_interactions = 0;
  EXPECT_NE(message({point_light(500)}, Medium{}, q).find("max_interactions"), std::string::npos);
  q = p;
  q.depths = {1};
  EXPECT_NE(message({point_light(500)}, Medium{}, q).find("plane-parallel"), std::string::npos);
  Light far = point_light(900);  // a line off the grid: emits nothing there
  EXPECT_NE(message({far}, Medium{}, p).find("emit nothing"), std::string::npos);
}

// ---- the real model's tables (src/ocean/water.cpp) through the kernel's own code

// n re-emitted wavelengths of process p excited at grid sample k, drawn on the device by
// the tracer's ocean_emission_nm from Philox uniforms.
std::vector<double> device_emissions(arcus_context_t* ctx, const WaterTables& w, int process, int k, size_t n) {
  static const arcus::KernelSource source{
      "ocean/test_emission",
      {"common/real.h", "common/philox.h", "ocean/ocean_desc.h", "ocean/trace.cl"},
      "__kernel void test_emission(__global const REAL* water, const ocean_desc d, int p, int k, ulong n,\n"
      "                            __global REAL* out) {\n"
      "  const ulong i = get_global_id(0);\n"
      "  if (i >= n) return;\n"
      "  REAL u0, u1;\n"
      "  ocean_draw2(99, i, 0, &u0, &u1);\n"
      "  out[i] = ocean_emission_nm(&d, water, p, k, u0);\n"
      "}\n"};
  std::lock_guard<std::mutex> lock(ctx->lock);
  arcus_ocean_desc d{};
  const std::vector<double> buf = arcus::ocean::water_buffer(w, true, &d);
  d.first_nm = w.grid.first_nm;
  d.step_nm = w.grid.step_nm;
  d.count = w.grid.count;
  arcus::DeviceBuffer water(ctx, buf.size() * sizeof(double), "water", buf.data());
  arcus::DeviceBuffer out(ctx, n * sizeof(double), "out");
  const auto built = ctx->runtime->program(source, 0, arcus::Layout{1, 1});
  arcus::KernelCall call(built.program, "test_emission");
  call.set(0, &water);
  call.set_value(1, d);
  call.set_value(2, int32_t(process));
  call.set_value(3, int32_t(k));
  call.set_value(4, uint64_t(n));
  call.set(5, &out);
  call.run(ctx, n);
  std::vector<double> nm(n);
  out.read(ctx, 0, n * sizeof(double), nm.data());
  return nm;
}

// Kolmogorov–Smirnov distance between samples and the analytic emission density of
// `process` from `excitation`, restricted to [lo, hi] and renormalised there (the
// tracer re-emits only inside the simulated range, §4.2), integrated at 0.01 nm.
double ks_distance(std::vector<double> x, int process, double excitation, double lo, double hi) {
  std::sort(x.begin(), x.end());
  const double h = 0.01;
  std::vector<double> cdf{0};
  for (double l = lo; l < hi - 1e-9; l += h)
    cdf.push_back(cdf.back() + 0.5 * h *
                                   (arcus::ocean::emission_density(process, excitation, l) +
                                    arcus::ocean::emission_density(process, excitation, l + h)));
  const double total = cdf.back();
  double d = 0;
  for (size_t i = 0; i < x.size(); ++i) {
    const double pos = (x[i] - lo) / h;
    const size_t j = std::min<size_t>(static_cast<size_t>(pos), cdf.size() - 2);
    const double f = (cdf[j] + (pos - j) * (cdf[j + 1] - cdf[j])) / total;
    d = std::max({d, std::fabs(f - double(i) / x.size()), std::fabs(f - double(i + 1) / x.size())});
  }
  return d;
}

TEST(OceanTrace, ReEmittedWavelengthsFollowTheAnalyticRedistribution) {
  Context ctx;
  Grid g{380, 1, 401};  // 1 nm: the tabulated density's linear interpolation is exact to ~1e-5
  arcus::ocean::Water water;
  water.bio.chlorophyll = 1;
  water.bio.a_y440 = 0.1;
  const WaterTables w = arcus::ocean::evaluate(water, g);
  const size_t n = 1000000;
  // KS at 10⁶ samples: P(D > 1.95/√n) = 0.001 for exact draws; the seed is fixed.
  const double bound = 1.95 / std::sqrt(double(n));
  struct Case {
    int process;
    double excitation;
  };
  for (const Case c : {Case{arcus::ocean::kRamanProcess, 488}, Case{arcus::ocean::kChlorophyll, 440},
                       Case{arcus::ocean::kCdomProcess, 400}}) {
    const int k = static_cast<int>(c.excitation - g.first_nm);
    const auto x = device_emissions(ctx, w, c.process, k, n);
    EXPECT_LT(ks_distance(x, c.process, c.excitation, g.first_nm, g.last_nm()), bound)
        << "process " << c.process << " from " << c.excitation << " nm";
    // Where the mass sits: Raman from 488 nm near 585 nm (the ≈ 3400 cm⁻¹ shift),
    // chlorophyll at 685 nm — the modes of 1 nm histograms of the samples.
    if (c.process != arcus::ocean::kCdomProcess) {
      std::vector<int> hist(401, 0);
      for (double l : x) ++hist[std::min(400, std::max(0, int(l - g.first_nm)))];
      const double mode = g.first_nm + (std::max_element(hist.begin(), hist.end()) - hist.begin()) + 0.5;
      EXPECT_NEAR(mode, c.process == arcus::ocean::kRamanProcess ? 585.0 : 685.0, 4.0);
    }
  }
}

TEST(OceanTrace, RouletteFrequenciesMatchTheBioOpticalAlbedos) {
  Context ctx;
  Grid g{380, 5, 81};
  arcus::ocean::Water water;
  water.bio.chlorophyll = 1;
  water.bio.a_d400 = 0.05;
  water.bio.a_y440 = 0.1;
  const WaterTables w = arcus::ocean::evaluate(water, g);
  for (double nm : {420.0, 550.0, 680.0}) {
    const int k = static_cast<int>((nm - g.first_nm) / g.step_nm);
    TraceParams p;
    p.photons = 1000000;
    p.max_interactions = 1;
    const auto job = run(ctx, w, {point_light(nm)}, Medium{}, p);
    double st = 0, chi2 = 0;
    int dof = -1;
    for (int e = 0; e < 10; ++e) st += w.event[e][k];
    for (int e = 0; e < 10; ++e) {
      const double expect = p.photons * w.event[e][k] / st;
      if (expect == 0) {
        EXPECT_EQ(job->tallies.count[e], 0.0);
        continue;
      }
      chi2 += std::pow(job->tallies.count[e] - expect, 2) / expect;
      ++dof;
    }
    // P(χ² > 33.7 | 9 dof) = 1e-4, and the bound only loosens with fewer dof.
    EXPECT_LT(chi2, 33.7) << nm << " nm, " << dof << " degrees of freedom";
  }
}

}  // namespace
