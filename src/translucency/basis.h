// The basis functions B_h of the profile (thesis eq. 3.14) and Table 3.2's five
// families, over x = r / r_max in [0, 1):
//   piecewise constant  m equal bins (the thesis' choice and the default);
//   Haar                the box, then Haar wavelets level by level (2^j of width 2^-j);
//   zero-mean Gaussian  exp(−x²/2s_h²), s_h geometric from 1/m to 1 (after d'Eon et al. 2007);
//   Hermite             the physicists' polynomials H_h(2x − 1);
//   Legendre            P_h(2x − 1).
// The estimate sums each pair's source into a fine distance bin (histogram.cl), so a
// column of A is the fine bins weighted by B_h at their middles: the matrix W here.
// Each column of W is scaled to a largest |value| of 1, so that condition numbers
// compare shapes, not scales.
#pragma once

#include <cstdint>
#include <vector>

namespace arcus::translucency {

const char* basis_name(int32_t family);

// How many fine bins the histograms need: 8 per function for piecewise-constant bins
// (each fine bin inside one), else the most the kernel keeps (256: a multiple of every
// Haar width; midpoint sums fine enough for the smooth families).
uint32_t fine_bins_for(int32_t family, uint32_t m);

// W: bins × m, row-major: B_h at the fine bins' middles.
std::vector<double> basis_matrix(int32_t family, uint32_t m, uint32_t bins);

}  // namespace arcus::translucency
