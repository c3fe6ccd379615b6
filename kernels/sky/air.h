/* Dry air, shared by the host and the kernels of every engine that looks through air:
 * the hydrostatic constant and the refractive index (the curved engine's atmosphere,
 * the sky's Rayleigh scattering; src/sky/us1976.h on the host). */
#ifndef ARCUS_SKY_AIR_H
#define ARCUS_SKY_AIR_H

#ifndef __OPENCL_C_VERSION__
#include "common/real.h" /* the device source has it prepended */
#endif

/* US Standard Atmosphere 1976: g0·M/R* in K/m (the hydrostatic equation). */
#define ARCUS_ATM_G_M_OVER_R 0.034163194736310366

/* (n − 1)·T/p of dry air, K/Pa, at a vacuum wavelength in nm: Ciddor (1996), Appl.
 * Opt. 35, 1566, eq. 1 (standard air: 15 °C, 101 325 Pa, 450 ppm CO2), scaled by the
 * ideal-gas law so that n − 1 = refractivity·p/T (the compressibility of air changes
 * n − 1 by < 0.05 %). */
ARCUS_INLINE REALV ciddor_refractivity(REALV wavelength_nm) {
  REALV sigma = RC(1000) / wavelength_nm; /* 1/µm */
  REALV sigma2 = sigma * sigma;
  REALV standard = RC(1e-8) * (RC(5792105) / (RC(238.0185) - sigma2) + RC(167917) / (RC(57.362) - sigma2));
  return standard * RC(288.15 / 101325.0);
}

#endif
