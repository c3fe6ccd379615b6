// Fitting the dipole to an estimate (thesis §3.3.1, "Fitting"), per channel, by
// Levenberg–Marquardt on (ln σ_a, ln σ_s′) from the best of a grid over (α′, ℓ_d):
//   to the profile: the dipole's bin averages (∫R_d 2πr dr / ∫2πr dr over each bin)
//     against the solve's bin weights, residuals weighted by the bin's middle radius (an
//     image weighs a bin by its ring's area), as the thesis fits;
//   to the image: the pixels the dipole predicts through the cached distance histograms
//     (Σ_f H_if R̄_d,f, R̄ the bin's area average, plus the near field's disc) against
//     the photo's, the fit that the
//     piecewise-constant profile only approximates where a bin is wider than the
//     profile's peak (src/translucency/estimate.cpp says which is used).
#pragma once

#include <functional>
#include <vector>

#include "translucency/dipole.h"

namespace arcus::translucency {

struct DipoleFit {
  Channel channel;     // σ_a, σ_s′ and the η fitted with (given)
  double error = 0;    // RMS residual over RMS of the data (both as weighted)
  int iterations = 0;  // LM steps taken
};

// The area average of R_d over [r0, r1) (composite Simpson in r, 32 intervals).
double bin_average(const Terms& t, double r0, double r1);

// Residuals of a candidate channel; `scale` is what makes them relative (the data's norm).
using Residuals = std::function<std::vector<double>(const Channel&)>;

// The grid start and LM; `reach` (mm) spans the grid's diffusion lengths (reach/1000 to
// reach).
DipoleFit fit_dipole(const Residuals& residuals, double data_norm, double eta, double reach);

// edges: m + 1 increasing distances from 0 (mm); weights: the m bin values (per mm²).
DipoleFit fit_to_profile(const std::vector<double>& edges, const std::vector<double>& weights, double eta);

// rows × bins histograms (H_if, one channel, row-major) over `edges` (bins + 1, mm), of
// which bins from `first_bin` count, each R_d taken as its area average there; each row's own irradiance E_i over a flat disc
// of `radius` for the bins left out (∫₀^radius 2πr R_d dr · E_i), and the rows' pixels
// b_i (radiance over the exit term).
DipoleFit fit_to_image(const std::vector<double>& edges, const std::vector<double>& histograms, size_t first_bin,
                       const std::vector<double>& near_irradiance, double radius, const std::vector<double>& pixels,
                       double eta);

}  // namespace arcus::translucency
