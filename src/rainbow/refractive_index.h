// Refractive indices for the rainbow engine (thesis §4.4.1) and the geometric rainbow
// angle of a sphere.  Every formula's and constant's source and range:
// data/rainbow/README.md.
//
// Water: IAPWS R9-97 (Harvey, Gallagher & Levelt Sengers 1998) gives n(ρ, T, λ); liquid
// water at 101.325 kPa gets its density from IAPWS SR6-08(2011), the IAPWS-95-consistent
// correlation for liquid water at 0.1 MPa.  Ice Ih: the real part of Warren & Brandt
// (2008) at −7 °C, tabulated.  Both are absolute indices (relative to vacuum) at vacuum
// wavelengths, as their sources define them.
//
// Out-of-range or non-finite arguments throw arcus::Error (INVALID_ARGUMENT) naming the
// parameter, its value and the valid range.
#pragma once

#include <vector>

namespace arcus::rainbow {

// Ranges the functions accept (inclusive).
constexpr double kWaterMinNm = 200, kWaterMaxNm = 1100;  // R9-97: 0.2–1.1 µm
constexpr double kWaterMinC = -12, kWaterMaxC = 100;     // R9-97 down to −12 °C (supercooled)
constexpr double kIceMinNm = 199, kIceMaxNm = 1100;      // the embedded Warren & Brandt rows

// n of liquid water at 101.325 kPa, vacuum wavelength λ (nm), temperature T (°C).
double water_index(double wavelength_nm, double temperature_c = 20.0);

// Density of liquid water (kg/m³) at 101.325 kPa, −12…100 °C (IAPWS SR6-08).
double water_density(double temperature_c);

// The R9-97 formula itself at any state inside the release's range: λ 200–1100 nm,
// T 261.15–773.15 K, ρ 0–1060 kg/m³ (for the release's check values and callers with
// their own equation of state).
double water_index_iapws(double wavelength_nm, double temperature_k, double density_kg_m3);

// Real part of the index of ice Ih at −7 °C, 199–1100 nm (Warren & Brandt 2008).
double ice_index(double wavelength_nm);

// One row of the embedded ice table, as printed in data/rainbow/ice_index.csv.
struct IceRow {
  double wavelength_um, n_real;
};
const std::vector<IceRow>& ice_table();

// Scattering angle (degrees, in [0, 180]) of the geometric rainbow of order p, p − 1
// internal reflections in a sphere of relative index n (p = 2 primary, 3 secondary);
// requires p >= 2 and 1 < n < p.  137.86° for n = 1.33257, p = 2 (thesis §4.4.1.1).
double rainbow_angle_deg(double n, int p);

}  // namespace arcus::rainbow
