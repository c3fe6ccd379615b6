/* Fresnel's equations at a smooth interface between media of real refractive indices
 * n1 (the incident side) and n2 (thesis §2.2.3): written once for every engine (the
 * rainbow engine's amplitudes, kernels/rainbow/optics.h; the translucency engine's
 * transmittances, src/translucency/).  Scalar code the host includes too, after
 * common/real.h. */
#ifndef ARCUS_FRESNEL_H
#define ARCUS_FRESNEL_H

/* The reflected amplitude ratios r_s and r_p (their signs: kernels/rainbow/optics.h)
 * and cos θ_t for cos θ_i = cos_i >= 0; under total internal reflection `total` is 1
 * and the rest is left for the caller (the amplitudes then carry a phase). */
typedef struct arcus_fresnel_real {
  REAL rs, rp, cos_t;
  REAL sin2_t; /* sin² θ_t by Snell's law: above 1 under total internal reflection */
  int total;
} arcus_fresnel_real;

ARCUS_INLINE arcus_fresnel_real arcus_fresnel_amplitudes(REAL cos_i, REAL n1, REAL n2) {
  arcus_fresnel_real f;
  const REAL eta = n1 / n2;
  f.sin2_t = eta * eta * fmax(RC(0), RC(1) - cos_i * cos_i);
  f.total = f.sin2_t > RC(1);
  f.rs = f.rp = RC(1);
  f.cos_t = RC(0);
  if (!f.total) {
    f.cos_t = sqrt(RC(1) - f.sin2_t);
    f.rs = (n1 * cos_i - n2 * f.cos_t) / (n1 * cos_i + n2 * f.cos_t);
    f.rp = (n2 * cos_i - n1 * f.cos_t) / (n2 * cos_i + n1 * f.cos_t);
  }
  return f;
}

/* The share of unpolarised power reflected, (r_s² + r_p²)/2: 1 under total internal
 * reflection and at grazing incidence; the rest (1 − R) is transmitted. */
ARCUS_INLINE REAL arcus_fresnel_reflectance(REAL cos_i, REAL n1, REAL n2) {
  const arcus_fresnel_real f = arcus_fresnel_amplitudes(cos_i, n1, n2);
  return f.total ? RC(1) : RC(0.5) * (f.rs * f.rs + f.rp * f.rp);
}

#endif /* ARCUS_FRESNEL_H */
