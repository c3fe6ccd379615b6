// Refractive indices of water and ice and the geometric rainbow angle (thesis §4.4.1.1).
// Sources and ranges of every number: data/rainbow/README.md.
#include "rainbow/refractive_index.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.h"
#include "core/format.h"

namespace arcus::rainbow {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = 180 / kPi;

// IAPWS R9-97, eq. (7) and Table 1: the Lorentz–Lorenz function
// (n² − 1)/(n² + 2)/ρ̄ = a0 + a1 ρ̄ + a2 T̄ + a3 λ̄² T̄ + a4/λ̄² + a5/(λ̄² − λ̄UV²)
//                      + a6/(λ̄² − λ̄IR²) + a7 ρ̄²,
// with ρ̄ = ρ/1000 kg m⁻³, T̄ = T/273.15 K, λ̄ = λ/0.589 µm.
constexpr double kA0 = 0.244257733, kA1 = 9.74634476e-3, kA2 = -3.73234996e-3, kA3 = 2.68678472e-4,
                 kA4 = 1.58920570e-3, kA5 = 2.45934259e-3, kA6 = 0.900704920, kA7 = -1.66626219e-2;
constexpr double kLambdaUV = 0.2292020, kLambdaIR = 5.432937;
constexpr double kRhoRef = 1000, kTRef = 273.15, kLambdaRefUm = 0.589;
// The release's range (its section "Range of validity").
constexpr double kIapwsMinK = 261.15, kIapwsMaxK = 773.15, kIapwsMaxRho = 1060;

// IAPWS SR6-08(2011), "Revised Supplementary Release on Properties of Liquid Water at
// 0.1 MPa" (Pátek et al. 2009): v0(T) (eq. 2) and (∂v/∂p)T (eq. 3) at p0 = 0.1 MPa,
// with α = Tr/(593 K − T), β = Tr/(T − 232 K), Tr = 10 K, valid 253.15–383.15 K.
constexpr double kR = 461.51805;  // J kg⁻¹ K⁻¹, the release's specific gas constant
constexpr double kTr = 10, kP0 = 1e5, kTa = 593, kTb = 232;
constexpr double kV0 = 1.93763157e-2;  // a5 of the release
constexpr double kVA[] = {6.74458446e3, -2.22521604e5, 1.00231247e8, -1.63552118e9, 8.32299658e9};  // a6..a10
constexpr int kVN[] = {4, 5, 7, 8, 9};
constexpr double kVB[] = {5.78545292e-3,  -1.53195665e-2, 3.11337859e-2,
                          -4.23546241e-2, 3.38713507e-2,  -1.19946761e-2};  // b5..b10
constexpr int kVM[] = {1, 2, 3, 4, 5, 6};
constexpr double kPA[] = {-7.5245878e-6, -1.3767418e-2, 1.0627293e1, -2.0457795e2, 1.2037414e3};  // a11..a15
constexpr int kPN[] = {1, 3, 5, 6, 7};
constexpr double kPB[] = {-3.1091470e-6, 2.8964919e-5,  -1.3112763e-4, 3.0410453e-4,
                          -3.9034594e-4, 2.3403117e-4, -4.8510101e-5};  // b11..b17
constexpr int kPM[] = {1, 3, 4, 5, 6, 7, 9};
constexpr double kAtmPa = 101325;  // "normal pressure": v = v0 + (∂v/∂p)(p − p0), release eq. (4)

// Warren & Brandt 2008, J. Geophys. Res. 113, D14220 (file IOP_2008_ASCIItable.dat of
// https://atmos.uw.edu/ice_optical_constants/, ice Ih at 266 K): the real part from 199 nm
// to 1.1 µm, wavelengths in µm as printed.  Copy of data/rainbow/ice_index.csv (tested).
const std::vector<IceRow> kIce = {
    {0.199, 1.3943}, {0.201, 1.3914}, {0.202, 1.3901}, {0.210, 1.3801}, {0.250, 1.3509}, {0.300, 1.3339},
    {0.350, 1.3249}, {0.390, 1.3203}, {0.400, 1.3194}, {0.410, 1.3185}, {0.420, 1.3177}, {0.430, 1.3170},
    {0.440, 1.3163}, {0.450, 1.3157}, {0.460, 1.3151}, {0.470, 1.3145}, {0.480, 1.3140}, {0.490, 1.3135},
    {0.500, 1.3130}, {0.510, 1.3126}, {0.520, 1.3121}, {0.530, 1.3117}, {0.540, 1.3114}, {0.550, 1.3110},
    {0.560, 1.3106}, {0.570, 1.3103}, {0.580, 1.3100}, {0.590, 1.3097}, {0.600, 1.3094}, {0.610, 1.3091},
    {0.620, 1.3088}, {0.630, 1.3085}, {0.640, 1.3083}, {0.650, 1.3080}, {0.660, 1.3078}, {0.670, 1.3076},
    {0.680, 1.3073}, {0.690, 1.3071}, {0.700, 1.3069}, {0.710, 1.3067}, {0.720, 1.3065}, {0.730, 1.3062},
    {0.740, 1.3060}, {0.750, 1.3059}, {0.760, 1.3057}, {0.770, 1.3055}, {0.780, 1.3053}, {0.790, 1.3051},
    {0.800, 1.3049}, {0.810, 1.3047}, {0.820, 1.3046}, {0.830, 1.3044}, {0.840, 1.3042}, {0.850, 1.3040},
    {0.860, 1.3039}, {0.870, 1.3037}, {0.880, 1.3035}, {0.890, 1.3033}, {0.900, 1.3032}, {0.910, 1.3030},
    {0.920, 1.3028}, {0.930, 1.3027}, {0.940, 1.3025}, {0.950, 1.3023}, {0.960, 1.3022}, {0.970, 1.3020},
    {0.980, 1.3019}, {0.990, 1.3017}, {1.000, 1.3015}, {1.010, 1.3014}, {1.020, 1.3012}, {1.030, 1.3010},
    {1.040, 1.3009}, {1.050, 1.3007}, {1.060, 1.3005}, {1.070, 1.3003}, {1.080, 1.3002}, {1.090, 1.3000},
    {1.100, 1.2998}};

// Throws naming the function, the parameter, the range and the value; NaN fails too.
void require_in(const char* fn, const char* name, double v, double lo, double hi, const char* unit,
                const char* source) {
  require(v >= lo && v <= hi, std::string(fn) + ": " + name + " must lie in [" + number(lo) + ", " + number(hi) +
                                  "] " + unit + " (" + source + "), got " + number(v));
}

double series(const double* c, const int* k, int count, double x) {
  double s = 0;
  for (int i = 0; i < count; ++i) s += c[i] * std::pow(x, k[i]);
  return s;
}

// R9-97 without range checks.
double iapws(double lambda_um, double t_k, double rho) {
  const double d = rho / kRhoRef, t = t_k / kTRef, l = lambda_um / kLambdaRefUm, l2 = l * l;
  const double a = d * (kA0 + kA1 * d + kA2 * t + kA3 * l2 * t + kA4 / l2 + kA5 / (l2 - kLambdaUV * kLambdaUV) +
                        kA6 / (l2 - kLambdaIR * kLambdaIR) + kA7 * d * d);
  return std::sqrt((2 * a + 1) / (1 - a));  // a = (n² − 1)/(n² + 2)
}

}  // namespace

double water_density(double temperature_c) {
  require_in("water_density", "temperature_c", temperature_c, kWaterMinC, kWaterMaxC, "°C",
             "IAPWS SR6-08 liquid at 101.325 kPa, within R9-97's range");
  const double t = temperature_c + 273.15;
  const double alpha = kTr / (kTa - t), beta = kTr / (t - kTb);
  const double v0 = kR * kTr / kP0 * (kV0 + series(kVA, kVN, 5, alpha) + series(kVB, kVM, 6, beta));
  const double vp = kR * kTr / (kP0 * kP0) * (series(kPA, kPN, 5, alpha) + series(kPB, kPM, 7, beta));
  return 1 / (v0 + vp * (kAtmPa - kP0));
}

double water_index_iapws(double wavelength_nm, double temperature_k, double density_kg_m3) {
  require_in("water_index_iapws", "wavelength_nm", wavelength_nm, kWaterMinNm, kWaterMaxNm, "nm", "IAPWS R9-97");
  require_in("water_index_iapws", "temperature_k", temperature_k, kIapwsMinK, kIapwsMaxK, "K", "IAPWS R9-97");
  require_in("water_index_iapws", "density_kg_m3", density_kg_m3, 0, kIapwsMaxRho, "kg/m³", "IAPWS R9-97");
  return iapws(wavelength_nm / 1000, temperature_k, density_kg_m3);
}

double water_index(double wavelength_nm, double temperature_c) {
  require_in("water_index", "wavelength_nm", wavelength_nm, kWaterMinNm, kWaterMaxNm, "nm", "IAPWS R9-97");
  require_in("water_index", "temperature_c", temperature_c, kWaterMinC, kWaterMaxC, "°C",
             "IAPWS R9-97 liquid at 101.325 kPa");
  return iapws(wavelength_nm / 1000, temperature_c + 273.15, water_density(temperature_c));
}

const std::vector<IceRow>& ice_table() { return kIce; }

double ice_index(double wavelength_nm) {
  require_in("ice_index", "wavelength_nm", wavelength_nm, kIceMinNm, kIceMaxNm, "nm", "Warren & Brandt 2008 table");
  const double um = wavelength_nm / 1000;
  // The first row at or beyond λ; exact at the nodes.
  const auto hi = std::lower_bound(kIce.begin(), kIce.end(), um,
                                   [](const IceRow& r, double x) { return r.wavelength_um < x; });
  if (hi == kIce.end()) return kIce.back().n_real;  // not reached: the range check holds λ to the table
  if (hi->wavelength_um == um || hi == kIce.begin()) return hi->n_real;
  const auto lo = hi - 1;
  // Linear in 1/λ² (Cauchy's form n ≈ A + B/λ²): the UV rows are 40–50 nm apart, where
  // linear-in-λ interpolation would be off by ~1e-3; in the visible the two agree to 1e-5.
  const auto inv2 = [](double x) { return 1 / (x * x); };
  const double f = (inv2(um) - inv2(lo->wavelength_um)) / (inv2(hi->wavelength_um) - inv2(lo->wavelength_um));
  return lo->n_real + f * (hi->n_real - lo->n_real);
}

double rainbow_angle_deg(double n, int p) {
  require(p >= 2, "rainbow_angle_deg: p must be >= 2 (p − 1 internal reflections), got " + std::to_string(p));
  require(n > 1 && n < p, "rainbow_angle_deg: n must lie in (1, " + std::to_string(p) + ") for p = " +
                              std::to_string(p) + ", got " + number(n));
  // Minimum deviation (Descartes): cos² i = (n² − 1)/(p² − 1), sin r = sin i / n, and the
  // deviation D = 2(i − p r) + (p − 1)·180° (thesis eq. 4.19 for p = 2).
  const double p2 = double(p) * p;
  const double i = std::acos(std::sqrt((n * n - 1) / (p2 - 1)));
  const double r = std::asin(std::sin(i) / n);
  double d = std::fmod(2 * (i - p * r) * kDeg + (p - 1) * 180.0, 360.0);
  if (d < 0) d += 360;
  return d > 180 ? 360 - d : d;  // a direction: the deviation folded into [0°, 180°]
}

}  // namespace arcus::rainbow
