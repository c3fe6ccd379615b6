// sRGB (IEC 61966-2-1): CIE XYZ to and from linear sRGB, the transfer function, 8-bit
// encoding.  Linear sRGB here is scaled so that reference white (Y = 1) is (1, 1, 1).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

namespace arcus::spectral {

// D65 white as the CIE 1931 2° observer integrates it (ASTM E308, 5 nm): the white
// point the matrices are built on, so a D65 spectrum rendered with cie.h maps to
// (1, 1, 1).  IEC 61966-2-1 rounds it to x, y = 0.3127, 0.3290 and prints its matrix
// to 4 digits; the two agree to 5e-4.
constexpr std::array<double, 3> kD65White{0.95047, 1.0, 1.08883};

std::array<double, 3> xyz_to_linear_srgb(const std::array<double, 3>& xyz);
std::array<double, 3> linear_srgb_to_xyz(const std::array<double, 3>& rgb);

// The transfer function: linear -> encoded (0.0031308 and 12.92 below, the 2.4 power
// above) and its inverse.  Both are odd-symmetric, so negatives round-trip too.
double srgb_encode(double linear);
double srgb_decode(double encoded);

// Linear -> 8-bit sRGB: encoded, clamped to [0, 1], rounded to nearest; NaN gives 0.
uint8_t srgb_encode_8bit(double linear);

// Three spectra S_r, S_g, S_b at `wavelengths` (strictly increasing, nm) that turn a
// linear sRGB colour into a spectrum, r·S_r + g·S_g + b·S_b, whose colour under cie.h's
// band weights for those same wavelengths is that colour exactly: so an RGB image can
// enter a spectral render and come out unchanged where nothing filters it.  Each is a
// combination of three Gaussians (440, 525, 640 nm; σ 30, 15, 20 nm), chosen so that
// the combinations are non-negative for grids over 380–700 nm from 8 to 200 samples:
// a colour inside the sRGB gamut becomes a non-negative spectrum.  [wavelength][r, g, b].
// INVALID_ARGUMENT when the wavelengths cannot hold three colours (fewer than 3, or
// none near one of the Gaussians).
std::vector<std::array<double, 3>> srgb_basis_spectra(const std::vector<double>& wavelengths);

}  // namespace arcus::spectral
