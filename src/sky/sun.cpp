#include "sky/sun.h"

#include <algorithm>
#include <cmath>

namespace arcus::sky {
namespace {
#include "sky/sky_data.inc"

// Neckel (2005), Table 2: per range a00, a01 (A0 = a00 + a01/λ) and ak0, ak5 for k = 2..5
// (Ak = ak0 + ak5/λ⁵), λ in µm; A1 makes the sum 1 at μ = 1.  The third range's a55 is
// −0.003347 (a copy with +0.003347 circulates; it is 29 % off Neckel & Labs 1994 at 444 nm,
// tests/unit/test_sky_sun.cpp).
struct NeckelRange {
  double from_nm, to_nm, a00, a01, a0[4], a5[4];
};
constexpr NeckelRange kNeckel[3] = {
    {300.0, 372.98, 0.35601, -0.085217, {-0.67237, 0.18696, 0.00038, 0.01373}, {0.003589, -0.002415, 0.000897, -0.000200}},
    {385.0, 422.57, 0.09900, 0.010643, {-2.80511, 3.32780, -2.17878, 0.58825}, {0.024873, -0.029317, 0.018273, -0.004663}},
    {422.57, 1100.0, 0.75267, -0.265577, {-1.89287, 2.42234, -1.71150, 0.49062}, {0.012582, -0.017117, 0.011977, -0.003347}},
};

// Σ Ak μ^k for one range's fit.
double neckel(const NeckelRange& r, double wavelength_nm, double mu) {
  const double l1 = 1000.0 / wavelength_nm, l5 = std::pow(l1, 5);
  double a[6];
  a[0] = r.a00 + r.a01 * l1;
  double rest = a[0];
  for (int k = 2; k <= 5; ++k) rest += a[k] = r.a0[k - 2] + r.a5[k - 2] * l5;
  a[1] = 1 - rest;
  double sum = 0;
  for (int k = 5; k >= 0; --k) sum = sum * mu + a[k];
  return sum;
}

// Index of the table interval [kSolarNm[i], kSolarNm[i + 1]] holding λ.
int solar_interval(double wavelength_nm) {
  const double* end = embedded::kSolarNm + embedded::kSolarRows;
  const int i = int(std::upper_bound(embedded::kSolarNm, end, wavelength_nm) - embedded::kSolarNm) - 1;
  return std::clamp(i, 0, embedded::kSolarRows - 2);
}

// ∫ of the interpolant from the table's start to λ.
double solar_cumulative(double wavelength_nm) {
  const int j = solar_interval(wavelength_nm);
  double sum = 0;
  for (int i = 0; i < j; ++i)
    sum += 0.5 * (embedded::kSolarIrradiance[i] + embedded::kSolarIrradiance[i + 1]) *
           (embedded::kSolarNm[i + 1] - embedded::kSolarNm[i]);
  const double x0 = embedded::kSolarNm[j], e0 = embedded::kSolarIrradiance[j];
  return sum + 0.5 * (e0 + solar_irradiance(wavelength_nm)) * (wavelength_nm - x0);
}

}  // namespace

double solar_irradiance(double wavelength_nm) {
  const int i = solar_interval(wavelength_nm);
  const double x0 = embedded::kSolarNm[i], x1 = embedded::kSolarNm[i + 1];
  const double t = (wavelength_nm - x0) / (x1 - x0);
  return (1 - t) * embedded::kSolarIrradiance[i] + t * embedded::kSolarIrradiance[i + 1];
}

double solar_irradiance_band(double from_nm, double to_nm) {
  if (to_nm <= from_nm) return solar_irradiance(from_nm);
  return (solar_cumulative(to_nm) - solar_cumulative(from_nm)) / (to_nm - from_nm);
}

double limb_darkening(double wavelength_nm, double mu) {
  mu = std::clamp(mu, 0.0, 1.0);
  for (const NeckelRange& r : kNeckel)
    if (wavelength_nm >= r.from_nm && wavelength_nm <= r.to_nm) return neckel(r, wavelength_nm, mu);
  // The gap between the first two fits: linear in λ between their ends.
  const NeckelRange &below = kNeckel[0], &above = kNeckel[1];
  const double t = std::clamp((wavelength_nm - below.to_nm) / (above.from_nm - below.to_nm), 0.0, 1.0);
  return (1 - t) * neckel(below, below.to_nm, mu) + t * neckel(above, above.from_nm, mu);
}

double limb_darkening_mean(double wavelength_nm) {
  // 2∫ I μ dμ with I a polynomial of degree 5: Gauss–Legendre with 4 nodes is exact.
  constexpr double x[4] = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563, 0.8611363115940526};
  constexpr double w[4] = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461, 0.3478548451374538};
  double sum = 0;
  for (int k = 0; k < 4; ++k) {
    const double mu = 0.5 * (x[k] + 1);
    sum += w[k] * 0.5 * limb_darkening(wavelength_nm, mu) * mu;
  }
  return 2 * sum;
}

}  // namespace arcus::sky
