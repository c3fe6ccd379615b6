#include "spectral/srgb.h"

#include <algorithm>
#include <cmath>

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

}  // namespace arcus::spectral
