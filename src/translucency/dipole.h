// The dipole diffusion model of subsurface scattering (thesis §3.1.4, with its eq. 3.7
// corrected; Jensen et al. 2001) and what comes with it: the closed-form total diffuse
// reflectance and its inverse (Jensen & Buhler 2002), the exit term's normalisation,
// Henyey–Greenstein.  Host code in double precision, one channel at a time; the C API
// (api.cpp) and, later, the rendering kernels use it.  Units: mm⁻¹ and mm.
#pragma once

#include <string>

#include "arcus/arcus_translucency.h"

namespace arcus::translucency {

// One channel of a medium: absorption σ_a >= 0, reduced scattering σ_s′ > 0, and η.
struct Channel {
  double sigma_a, sigma_s_prime, eta;
};

// F_dr: the diffuse Fresnel reflectance of the boundary seen from inside (Egan &
// Hilgeman's fit, as the thesis and Jensen 2001 use it), and A = (1 + F_dr)/(1 − F_dr).
double diffuse_fresnel_reflectance(double eta);
double boundary_mismatch(double eta);

// The derived terms of one channel.
struct Terms {
  double albedo;          // α′ = σ_s′/σ_t′
  double sigma_t_prime;   // σ_t′
  double sigma_tr;        // sqrt(3 σ_a σ_t′)
  double z_r, z_v;        // source depths: 1/σ_t′ and z_r(1 + 4A/3)
};
Terms terms(const Channel& c);

// R_d(r) per mm² at distance r mm (eq. 3.7 corrected), from a channel's terms (computed
// once for all the distances a caller evaluates).
double diffuse_reflectance(const Terms& t, double r);

// ∫₀^ρ 2πr R_d(r) dr in closed form: (α′/2) Σ_sources z(e^{−σ_tr z}/z − e^{−σ_tr d}/d),
// d = sqrt(ρ² + z²) (each source's term integrates to −e^{−σ_tr d}/d in d).
double reflectance_within(const Terms& t, double radius);

// ∫ 2πr R_d(r) dr in closed form: (α′/2)(1 + e^{−(4/3)A s}) e^{−s}, s = sqrt(3(1 − α′)).
double total_reflectance(double albedo, double eta);

// The reduced albedo α′ whose total reflectance is `total` (0 < total < 1), by bisection.
double albedo_for_reflectance(double total, double eta);

// ∫ over the outgoing hemisphere of (1/π) F_t(η, ω) cos θ dω = 1 − 2∫₀¹ R(μ) μ dμ, with
// the exact Fresnel reflectance R for light arriving from outside: what eq. 3.6's exit
// term sends out of a uniformly lit boundary.
double exit_transmittance(double eta);

// Henyey–Greenstein: (1 − g²)/(4π(1 + g² − 2g cos θ)^{3/2}) per steradian.
double henyey_greenstein(double g, double cos_theta);

// The exact unpolarised Fresnel reflectance (kernels/common/fresnel.h).
double fresnel_reflectance(double cos_i, double n1, double n2);

// Every derived term of a (valid) dipole, per channel, as the C API reports them.
arcus_dipole_terms dipole_terms(const arcus_dipole& d);

// Checks, naming the argument: a coefficient set (sigma_a[c] >= 0, sigma_s_prime[c] > 0,
// finite) and the dipole's η (1 to 3: F_dr's fit, eq. above, is for a medium optically
// denser than its surroundings; below 1 it turns negative).
void check_channel(const Channel& c, const std::string& where, int channel);
void check_eta(double eta, const std::string& name);

}  // namespace arcus::translucency
