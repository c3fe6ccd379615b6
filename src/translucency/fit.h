// Fitting the dipole to an estimate (thesis §3.3.1, "Fitting"), per channel.  Both fits
// minimise a quadratic form in a model vector a(σ_a, σ_s′),
//   cost = |L a − y|² = aᵀQa − 2aᵀg + c   (Q = LᵀL, g = Lᵀy, c = yᵀy, formed once),
// by Levenberg–Marquardt on (ln σ_a, ln σ_s′), started from the best few points of a
// grid over (α′, ℓ_d):
//   to the profile: a = the dipole's bin averages (∫R_d 2πr dr / ∫2πr dr over each bin)
//     times the bin's middle radius, y the solve's weights times the same (an image
//     weighs a bin by its ring's area), as the thesis fits;
//   to the image: a = the fine bins' area averages of R_d and the near field's disc
//     integral, L the pixels' cached histograms (and own irradiance), y the pixels: the
//     dipole's prediction of the photo against the photo.  src/translucency/estimate.cpp
//     says why this is the default.
#pragma once

#include <functional>
#include <vector>

#include "translucency/dipole.h"

namespace arcus::translucency {

struct DipoleFit {
  Channel channel;     // σ_a, σ_s′ and the η fitted with (given)
  double error = 0;    // sqrt(cost / c): the RMS residual over the data's RMS
  int iterations = 0;  // LM steps of the best start
};

// The area average of R_d over [r0, r1) (composite Simpson in r, 32 intervals).
double bin_average(const Terms& t, double r0, double r1);

// The quadratic form of a least-squares problem in k unknowns.
struct QuadraticForm {
  size_t k = 0;
  std::vector<double> q;  // k × k, row-major
  std::vector<double> g;  // k
  double c = 0;
  // From rows × k values L (row-major) and the rows' data y.
  static QuadraticForm of(const std::vector<double>& l, size_t rows, size_t k, const std::vector<double>& y);
  double cost(const std::vector<double>& a) const;
};

using Model = std::function<std::vector<double>(const Channel&)>;

// `reach` (mm) spans the grid's diffusion lengths (reach/1000 to reach).
DipoleFit fit_dipole(const Model& model, const QuadraticForm& form, double eta, double reach);

// edges: m + 1 increasing distances from 0 (mm); weights: the m bin values (per mm²).
DipoleFit fit_to_profile(const std::vector<double>& edges, const std::vector<double>& weights, double eta);

// rows × bins histograms (H_if, one channel, row-major) over `edges` (bins + 1, mm), of
// which bins from `first_bin` count; each row's own irradiance E_i over a flat disc of
// `radius` for the bins left out (∫₀^radius 2πr R_d dr · E_i); the rows' pixels b_i
// (radiance over the exit term).
DipoleFit fit_to_image(const std::vector<double>& edges, const std::vector<double>& histograms, size_t first_bin,
                       const std::vector<double>& near_irradiance, double radius, const std::vector<double>& pixels,
                       double eta);

}  // namespace arcus::translucency
