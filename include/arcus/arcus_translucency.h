/*
 * arcus translucency: subsurface light transport by the dipole diffusion model (thesis
 * §3.1.4; Jensen, Marschner, Levoy & Hanrahan, SIGGRAPH 2001), its measured materials,
 * and the inversion from what a photograph shows (total diffuse reflectance and diffuse
 * mean free path) to coefficients (Jensen & Buhler, TOG 2002).  docs/translucency.md.
 * Include arcus.h.
 *
 * Units: coefficients in mm⁻¹ and distances in mm (as the measured tables give them);
 * R_d(r) per mm²; three channels R, G, B.  η is the medium's refractive index relative
 * to its surroundings.
 *
 * Two misprints of the thesis are corrected here (docs/translucency.md says why):
 * eq. 3.7's virtual source lies at z_v = z_r(1 + 4A/3) and R_d carries no extra
 * 1/σ′_t; eq. 3.5's Henyey–Greenstein is the standard, normalised one.
 *
 * These calls are host code and take no context: errors go to arcus_last_error()
 * (thread-local), naming the argument.
 */
#ifndef ARCUS_TRANSLUCENCY_H
#define ARCUS_TRANSLUCENCY_H

#include "arcus_core.h"

#ifdef __cplusplus
extern "C" {
#endif

/* A homogeneous translucent medium for the dipole: per channel the absorption σ_a >= 0
 * and the reduced scattering σ_s′ = (1 − g)σ_s > 0 [mm⁻¹], and η > 0. */
typedef struct arcus_dipole {
  double sigma_a[3];
  double sigma_s_prime[3];
  double eta;
} arcus_dipole;

/* What follows from a dipole (thesis §3.1.4, corrected), per channel unless scalar. */
typedef struct arcus_dipole_terms {
  double albedo[3];            /* reduced albedo α′ = σ_s′/σ_t′                       */
  double sigma_t_prime[3];     /* σ_t′ = σ_a + σ_s′ [mm⁻¹]                            */
  double sigma_tr[3];          /* effective extinction sqrt(3σ_a σ_t′) [mm⁻¹]         */
  double diffuse_length[3];    /* ℓ_d = 1/σ_tr [mm]; infinite when σ_a = 0             */
  double z_r[3], z_v[3];       /* depths of the real and virtual sources [mm]         */
  double total_reflectance[3]; /* R_total = ∫ 2πr R_d(r) dr, in closed form           */
  int32_t diffusive[3];        /* 1 where α′ >= 0.5; below, diffusion is a poor model   */
                               /* (e.g. ketchup's G and B): warn, the numbers still hold */
  double f_dr;                 /* diffuse Fresnel reflectance inside (Egan & Hilgeman)  */
  double a;                    /* A = (1 + F_dr)/(1 − F_dr)                            */
  double exit_transmittance;   /* ∫ (1/π)F_t(η, ω_o) cos θ_o dω_o = 1 − 2·FM1, by the  */
                               /* exact Fresnel equations (0.939 at η = 1.3)           */
} arcus_dipole_terms;

ARCUS_API arcus_status arcus_translucency_dipole_get_terms(const arcus_dipole* dipole, arcus_dipole_terms* terms);

/* How a profile is stretched by a factor s > 0 (thesis §5.2's edits). */
typedef enum arcus_profile_scaling {
  ARCUS_PROFILE_SCALE_ENERGY = 0, /* R_d(r/s)/s²: the same total reflectance (default)  */
  ARCUS_PROFILE_SCALE_THESIS = 1  /* R_d(r/s), as the thesis writes it: s² times more   */
} arcus_profile_scaling;

/* R_d at `count` distances r_mm[i] >= 0 (finite) from where light enters, stretched by
 * `scale` (1: none) as `scaling` says: rd[3 i + c] per mm², channel c. */
ARCUS_API arcus_status arcus_translucency_dipole_profile(const arcus_dipole* dipole, double scale, int32_t scaling,
                                                         size_t count, const double* r_mm, double* rd);

/* Jensen et al. 2001's measured materials by name (lower case): "apple", "chicken1",
 * "chicken2", "cream", "ketchup", "marble", "potato", "skimmilk", "skin1", "skin2",
 * "spectralon", "wholemilk"; η = 1.3, marble 1.5 (data/translucency/README.md gives the
 * source).  arcus_translucency_material_name(i, &name) lists them: i from 0 until it
 * returns ARCUS_ERROR_INVALID_ARGUMENT. */
ARCUS_API arcus_status arcus_translucency_dipole_from_material(const char* name, arcus_dipole* out);
ARCUS_API arcus_status arcus_translucency_material_name(uint32_t index, const char** name);

/* The dipole with the given total diffuse reflectance 0 < R_total < 1 and diffuse mean
 * free path ℓ_d = 1/σ_tr > 0 [mm] per channel, at η (Jensen & Buhler 2002: α′ from
 * R_total by bisection, R_total rising with α′; then σ_t′ = 1/(ℓ_d sqrt(3(1 − α′)))). */
ARCUS_API arcus_status arcus_translucency_dipole_from_reflectance(const double total_reflectance[3],
                                                                  const double diffuse_length[3], double eta,
                                                                  arcus_dipole* out);

/* The Henyey–Greenstein phase function of asymmetry g (−1 < g < 1) at `count` cosines
 * of the scattering angle: (1 − g²)/(4π(1 + g² − 2g cos θ)^{3/2}) per steradian. */
ARCUS_API arcus_status arcus_translucency_henyey_greenstein(double g, size_t count, const double* cos_theta,
                                                            double* phase);

/* Unpolarised Fresnel reflectance of light arriving at cos θ = cos_i (0..1) from a
 * medium of index n1 on one of n2 (exact, 1 under total internal reflection): the
 * formulas the rainbow engine's amplitudes use (kernels/common/fresnel.h). */
ARCUS_API arcus_status arcus_translucency_fresnel_reflectance(double cos_i, double n1, double n2,
                                                              double* reflectance);

#ifdef __cplusplus
}
#endif
#endif /* ARCUS_TRANSLUCENCY_H */
