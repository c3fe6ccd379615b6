#include "sky/rayleigh.h"

#include <cmath>

#include "common/real.h"
#include "sky/air.h"  // kernels/sky/air.h
#include "sky/us1976.h"

namespace arcus::sky {
namespace {

constexpr double kAvogadro = 6.02214076e23;  // 1/mol (SI 2019, exact)
constexpr double kStandardTemperature = 288.15, kStandardPressure = 101325.0;  // Ciddor's standard air

}  // namespace

double king_factor(double wavelength_nm, double co2_ppm) {
  const double inverse2 = 1e6 / (wavelength_nm * wavelength_nm);  // 1/µm²
  const double n2 = 1.034 + 3.17e-4 * inverse2;
  const double o2 = 1.096 + 1.385e-3 * inverse2 + 1.448e-4 * inverse2 * inverse2;
  const double co2 = co2_ppm * 1e-4;  // percent by volume
  return (78.084 * n2 + 20.946 * o2 + 0.934 * 1.0 + co2 * 1.15) / (78.084 + 20.946 + 0.934 + co2);
}

double depolarisation_ratio(double wavelength_nm, double co2_ppm) {
  const double f = king_factor(wavelength_nm, co2_ppm);
  return 6 * (f - 1) / (3 + 7 * f);
}

double rayleigh_phase(double cos_theta, double wavelength_nm, double co2_ppm) {
  const double rho = depolarisation_ratio(wavelength_nm, co2_ppm), gamma = rho / (2 - rho);
  return 3 / (16 * M_PI * (1 + 2 * gamma)) * ((1 + 3 * gamma) + (1 - gamma) * cos_theta * cos_theta);
}

double rayleigh_cross_section(double wavelength_nm, double co2_ppm) {
  // Ciddor's n − 1 is for 450 ppm of CO2; his eq. 2 carries it to another content.
  const double n_minus_1 = ciddor_refractivity(wavelength_nm) * kStandardPressure / kStandardTemperature *
                           (1 + 0.534e-6 * (co2_ppm - 450));
  const double n2 = (1 + n_minus_1) * (1 + n_minus_1);
  const double density = number_density(kStandardPressure, kStandardTemperature);  // 1/m³
  const double lambda = wavelength_nm * 1e-9;
  const double ratio = (n2 - 1) / (n2 + 2);
  return 24 * M_PI * M_PI * M_PI * ratio * ratio / (lambda * lambda * lambda * lambda * density * density) *
         king_factor(wavelength_nm, co2_ppm);
}

double dry_air_molar_mass(double co2_ppm) { return (28.9595 + 15.0556 * co2_ppm * 1e-6) * 1e-3; }

double gravity(double latitude_deg, double height_m) {
  const double c = std::cos(2 * latitude_deg * M_PI / 180);
  const double z = height_m;
  const double g0 = 980.6160 * (1 - 0.0026373 * c + 0.0000059 * c * c);  // cm/s² at sea level
  const double g = g0 - (3.085462e-4 + 2.27e-7 * c) * z + (7.254e-11 + 1.0e-13 * c) * z * z -
                   (1.517e-17 + 6e-20 * c) * z * z * z;
  return g * 1e-2;
}

double rayleigh_optical_depth(double wavelength_nm, double surface_pressure_pa, double latitude_deg,
                              double site_height_m, double co2_ppm) {
  const double centre_of_mass = 0.73737 * site_height_m + 5517.56;
  const double molecules = surface_pressure_pa * kAvogadro /
                           (dry_air_molar_mass(co2_ppm) * gravity(latitude_deg, centre_of_mass));  // per m²
  return rayleigh_cross_section(wavelength_nm, co2_ppm) * molecules;
}

}  // namespace arcus::sky
