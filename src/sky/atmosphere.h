// The clear atmosphere every engine's sun and sky shine through: the US Standard
// Atmosphere 1976's air (Rayleigh scattering with the King factor, src/sky/rayleigh.h),
// an ozone layer (Serdyuchenko et al. 2014's cross-section, data/sky/README.md) and an
// aerosol layer (an optical depth at 500 nm, Ångström's exponent, an exponential
// profile), along the refracted path of src/sky/paths.h.  Water vapour and the O2
// bands are left out (the visible has no strong band below 686 nm).  Host code; nm, m.
#pragma once

#include <string>

namespace arcus::sky {

struct Atmosphere {
  double site_height_m = 0;             // the observer's geometric height
  double ozone_du = 300;                // the ozone column above sea level, Dobson units
  double aerosol_depth_500 = 0.1;       // the aerosol's vertical optical depth above the site, 500 nm
  double angstrom_exponent = 1.3;       // τ_a(λ) = τ_a(500)·(λ/500)^−α (Ångström 1929)
  double aerosol_scale_height_m = 1200; // the aerosol's number density falls as exp(−(h − site)/H)
  double aerosol_albedo = 0.95;         // its single-scattering albedo (the rest it absorbs)
  double aerosol_asymmetry = 0.7;       // g of its Henyey–Greenstein phase function
  double co2_ppm = 415;                 // in the air's King factor and index
  double ground_albedo = 0;             // the Lambertian ground under the air, lighting the sky
                                        // back (scattering.h); 0: black, the sky of air alone
};

// Throws INVALID_ARGUMENT naming the first field out of its range (prefix + name): the
// site 0–80 km, ozone 0–1000 DU, τ(500) 0–10, α −1..4, H 100 m–20 km, CO2 0–10⁴ ppm,
// albedo 0–1, g −0.99..0.99.  Every reader of an atmosphere (the C API, scene files)
// checks with it.  The ground's albedo lies in 0..1.
void check_atmosphere(const Atmosphere& atmosphere, const std::string& prefix);

// Throws an invalid-argument error unless value is finite and within [lo, hi], naming it:
// "<name> must lie in [lo, hi], got value".
void require_within(double value, double lo, double hi, const std::string& name);

// Optical depths of the three absorbers and scatterers.
struct OpticalDepths {
  double rayleigh = 0, ozone = 0, aerosol = 0;
  double total() const { return rayleigh + ozone + aerosol; }
};

// The Dobson unit: molecules per m² of a 10 µm layer at 0 °C and 1 atm (Loschmidt's
// number 2.6867811·10²⁵ m⁻³ × 10⁻⁵ m).
constexpr double kDobsonUnit = 2.6867811e20;

// The ozone layer's shape: number density per DU of column as a tent from 10 to 40 km
// peaking at 25 km (Bruneton 2017's approximation of the mid-latitude profile), m⁻³.
double ozone_profile(double height_m);

// Ozone's absorption cross-section at 233 K (m²), linear between its 10 nm bins'
// centres; wavelength in [kDaylightMinNm, kDaylightMaxNm].
double ozone_cross_section(double wavelength_nm);

// The columns of air, ozone and aerosol along the ray that leaves the site at apparent
// zenith angle `zenith` (radians, 0..π/2), and their optical depths at any wavelength
// in the daylight range.  The path bends with the air's index, which depends on the
// wavelength; the columns are integrated for the range's two ends and interpolated
// linearly in the air's refractivity (second order in a dispersion that changes a
// horizontal path's air mass by 0.1 %), so one path serves every wavelength.
class SlantPath {
 public:
  SlantPath(const Atmosphere& atmosphere, double zenith);
  OpticalDepths depths(double wavelength_nm) const;

 private:
  Atmosphere atmosphere_;
  double refractivity_[2];  // (n − 1)·T/p at the range's two ends
  double columns_[2][3];    // air (m⁻²), ozone (m⁻² per DU), aerosol (m) at each end
};

// The depths from the site straight up to the top of the atmosphere.
OpticalDepths vertical_depths(const Atmosphere& atmosphere, double wavelength_nm);

}  // namespace arcus::sky
