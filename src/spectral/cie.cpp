#include "spectral/cie.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/format.h"

namespace arcus::spectral {

namespace {

#include "spectral/cie_table.inc"

static_assert(kTableFirstNm == kCmfFirstNm && kTableFirstNm + (kTableRows - 1) * kTableStepNm == kCmfLastNm,
              "cie.h's range is the table's");

// Channel c (0: x̄, 1: ȳ, 2: z̄) at nm, linear between rows.
double interpolate(double nm, int c) {
  if (!(nm >= kCmfFirstNm && nm <= kCmfLastNm)) return 0.0;  // NaN too
  const double t = (nm - kTableFirstNm) / kTableStepNm;
  const int i = std::min(static_cast<int>(t), kTableRows - 2);
  const double f = t - i;
  return kTable[i][c] + f * (kTable[i + 1][c] - kTable[i][c]);
}

// ∫ȳ over the whole table: the Y of a flat spectrum of 1, which band_weights divides by.
double y_total() {
  static const double total = cmf_integral(kCmfFirstNm, kCmfLastNm)[1];
  return total;
}

}  // namespace

double cmf_x(double nm) { return interpolate(nm, 0); }
double cmf_y(double nm) { return interpolate(nm, 1); }
double cmf_z(double nm) { return interpolate(nm, 2); }

std::array<double, 3> cmf_integral(double a, double b) {
  std::array<double, 3> sum{0.0, 0.0, 0.0};
  a = std::max(a, kCmfFirstNm);
  b = std::min(b, kCmfLastNm);
  // Row by row, each piece by the trapezoid rule, exact for linear interpolation.
  for (double lo = a; lo < b;) {
    const int row = std::min(static_cast<int>((lo - kTableFirstNm) / kTableStepNm), kTableRows - 2);
    const double hi = std::min(b, kTableFirstNm + (row + 1) * kTableStepNm);
    for (int c = 0; c < 3; ++c) sum[c] += 0.5 * (hi - lo) * (interpolate(lo, c) + interpolate(hi, c));
    lo = hi;
  }
  return sum;
}

std::vector<std::array<double, 3>> band_weights(const std::vector<double>& wavelengths) {
  const size_t n = wavelengths.size();
  require(n > 0, "band_weights: no wavelengths");
  for (size_t i = 0; i < n; ++i) {
    if (!std::isfinite(wavelengths[i]))
      fail(ARCUS_ERROR_INVALID_ARGUMENT, "band_weights: wavelength " + std::to_string(i) + " is not finite");
    if (i > 0 && !(wavelengths[i] > wavelengths[i - 1]))
      fail(ARCUS_ERROR_INVALID_ARGUMENT, "band_weights: wavelengths must increase strictly (" +
                                             number(wavelengths[i - 1]) + " then " + number(wavelengths[i]) + " nm)");
  }
  std::vector<std::array<double, 3>> weights(n);
  for (size_t i = 0; i < n; ++i) {
    const double lo = i == 0 ? kCmfFirstNm : 0.5 * (wavelengths[i - 1] + wavelengths[i]);
    const double hi = i + 1 == n ? kCmfLastNm : 0.5 * (wavelengths[i] + wavelengths[i + 1]);
    weights[i] = cmf_integral(lo, hi);
    for (double& w : weights[i]) w /= y_total();
  }
  return weights;
}

void spectrum_to_xyz(const double* nm, const double* values, size_t n, double xyz[3]) {
  require_pointer(nm, "nm");
  require_pointer(values, "values");
  require_pointer(xyz, "xyz");
  const auto weights = band_weights(std::vector<double>(nm, nm + n));
  xyz[0] = xyz[1] = xyz[2] = 0.0;
  for (size_t i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) xyz[c] += values[i] * weights[i][c];
}

}  // namespace arcus::spectral
