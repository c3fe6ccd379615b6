// §3.4's plausible profile (thesis §3.4, "we relax our fitting to a function defined by
// a set of piecewise cubic Hermite polynomials ... differentiable and monotonically
// decreasing"; after SubEdit, Song et al. 2009): from the estimate's bin averages,
//   1. the closest non-increasing sequence, weighting each bin by its ring's area
//      (pool-adjacent-violators: each pooled block keeps its energy Σ area·R), then
//      clamped at 0;
//   2. Fritsch & Carlson's monotone cubic Hermite interpolation (SIAM J. Numer. Anal.
//      17, 1980) through the bins' middle radii, with a knot at r = 0 continuing the
//      first segment's line (capped so it never rises) and one at r_max at 0;
//   3. scaled so that ∫2πr R dr equals the monotone bins' Σ area·R (interpolation
//      moves energy between rings; the estimate's total is what the photo fixed).
#pragma once

#include <cstdint>
#include <vector>

namespace arcus::translucency {

// The profile sampled at r_k = edges.back() · (k / (count − 1))² (arcus_profile_table),
// for one channel's m bin averages over the m + 1 `edges` (mm).
std::vector<double> monotone_hermite_profile(const std::vector<double>& edges, const std::vector<double>& averages,
                                             uint32_t count);

}  // namespace arcus::translucency
