// The water of the ocean engine: the bio-optical model of thesis §3.5 (Tables 3.4, 3.5,
// 4.3), water given by IOPs, and their evaluation on a wavelength grid (§4.2).  Every
// number's source: data/ocean/README.md.
#include "ocean/water.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "core/error.h"

namespace arcus::ocean {
namespace {

#include "ocean/water_data.inc"

constexpr double kPi = 3.14159265358979323846;
constexpr double kFourLn2 = 2.772588722239781;  // 4 ln 2: FWHM → Gaussian exponent
constexpr double kMinNm = 300, kMaxNm = 1000;   // the grid's allowed range

// Pure seawater scattering, eq. 3.25: β_sw(λ0, 90°) of Morel 1974 at λ0 = 400 nm.
constexpr double kMorelBeta90 = 4.72e-4, kMorelNm = 400, kMorelExponent = 4.32;
// Raman: b_r(488) (Marshall & Smith 1990) and the photon-normalised excitation
// exponent 5.3 of Bartlett et al. 1998 (this engine counts photons).
constexpr double kRaman488 = 2.6e-4, kRamanExponent = 5.3;
// Chlorophyll fluorescence, eq. 3.30 and 3.32.
constexpr double kChlExciteLo = 370, kChlExciteHi = 690, kChlPeakNm = 685, kChlSigmaNm = 10.6;
// Hawes 1992 (Mobley 1994 §5.14): the emission Gaussian in 1/λo.
constexpr double kHawesA1 = 0.470, kHawesA2 = 0.407, kHawesB1 = 8.077e-4, kHawesB2 = -4.57e-4;
// Hawes' fit says nothing far from its Gaussian's core, whose 1/λ² Jacobian would make
// the integral over all λo diverge: emission is kept within 5 widths of the centre in
// 1/λo and below 2000 nm (what is cut is < 1e-3 of the yield; README).
constexpr double kCdomWidths = 5, kCdomMaxNm = 2000;
constexpr int kCdomSteps = 4000;  // Simpson intervals over the support
// Phytoplankton scattering, eq. 3.27 (Gordon & Morel 1983).
constexpr double kPhytoB = 0.30, kPhytoExponent = 0.62, kPhytoScatterNm = 550;

// Linear interpolation in a table, constant beyond its ends; exact at the nodes.
double interpolate(const double* x, const double* y, int n, double at) {
  if (at <= x[0]) return y[0];
  if (at >= x[n - 1]) return y[n - 1];
  const int i = int(std::upper_bound(x, x + n, at) - x) - 1;
  const double t = (at - x[i]) / (x[i + 1] - x[i]);
  return y[i] + t * (y[i + 1] - y[i]);
}

double interpolate(const Spectrum& s, double at) {
  return interpolate(s.nm.data(), s.values.data(), int(s.nm.size()), at);
}

std::string text(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

void finite_non_negative(double v, const std::string& name) {
  require(std::isfinite(v) && v >= 0, name + ": must be finite and >= 0, got " + text(v));
}

void in_range(double v, double lo, double hi, bool open, const std::string& name) {
  const bool ok = std::isfinite(v) && (open ? (v > lo && v < hi) : (v >= lo && v <= hi));
  const std::string range = open ? "(" + text(lo) + ", " + text(hi) + ")" : "[" + text(lo) + ", " + text(hi) + "]";
  require(ok, name + ": must lie in " + range + ", got " + text(v));
}

void check_spectrum(const Spectrum& s, const std::string& name) {
  require(!s.nm.empty() && !s.values.empty(), name + ": is empty");
  require(s.nm.size() == s.values.size(), name + ": nm and values differ in length (" + text(double(s.nm.size())) +
                                              " vs " + text(double(s.values.size())) + ")");
  for (size_t i = 0; i < s.nm.size(); ++i) {
    const std::string at = "[" + std::to_string(i) + "]";
    finite_non_negative(s.values[i], name + ".values" + at);
    require(std::isfinite(s.nm[i]), name + ".nm" + at + ": must be finite, got " + text(s.nm[i]));
    // One entry is a single value, its wavelength ignored.
    if (s.nm.size() > 1)
      require(s.nm[i] >= kMinNm && s.nm[i] <= kMaxNm,
              name + ".nm" + at + ": must lie in 300-1000 nm, got " + text(s.nm[i]));
    if (i > 0)
      require(s.nm[i] > s.nm[i - 1], name + ".nm" + at + ": must increase strictly, got " + text(s.nm[i]) +
                                         " after " + text(s.nm[i - 1]));
  }
}

// 2π ∫ p dcosθ of a table, linear between its cosines.
double table_integral(const Phase& p) {
  double sum = 0;
  for (size_t i = 1; i < p.cosines.size(); ++i)
    sum += 0.5 * (p.values[i] + p.values[i - 1]) * (p.cosines[i] - p.cosines[i - 1]);
  return 2 * kPi * sum;
}

void check_phase(const Phase& p, const std::string& name) {
  switch (p.kind) {
    case Phase::isotropic:
      return;
    case Phase::rayleigh_like:  // 1 + a cos²θ ≥ 0 everywhere
      require(std::isfinite(p.a) && p.a >= -1, name + ".a: must be finite and >= -1, got " + text(p.a));
      return;
    case Phase::hg:
      in_range(p.g_forward, -1, 1, true, name + ".g_forward");
      return;
    case Phase::two_term_hg:  // thesis §3.5.3: g_f ∈ [0, 1), g_b ∈ (−1, 0]
      in_range(p.g_forward, 0, 1, false, name + ".g_forward");
      require(p.g_forward < 1, name + ".g_forward: must be < 1, got " + text(p.g_forward));
      in_range(p.g_backward, -1, 0, false, name + ".g_backward");
      require(p.g_backward > -1, name + ".g_backward: must be > -1, got " + text(p.g_backward));
      in_range(p.forward_weight, 0, 1, false, name + ".forward_weight");
      return;
    case Phase::table: {
      require(p.cosines.size() >= 2 && p.cosines.size() == p.values.size(),
              name + ".cosines: needs at least 2 cosines and as many values");
      for (size_t i = 0; i < p.cosines.size(); ++i) {
        finite_non_negative(p.values[i], name + ".values[" + std::to_string(i) + "]");
        require(std::isfinite(p.cosines[i]), name + ".cosines: must be finite");
        if (i > 0) require(p.cosines[i] > p.cosines[i - 1], name + ".cosines: must increase strictly");
      }
      require(p.cosines.front() == -1 && p.cosines.back() == 1,
              name + ".cosines: must span [-1, 1], got [" + text(p.cosines.front()) + ", " + text(p.cosines.back()) + "]");
      require(table_integral(p) > 0, name + ".values: must integrate to a positive number");
      return;
    }
  }
  fail(ARCUS_ERROR_INVALID_ARGUMENT, name + ".kind: unknown phase kind " + std::to_string(int(p.kind)));
}

double hg(double g, double c) { return (1 - g * g) / (4 * kPi * std::pow(1 + g * g - 2 * g * c, 1.5)); }

double normal_cdf(double x) { return 0.5 * std::erfc(-x / std::sqrt(2.0)); }

// Raman, eq. 3.35–3.36: the normalised density of the wavenumber shift [cm], Walrafen's
// four Gaussians with FWHM Δν̃ (the thesis' exponent lacks the 4 ln 2 its normalisation
// sqrt(π / 4 ln 2) implies), and its cumulative integral.
double raman_shift_density(double shift) {
  double sum = 0, weights = 0;
  for (int j = 0; j < 4; ++j) {
    const double x = (shift - kRamanCentre[j]) / kRamanFwhm[j];
    sum += kRamanWeight[j] * std::sqrt(kFourLn2 / kPi) / kRamanFwhm[j] * std::exp(-kFourLn2 * x * x);
    weights += kRamanWeight[j];
  }
  return sum / weights;
}

double raman_shift_cdf(double shift) {
  double sum = 0, weights = 0;
  for (int j = 0; j < 4; ++j) {
    sum += kRamanWeight[j] * 0.5 * std::erfc(-std::sqrt(kFourLn2) * (shift - kRamanCentre[j]) / kRamanFwhm[j]);
    weights += kRamanWeight[j];
  }
  return sum / weights;
}

double raman_shift(double excitation_nm, double emission_nm) { return 1e7 * (1 / excitation_nm - 1 / emission_nm); }

// Hawes' Gaussian in ν = 1/λo [1/nm]: centre, width (0.6 (A2/λi + B2)) and the support.
struct CdomGaussian {
  double centre, width, lo, hi;  // lo, hi: the support in ν
  bool valid;
};

CdomGaussian cdom_gaussian(double excitation_nm) {
  CdomGaussian g;
  g.centre = kHawesA1 / excitation_nm + kHawesB1;
  g.width = 0.6 * (kHawesA2 / excitation_nm + kHawesB2);
  g.valid = g.width > 0 && std::isfinite(g.width);  // the width turns negative past ~890 nm
  g.lo = std::max(g.centre - kCdomWidths * g.width, 1 / kCdomMaxNm);
  g.hi = g.centre + kCdomWidths * g.width;
  g.valid = g.valid && g.hi > g.lo;
  return g;
}

// η / A0 at emission ν, per unit λo (0 outside the support).
double cdom_shape(const CdomGaussian& g, double nu) {
  if (!g.valid || nu < g.lo || nu > g.hi) return 0;
  const double x = (nu - g.centre) / g.width;
  return std::exp(-x * x);
}

// ∫ η/A0 dλo over emission ν in [nu_lo, nu_hi] (dλo = dν/ν²), composite Simpson.
double cdom_integral(const CdomGaussian& g, double nu_lo, double nu_hi) {
  const double a = std::max(nu_lo, g.lo), b = std::min(nu_hi, g.hi);
  if (!g.valid || !(b > a)) return 0;
  const double h = (b - a) / kCdomSteps;
  double sum = 0;
  for (int i = 0; i <= kCdomSteps; ++i) {
    const double nu = a + i * h;
    const double w = (i == 0 || i == kCdomSteps) ? 1 : (i % 2 ? 4 : 2);
    sum += w * cdom_shape(g, nu) / (nu * nu);
  }
  return sum * h / 3;
}

// The probability that re-emission from excitation λi lands in [lo_nm, hi_nm].
double inside_probability(int process, double excitation_nm, double lo_nm, double hi_nm) {
  if (!(hi_nm > lo_nm)) return 0;  // a one-sample grid: a zero-width range
  switch (process) {
    case kRamanProcess:
      return std::max(0.0, raman_shift_cdf(raman_shift(excitation_nm, hi_nm)) -
                               raman_shift_cdf(raman_shift(excitation_nm, lo_nm)));
    case kChlorophyll:
      return std::max(0.0, normal_cdf((hi_nm - kChlPeakNm) / kChlSigmaNm) - normal_cdf((lo_nm - kChlPeakNm) / kChlSigmaNm));
    case kCdomProcess: {
      const CdomGaussian g = cdom_gaussian(excitation_nm);
      const double total = cdom_integral(g, g.lo, g.hi);
      return total > 0 ? std::min(1.0, cdom_integral(g, 1 / hi_nm, 1 / lo_nm) / total) : 0;
    }
  }
  return 0;
}

// The bio-optical constituents' coefficients at one wavelength [1/m].
double detritus_absorption(const BioOptical& b, double nm) { return b.a_d400 * std::exp(-b.s_d * (nm - 400)); }
double cdom_absorption(double a_y440, double s_y, double nm) { return a_y440 * std::exp(-s_y * (nm - 440)); }
double phyto_scattering(double c, double nm) { return kPhytoB * std::pow(c, kPhytoExponent) * (kPhytoScatterNm / nm); }

double trapezoid(const std::vector<double>& y, double step, size_t first, size_t n) {
  double sum = 0;
  for (size_t m = 1; m < n; ++m) sum += 0.5 * (y[first + m] + y[first + m - 1]) * step;
  return sum;
}

Phase normalised(Phase p) {
  if (p.kind == Phase::table) {
    const double total = table_integral(p);
    for (double& v : p.values) v /= total;
  }
  return p;
}

}  // namespace

void check_grid(const Grid& grid) {
  require(grid.count >= 1, "grid.count: must be >= 1, got " + std::to_string(grid.count));
  require(std::isfinite(grid.first_nm) && grid.first_nm >= kMinNm && grid.first_nm <= kMaxNm,
          "grid.first_nm: must lie in 300-1000 nm, got " + text(grid.first_nm));
  if (grid.count == 1) return;
  require(std::isfinite(grid.step_nm) && grid.step_nm > 0, "grid.step_nm: must be finite and > 0, got " + text(grid.step_nm));
  require(grid.last_nm() <= kMaxNm * (1 + 1e-12),
          "grid.step_nm: the last wavelength " + text(grid.last_nm()) + " nm lies past 1000 nm");
}

const char* event_name(int event) {
  static const char* const names[kEventCount] = {"absorb_water",    "raman",          "absorb_detritus", "absorb_phyto",
                                                 "fluoresce_phyto", "absorb_cdom",    "fluoresce_cdom",  "scatter_water",
                                                 "scatter_detritus", "scatter_phyto"};
  return event >= 0 && event < kEventCount ? names[event] : "unknown";
}

double phase_value(const Phase& p, double c) {
  switch (p.kind) {
    case Phase::isotropic:
      return 1 / (4 * kPi);  // the thesis prints 1/π (§3.5.3), not normalised
    case Phase::rayleigh_like:
      return (1 + p.a * c * c) / (4 * kPi * (1 + p.a / 3));  // a = 0.835: 0.06225 (eq. 3.26)
    case Phase::hg:
      return hg(p.g_forward, c);
    case Phase::two_term_hg:  // eq. 3.28–3.29
      return p.forward_weight * hg(p.g_forward, c) + (1 - p.forward_weight) * hg(p.g_backward, c);
    case Phase::table:
      return interpolate(p.cosines.data(), p.values.data(), int(p.cosines.size()), c) / table_integral(p);
  }
  return 0;
}

Phase petzold_like_detritus_phase() {
  Phase p;
  p.kind = Phase::two_term_hg;
  p.g_forward = kDetritusGForward;
  p.g_backward = kDetritusGBackward;
  p.forward_weight = kDetritusForwardWeight;
  return p;
}

BioOptical bio_optical_defaults() { return BioOptical{}; }

std::vector<std::string> preset_names() {
  std::vector<std::string> names;
  for (const PresetRow& row : kPresets) names.push_back(row.name);
  return names;
}

BioOptical preset(const std::string& name) {
  for (const PresetRow& row : kPresets) {
    if (name != row.name) continue;
    // Babin et al. 2003 report a_NAP and a_CDOM at 443 nm: carried to the model's
    // reference wavelengths with its own slopes (eq. 3.24, 3.22).
    BioOptical b = bio_optical_defaults();
    b.chlorophyll = row.chlorophyll;
    b.a_d400 = row.a_nap443 * std::exp(b.s_d * (443 - 400));
    b.a_y440 = row.a_cdom443 * std::exp(b.s_y * (443 - 440));
    return b;
  }
  std::string known;
  for (const std::string& n : preset_names()) known += (known.empty() ? "" : ", ") + n;
  fail(ARCUS_ERROR_INVALID_ARGUMENT, "water preset \"" + name + "\": unknown; known: " + known);
}

void check_water(const Water& water) {
  if (water.kind == Water::kBioOptical) {
    const BioOptical& b = water.bio;
    finite_non_negative(b.chlorophyll, "water.bio.chlorophyll");
    finite_non_negative(b.a_d400, "water.bio.a_d400");
    finite_non_negative(b.a_y440, "water.bio.a_y440");
    finite_non_negative(b.s_d, "water.bio.s_d");
    finite_non_negative(b.s_y, "water.bio.s_y");
    in_range(b.chlorophyll_yield, 0, 1, false, "water.bio.chlorophyll_yield");
    finite_non_negative(b.cdom_yield_scale, "water.bio.cdom_yield_scale");
    finite_non_negative(b.raman_scale, "water.bio.raman_scale");
    require(std::isfinite(b.detritus_scattering_reference_a_d400) && b.detritus_scattering_reference_a_d400 > 0,
            "water.bio.detritus_scattering_reference_a_d400: must be finite and > 0, got " +
                text(b.detritus_scattering_reference_a_d400));
    check_phase(b.detritus_phase, "water.bio.detritus_phase");
    return;
  }
  require(water.kind == Water::kIops, "water.kind: unknown kind " + std::to_string(int(water.kind)));
  const Iops& i = water.iops;
  check_spectrum(i.absorption, "water.iops.absorption");
  check_spectrum(i.scattering, "water.iops.scattering");
  check_phase(i.phase, "water.iops.phase");
  finite_non_negative(i.chlorophyll, "water.iops.chlorophyll");
  in_range(i.chlorophyll_yield, 0, 1, false, "water.iops.chlorophyll_yield");
  finite_non_negative(i.a_y440, "water.iops.a_y440");
  finite_non_negative(i.s_y, "water.iops.s_y");
}

double pure_water_absorption(double nm) { return interpolate(kSmithBakerNm, kSmithBakerAw, kSmithBakerRows, nm); }

double pure_water_scattering(double nm) {
  return 16.06 * kMorelBeta90 * std::pow(kMorelNm / nm, kMorelExponent);
}

double phytoplankton_specific_absorption(double nm) { return interpolate(kPhytoNm, kPhytoAstar, kPhytoRows, nm); }

double detritus_table_scattering(double nm) { return interpolate(kDetritusNm, kDetritusTotal, kDetritusRows, nm); }

double cdom_fluorescence_a0(double excitation_nm) {
  if (excitation_nm < kCdomA0Nm[0] || excitation_nm > kCdomA0Nm[kCdomA0Rows - 1]) return 0;
  return interpolate(kCdomA0Nm, kCdomA0, kCdomA0Rows, excitation_nm);
}

double raman_coefficient(double excitation_nm) { return kRaman488 * std::pow(488 / excitation_nm, kRamanExponent); }

double photon_yield(int process, double excitation_nm) {
  switch (process) {
    case kRamanProcess:
      return raman_coefficient(excitation_nm);
    case kChlorophyll:  // eq. 3.30
      return excitation_nm >= kChlExciteLo && excitation_nm <= kChlExciteHi ? 1 : 0;
    case kCdomProcess: {
      const double a0 = cdom_fluorescence_a0(excitation_nm);
      if (a0 == 0) return 0;
      const CdomGaussian g = cdom_gaussian(excitation_nm);
      return a0 * cdom_integral(g, g.lo, g.hi);
    }
  }
  fail(ARCUS_ERROR_INVALID_ARGUMENT, "process " + std::to_string(process) + ": unknown");
}

double emission_density(int process, double excitation_nm, double emission_nm) {
  if (!(emission_nm > 0) || !(excitation_nm > 0)) return 0;
  switch (process) {
    case kRamanProcess:  // density in λo: the shift's density times |dν̃/dλo| = 10⁷/λo²
      return raman_shift_density(raman_shift(excitation_nm, emission_nm)) * 1e7 / (emission_nm * emission_nm);
    case kChlorophyll: {  // eq. 3.32
      const double x = (emission_nm - kChlPeakNm) / kChlSigmaNm;
      return std::exp(-0.5 * x * x) / (std::sqrt(2 * kPi) * kChlSigmaNm);
    }
    case kCdomProcess: {  // eq. 3.33–3.34 divided by the yield (A0 cancels)
      // Callers sweep λo at one λi: its normaliser is kept (a pure function of λi).
      thread_local double cached_nm = std::nan(""), cached_total = 0;
      const CdomGaussian g = cdom_gaussian(excitation_nm);
      if (excitation_nm != cached_nm) cached_nm = excitation_nm, cached_total = cdom_integral(g, g.lo, g.hi);
      return cached_total > 0 ? cdom_shape(g, 1 / emission_nm) / cached_total : 0;
    }
  }
  fail(ARCUS_ERROR_INVALID_ARGUMENT, "process " + std::to_string(process) + ": unknown");
}

namespace {

// Emission on the grid, restricted to it and renormalised by the trapezoid rule (what
// the kernel's piecewise-linear sampling inverts).  A row that misses every sample
// counts as leaving the range.
void emission_on_grid(bool anti_stokes, WaterTables* out) {
  WaterTables& t = *out;
  const Grid& grid = t.grid;
  const size_t n = size_t(grid.count);
  for (int p = 0; p < kProcessCount; ++p) {
    for (size_t k = 0; k < n; ++k) {
      const size_t row = k * n;
      if (t.inside[p][k] > 0) {
        for (size_t m = 0; m < n; ++m)
          t.emission[p][row + m] =
              anti_stokes || m > k ? emission_density(p, grid.nm(int(k)), grid.nm(int(m))) : 0.0;
        const double total = trapezoid(t.emission[p], grid.step_nm, row, n);
        if (total > 0 && std::isfinite(total)) {
          double sum = 0;
          for (size_t m = 1; m < n; ++m) {
            sum += 0.5 * (t.emission[p][row + m] + t.emission[p][row + m - 1]) * grid.step_nm;
            t.cdf[p][row + m] = sum / total;
          }
          t.cdf[p][row + n - 1] = 1;
          for (size_t m = 0; m < n; ++m) t.emission[p][row + m] /= total;
          continue;
        }
      }
      t.inside[p][k] = 0;
      std::fill(t.emission[p].begin() + row, t.emission[p].begin() + row + n, 0.0);
    }
  }
}

// Events (thesis §4.2): an inelastic process' event is a_j·Y·P_in, its absorption event
// the rest of a_j (photons that would leave the range are absorbed).
void fill_events(WaterTables* out) {
  WaterTables& t = *out;
  const size_t n = size_t(t.grid.count);
  for (size_t k = 0; k < n; ++k) {
    const double raman_in = t.absorption[0][k] * t.yield[kRamanProcess][k] * t.inside[kRamanProcess][k];
    const double phyto_in = t.absorption[2][k] * t.yield[kChlorophyll][k] * t.inside[kChlorophyll][k];
    const double cdom_in = t.absorption[3][k] * t.yield[kCdomProcess][k] * t.inside[kCdomProcess][k];
    t.event[kAbsorbWater][k] = t.absorption[0][k] - raman_in;
    t.event[kRaman][k] = raman_in;
    t.event[kAbsorbDetritus][k] = t.absorption[1][k];
    t.event[kAbsorbPhyto][k] = t.absorption[2][k] - phyto_in;
    t.event[kFluorescePhyto][k] = phyto_in;
    t.event[kAbsorbCdom][k] = t.absorption[3][k] - cdom_in;
    t.event[kFluoresceCdom][k] = cdom_in;
    t.event[kScatterWater][k] = t.scattering[0][k];
    t.event[kScatterDetritus][k] = t.scattering[1][k];
    t.event[kScatterPhyto][k] = t.scattering[2][k];
  }
}

}  // namespace

WaterTables evaluate(const Water& water, const Grid& grid) {
  check_grid(grid);
  check_water(water);
  const bool bio = water.kind == Water::kBioOptical;
  const BioOptical& b = water.bio;
  const Iops& iops = water.iops;
  const size_t n = size_t(grid.count);
  const bool anti_stokes = water.kind == Water::kBioOptical ? water.bio.anti_stokes : water.iops.anti_stokes;
  const double lo = grid.first_nm, hi = grid.count > 1 ? grid.last_nm() : grid.first_nm;

  WaterTables t;
  t.grid = grid;
  for (auto& e : t.event) e.assign(n, 0);
  for (auto& a : t.absorption) a.assign(n, 0);
  for (auto& s : t.scattering) s.assign(n, 0);
  for (int p = 0; p < kProcessCount; ++p) {
    t.yield[p].assign(n, 0);
    t.inside[p].assign(n, 0);
    t.emission[p].assign(n * n, 0);
    t.cdf[p].assign(n * n, 0);
  }
  Phase einstein_smoluchowski;  // eq. 3.26
  einstein_smoluchowski.kind = Phase::rayleigh_like;
  einstein_smoluchowski.a = 0.835;
  t.phase[kWater] = bio ? einstein_smoluchowski : normalised(iops.phase);
  t.phase[kDetritus] = bio ? normalised(b.detritus_phase) : Phase{};
  t.phase[kPhyto] = Phase{};  // isotropic (§3.5.3)

  const double chlorophyll = bio ? b.chlorophyll : iops.chlorophyll;
  const double chl_yield = bio ? b.chlorophyll_yield : iops.chlorophyll_yield;
  const double a_y440 = bio ? b.a_y440 : iops.a_y440, s_y = bio ? b.s_y : iops.s_y;
  const double cdom_scale = bio ? b.cdom_yield_scale : 1;
  const bool raman = bio ? b.raman_scale > 0 : iops.raman;
  const double raman_scale = bio ? b.raman_scale : (iops.raman ? 1 : 0);

  for (size_t k = 0; k < n; ++k) {
    const double nm = grid.nm(int(k));
    // Per constituent (water, detritus, phytoplankton, CDOM) absorption and scattering.
    const double a_w = bio ? pure_water_absorption(nm) : interpolate(iops.absorption, nm);
    const double a_d = bio ? detritus_absorption(b, nm) : 0;
    const double a_p = chlorophyll * phytoplankton_specific_absorption(nm);  // eq. 3.23
    const double a_y = cdom_absorption(a_y440, s_y, nm);                     // eq. 3.22
    const double b_w = bio ? pure_water_scattering(nm) : interpolate(iops.scattering, nm);
    // Table 3.5 is "typical": scaled with a_d(400) so murkier water scatters more (Fig. 5.8).
    const double b_d = bio ? detritus_table_scattering(nm) * b.a_d400 / b.detritus_scattering_reference_a_d400 : 0;
    const double b_p = bio ? phyto_scattering(chlorophyll, nm) : 0;
    const double b_r = raman_scale * raman_coefficient(nm);
    if (raman)
      require(b_r <= a_w, (bio ? "water.bio.raman_scale: Raman's b_r " : "water.iops.absorption: must hold Raman's b_r ") +
                              text(b_r) + " 1/m exceeds the water's absorption " + text(a_w) + " 1/m at " + text(nm) + " nm");
    t.absorption[0][k] = a_w, t.absorption[1][k] = a_d, t.absorption[2][k] = a_p, t.absorption[3][k] = a_y;
    t.scattering[0][k] = b_w, t.scattering[1][k] = b_d, t.scattering[2][k] = b_p;

    // Photon yields (water.h): the share of each process' absorbed photons re-emitted.
    t.yield[kRamanProcess][k] = a_w > 0 ? b_r / a_w : 0;
    t.yield[kChlorophyll][k] = chl_yield * photon_yield(kChlorophyll, nm);
    t.yield[kCdomProcess][k] = cdom_scale * photon_yield(kCdomProcess, nm);
    require(t.yield[kCdomProcess][k] <= 1, "water.bio.cdom_yield_scale: makes the CDOM photon yield " +
                                               text(t.yield[kCdomProcess][k]) + " exceed 1 at " + text(nm) + " nm");
    // Without anti-Stokes re-emission only λo ≥ λi lands in the range (thesis Fig. 5.11).
    for (int p = 0; p < kProcessCount; ++p) t.inside[p][k] = inside_probability(p, nm, anti_stokes ? lo : nm, hi);
  }

  emission_on_grid(anti_stokes, &t);
  fill_events(&t);
  return t;
}

}  // namespace arcus::ocean
