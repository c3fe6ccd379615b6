// The water of the ocean engine (thesis §3.5, §4.2, Tables 3.4, 3.5, 4.1–4.3): its
// constituents' absorption, elastic scattering and inelastic re-emission, given either
// by the bio-optical model (chlorophyll C, minerals and detritus a_d(400), CDOM
// a_y(440) and the rest of Table 4.3; named presets) or directly by inherent optical
// properties, as ocean-optics users specify water for other radiative-transfer codes.
//
// evaluate() turns a description into the tables the photon tracer reads: on a grid of
// wavelengths, the coefficient of each of the ten events of §4.2 (so the roulette's
// albedos of eq. 4.3–4.4 are coefficient / extinction), the phase function of each
// scatterer, and for each inelastic process the distribution of the re-emitted
// wavelength given the exciting one.
//
// Inelastic events are counted in photons: a process with photon yield Y(λi) (Raman:
// b_r(λi)/a_w(λi); chlorophyll: Γ_p g_p(λi); CDOM: ∫ Hawes' η(λi, λo) dλo) turns that
// fraction of the absorbed photons into photons at λo, drawn from the normalised
// emission distribution h(λo | λi), each carrying energy λi/λo times the absorbed one's
// (so the thesis' energy redistribution function is f_λ = Y h λi/λo, eq. 3.31).  Only
// re-emission inside the simulated range is an inelastic event: photons that would
// leave it are absorbed (§4.2), so the inelastic event's coefficient is
// a_j(λ) Y(λ) P_in(λ), P_in the probability of landing inside the grid's range, and
// the absorption event's the rest of a_j.
#pragma once

#include <array>
#include <string>
#include <vector>

namespace arcus::ocean {

// A uniform wavelength grid, first_nm + k·step_nm for k = 0..count−1, inside
// 300–1000 nm (one sample: step_nm is ignored, the range is that one wavelength).
struct Grid {
  double first_nm = 380, step_nm = 5;
  int count = 81;
  double nm(int k) const { return first_nm + step_nm * k; }
  double last_nm() const { return nm(count - 1); }
};
// Throws INVALID_ARGUMENT naming the bad member.
void check_grid(const Grid& grid);

// The ten events of §4.2, in the order of the thesis' roulette (eq. 4.4).
enum Event : int {
  kAbsorbWater = 0,
  kRaman = 1,
  kAbsorbDetritus = 2,  // minerals and detritus
  kAbsorbPhyto = 3,
  kFluorescePhyto = 4,
  kAbsorbCdom = 5,
  kFluoresceCdom = 6,
  kScatterWater = 7,
  kScatterDetritus = 8,
  kScatterPhyto = 9,
  kEventCount = 10
};
const char* event_name(int event);  // "absorb_water", "raman", ...

// The scatterers (events 7, 8, 9) and the inelastic processes (events 1, 4, 6).
enum Scatterer : int { kWater = 0, kDetritus = 1, kPhyto = 2, kScattererCount = 3 };
enum Process : int { kRamanProcess = 0, kChlorophyll = 1, kCdomProcess = 2, kProcessCount = 3 };

// A phase function, normalised to 1 over the sphere.
struct Phase {
  enum Kind : int { isotropic = 0, rayleigh_like = 1, hg = 2, two_term_hg = 3, table = 4 } kind = isotropic;
  double a = 0;         // rayleigh_like: p ∝ 1 + a cos²θ (pure water, eq. 3.26: a = 0.835)
  double g_forward = 0; // hg: g; two_term_hg: the forward lobe's g (eq. 3.28–3.29)
  double g_backward = 0;       // two_term_hg: the backward lobe's g (≤ 0)
  double forward_weight = 1;   // two_term_hg: ζ
  std::vector<double> cosines, values;  // table: p at strictly increasing cosines spanning [−1, 1]
};

// The value of a phase function at the cosine of the scattering angle [1/sr]; a table is
// interpolated linearly in the cosine and normalised (evaluate() hands tables on
// normalised the same way).
double phase_value(const Phase& phase, double cosine);

// Minerals and detritus' default phase (the thesis gives no ζ, g_f, g_b): the two-term HG
// with Petzold's average-particle mean cosine 0.924 and backscatter fraction 0.0183,
// g_b = −0.5 (data/ocean/README.md; fitted by data/ocean/make_water_tables.py).
Phase petzold_like_detritus_phase();

// The bio-optical model (§3.5, Table 4.3).  Defaults: the thesis' values.
struct BioOptical {
  double chlorophyll = 0.1;     // C [mg/m³] (eq. 3.23, 3.27)
  double a_d400 = 0.01;         // minerals and detritus absorption at 400 nm [1/m] (eq. 3.24)
  double a_y440 = 0.01;         // CDOM absorption at 440 nm [1/m] (eq. 3.22)
  double s_d = 0.011;           // [1/nm] (eq. 3.24)
  double s_y = 0.014;           // [1/nm] (eq. 3.22)
  double chlorophyll_yield = 0.1;  // Γ_p (eq. 3.31; Table 4.3)
  double cdom_yield_scale = 1;     // multiplies Hawes' A0 (0: no CDOM fluorescence)
  double raman_scale = 1;          // multiplies the Raman coefficient b_r (0: no Raman)
  // false: inelastic re-emission only toward longer wavelengths (λo ≥ λi, to the grid's
  // resolution); the shorter ones count as absorbed (thesis Fig. 5.11, right).
  bool anti_stokes = true;
  // Minerals and detritus scattering, Table 3.5 scaled by a_d400 / this (data/ocean/README.md).
  double detritus_scattering_reference_a_d400 = 0.1;
  Phase detritus_phase = petzold_like_detritus_phase();  // data/ocean/README.md
};
BioOptical bio_optical_defaults();

// Named presets (Fig. 5.10): "atlantic", "mediterranean", "baltic", "north_sea",
// "cdom_coastal"; values and sources in data/ocean/presets.csv.  An unknown name is
// INVALID_ARGUMENT listing the known ones.
BioOptical preset(const std::string& name);
std::vector<std::string> preset_names();

// Water given by its inherent optical properties: absorption and scattering as spectra
// (wavelengths strictly increasing, values ≥ 0, interpolated linearly, constant beyond
// the ends) or single values (one entry with any wavelength), and one phase function;
// optionally the bio-optical inelastic constituents added on top (their absorption
// adds to `absorption`; Raman's b_r is taken out of `absorption`, which must hold it).
struct Spectrum {
  std::vector<double> nm, values;
};
struct Iops {
  Spectrum absorption, scattering;
  Phase phase;
  bool raman = false;                 // Raman by the water (b_r ≤ absorption is checked)
  double chlorophyll = 0;             // adds phytoplankton absorption and fluorescence (no scattering)
  double chlorophyll_yield = 0.1;
  double a_y440 = 0, s_y = 0.014;     // adds CDOM absorption and fluorescence
  bool anti_stokes = true;            // as BioOptical::anti_stokes
};

struct Water {
  enum Kind : int { kBioOptical = 0, kIops = 1 } kind = kBioOptical;
  BioOptical bio = bio_optical_defaults();
  Iops iops;
};

// Checks every coefficient: negative or non-finite values, an empty spectrum,
// wavelengths not increasing, a phase table not spanning [−1, 1] or not positive, g
// outside (−1, 1), ζ outside [0, 1] → INVALID_ARGUMENT naming the parameter
// ("water.bio.chlorophyll: must be finite and >= 0, got -1").
void check_water(const Water& water);

// The evaluated water on a grid: what the kernels read.
struct WaterTables {
  Grid grid;
  // event[e][k]: the coefficient of event e at grid sample k [1/m]; their sum over e is
  // the extinction σ_t, each divided by σ_t is the roulette's albedo Λ_e (eq. 4.3–4.4).
  std::array<std::vector<double>, kEventCount> event;
  // Reporting: per constituent (water, detritus, phytoplankton, CDOM) its whole
  // absorption and scattering [1/m] per sample.
  std::array<std::vector<double>, 4> absorption, scattering;
  std::array<Phase, kScattererCount> phase;  // of events 7, 8, 9
  // Per process p and exciting sample k: the photon yield Y(λ_k) (all wavelengths) and
  // P_in(λ_k), the part of it landing inside [first_nm, last_nm].
  std::array<std::vector<double>, kProcessCount> yield, inside;
  // emission[p][k·count + m]: the normalised emission density h(λ_m | λ_k) [1/nm] at
  // the grid's samples, restricted to the range and renormalised there (∫ = 1 with
  // linear interpolation between samples, i.e. the trapezoid rule), 0 where P_in = 0;
  // cdf[p][k·count + m]: its cumulative trapezoid integral, 0 at m = 0, 1 at m = count−1.
  // Rows where P_in = 0 (one-sample grids, emission missing every sample) are all 0, and
  // their inelastic event's coefficient is 0.  Phase tables come back normalised.
  std::array<std::vector<double>, kProcessCount> emission, cdf;
};
WaterTables evaluate(const Water& water, const Grid& grid);

// The analytic normalised emission densities over all wavelengths (not restricted to a
// range) [1/nm], for tests and for evaluate(): Raman (eq. 3.35–3.36, Walrafen's four
// bands), chlorophyll (eq. 3.32), CDOM (Hawes, eq. 3.33–3.34, divided by its yield).
double emission_density(int process, double excitation_nm, double emission_nm);
// The analytic photon yields Y(λi): Raman b_r(λi)/a_w(λi) is water-dependent, so this
// gives b_r(λi) [1/m] for process kRamanProcess; g_p(λi) for chlorophyll (times Γ_p
// gives the yield); ∫ η dλo for CDOM (with the default A0 table, cdom_yield_scale 1).
double photon_yield(int process, double excitation_nm);
double raman_coefficient(double excitation_nm);  // b_r = 2.6e-4 (488/λi)^5.3 [1/m]
double pure_water_absorption(double nm);  // Smith & Baker 1981, linear in the table
double pure_water_scattering(double nm);  // eq. 3.25, Morel's seawater β(400 nm, 90°)
// The other tables, linear, constant beyond their ends (data/ocean/README.md):
double phytoplankton_specific_absorption(double nm);  // Table 3.4 a*_p [m²/mg]
double detritus_table_scattering(double nm);          // Table 3.5 total σ_s,d [1/m], unscaled
double cdom_fluorescence_a0(double excitation_nm);    // Hawes' A0 [1/nm], 0 outside 310–550

}  // namespace arcus::ocean
