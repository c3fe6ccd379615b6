// The ocean's water (src/ocean/water, embedded from data/ocean/*.csv): the bio-optical
// model of thesis §3.5 checked against its closed forms and the published numbers
// (data/ocean/README.md), the IOP mode, evaluate()'s tables and the validation.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "unit_util.h"
#include "core/error.h"
#include "ocean/water.h"

#ifndef ARCUS_SOURCE_DIR
#define ARCUS_SOURCE_DIR "."
#endif

namespace {

using namespace arcus::ocean;

namespace embedded {
#include "ocean/water_data.inc"
}

constexpr double kPi = 3.14159265358979323846;

using arcus_unit::Rows;

// A CSV under data/ocean/ without its header (checked).
Rows read_csv(const std::string& name, const std::string& header) {
  return arcus_unit::read_data_csv("ocean", name, header);
}

using arcus_unit::Failure;
using arcus_unit::failure_of;

// Composite Simpson of f over [a, b] with n (even) intervals.
double simpson(const std::function<double(double)>& f, double a, double b, int n) {
  const double h = (b - a) / n;
  double sum = f(a) + f(b);
  for (int i = 1; i < n; ++i) sum += (i % 2 ? 4 : 2) * f(a + i * h);
  return sum * h / 3;
}

// 2π ∫ p(θ) sin θ dθ: in θ, so peaked phases are resolved near θ = 0.
double sphere_integral(const Phase& p, const std::function<double(double)>& weight = [](double) { return 1.0; }) {
  return 2 * kPi * simpson([&](double t) { return phase_value(p, std::cos(t)) * weight(std::cos(t)) * std::sin(t); }, 0, kPi,
                           200000);
}

Phase hg_phase(double g) {
  Phase p;
  p.kind = Phase::hg;
  p.g_forward = g;
  return p;
}

Water iops_water() {
  Water w;
  w.kind = Water::kIops;
  w.iops.absorption = {{400, 500, 600}, {0.05, 0.04, 0.3}};
  w.iops.scattering = {{450}, {0.2}};  // a single value
  w.iops.phase = hg_phase(0.9);
  return w;
}

// ---- the embedded tables are the CSVs ----------------------------------------------

TEST(WaterData, EmbeddedTablesAreTheCsvs) {
  // The generated .inc holds the CSVs' own text, so the doubles are identical.
  const Rows sb = read_csv("smith_baker_1981.csv", "wavelength_nm,a_w_per_m,b_sw_per_m");
  ASSERT_EQ(int(sb.size()), embedded::kSmithBakerRows);
  for (size_t i = 0; i < sb.size(); ++i) {
    EXPECT_EQ(embedded::kSmithBakerNm[i], std::stod(sb[i][0]));
    EXPECT_EQ(embedded::kSmithBakerAw[i], std::stod(sb[i][1]));
    EXPECT_EQ(pure_water_absorption(std::stod(sb[i][0])), std::stod(sb[i][1])) << sb[i][0];
  }
  const Rows phyto = read_csv("phytoplankton_specific_absorption.csv", "wavelength_nm,a_star_p_m2_per_mg");
  ASSERT_EQ(int(phyto.size()), embedded::kPhytoRows);
  for (const auto& r : phyto) EXPECT_EQ(phytoplankton_specific_absorption(std::stod(r[0])), std::stod(r[1])) << r[0];
  const Rows det = read_csv("detritus_scattering.csv", "wavelength_nm,detritus_per_m,minerals_per_m,total_per_m");
  ASSERT_EQ(int(det.size()), embedded::kDetritusRows);
  for (size_t i = 0; i < det.size(); ++i) {
    EXPECT_EQ(embedded::kDetritusBd[i], std::stod(det[i][1]));
    EXPECT_EQ(embedded::kDetritusBm[i], std::stod(det[i][2]));
    EXPECT_EQ(detritus_table_scattering(std::stod(det[i][0])), std::stod(det[i][3])) << det[i][0];
  }
  const Rows a0 = read_csv("cdom_fluorescence_a0.csv", "excitation_nm,a0_per_nm,origin");
  ASSERT_EQ(int(a0.size()), embedded::kCdomA0Rows);
  for (const auto& r : a0) EXPECT_EQ(cdom_fluorescence_a0(std::stod(r[0])), std::stod(r[1])) << r[0];
  const Rows raman = read_csv("raman_bands.csv", "band,weight,centre_shift_per_cm,fwhm_per_cm");
  ASSERT_EQ(raman.size(), 4u);
  for (size_t j = 0; j < 4; ++j) {
    EXPECT_EQ(embedded::kRamanWeight[j], std::stod(raman[j][1]));
    EXPECT_EQ(embedded::kRamanCentre[j], std::stod(raman[j][2]));
    EXPECT_EQ(embedded::kRamanFwhm[j], std::stod(raman[j][3]));
  }
}

TEST(WaterData, PresetsAreTheCsvConverted) {
  const Rows rows = read_csv("presets.csv", "name,chlorophyll_mg_per_m3,a_nap_443_per_m,a_cdom_443_per_m,status");
  std::vector<std::string> names;
  for (const auto& r : rows) names.push_back(r[0]);
  EXPECT_EQ(preset_names(), names);
  EXPECT_EQ(names, (std::vector<std::string>{"atlantic", "mediterranean", "baltic", "north_sea", "cdom_coastal"}));
  for (const auto& r : rows) {
    const BioOptical b = preset(r[0]);
    EXPECT_EQ(b.chlorophyll, std::stod(r[1]));
    // Babin's 443 nm values carried to 400 and 440 nm with the model's slopes.
    EXPECT_DOUBLE_EQ(b.a_d400, std::stod(r[2]) * std::exp(0.011 * 43));
    EXPECT_DOUBLE_EQ(b.a_y440, std::stod(r[3]) * std::exp(0.014 * 3));
    EXPECT_NO_THROW(evaluate(Water{Water::kBioOptical, b, {}}, Grid{})) << r[0];
  }
  const Failure f = failure_of([] { preset("arctic"); });
  EXPECT_EQ(f.status, ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(f.message.find("arctic"), std::string::npos) << f.message;
  for (const std::string& n : names) EXPECT_NE(f.message.find(n), std::string::npos) << f.message;
}

// ---- absorption ----------------------------------------------------------------------

TEST(WaterAbsorption, Table34PointsReproduced) {
  // Thesis Table 3.4 (cm⁻¹ there, m⁻¹ here) is eight rows of Smith & Baker's table.
  const double nm[] = {380, 440, 500, 550, 610, 670, 720, 780};
  const double a_w[] = {0.022, 0.0145, 0.0257, 0.0638, 0.289, 0.43, 1.169, 2.36};
  const double a_p[] = {0.025, 0.035, 0.02, 0.01, 0.007, 0.015, 0.001, 0.0001};
  for (int i = 0; i < 8; ++i) {
    EXPECT_EQ(pure_water_absorption(nm[i]), a_w[i]) << nm[i];
    EXPECT_EQ(phytoplankton_specific_absorption(nm[i]), a_p[i]) << nm[i];
  }
  // Linear between the points, constant beyond the ends.
  EXPECT_DOUBLE_EQ(phytoplankton_specific_absorption(470), 0.0275);
  EXPECT_EQ(phytoplankton_specific_absorption(320), 0.025);
  EXPECT_EQ(phytoplankton_specific_absorption(900), 0.0001);
  EXPECT_DOUBLE_EQ(pure_water_absorption(445), 0.0145);
  EXPECT_EQ(pure_water_absorption(950), 2.07);
}

TEST(WaterAbsorption, ConstituentsFollowTheirEquations) {
  Water w;
  w.bio.chlorophyll = 0.7;
  w.bio.a_d400 = 0.05, w.bio.s_d = 0.012;
  w.bio.a_y440 = 0.08, w.bio.s_y = 0.016;
  const Grid g{300, 10, 71};
  const WaterTables t = evaluate(w, g);
  for (int k = 0; k < g.count; ++k) {
    const double nm = g.nm(k);
    // Closed forms evaluated the same way: equal to rounding.
    EXPECT_NEAR(t.absorption[0][k], pure_water_absorption(nm), 1e-15) << nm;
    EXPECT_NEAR(t.absorption[1][k], 0.05 * std::exp(-0.012 * (nm - 400)), 1e-14) << nm;  // eq. 3.24
    EXPECT_NEAR(t.absorption[2][k], 0.7 * phytoplankton_specific_absorption(nm), 1e-15) << nm;  // eq. 3.23
    EXPECT_NEAR(t.absorption[3][k], 0.08 * std::exp(-0.016 * (nm - 440)), 1e-14) << nm;  // eq. 3.22
  }
  EXPECT_DOUBLE_EQ(t.absorption[1][10], 0.05);  // 400 nm
  EXPECT_DOUBLE_EQ(t.absorption[3][14], 0.08);  // 440 nm
}

// ---- elastic scattering --------------------------------------------------------------

TEST(WaterScattering, PureWaterMatchesSmithBakerSeawater) {
  // Eq. 3.25 with Morel's β_sw(400, 90°) = 4.72e-4 against SB81's b_sw: SB81 prints 4
  // decimals (±5e-5 m⁻¹) and a λ^-4.32 power law fits Morel's values to a few percent.
  for (const auto& r : read_csv("smith_baker_1981.csv", "wavelength_nm,a_w_per_m,b_sw_per_m")) {
    const double nm = std::stod(r[0]), b_sw = std::stod(r[2]);
    if (nm < 300 || nm > 700) continue;
    EXPECT_NEAR(pure_water_scattering(nm), b_sw, 0.03 * b_sw + 5e-5) << nm;
  }
  EXPECT_NEAR(pure_water_scattering(500), 0.0029, 5e-5);
  EXPECT_DOUBLE_EQ(pure_water_scattering(400), 16.06 * 4.72e-4);
}

TEST(WaterScattering, PhytoplanktonAndDetritus) {
  Water w;
  w.bio.chlorophyll = 0.5;
  w.bio.a_d400 = 0.03;
  const Grid g{380, 20, 21};
  const WaterTables t = evaluate(w, g);
  const double table35[] = {0.1125, 0.09, 0.0825, 0.075, 0.0685, 0.0635, 0.061, 0.059};
  const double nodes[] = {380, 440, 500, 550, 610, 670, 720, 780};
  for (int i = 0; i < 8; ++i) EXPECT_EQ(detritus_table_scattering(nodes[i]), table35[i]) << nodes[i];
  for (int k = 0; k < g.count; ++k) {
    const double nm = g.nm(k);
    EXPECT_NEAR(t.scattering[0][k], pure_water_scattering(nm), 1e-15);
    // Table 3.5 scaled by a_d(400) / 0.1 (data/ocean/README.md).
    EXPECT_NEAR(t.scattering[1][k], detritus_table_scattering(nm) * 0.03 / 0.1, 1e-15) << nm;
    EXPECT_NEAR(t.scattering[2][k], 0.30 * std::pow(0.5, 0.62) * 550 / nm, 1e-14) << nm;  // eq. 3.27
    EXPECT_EQ(t.scattering[3][k], 0);  // CDOM does not scatter elastically
  }
}

TEST(WaterPhase, EinsteinSmoluchowskiIsNormalised) {
  // The thesis' 0.06225 (1 + 0.835 cos²θ) (eq. 3.26) integrates to 1 over the sphere to
  // its rounding (0.06225 has 4 digits): 1e-3.
  const double printed = 2 * kPi * simpson([](double c) { return 0.06225 * (1 + 0.835 * c * c); }, -1, 1, 100);
  EXPECT_NEAR(printed, 1, 1e-3);
  const WaterTables t = evaluate(Water{}, Grid{});
  EXPECT_EQ(t.phase[kWater].kind, Phase::rayleigh_like);
  EXPECT_EQ(t.phase[kWater].a, 0.835);
  for (double c = -1; c <= 1; c += 0.25)
    EXPECT_NEAR(phase_value(t.phase[kWater], c), 0.06225 * (1 + 0.835 * c * c), 1e-5) << c;  // the rounding
  EXPECT_NEAR(sphere_integral(t.phase[kWater]), 1, 1e-9);
  // Phytoplankton: isotropic 1/(4π), not the thesis' 1/π.
  EXPECT_EQ(t.phase[kPhyto].kind, Phase::isotropic);
  EXPECT_DOUBLE_EQ(phase_value(t.phase[kPhyto], 0.3), 1 / (4 * kPi));
}

TEST(WaterPhase, HenyeyGreensteinAndTwoTermAreNormalised) {
  // Simpson in θ with 2e5 intervals resolves even g = 0.99's forward peak: 1e-6.
  for (double g : {-0.7, 0.0, 0.5, 0.9, 0.99}) {
    EXPECT_NEAR(sphere_integral(hg_phase(g)), 1, 1e-6) << g;
    EXPECT_NEAR(sphere_integral(hg_phase(g), [](double c) { return c; }), g, 1e-6) << g;  // mean cosine g
  }
  Phase tthg;
  tthg.kind = Phase::two_term_hg;
  tthg.g_forward = 0.8, tthg.g_backward = -0.3, tthg.forward_weight = 0.9;
  EXPECT_NEAR(sphere_integral(tthg), 1, 1e-6);
  EXPECT_NEAR(sphere_integral(tthg, [](double c) { return c; }), 0.9 * 0.8 - 0.1 * 0.3, 1e-6);
}

TEST(WaterPhase, DetritusDefaultIsPetzoldLike) {
  // Petzold's average particle: mean cosine 0.924 and backscatter fraction 0.0183
  // (data/ocean/README.md); the fit is exact, the integration good to 1e-6.
  const Phase p = bio_optical_defaults().detritus_phase;
  EXPECT_EQ(p.kind, Phase::two_term_hg);
  EXPECT_EQ(BioOptical{}.detritus_phase.g_forward, p.g_forward);
  EXPECT_NEAR(sphere_integral(p), 1, 1e-6);
  EXPECT_NEAR(sphere_integral(p, [](double c) { return c; }), 0.924, 1e-6);
  EXPECT_NEAR(sphere_integral(p, [](double c) { return c < 0 ? 1.0 : 0.0; }), 0.0183, 1e-5);  // step at 90°: 1e-5
}

TEST(WaterPhase, TablesAreNormalised) {
  Water w = iops_water();
  w.iops.phase.kind = Phase::table;
  w.iops.phase.cosines = {-1, 0, 1};
  w.iops.phase.values = {1, 2, 5};  // not normalised: 2π ∫ = 2π · 5 = 10π
  const WaterTables t = evaluate(w, Grid{});
  const Phase& p = t.phase[kWater];
  EXPECT_NEAR(p.values[2], 5 / (10 * kPi), 1e-15);
  EXPECT_NEAR(2 * kPi * simpson([&](double c) { return phase_value(p, c); }, -1, 1, 2000), 1, 1e-9);
  EXPECT_NEAR(phase_value(w.iops.phase, 0.5), 3.5 / (10 * kPi), 1e-15);  // phase_value normalises too
}

// ---- inelastic -----------------------------------------------------------------------

TEST(WaterInelastic, RamanFrom488PeaksNear585) {
  double best = 0, peak = 0;
  for (double lo = 520; lo <= 650; lo += 0.01) {
    const double h = emission_density(kRamanProcess, 488, lo);
    if (h > best) best = h, peak = lo;
  }
  EXPECT_NEAR(peak, 585, 3);
  // Normalised in λo (the Jacobian 10⁷/λo²): Simpson over 450–800 nm, 1e-6.
  EXPECT_NEAR(simpson([](double lo) { return emission_density(kRamanProcess, 488, lo); }, 450, 800, 70000), 1, 1e-6);
  EXPECT_DOUBLE_EQ(raman_coefficient(488), 2.6e-4);
  EXPECT_NEAR(raman_coefficient(400), 2.6e-4 * std::pow(488.0 / 400, 5.3), 1e-18);
  EXPECT_EQ(photon_yield(kRamanProcess, 450), raman_coefficient(450));
}

TEST(WaterInelastic, ChlorophyllEmissionIs685Sigma10_6) {
  auto h = [](double lo) { return emission_density(kChlorophyll, 440, lo); };
  // Moments by Simpson over ±10σ: the Gaussian's tails beyond hold < 1e-20.
  const double lo = 685 - 106, hi = 685 + 106;
  const double norm = simpson(h, lo, hi, 20000);
  const double mean = simpson([&](double x) { return x * h(x); }, lo, hi, 20000);
  const double var = simpson([&](double x) { return (x - 685) * (x - 685) * h(x); }, lo, hi, 20000);
  EXPECT_NEAR(norm, 1, 1e-9);
  EXPECT_NEAR(mean, 685, 1e-6);
  EXPECT_NEAR(std::sqrt(var), 10.6, 1e-6);
  EXPECT_GT(h(685), h(684.9));
  EXPECT_GT(h(685), h(685.1));
  // Excitation window, eq. 3.30: yield 0 outside 370–690 nm.
  EXPECT_EQ(photon_yield(kChlorophyll, 369.9), 0);
  EXPECT_EQ(photon_yield(kChlorophyll, 370), 1);
  EXPECT_EQ(photon_yield(kChlorophyll, 690), 1);
  EXPECT_EQ(photon_yield(kChlorophyll, 690.1), 0);
  Water w;
  w.bio.chlorophyll_yield = 0.05;
  const Grid g{300, 10, 51};
  const WaterTables t = evaluate(w, g);
  for (int k = 0; k < g.count; ++k) {
    const bool window = g.nm(k) >= 370 && g.nm(k) <= 690;
    EXPECT_EQ(t.yield[kChlorophyll][k], window ? 0.05 : 0) << g.nm(k);
    if (!window) {
      EXPECT_EQ(t.event[kFluorescePhyto][k], 0) << g.nm(k);
    }
  }
}

TEST(WaterInelastic, CdomYieldInTheThesisRange) {
  // The thesis quotes CDOM photon yields of 0.005–0.025 (§3.5.4.1).
  for (double li = 350; li <= 450; li += 1) {
    const double y = photon_yield(kCdomProcess, li);
    EXPECT_GE(y, 0.005) << li;
    EXPECT_LE(y, 0.025) << li;
  }
  // The yield is Hawes' η integrated over λo: a plain trapezoid over 300–2000 nm at
  // 0.005 nm agrees to 1e-4 relative (the library's support, 5 widths about the centre
  // in 1/λo, reaches below 300 nm from 350 nm: 1.5e-5 of the yield).
  for (double li : {350.0, 420.0, 470.0}) {
    auto eta = [&](double lo) {
      const double x = (1 / lo - 0.470 / li - 8.077e-4) / (0.6 * (0.407 / li - 4.57e-4));
      return cdom_fluorescence_a0(li) * std::exp(-x * x);
    };
    double sum = 0;
    for (double lo = 300; lo < 2000; lo += 0.005) sum += 0.5 * (eta(lo) + eta(lo + 0.005)) * 0.005;
    EXPECT_NEAR(photon_yield(kCdomProcess, li), sum, 1e-4 * sum) << li;
    EXPECT_NEAR(simpson([&](double lo) { return emission_density(kCdomProcess, li, lo); }, 300, 2000, 200000), 1, 1e-4)
        << li;
  }
  EXPECT_EQ(photon_yield(kCdomProcess, 300), 0);  // outside Hawes' table
  EXPECT_EQ(photon_yield(kCdomProcess, 600), 0);
}

// ---- evaluate() ------------------------------------------------------------------------

// Σ events = a + b at every sample, for a water.
void expect_events_sum(const WaterTables& t) {
  for (int k = 0; k < t.grid.count; ++k) {
    double events = 0, ab = 0;
    for (int e = 0; e < kEventCount; ++e) {
      events += t.event[e][k];
      EXPECT_GE(t.event[e][k], 0) << event_name(e) << " at " << t.grid.nm(k);
    }
    for (int c = 0; c < 4; ++c) ab += t.absorption[c][k] + t.scattering[c][k];
    EXPECT_NEAR(events, ab, 1e-12 * ab) << t.grid.nm(k);
  }
}

TEST(WaterEvaluate, EventsSumToExtinction) {
  expect_events_sum(evaluate(Water{}, Grid{}));
  for (const std::string& name : preset_names()) expect_events_sum(evaluate(Water{Water::kBioOptical, preset(name), {}}, Grid{300, 7, 101}));
  Water w = iops_water();
  w.iops.raman = true, w.iops.chlorophyll = 0.3, w.iops.a_y440 = 0.05;
  expect_events_sum(evaluate(w, Grid{}));
}

TEST(WaterEvaluate, InelasticEventsAreYieldTimesInside) {
  Water w;
  w.bio.a_y440 = 0.1;
  const Grid g{380, 5, 81};
  const WaterTables t = evaluate(w, g);
  for (int k = 0; k < g.count; ++k) {
    const double nm = g.nm(k), b_r = raman_coefficient(nm);
    EXPECT_NEAR(t.yield[kRamanProcess][k], b_r / pure_water_absorption(nm), 1e-15);
    EXPECT_NEAR(t.event[kRaman][k], b_r * t.inside[kRamanProcess][k], 1e-18) << nm;
    EXPECT_NEAR(t.event[kAbsorbWater][k], pure_water_absorption(nm) - t.event[kRaman][k], 1e-16) << nm;
    EXPECT_NEAR(t.event[kFluoresceCdom][k], t.absorption[3][k] * t.yield[kCdomProcess][k] * t.inside[kCdomProcess][k], 1e-18);
    EXPECT_NEAR(t.event[kFluorescePhyto][k], t.absorption[2][k] * t.yield[kChlorophyll][k] * t.inside[kChlorophyll][k], 1e-18);
  }
}

TEST(WaterEvaluate, InsideMatchesTheAnalyticDensity) {
  // P_in from the analytic density, not the grid: compared with a fine Simpson of
  // emission_density over the grid's range (1e-6).
  const Grid g{400, 10, 21};  // 400–600 nm
  const WaterTables t = evaluate(Water{}, g);
  for (int p = 0; p < kProcessCount; ++p)
    for (int k : {0, 8, 14}) {
      const double li = g.nm(k);
      const double expected = simpson([&](double lo) { return emission_density(p, li, lo); }, 400, 600, 40000);
      EXPECT_NEAR(t.inside[p][k], expected, 1e-6) << p << " from " << li;
    }
  // Raman from 540 nm lands near 660 nm: mostly outside 400–600.
  EXPECT_LT(t.inside[kRamanProcess][14], 0.01);
  EXPECT_GT(t.inside[kRamanProcess][0], 0.99);
}

TEST(WaterEvaluate, EmissionTablesAreNormalisedAndTheirCdfsEndAtOne) {
  Water w;
  w.bio.a_y440 = 0.1;
  const Grid g{380, 5, 81};
  const WaterTables t = evaluate(w, g);
  const size_t n = size_t(g.count);
  for (int p = 0; p < kProcessCount; ++p)
    for (size_t k = 0; k < n; ++k) {
      const size_t row = k * n;
      if (t.inside[p][k] == 0) {
        for (size_t m = 0; m < n; ++m) EXPECT_EQ(t.emission[p][row + m], 0);
        continue;
      }
      double trapezoid = 0;
      for (size_t m = 1; m < n; ++m) {
        trapezoid += 0.5 * (t.emission[p][row + m] + t.emission[p][row + m - 1]) * g.step_nm;
        EXPECT_GE(t.cdf[p][row + m], t.cdf[p][row + m - 1]);
        EXPECT_NEAR(t.cdf[p][row + m], trapezoid, 1e-12);
      }
      EXPECT_NEAR(trapezoid, 1, 1e-12) << p << " " << k;
      EXPECT_EQ(t.cdf[p][row], 0);
      EXPECT_EQ(t.cdf[p][row + n - 1], 1);
    }
}

TEST(WaterEvaluate, OneSampleGridHasNothingInside) {
  // Nothing can land in a zero-width range: P_in = 0, no inelastic event.
  Water w;
  w.bio.a_y440 = 0.1;
  const WaterTables t = evaluate(w, Grid{500, 5, 1});
  for (int p = 0; p < kProcessCount; ++p) {
    EXPECT_EQ(t.inside[p][0], 0);
    EXPECT_EQ(t.emission[p].size(), 1u);
    EXPECT_EQ(t.cdf[p][0], 0);
  }
  EXPECT_EQ(t.event[kRaman][0], 0);
  EXPECT_EQ(t.event[kFluorescePhyto][0], 0);
  EXPECT_EQ(t.event[kFluoresceCdom][0], 0);
  EXPECT_EQ(t.event[kAbsorbWater][0], pure_water_absorption(500));
  expect_events_sum(t);
}

TEST(WaterEvaluate, IopMode) {
  Water w = iops_water();
  w.iops.raman = true;
  w.iops.chlorophyll = 0.4;
  w.iops.a_y440 = 0.02;
  const Grid g{400, 10, 21};
  const WaterTables t = evaluate(w, g);
  for (int k = 0; k < g.count; ++k) {
    const double nm = g.nm(k);
    const double a = nm <= 500 ? 0.05 - 0.01 * (nm - 400) / 100 : 0.04 + 0.26 * (nm - 500) / 100;
    EXPECT_NEAR(t.absorption[0][k], a, 1e-15) << nm;
    EXPECT_NEAR(t.event[kRaman][k], raman_coefficient(nm) * t.inside[kRamanProcess][k], 1e-18);
    EXPECT_NEAR(t.event[kAbsorbWater][k], a - t.event[kRaman][k], 1e-15);
    EXPECT_EQ(t.event[kScatterWater][k], 0.2);  // a single value
    EXPECT_EQ(t.event[kScatterDetritus][k], 0);
    EXPECT_EQ(t.event[kScatterPhyto][k], 0);
    EXPECT_EQ(t.event[kAbsorbDetritus][k], 0);
    EXPECT_NEAR(t.absorption[2][k], 0.4 * phytoplankton_specific_absorption(nm), 1e-15);
    EXPECT_NEAR(t.absorption[3][k], 0.02 * std::exp(-0.014 * (nm - 440)), 1e-15);
  }
  EXPECT_EQ(t.phase[kWater].kind, Phase::hg);
  EXPECT_EQ(t.phase[kWater].g_forward, 0.9);
  // Without Raman the water's absorption is all absorption.
  w.iops.raman = false;
  const WaterTables u = evaluate(w, g);
  for (int k = 0; k < g.count; ++k) {
    EXPECT_EQ(u.event[kRaman][k], 0);
    EXPECT_EQ(u.event[kAbsorbWater][k], u.absorption[0][k]);
  }
}

TEST(WaterEvaluate, RamanMustFitInTheWatersAbsorption) {
  Water w;
  w.bio.raman_scale = 1e3;  // b_r(430) ≈ 0.5 m⁻¹ > a_w(430) = 0.0144
  Failure f = failure_of([&] { evaluate(w, Grid{}); });
  EXPECT_EQ(f.status, ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(f.message.find("water.bio.raman_scale"), std::string::npos) << f.message;
  Water i = iops_water();
  i.iops.raman = true;
  i.iops.absorption = {{500}, {1e-5}};
  f = failure_of([&] { evaluate(i, Grid{}); });
  EXPECT_EQ(f.status, ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(f.message.find("water.iops.absorption"), std::string::npos) << f.message;
}

TEST(WaterEvaluate, IsDeterministic) {
  Water w;
  w.bio = preset("baltic");
  const Grid g{350, 4, 101};
  const WaterTables a = evaluate(w, g), b = evaluate(w, g);
  for (int e = 0; e < kEventCount; ++e) EXPECT_EQ(a.event[e], b.event[e]);
  for (int p = 0; p < kProcessCount; ++p) {
    EXPECT_EQ(a.yield[p], b.yield[p]);
    EXPECT_EQ(a.inside[p], b.inside[p]);
    EXPECT_EQ(a.emission[p], b.emission[p]);
    EXPECT_EQ(a.cdf[p], b.cdf[p]);
  }
}

TEST(WaterEvaluate, EventNames) {
  EXPECT_STREQ(event_name(kAbsorbWater), "absorb_water");
  EXPECT_STREQ(event_name(kRaman), "raman");
  EXPECT_STREQ(event_name(kFluoresceCdom), "fluoresce_cdom");
  EXPECT_STREQ(event_name(kScatterPhyto), "scatter_phyto");
}

// ---- validation ------------------------------------------------------------------------

// Each bad value is INVALID_ARGUMENT with a message naming the parameter.
void expect_rejected(const std::function<void(Water&, Grid&)>& spoil, const std::string& name, bool iops = false) {
  Water w = iops ? iops_water() : Water{};
  Grid g;
  spoil(w, g);
  const Failure f = failure_of([&] { evaluate(w, g); });
  EXPECT_EQ(f.status, ARCUS_ERROR_INVALID_ARGUMENT) << name;
  EXPECT_NE(f.message.find(name), std::string::npos) << name << ": " << f.message;
}

TEST(WaterValidation, BioOpticalParametersAreNamed) {
  const double nan = std::nan("");
  expect_rejected([](Water& w, Grid&) { w.bio.chlorophyll = -1; }, "water.bio.chlorophyll: must be finite and >= 0, got -1");
  expect_rejected([&](Water& w, Grid&) { w.bio.a_d400 = nan; }, "water.bio.a_d400");
  expect_rejected([](Water& w, Grid&) { w.bio.a_y440 = -0.1; }, "water.bio.a_y440");
  expect_rejected([](Water& w, Grid&) { w.bio.s_d = -1; }, "water.bio.s_d");
  expect_rejected([&](Water& w, Grid&) { w.bio.s_y = INFINITY; }, "water.bio.s_y");
  expect_rejected([](Water& w, Grid&) { w.bio.chlorophyll_yield = 1.5; }, "water.bio.chlorophyll_yield");
  expect_rejected([](Water& w, Grid&) { w.bio.cdom_yield_scale = -1; }, "water.bio.cdom_yield_scale");
  expect_rejected([](Water& w, Grid&) { w.bio.cdom_yield_scale = 100; }, "water.bio.cdom_yield_scale");  // yield > 1
  expect_rejected([](Water& w, Grid&) { w.bio.raman_scale = -1; }, "water.bio.raman_scale");
  expect_rejected([](Water& w, Grid&) { w.bio.detritus_scattering_reference_a_d400 = 0; },
                  "water.bio.detritus_scattering_reference_a_d400");
  expect_rejected([](Water& w, Grid&) { w.bio.detritus_phase.g_forward = 1; }, "water.bio.detritus_phase.g_forward");
  expect_rejected([](Water& w, Grid&) { w.bio.detritus_phase.g_backward = 0.2; }, "water.bio.detritus_phase.g_backward");
  expect_rejected([](Water& w, Grid&) { w.bio.detritus_phase.forward_weight = 1.1; },
                  "water.bio.detritus_phase.forward_weight");
  expect_rejected([](Water& w, Grid&) { w.kind = Water::Kind(7); }, "water.kind");
}

TEST(WaterValidation, IopsAndPhasesAreNamed) {
  expect_rejected([](Water& w, Grid&) { w.iops.absorption = {}; }, "water.iops.absorption: is empty", true);
  expect_rejected([](Water& w, Grid&) { w.iops.scattering = {{400, 500}, {0.1}}; }, "water.iops.scattering", true);
  expect_rejected([](Water& w, Grid&) { w.iops.absorption.nm = {400, 600, 500}; }, "water.iops.absorption.nm[2]", true);
  expect_rejected([](Water& w, Grid&) { w.iops.absorption.nm = {250, 500, 600}; }, "water.iops.absorption.nm[0]", true);
  expect_rejected([](Water& w, Grid&) { w.iops.absorption.nm = {400, 500, 1100}; }, "water.iops.absorption.nm[2]", true);
  expect_rejected([](Water& w, Grid&) { w.iops.absorption.values[1] = -0.01; }, "water.iops.absorption.values[1]", true);
  expect_rejected([](Water& w, Grid&) { w.iops.scattering.values[0] = std::nan(""); }, "water.iops.scattering.values[0]",
                  true);
  expect_rejected([](Water& w, Grid&) { w.iops.phase.g_forward = -1; }, "water.iops.phase.g_forward", true);
  expect_rejected([](Water& w, Grid&) { w.iops.phase = Phase{}, w.iops.phase.kind = Phase::rayleigh_like, w.iops.phase.a = -2; },
                  "water.iops.phase.a", true);
  expect_rejected(
      [](Water& w, Grid&) {
        w.iops.phase.kind = Phase::table;
        w.iops.phase.cosines = {-0.9, 1};
        w.iops.phase.values = {1, 1};
      },
      "water.iops.phase.cosines", true);
  expect_rejected(
      [](Water& w, Grid&) {
        w.iops.phase.kind = Phase::table;
        w.iops.phase.cosines = {-1, 1};
        w.iops.phase.values = {0, 0};
      },
      "water.iops.phase.values", true);
  expect_rejected([](Water& w, Grid&) { w.iops.phase.kind = Phase::Kind(9); }, "water.iops.phase.kind", true);
  expect_rejected([](Water& w, Grid&) { w.iops.chlorophyll = -1; }, "water.iops.chlorophyll", true);
  expect_rejected([](Water& w, Grid&) { w.iops.chlorophyll_yield = -0.1; }, "water.iops.chlorophyll_yield", true);
  expect_rejected([](Water& w, Grid&) { w.iops.a_y440 = -1; }, "water.iops.a_y440", true);
  // A single value's wavelength is ignored.
  Water w = iops_water();
  w.iops.scattering = {{2000}, {0.1}};
  EXPECT_NO_THROW(evaluate(w, Grid{}));
}

TEST(WaterValidation, GridIsNamed) {
  expect_rejected([](Water&, Grid& g) { g.count = 0; }, "grid.count");
  expect_rejected([](Water&, Grid& g) { g.first_nm = 250; }, "grid.first_nm");
  expect_rejected([](Water&, Grid& g) { g.first_nm = std::nan(""); }, "grid.first_nm");
  expect_rejected([](Water&, Grid& g) { g.step_nm = 0; }, "grid.step_nm");
  expect_rejected([](Water&, Grid& g) { g.step_nm = 10; }, "grid.step_nm");  // 380 + 800 nm > 1000
  EXPECT_NO_THROW(check_grid(Grid{300, 7, 101}));  // ends exactly at 1000
  EXPECT_NO_THROW(check_grid(Grid{1000, 0, 1}));   // one sample: the step is ignored
}

}  // namespace
