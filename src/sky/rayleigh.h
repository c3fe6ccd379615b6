// Rayleigh scattering by dry air, as Bodhaine, Wood, Dutton & Slusser (1999, "On
// Rayleigh optical depth calculations", J. Atmos. Oceanic Technol. 16, 1854) compute
// it: a molecule's cross-section from the refractive index of standard air and the
// King factor of Bates (1984), and the optical depth of the column above a site from
// the column's mass.  The first piece of the sky every engine shares (src/sky/).
// Host code in double precision.  Units: nm, m², Pa, m, degrees; CO2 in ppm by volume.
#pragma once

namespace arcus::sky {

// F_K of dry air: N2's and O2's terms of Bates (1984), argon 1, CO2 1.15, weighted by
// the gases' volume fractions (78.084%, 20.946%, 0.934%, CO2).
double king_factor(double wavelength_nm, double co2_ppm);

// The depolarisation ratio ρ_n that the King factor stands for, F_K = (6 + 3ρ_n)/(6 − 7ρ_n).
double depolarisation_ratio(double wavelength_nm, double co2_ppm);

// Rayleigh's phase function of air per steradian, normalised over the sphere, with its
// molecules' anisotropy (Chandrasekhar 1950; Bucholtz 1995, eq. 12):
// 3/(16π(1 + 2γ))·((1 + 3γ) + (1 − γ)cos²θ), γ = ρ_n/(2 − ρ_n).
double rayleigh_phase(double cos_theta, double wavelength_nm, double co2_ppm);

// σ per molecule (m²): 24π³(n_s² − 1)²/(λ⁴ N_s² (n_s² + 2)²) · F_K, with n_s the index
// of standard air (15 °C, 101 325 Pa; Ciddor 1996, kernels/sky/air.h, with Ciddor's
// CO2 term) and N_s its number density (ideal gas).
double rayleigh_cross_section(double wavelength_nm, double co2_ppm);

// The mean molar mass of dry air (kg/mol): 28.9595 g/mol plus 15.0556 g/mol times
// CO2's volume fraction.
double dry_air_molar_mass(double co2_ppm);

// Normal gravity (m/s²) at a latitude and a height above sea level (the Smithsonian
// Meteorological Tables' expansion, as Bodhaine et al. use it).
double gravity(double latitude_deg, double height_m);

// τ_R of the whole column of air above a site: σ · p · N_A / (m_a · g), the molecules
// over a unit area, with g taken at the height of the column's centre of mass,
// 0.73737 z + 5517.56 m (Bodhaine et al.'s fit to the US Standard Atmosphere 1976).
double rayleigh_optical_depth(double wavelength_nm, double surface_pressure_pa, double latitude_deg,
                              double site_height_m, double co2_ppm);

}  // namespace arcus::sky
