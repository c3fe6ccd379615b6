// The US Standard Atmosphere 1976 (NOAA-S/T 76-1562): temperature piecewise linear in
// geopotential height through the standard's layers to 84.852 km (isothermal above),
// pressure from the hydrostatic equation in closed form, number density by the
// ideal-gas law.  The curved engine's atmosphere (src/curved/fields.cpp) adds its
// inversion layers to it; the sky takes the air's density from it.  Host code; SI
// units, heights in metres.
#pragma once

namespace arcus::sky {

// The standard's table 4: base geopotential heights (m) and lapse rates (K/m).
constexpr int kStandardLayers = 8;
constexpr double kStandardBase[kStandardLayers] = {0.0, 11000.0, 20000.0, 32000.0, 47000.0, 51000.0, 71000.0, 84852.0};
constexpr double kStandardLapse[kStandardLayers] = {-0.0065, 0.0, 0.001, 0.0028, 0.0, -0.0028, -0.002, 0.0};
constexpr double kGeopotentialRadius = 6356766.0;  // r0 of the standard's H = r0·h/(r0 + h)

double geopotential_height(double geometric_m);
double geometric_height(double geopotential_m);

// T at geopotential height H for a sea-level temperature (288.15 K in the standard);
// below sea level the first lapse rate continues.
double standard_temperature(double geopotential_m, double sea_level_temperature);

// p(H0 + dH)/p(H0) where the temperature is T0 at H0 and changes by `lapse` per metre:
// exp(−(g0·M/R*)·∫dH/T), the integral log(1 + lapse·dH/T0)/lapse (dH/T0 when isothermal).
double pressure_ratio(double dH, double T0, double lapse);

// p at geopotential height H >= 0 through the standard's layers.
double standard_pressure(double geopotential_m, double sea_level_pressure, double sea_level_temperature);

// Molecules per m³ of an ideal gas.
double number_density(double pressure_pa, double temperature_k);

}  // namespace arcus::sky
