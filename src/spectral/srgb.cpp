#include "spectral/srgb.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.h"
#include "core/format.h"
#include "spectral/cie.h"

namespace arcus::spectral {

namespace {

using Matrix = std::array<std::array<double, 3>, 3>;

Matrix inverse(const Matrix& m) {
  const double c00 = m[1][1] * m[2][2] - m[1][2] * m[2][1];
  const double c01 = m[1][2] * m[2][0] - m[1][0] * m[2][2];
  const double c02 = m[1][0] * m[2][1] - m[1][1] * m[2][0];
  const double det = m[0][0] * c00 + m[0][1] * c01 + m[0][2] * c02;
  return {{{c00 / det, (m[0][2] * m[2][1] - m[0][1] * m[2][2]) / det, (m[0][1] * m[1][2] - m[0][2] * m[1][1]) / det},
           {c01 / det, (m[0][0] * m[2][2] - m[0][2] * m[2][0]) / det, (m[0][2] * m[1][0] - m[0][0] * m[1][2]) / det},
           {c02 / det, (m[0][1] * m[2][0] - m[0][0] * m[2][1]) / det, (m[0][0] * m[1][1] - m[0][1] * m[1][0]) / det}}};
}

std::array<double, 3> apply(const Matrix& m, const std::array<double, 3>& v) {
  return {m[0][0] * v[0] + m[0][1] * v[1] + m[0][2] * v[2], m[1][0] * v[0] + m[1][1] * v[1] + m[1][2] * v[2],
          m[2][0] * v[0] + m[2][1] * v[1] + m[2][2] * v[2]};
}

// Linear sRGB -> XYZ, built as the standard defines it rather than typed in: columns are
// the primaries' chromaticities (R 0.64, 0.33; G 0.30, 0.60; B 0.15, 0.06) as XYZ with
// Y = 1, each scaled so that together they make the white point.
Matrix make_rgb_to_xyz() {
  const double xy[3][2] = {{0.64, 0.33}, {0.30, 0.60}, {0.15, 0.06}};
  Matrix p;
  for (int c = 0; c < 3; ++c) {
    p[0][c] = xy[c][0] / xy[c][1];
    p[1][c] = 1.0;
    p[2][c] = (1.0 - xy[c][0] - xy[c][1]) / xy[c][1];
  }
  const std::array<double, 3> scale = apply(inverse(p), kD65White);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) p[r][c] *= scale[c];
  return p;
}

const Matrix& rgb_to_xyz() {
  static const Matrix m = make_rgb_to_xyz();
  return m;
}

const Matrix& xyz_to_rgb() {
  static const Matrix m = inverse(rgb_to_xyz());
  return m;
}

}  // namespace

std::array<double, 3> xyz_to_linear_srgb(const std::array<double, 3>& xyz) { return apply(xyz_to_rgb(), xyz); }
std::array<double, 3> linear_srgb_to_xyz(const std::array<double, 3>& rgb) { return apply(rgb_to_xyz(), rgb); }

double srgb_encode(double linear) {
  const double a = std::fabs(linear);
  const double e = a <= 0.0031308 ? 12.92 * a : 1.055 * std::pow(a, 1.0 / 2.4) - 0.055;
  return std::copysign(e, linear);
}

double srgb_decode(double encoded) {
  const double a = std::fabs(encoded);
  const double l = a <= 0.04045 ? a / 12.92 : std::pow((a + 0.055) / 1.055, 2.4);
  return std::copysign(l, encoded);
}

uint8_t srgb_encode_8bit(double linear) {
  if (!(linear > 0.0)) return 0;  // NaN too
  return static_cast<uint8_t>(std::lround(std::min(srgb_encode(linear), 1.0) * 255.0));
}

std::vector<std::array<double, 3>> srgb_basis_spectra(const std::vector<double>& wavelengths) {
  require(wavelengths.size() >= 3, "an RGB colour needs at least 3 wavelengths to become a spectrum, got " +
                                       std::to_string(wavelengths.size()));
  const auto weights = band_weights(wavelengths);
  // The Gaussians' colours P (XYZ × Gaussian), then the mix K = P⁻¹·M that gives each
  // primary's XYZ (M's columns): S_c = Σ_k G_k·K[k][c].
  constexpr double kCentre[3] = {440, 525, 640}, kSigma[3] = {30, 15, 20};
  std::vector<std::array<double, 3>> gauss(wavelengths.size());
  Matrix p{};
  for (size_t l = 0; l < wavelengths.size(); ++l)
    for (int k = 0; k < 3; ++k) {
      const double z = (wavelengths[l] - kCentre[k]) / kSigma[k];
      gauss[l][k] = std::exp(-0.5 * z * z);
      for (int j = 0; j < 3; ++j) p[j][k] += weights[l][j] * gauss[l][k];
    }
  const Matrix pinv = inverse(p);
  Matrix mix{};
  double largest = 0;
  for (int k = 0; k < 3; ++k)
    for (int c = 0; c < 3; ++c) {
      for (int j = 0; j < 3; ++j) mix[k][c] += pinv[k][j] * rgb_to_xyz()[j][c];
      largest = std::max(largest, std::fabs(mix[k][c]));
    }
  // Over 380–700 nm the mix stays below 2; a huge or non-finite one means the grid
  // misses a Gaussian and its spectra would be enormous, cancelling lobes.
  require(std::isfinite(largest) && largest < 100,
          "the wavelengths " + number(wavelengths.front()) + "–" + number(wavelengths.back()) + " nm (" +
              std::to_string(wavelengths.size()) +
              " samples) cannot turn RGB into spectra: they must sample blue, green and red (around 440, 525 "
              "and 640 nm)");
  std::vector<std::array<double, 3>> out(wavelengths.size());
  for (size_t l = 0; l < wavelengths.size(); ++l)
    for (int c = 0; c < 3; ++c)
      for (int k = 0; k < 3; ++k) out[l][c] += gauss[l][k] * mix[k][c];
  return out;
}

}  // namespace arcus::spectral
