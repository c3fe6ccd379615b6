// The sun above the atmosphere: its spectral irradiance (ASTM G173-03's extraterrestrial
// spectrum, data/sky/README.md) and its disc's limb darkening (Neckel 2005).  What the
// atmosphere (src/sky/atmosphere.h) then attenuates.  Host code; nm, W m⁻² nm⁻¹.
#pragma once

namespace arcus::sky {

// The daylight spectrum's range: where both measured spectra (the sun's and ozone's)
// are tabulated, and the eye's (CIE 1931 from 360 to 830 nm).
constexpr double kDaylightMinNm = 360.0, kDaylightMaxNm = 830.0;

// The sun's mean angular radius seen from 1 AU: 959.63″ (Auwers' 959.63″; the IAU's
// nominal R☉ = 695 700 km at 1 AU gives 959.2″).
constexpr double kSunAngularRadiusDeg = 959.63 / 3600.0;

// Spectral irradiance above the atmosphere at 1 AU (W m⁻² nm⁻¹), linear between the
// table's points; wavelength in [300, 1000] nm.
double solar_irradiance(double wavelength_nm);

// The irradiance averaged over [from_nm, to_nm] (the table integrated by trapezoids,
// exact for its piecewise-linear interpolant), for band-averaged spectra.
double solar_irradiance_band(double from_nm, double to_nm);

// I(μ)/I(1): the disc's radiance at μ = cos of the angle between the line of sight
// and the sun's surface normal (1 at the centre, 0 at the limb) relative to the
// centre's.  Neckel (2005, Solar Physics 229, 13, eqs. 2–3 with Table 2's
// coefficients): a fifth-degree polynomial in μ whose coefficients are polynomials in
// 1/λ, fitted over 300–372.98, 385–422.57 and 422.57–1100 nm; between 372.98 and 385 nm
// (strong lines, no fit) linear between the neighbouring fits.
double limb_darkening(double wavelength_nm, double mu);

// The mean of limb_darkening over the disc's area, 2∫I(μ)μ dμ: the disc's mean radiance
// over its centre's (~0.83 at 550 nm).
double limb_darkening_mean(double wavelength_nm);

}  // namespace arcus::sky
