// Lorenz–Mie scattering by a homogeneous sphere, and its Debye-series decomposition:
// the reference the rainbow engine's ray tracer is validated against, bounce by bounce
// (thesis "Light Transport in Participating Media" §4.4.1.1 and §5.5.1, Figs. 5.16–5.19:
// the p-th Debye term is exactly the light that left the drop after p − 1 internal
// reflections, which is what a ray tracer counts, with all the wave effects — Airy
// rainbow, supernumeraries, interference — that rays miss).
//
// Conventions (Bohren & Huffman 1983, ch. 4): time dependence e^{−iωt}, so an absorbing
// sphere has m = n + iκ with κ ≥ 0; x = 2πa/λ with λ the wavelength in the surrounding
// medium and m relative to it; S1 is the amplitude for the electric field perpendicular
// to the scattering plane, S2 parallel to it; Wiscombe's MIEV0 uses e^{+iωt}, so its
// amplitudes are the complex conjugates of these (for the conjugate m).
//
// Numerics (Wiscombe 1980, Appl. Opt. 19, 1505): N = x + 6 x^{1/3} + 2 terms (a little
// beyond Wiscombe's x + 4.05 x^{1/3} + 2, so backscatter is converged too); the
// logarithmic derivative D_n(mx) by downward recurrence from well beyond max(N, |mx|);
// ψ_n, ξ_n by upward recurrence; π_n, τ_n by recurrence, looping over n outside and
// angles inside.  Accurate and fast up to x = 20 000 and beyond (x ≤ 1e8 accepted;
// x = 10⁴ at 3600 angles takes ~0.06 s on one core).
// The Debye series (Hovenac & Lock 1992, JOSA A 9, 781) is evaluated from the
// logarithmic derivatives of the Riccati–Hankel functions and their ratios, never from
// the functions themselves, so nothing overflows for n > mx.
#pragma once

#include <complex>
#include <vector>

namespace arcus::rainbow::mie {

using complex = std::complex<double>;

// Number of terms N of the Mie series for size parameter x: x + 6 x^{1/3} + 2.
int series_terms(double x);

// The partial-wave coefficients a_n, b_n, n = 1..N, stored at index n − 1.
struct Coefficients {
  std::vector<complex> a, b;
};
// Throws INVALID_ARGUMENT naming x or m when x ≤ 0, x > 1e8, non-finite, Re m ≤ 0 or
// Im m < 0.
Coefficients coefficients(double x, complex m);

// Scattering amplitudes at the requested cos θ (same order).
struct Amplitudes {
  std::vector<complex> s1, s2;
};

struct Result : Amplitudes {
  double q_ext = 0, q_sca = 0;  // efficiencies: cross-section / πa²
  double q_back = 0;            // radar backscatter efficiency 4|S(π)|²/x²
  double g = 0;                 // asymmetry parameter <cos θ>
  int terms = 0;                // N, the number of partial waves summed
};

// Lorenz–Mie solution at the cosines `mu` (each in [−1, 1]).  Throws INVALID_ARGUMENT
// naming x, m or mu.
Result scatter(double x, complex m, const std::vector<double>& mu);

// The phase function per steradian, normalised so ∫ p dΩ = 1:
// p = (|S1|² + |S2|²) / (2π x² q_sca).  For a Debye term pass its amplitudes and the
// whole sphere's q_sca, so terms are on the same scale as the full phase function.
std::vector<double> phase_function(const Amplitudes& s, double x, double q_sca);
inline std::vector<double> phase_function(const Result& r, double x) { return phase_function(r, x, r.q_sca); }

// The same split by polarisation, parallel (|S2|²) and perpendicular (|S1|²) to the
// scattering plane, each with the factor 1/2 so that parallel + perpendicular = p.
struct Polarised {
  std::vector<double> parallel, perpendicular;
};
Polarised polarised_phase_function(const Amplitudes& s, double x, double q_sca);
inline Polarised polarised_phase_function(const Result& r, double x) {
  return polarised_phase_function(r, x, r.q_sca);
}

// The Debye series: S = Σ_p S_p.  terms[p], p = 0..max_p, is the light leaving after
// p − 1 internal reflections (p = 0: diffraction plus external reflection, p = 1: two
// refractions, p = 2: the primary rainbow, p = 3: the secondary, ...); remainder is
// every p > max_p together, in closed form, so that Σ terms + remainder equals scatter()'s
// amplitudes.  terms[0] = diffraction + reflection, split by the localization principle:
// diffraction is the partial waves n + ½ ≤ x with coefficient ½ (Fraunhofer diffraction
// by the drop's silhouette), reflection the rest of p = 0.
struct Debye {
  std::vector<Amplitudes> terms;
  Amplitudes remainder, diffraction, reflection;
  int series_terms = 0;  // N, as in Result::terms
};

// Per-partial-wave Debye coefficients: the p-th term of a_n is a_p[p][n − 1] (likewise
// b), the remainder a_rest[n − 1]; Σ_p a_p + a_rest = coefficients().a.
struct DebyeCoefficients {
  std::vector<std::vector<complex>> a_p, b_p;
  std::vector<complex> a_rest, b_rest;
  std::vector<complex> a_diffraction;  // ½ for n + ½ ≤ x, else 0 (the same for b)
};
// Throws INVALID_ARGUMENT as coefficients(), and naming max_p unless 0 ≤ max_p ≤ 1000.
DebyeCoefficients debye_coefficients(double x, complex m, int max_p);

Debye debye(double x, complex m, const std::vector<double>& mu, int max_p);

}  // namespace arcus::rainbow::mie
