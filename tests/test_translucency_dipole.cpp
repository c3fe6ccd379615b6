// The dipole model of translucency (arcus_translucency.h) against closed forms,
// conservation and Jensen et al. 2001's published reflectances: the profile integrates
// to the closed-form total reflectance, Henyey–Greenstein is normalised with mean
// cosine g, the Fresnel equations meet their special angles and reciprocity, and bad
// input is refused naming the argument.  Integrals are this file's own (composite
// Simpson), not the library's.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "arcus/arcus.h"

namespace {

// ∫_a^b f by composite Simpson with n (even) intervals.
double simpson(const std::function<double(double)>& f, double a, double b, int n) {
  const double h = (b - a) / n;
  double sum = f(a) + f(b);
  for (int i = 1; i < n; ++i) sum += (i % 2 ? 4 : 2) * f(a + i * h);
  return sum * h / 3;
}

arcus_dipole material(const char* name) {
  arcus_dipole d{};
  EXPECT_EQ(arcus_translucency_dipole_from_material(name, &d), ARCUS_SUCCESS) << arcus_last_error();
  return d;
}

arcus_dipole_terms terms_of(const arcus_dipole& d) {
  arcus_dipole_terms t{};
  EXPECT_EQ(arcus_translucency_dipole_get_terms(&d, &t), ARCUS_SUCCESS) << arcus_last_error();
  return t;
}

std::vector<std::string> material_names() {
  std::vector<std::string> names;
  const char* name = nullptr;
  for (uint32_t i = 0; arcus_translucency_material_name(i, &name) == ARCUS_SUCCESS; ++i) names.push_back(name);
  return names;
}

// ∫₀^∞ 2πr R_d(r) dr of one channel, stretched by `scale`, with r = z·sinh(x): the
// profile's core (r ~ z_r) and its 1/r³ tail (σ_a = 0) both get enough points; x up
// to 22 reaches r = 1.8e9 z, where a 1/r³ tail leaves less than 1e-9.
double integrated_profile(const arcus_dipole& d, int channel, double scale = 1,
                          int32_t scaling = ARCUS_PROFILE_SCALE_ENERGY) {
  const double z = terms_of(d).z_r[channel] * scale;
  return simpson(
      [&](double x) {
        const double r = z * std::sinh(x);
        double rd[3];
        EXPECT_EQ(arcus_translucency_dipole_profile(&d, scale, scaling, 1, &r, rd), ARCUS_SUCCESS);
        return 2 * M_PI * r * rd[channel] * z * std::cosh(x);
      },
      0, 22, 20000);
}

TEST(TranslucencyDipole, TwelveMeasuredMaterialsAreListed) {
  const std::vector<std::string> names = material_names();
  EXPECT_EQ(names, (std::vector<std::string>{"apple", "chicken1", "chicken2", "cream", "ketchup", "marble", "potato",
                                              "skimmilk", "skin1", "skin2", "spectralon", "wholemilk"}));
}

// The corrected eq. 3.7 conserves what the dipole's closed form says leaves the
// surface: to 1e-6 (the bound; Simpson's error here is below 1e-9), for every
// material and channel, spectralon's unabsorbing 1/r³ tail included.
TEST(TranslucencyDipole, TheProfileIntegratesToTheClosedFormTotalReflectance) {
  for (const std::string& name : material_names()) {
    const arcus_dipole d = material(name.c_str());
    const arcus_dipole_terms t = terms_of(d);
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(integrated_profile(d, c), t.total_reflectance[c], 1e-6) << name << " channel " << c;
  }
}

// Jensen et al. 2001 (Figure 5) print apple's diffuse reflectance as 0.85, 0.84, 0.53:
// two decimals, so within 0.005.  Marble's red at the thesis' η = 1.3 is 0.8665 in the
// issue's independent evaluation (eq. 3.7 as printed integrates to 0.351 instead).
TEST(TranslucencyDipole, PublishedReflectancesAreMet) {
  const arcus_dipole_terms apple = terms_of(material("apple"));
  const double published[3] = {0.85, 0.84, 0.53};
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(apple.total_reflectance[c], published[c], 0.005) << c;
  arcus_dipole marble_13 = material("marble");
  marble_13.eta = 1.3;
  EXPECT_NEAR(terms_of(marble_13).total_reflectance[0], 0.8665, 5e-5);
  // Spectralon absorbs nothing: every photon that enters leaves (α′ = 1, R_total = 1).
  const arcus_dipole_terms spectralon = terms_of(material("spectralon"));
  for (int c = 0; c < 3; ++c) {
    EXPECT_DOUBLE_EQ(spectralon.total_reflectance[c], 1.0);
    EXPECT_TRUE(std::isinf(spectralon.diffuse_length[c]));
  }
}

// Round trip: (R_total, ℓ_d, η) of each material gives back its coefficients.
TEST(TranslucencyDipole, TheInverseFromReflectanceRecoversEveryMaterial) {
  for (const std::string& name : material_names()) {
    if (name == "spectralon") continue;  // R_total = 1: no finite dipole has it
    const arcus_dipole d = material(name.c_str());
    const arcus_dipole_terms t = terms_of(d);
    arcus_dipole back{};
    ASSERT_EQ(arcus_translucency_dipole_from_reflectance(t.total_reflectance, t.diffuse_length, d.eta, &back),
              ARCUS_SUCCESS)
        << name << ": " << arcus_last_error();
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(back.sigma_a[c], d.sigma_a[c], 1e-9 * d.sigma_a[c] + 1e-15) << name << " " << c;
      EXPECT_NEAR(back.sigma_s_prime[c], d.sigma_s_prime[c], 1e-9 * d.sigma_s_prime[c]) << name << " " << c;
    }
  }
}

// Stretching by s: R_d(r/s)/s² keeps ∫2πr R_d dr, R_d(r/s) multiplies it by s².
TEST(TranslucencyDipole, EnergyPreservingScalingKeepsTheTotalAndTheThesisScalingMultipliesIt) {
  const arcus_dipole d = material("skimmilk");
  const double total = terms_of(d).total_reflectance[1];
  EXPECT_NEAR(integrated_profile(d, 1, 2.5, ARCUS_PROFILE_SCALE_ENERGY), total, 1e-6);
  EXPECT_NEAR(integrated_profile(d, 1, 2.5, ARCUS_PROFILE_SCALE_THESIS), 2.5 * 2.5 * total, 1e-5);
}

// The standard Henyey–Greenstein: ∫ p dω = 1 and ∫ p cos θ dω = g (eq. 3.5 as printed
// has neither).  2^18 intervals resolve g = 0.95's forward peak (width ~ (1 − g)²).
TEST(TranslucencyDipole, HenyeyGreensteinIsNormalisedWithMeanCosineG) {
  for (const double g : {-0.9, -0.3, 0.0, 0.5, 0.95}) {
    auto p = [&](double mu) {
      double v = 0;
      EXPECT_EQ(arcus_translucency_henyey_greenstein(g, 1, &mu, &v), ARCUS_SUCCESS);
      return v;
    };
    const int n = 1 << 18;
    EXPECT_NEAR(simpson([&](double mu) { return 2 * M_PI * p(mu); }, -1, 1, n), 1.0, 1e-6) << g;
    EXPECT_NEAR(simpson([&](double mu) { return 2 * M_PI * p(mu) * mu; }, -1, 1, n), g, 1e-6) << g;
  }
}

double fresnel(double cos_i, double n1, double n2) {
  double r = -1;
  EXPECT_EQ(arcus_translucency_fresnel_reflectance(cos_i, n1, n2, &r), ARCUS_SUCCESS) << arcus_last_error();
  return r;
}

// Normal incidence ((n1 − n2)/(n1 + n2))²; Brewster's angle from outside, tan θ_i = n,
// where r_p = 0 and r_s = (1 − n²)/(1 + n²), so R = r_s²/2; total reflection beyond
// the critical angle from inside, and at grazing incidence.
TEST(TranslucencyDipole, FresnelMeetsItsSpecialAngles) {
  for (const double n : {1.3, 1.5, 2.4}) {
    EXPECT_NEAR(fresnel(1, 1, n), std::pow((1 - n) / (1 + n), 2), 1e-15);
    const double brewster = std::atan(n);  // from outside
    const double rs = (1 - n * n) / (1 + n * n);
    EXPECT_NEAR(fresnel(std::cos(brewster), 1, n), rs * rs / 2, 1e-14);
    const double critical = std::asin(1 / n);  // from inside
    EXPECT_EQ(fresnel(std::cos(critical + 1e-6), n, 1), 1.0);
    EXPECT_LT(fresnel(std::cos(critical - 1e-3), n, 1), 1.0);
    EXPECT_EQ(fresnel(0, 1, n), 1.0);
  }
}

// What the boundary lets out, by the exact Fresnel equations: 1 − F̄ = 0.939 at η = 1.3
// (the figure, 3 digits); reciprocity ties it to the diffuse reflectance seen
// from inside, 1 − F_dr,exact = (1 − F̄)/η² (Stokes); and Egan & Hilgeman's fit F_dr
// lies within 0.005 of the exact value (its stated accuracy is about 1%).
TEST(TranslucencyDipole, TheBoundaryTermsAgreeWithTheExactFresnelEquations) {
  for (const double eta : {1.3, 1.5}) {
    arcus_dipole d = material("apple");
    d.eta = eta;
    const arcus_dipole_terms t = terms_of(d);
    const double inside =
        simpson([&](double mu) { return 2 * fresnel(mu, eta, 1) * mu; }, 0, 1, 1 << 16);  // kinked at TIR
    EXPECT_NEAR(1 - inside, t.exit_transmittance / (eta * eta), 2e-6) << eta;
    EXPECT_NEAR(t.f_dr, inside, 0.005) << eta;
    EXPECT_DOUBLE_EQ(t.a, (1 + t.f_dr) / (1 - t.f_dr));
  }
  arcus_dipole d = material("apple");
  EXPECT_NEAR(terms_of(d).exit_transmittance, 0.939, 5e-4);
  // The virtual source's depth carries z_r (eq. 3.7 misprints it as 1 + 4A/3).
  const arcus_dipole_terms t = terms_of(d);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(t.z_v[c], t.z_r[c] * (1 + 4 * t.a / 3), 1e-15 * t.z_v[c]);
}

// Ketchup's green and blue (α′ = 0.067, 0.020) lie outside diffusion: flagged, kept.
TEST(TranslucencyDipole, ChannelsOutsideDiffusionAreFlaggedNotRefused) {
  const arcus_dipole_terms t = terms_of(material("ketchup"));
  EXPECT_EQ(t.diffusive[0], 1);
  EXPECT_EQ(t.diffusive[1], 0);
  EXPECT_EQ(t.diffusive[2], 0);
  EXPECT_NEAR(t.albedo[1], 0.07 / 1.04, 1e-12);
}

// Every bad argument is refused with its name, and the output is left as it was.
TEST(TranslucencyDipole, BadInputIsRefusedNamingTheArgument) {
  const arcus_dipole good = material("marble");
  auto refused = [](arcus_status st, const char* words) {
    EXPECT_EQ(st, ARCUS_ERROR_INVALID_ARGUMENT) << words;
    EXPECT_NE(std::string(arcus_last_error()).find(words), std::string::npos) << arcus_last_error();
  };
  arcus_dipole_terms t{};
  t.f_dr = -7;
  arcus_dipole bad = good;
  bad.sigma_a[1] = -0.1;
  refused(arcus_translucency_dipole_get_terms(&bad, &t), "dipole->sigma_a[1] = -0.1");
  bad = good;
  bad.sigma_s_prime[2] = NAN;
  refused(arcus_translucency_dipole_get_terms(&bad, &t), "dipole->sigma_s_prime[2] = nan");
  bad = good;
  bad.eta = 0.8;
  refused(arcus_translucency_dipole_get_terms(&bad, &t), "dipole->eta = 0.8 is outside 1..3");
  refused(arcus_translucency_dipole_get_terms(nullptr, &t), "dipole is NULL");
  refused(arcus_translucency_dipole_get_terms(&good, nullptr), "terms is NULL");
  EXPECT_EQ(t.f_dr, -7);

  double r = 1, rd[3] = {-1, -1, -1};
  refused(arcus_translucency_dipole_profile(&good, 0, 0, 1, &r, rd), "scale = 0");
  refused(arcus_translucency_dipole_profile(&good, 1, 7, 1, &r, rd), "scaling = 7");
  r = -2;
  refused(arcus_translucency_dipole_profile(&good, 1, 0, 1, &r, rd), "r_mm[0] = -2");
  refused(arcus_translucency_dipole_profile(&good, 1, 0, 1, nullptr, rd), "r_mm is NULL");
  refused(arcus_translucency_dipole_profile(&good, 1, 0, SIZE_MAX / 2, &r, rd), "count");
  EXPECT_EQ(rd[0], -1);

  arcus_dipole out = good;
  refused(arcus_translucency_dipole_from_material("granite", &out), "no measured material \"granite\"");
  refused(arcus_translucency_dipole_from_material(nullptr, &out), "name is NULL");
  const double totals[3] = {0.5, 1.0, 0.5}, lengths[3] = {1, 1, 0};
  const double fine[3] = {0.5, 0.5, 0.5};
  refused(arcus_translucency_dipole_from_reflectance(totals, fine, 1.3, &out), "total_reflectance[1] = 1");
  refused(arcus_translucency_dipole_from_reflectance(fine, lengths, 1.3, &out), "diffuse_length[2] = 0");
  refused(arcus_translucency_dipole_from_reflectance(fine, fine, NAN, &out), "eta = nan");
  EXPECT_EQ(out.eta, good.eta);
  EXPECT_EQ(out.sigma_a[0], good.sigma_a[0]);

  const char* name = nullptr;
  refused(arcus_translucency_material_name(12, &name), "index 12 is not below the 12");
  double mu = 0.5, p = 0;
  refused(arcus_translucency_henyey_greenstein(1.0, 1, &mu, &p), "g = 1");
  mu = 1.5;
  refused(arcus_translucency_henyey_greenstein(0.3, 1, &mu, &p), "cos_theta[0] = 1.5");
  refused(arcus_translucency_fresnel_reflectance(1.2, 1, 1.3, &p), "cos_i = 1.2");
  refused(arcus_translucency_fresnel_reflectance(0.5, 1, -1, &p), "n2 = -1");
}

}  // namespace
