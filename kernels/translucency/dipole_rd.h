/* The dipole's diffuse reflectance R_d (thesis eq. 3.7, corrected: the virtual source
 * at z_v = z_r(1 + 4A/3) and no extra 1/σ′_t; Jensen et al. 2001, eq. 4–5), per mm², at
 * squared distance r² [mm²] from where the light entered, for one channel's terms.
 * Written once for the host (src/translucency/dipole.cpp) and the gather kernels
 * (gather.cl, ARCUS_LANES points side by side); include it after common/real.h. */
#ifndef ARCUS_TRANSLUCENCY_DIPOLE_RD_H
#define ARCUS_TRANSLUCENCY_DIPOLE_RD_H

/* One channel's terms, as the kernels take them (4 REALs a channel). */
#define ARCUS_DIPOLE_Z_R 0
#define ARCUS_DIPOLE_Z_V 1
#define ARCUS_DIPOLE_SIGMA_TR 2
#define ARCUS_DIPOLE_WEIGHT 3 /* α′/4π, times whatever scales the whole profile */
#define ARCUS_DIPOLE_TERMS 4

/* Each source contributes z(1 + σ_tr d)e^{−σ_tr d}/d³, d its distance. */
ARCUS_INLINE REALV arcus_dipole_rd(REALV r2, REAL z_r, REAL z_v, REAL sigma_tr, REAL weight) {
  const REALV d_r = sqrt(r2 + z_r * z_r), d_v = sqrt(r2 + z_v * z_v);
  const REALV real_source = z_r * (RC(1.0) + sigma_tr * d_r) * exp(-sigma_tr * d_r) / (d_r * d_r * d_r);
  const REALV virtual_source = z_v * (RC(1.0) + sigma_tr * d_v) * exp(-sigma_tr * d_v) / (d_v * d_v * d_v);
  return weight * (real_source + virtual_source);
}

#endif /* ARCUS_TRANSLUCENCY_DIPOLE_RD_H */
