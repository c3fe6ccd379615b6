// The CIE 1931 2° standard colorimetric observer (colour-matching functions x̄, ȳ, z̄ of
// CIE 15:2004 at 5 nm, 360–830 nm, embedded from data/spectra/, whose README gives the
// source and the checks) and the weights that turn a spectrum sampled at a few
// wavelengths into CIE XYZ.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

namespace arcus::spectral {

// The tabulated range; the functions are 0 outside it.
constexpr double kCmfFirstNm = 360.0;
constexpr double kCmfLastNm = 830.0;

// x̄, ȳ, z̄ at `nm`, linearly interpolated between the 5 nm rows; 0 outside the table.
double cmf_x(double nm);
double cmf_y(double nm);
double cmf_z(double nm);

// ∫ x̄, ȳ, z̄ dλ over [a, b] nm (a <= b), exact for the interpolated functions.
std::array<double, 3> cmf_integral(double a, double b);

// Per sample, the XYZ weight of the band it stands for: the colour-matching functions
// integrated over the wavelengths nearer to it than to any other sample (the first band
// reaches down to 360 nm, the last up to 830 nm), divided by ∫ȳ over 360–830 nm.  So
// XYZ = Σ radiance_i · weight_i, and a flat spectrum of 1 gives Y = 1 and the chromaticity
// of equal-energy white (1/3, 1/3 to 1e-4) whether there are 8 samples or 471: every bit
// of each function is counted once.  Wavelengths must be finite and strictly increasing
// (INVALID_ARGUMENT otherwise); samples outside 360–830 nm may get zero weight.
std::vector<std::array<double, 3>> band_weights(const std::vector<double>& wavelengths);

// XYZ of a spectrum given at n >= 1 strictly increasing wavelengths: Σ values_i · weight_i
// with band_weights' weights, so Y = 1 for a flat spectrum of 1 (relative colorimetry).
// Each sample is taken to hold across its band; with dense samples (5 nm) this converges
// like the trapezoid rule, and with few (8) it still keeps a flat spectrum white, which
// the trapezoid rule, reading the functions at 8 points only, does not.
void spectrum_to_xyz(const double* nm, const double* values, size_t n, double xyz[3]);

}  // namespace arcus::spectral
