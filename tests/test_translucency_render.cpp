// Rendering through the dipole (arcus_translucency_render) against closed forms and the
// brute-force gather: a wide slab lit and seen at normal incidence shows
// (1/π)·T·R_total·T·E at its centre (T = 1 − F_r(0°), R_total in closed form, written
// here again); the hierarchical gather agrees with the brute-force one; lights facing
// away and occluders give no light; bad input is refused naming the parameter.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "test_util.h"
#include "translucency_fixture.h"

namespace {

using arcus_test::ArcusTest;

// A medium of diffusion lengths 0.5–1.3 mm and mean free paths 0.3–0.5 mm, short
// beside the objects below.
arcus_dipole test_medium() {
  arcus_dipole d{};
  const double a[3] = {0.1, 0.2, 0.4}, s[3] = {2.0, 2.5, 3.0};
  for (int c = 0; c < 3; ++c) {
    d.sigma_a[c] = a[c];
    d.sigma_s_prime[c] = s[c];
  }
  d.eta = 1.3;
  return d;
}

// R_total in closed form (Jensen et al. 2001, eq. 6 integrated; thesis §3.1.4),
// written here independently of the library: (α′/2)(1 + e^{−(4/3)A s})e^{−s},
// s = sqrt(3(1 − α′)), A from Egan & Hilgeman's F_dr.
double closed_total(double sigma_a, double sigma_s_prime, double eta) {
  const double albedo = sigma_s_prime / (sigma_a + sigma_s_prime);
  const double f_dr = -1.440 / (eta * eta) + 0.710 / eta + 0.668 + 0.0636 * eta;
  const double a = (1 + f_dr) / (1 - f_dr), s = std::sqrt(3 * (1 - albedo));
  return albedo / 2 * (1 + std::exp(-4.0 / 3.0 * a * s)) * std::exp(-s);
}

struct Image {
  std::vector<float> rgb, subsurface;
  std::vector<uint8_t> covered;
  arcus_translucency_render_stats stats{};
  arcus_features features = 0;
};

class TranslucencyRender : public ArcusTest {
 protected:
  Image render(arcus_mesh_t* mesh, const arcus_dipole& d, const std::vector<arcus_directional_light>& lights,
               const arcus_translucency_render_params& p) {
    Image out;
    arcus_job_t* job = nullptr;
    EXPECT_EQ(arcus_translucency_render(ctx(), mesh, &d, lights.size(), lights.data(), &p, &job), ARCUS_SUCCESS)
        << last_error();
    if (!job) return out;
    EXPECT_EQ(arcus_job_get_translucency_stats(job, &out.stats), ARCUS_SUCCESS);
    const size_t pixels = size_t(out.stats.width) * out.stats.height;
    out.rgb.resize(3 * pixels);
    out.subsurface.resize(3 * pixels);
    out.covered.resize(pixels);
    EXPECT_EQ(arcus_job_get_translucency_image(job, out.rgb.data(), out.subsurface.data(), out.covered.data()),
              ARCUS_SUCCESS);
    EXPECT_EQ(arcus_job_get_features(job, &out.features), ARCUS_SUCCESS);
    arcus_job_release(job);
    return out;
  }

  static arcus_translucency_render_params looking_down(uint32_t side, double height) {
    arcus_translucency_render_params p{};
    EXPECT_EQ(arcus_translucency_render_params_init(&p), ARCUS_SUCCESS);
    p.camera = arcus_camera{{0, 0, 50}, {0, 0, 0}, {0, 1, 0}, 30, side, side};
    p.ortho_height = height;
    p.highlight_deg = 0;
    return p;
  }
};

// The 40 × 40 × 10 mm slab the closed-form tests look down on, its top at z = 0.
void slab_arrays(std::vector<double>* v, std::vector<uint32_t>* t) {
  const double lo[3] = {-20, -20, -10}, hi[3] = {20, 20, 0};
  box(lo, hi, v, t);
}

MeshHandle slab(arcus_context_t* ctx) {
  std::vector<double> v;
  std::vector<uint32_t> t;
  slab_arrays(&v, &t);
  return MeshHandle(ctx, v, t);  // built in place (C++17): never copied
}

const std::vector<arcus_directional_light> kOverhead{{{0, 0, 1}, {1, 1, 1}}};

// The exact Fresnel reflectance for unpolarised light from air into η (written here
// again: the library's is kernels/common/fresnel.h).
double fresnel(double cos_i, double eta) {
  const double sin_t = std::sqrt(1 - cos_i * cos_i) / eta, cos_t = std::sqrt(1 - sin_t * sin_t);
  const double rs = (cos_i - eta * cos_t) / (cos_i + eta * cos_t), rp = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
  return 0.5 * (rs * rs + rp * rp);
}

// A 40 × 40 × 10 mm slab, seen straight down at its centre: the diffusion lengths are
// 16–40 times shorter than the way to an edge and 8–20 times than the way to the
// bottom, so the profile's tail beyond the slab (e^{−16} of R_total and less) is far
// below the tolerance.  What remains is the samples' lattice sum standing for the
// integral (measured 2e-5 at the automatic spacing, 1/σ′_t) and the float image
// (6e-8): 1e-3 holds both with room, and a finer spacing must not do worse.
TEST_F(TranslucencyRender, SlabCentreMatchesClosedForm) {
  MeshHandle mesh = slab(ctx());
  const arcus_dipole d = test_medium();
  // Straight down, then 50° off the normal: E = F_t(θ)·cos θ·E_light (eq. 3.8).
  const double theta = arcus_test::rad(50);
  const std::vector<arcus_directional_light> slanted{{{std::sin(theta), 0, std::cos(theta)}, {1, 1, 1}}};
  for (const auto* lights : {&kOverhead, &slanted}) {
    const double cos_i = (*lights)[0].direction[2];
    double error_auto[3] = {0, 0, 0};
    for (double spacing : {0.0, 0.15}) {
      auto p = looking_down(4, 0.4);
      p.gather = ARCUS_GATHER_BRUTE_FORCE;
      p.sample_spacing_mm = spacing;
      const Image img = render(mesh.mesh, d, *lights, p);
      ASSERT_EQ(img.stats.covered_pixels, 16u);
      EXPECT_EQ(img.features, ARCUS_FEATURE_TRANSLUCENCY_DIPOLE);
      for (int c = 0; c < 3; ++c) {
        const double expected = (1 - fresnel(1, d.eta)) / M_PI * closed_total(d.sigma_a[c], d.sigma_s_prime[c], d.eta) *
                                (1 - fresnel(cos_i, d.eta)) * cos_i;
        double worst = 0;
        for (int px = 0; px < 16; ++px) worst = std::max(worst, std::fabs(img.rgb[3 * px + c] / expected - 1));
        EXPECT_LT(worst, 1e-3) << "channel " << c << " spacing " << img.stats.sample_spacing_mm << " cos_i " << cos_i;
        if (spacing == 0)
          error_auto[c] = worst;
        else
          EXPECT_LE(worst, error_auto[c] + 1e-6) << "channel " << c;
      }
    }
  }
}

// The exit term as an option: NORMALIZED is THESIS divided by 1 − 2·FM1(η), which for
// η = 1.3 is 0.939 (the hemispherical integral of (1/π)F_t cos θ, done here by Simpson).
TEST_F(TranslucencyRender, NormalizedExitDividesByTheExitTransmittance) {
  MeshHandle mesh = slab(ctx());
  const arcus_dipole d = test_medium();
  double transmittance = 0;
  const int n = 2000;
  for (int i = 0; i <= n; ++i) {
    const double mu = double(i) / n;
    transmittance += (i == 0 || i == n ? 1 : i % 2 ? 4 : 2) * 2 * (1 - (mu > 0 ? fresnel(mu, d.eta) : 1)) * mu;
  }
  transmittance /= 3.0 * n;
  EXPECT_NEAR(transmittance, 0.939, 0.001);
  auto p = looking_down(2, 0.4);
  p.gather = ARCUS_GATHER_BRUTE_FORCE;
  const Image thesis = render(mesh.mesh, d, kOverhead, p);
  p.exit = ARCUS_EXIT_NORMALIZED;
  const Image normalized = render(mesh.mesh, d, kOverhead, p);
  for (size_t k = 0; k < thesis.rgb.size(); ++k) EXPECT_NEAR(normalized.rgb[k] * transmittance / thesis.rgb[k], 1, 1e-5);
}

// Energy scaling (§5.2): stretching by s keeps R_total, so a wide slab's centre is
// unchanged; the thesis' R_d(r/s) multiplies it by s².
TEST_F(TranslucencyRender, ProfileScalingKeepsOrScalesTheSlab) {
  MeshHandle mesh = slab(ctx());
  const arcus_dipole d = test_medium();
  auto p = looking_down(2, 0.4);
  p.gather = ARCUS_GATHER_BRUTE_FORCE;
  const Image plain = render(mesh.mesh, d, kOverhead, p);
  p.profile_scale = 1.5;
  const Image energy = render(mesh.mesh, d, kOverhead, p);
  p.profile_scaling = ARCUS_PROFILE_SCALE_THESIS;
  const Image thesis = render(mesh.mesh, d, kOverhead, p);
  for (size_t k = 0; k < plain.rgb.size(); ++k) {
    EXPECT_NEAR(energy.rgb[k] / plain.rgb[k], 1, 1e-3);
    EXPECT_NEAR(thesis.rgb[k] / plain.rgb[k], 2.25, 2.25e-3);
  }
}

// The hierarchical gather at its default bound against every sample, over a sphere of
// radius 10 mm under two lights, seen whole by a pinhole: RMSE within 1% of the mean
// radiance (issue 21, §2), for the short-ranged test medium and for marble, whose red
// diffusion length (8.5 mm) nearly spans the sphere.  Also at 0.4 sr, 80× the bound
// Jensen & Buhler's centroid alone needed here (0.005 sr: at 0.05 sr it was 37% off on a
// slab): the second-order term over the node's spread keeps it within the 1% (measured
// 3–4 × 10⁻³; docs/translucency.md's table).
TEST_F(TranslucencyRender, HierarchicalAgreesWithBruteForce) {
  std::vector<double> v;
  std::vector<uint32_t> t;
  icosphere(4, &v, &t);
  MeshHandle mesh(ctx(), v, t);
  arcus_dipole marble{};
  ASSERT_EQ(arcus_translucency_dipole_from_material("marble", &marble), ARCUS_SUCCESS);
  for (const arcus_dipole& d : {test_medium(), marble}) {
    auto p = looking_down(40, 0);
    p.camera.position[2] = 4;  // 4 radii away: a 30° view holds the whole sphere
    p.mm_per_unit = 10;
    p.highlight_deg = 10;
    const std::vector<arcus_directional_light> lights{{{1, 1, 1}, {1, 0.8, 0.6}}, {{-1, 0, 0.2}, {0.2, 0.3, 0.5}}};
    p.gather = ARCUS_GATHER_BRUTE_FORCE;
    const Image brute = render(mesh.mesh, d, lights, p);
    p.gather = ARCUS_GATHER_HIERARCHICAL;
    for (const double bound : {0.0, 0.4}) {  // 0: the default
    p.max_solid_angle = bound;
    const Image tree = render(mesh.mesh, d, lights, p);
    EXPECT_EQ(tree.features, ARCUS_FEATURE_TRANSLUCENCY_DIPOLE | ARCUS_FEATURE_TRANSLUCENCY_HIERARCHICAL);
    ASSERT_EQ(brute.covered, tree.covered);
    ASSERT_GT(brute.stats.covered_pixels, 800u);
    double sum2 = 0, mean = 0;
    size_t n = 0;
    for (size_t px = 0; px < brute.covered.size(); ++px)
      if (brute.covered[px])
        for (int c = 0; c < 3; ++c) {
          const double a = brute.subsurface[3 * px + c], b = tree.subsurface[3 * px + c];
          sum2 += (a - b) * (a - b);
          mean += a;
          ++n;
        }
    const double rmse = std::sqrt(sum2 / double(n)), relative = rmse / (mean / double(n));
    std::printf("bound %g sr: samples %llu, nodes %llu, %.1f visits a pixel; relative RMSE %.2e; gather %.3f s vs "
                "%.3f s\n", bound, (unsigned long long)tree.stats.samples, (unsigned long long)tree.stats.tree_nodes,
                tree.stats.mean_visits, relative, tree.stats.gather_seconds, brute.stats.gather_seconds);
    EXPECT_LT(relative, 0.01) << "bound " << bound;
    EXPECT_GT(tree.stats.mean_visits, 1.0);
    EXPECT_LT(tree.stats.mean_visits, double(tree.stats.tree_nodes));
    }
  }
}

// The genetic search from C: a 24-pixel render of the test medium as the target, a few
// generations; the history's best never rises, the callback sees every generation and
// stops the search when asked (tests/python/test_translucency_genetic.py checks what it
// finds).
int32_t stop_after_two(void* user, uint32_t generation, double, const double*) {
  ++*static_cast<uint32_t*>(user);
  return generation >= 2;
}

TEST_F(TranslucencyRender, AGeneticSearchRunsFromCAndStopsWhenAsked) {
  std::vector<double> v;
  std::vector<uint32_t> t;
  icosphere(2, &v, &t);
  MeshHandle mesh(ctx(), v, t);
  auto p = looking_down(24, 0);
  p.camera.position[2] = 4;
  p.mm_per_unit = 10;
  const std::vector<arcus_directional_light> lights{{{1, 1, 1}, {1, 0.8, 0.6}}};
  const Image target = render(mesh.mesh, test_medium(), lights, p);
  arcus_genetic_params g{};
  ASSERT_EQ(arcus_translucency_genetic_params_init(ARCUS_GENETIC_DIPOLE, &g), ARCUS_SUCCESS);
  EXPECT_EQ(g.population, 40u);
  EXPECT_EQ(g.initial[7], 1.3);  // Table 3.1's η
  EXPECT_EQ(g.polish_steps, 20u);
  g.camera = p.camera;
  g.mm_per_unit = p.mm_per_unit;
  g.population = 8;
  g.generations = 4;
  arcus_job_t* job = nullptr;
  ASSERT_EQ(arcus_translucency_genetic(ctx(), mesh.mesh, 24, 24, target.rgb.data(), lights.size(), lights.data(), &g,
                                       &job),
            ARCUS_SUCCESS)
      << last_error();
  arcus_genetic_result r{};
  ASSERT_EQ(arcus_job_get_translucency_genetic(job, &r), ARCUS_SUCCESS);
  EXPECT_EQ(r.gene_count, 9u);
  EXPECT_EQ(r.generations_run, 4u);
  EXPECT_EQ(r.evaluations, 8u + 4u * 6u);  // 80% of 8, rounded: 6 replaced a generation
  std::vector<double> best(5), mean(5), genes(5 * 9);
  ASSERT_EQ(arcus_job_get_translucency_genetic_history(job, best.data(), mean.data(), genes.data()), ARCUS_SUCCESS);
  for (size_t k = 1; k < best.size(); ++k) EXPECT_LE(best[k], best[k - 1]);
  EXPECT_EQ(best.back(), r.search_fitness);
  EXPECT_LE(r.best_fitness, r.search_fitness);  // the polish keeps only steps that lower it
  EXPECT_LE(r.polish_steps, 20u);
  EXPECT_GT(r.polish_evaluations, 0u);
  std::vector<float> image(24 * 24 * 3);
  ASSERT_EQ(arcus_job_get_translucency_genetic_image(job, image.data()), ARCUS_SUCCESS);
  arcus_job_release(job);
  uint32_t calls = 0;
  g.on_generation = stop_after_two;
  g.generation_user = &calls;
  job = nullptr;
  EXPECT_EQ(arcus_translucency_genetic(ctx(), mesh.mesh, 24, 24, target.rgb.data(), lights.size(), lights.data(), &g,
                                       &job),
            ARCUS_ERROR_CANCELLED);
  EXPECT_EQ(calls, 3u);  // generations 0, 1, 2
  ASSERT_NE(job, nullptr);
  ASSERT_EQ(arcus_job_get_translucency_genetic(job, &r), ARCUS_SUCCESS);
  EXPECT_EQ(r.generations_run, 2u);
  arcus_job_release(job);
  g.population = 1;
  job = nullptr;
  expect_invalid(arcus_translucency_genetic(ctx(), mesh.mesh, 24, 24, target.rgb.data(), lights.size(),
                                            lights.data(), &g, &job),
                 "params->population", "population 1");
  EXPECT_EQ(job, nullptr);
  g.population = 8;
  g.polish_steps = 1001;
  expect_invalid(arcus_translucency_genetic(ctx(), mesh.mesh, 24, 24, target.rgb.data(), lights.size(),
                                            lights.data(), &g, &job),
                 "params->polish_steps", "1001");
  EXPECT_EQ(job, nullptr);
}

// A light from below reaches the top only through 10 mm of medium (8–20 diffusion
// lengths: e^{−8} and less); a plate above the slab's centre shadows it.
TEST_F(TranslucencyRender, LightsFacingAwayAndOccludersGiveNoLight) {
  MeshHandle open = slab(ctx());
  {
    auto p = looking_down(2, 0.4);
    const Image lit = render(open.mesh, test_medium(), kOverhead, p);
    const Image below = render(open.mesh, test_medium(), {{{0, 0.3, -1}, {1, 1, 1}}}, p);
    for (size_t k = 0; k < lit.rgb.size(); ++k) EXPECT_LT(below.rgb[k], 1e-3 * lit.rgb[k]) << k;
  }
  // A 30 × 30 mm plate 30 mm above the centre, wide enough that the light reaching the
  // slab lands 15 mm or more (12+ diffusion lengths: e^{−12}·13 of R_total) from it.
  // The plate is of the same medium (one mesh, one medium): R_d joins any two surface
  // points, so it is put 24+ diffusion lengths away, where what it passes on is nil.
  std::vector<double> v;
  std::vector<uint32_t> t;
  slab_arrays(&v, &t);
  const double plate_lo[3] = {-15, -15, 30}, plate_hi[3] = {15, 15, 30.1};
  box(plate_lo, plate_hi, &v, &t);
  MeshHandle mesh(ctx(), v, t);
  auto p = looking_down(2, 0.4);
  p.camera.position[2] = 20;  // below the plate
  const Image shaded = render(mesh.mesh, test_medium(), kOverhead, p);
  const Image lit = render(open.mesh, test_medium(), kOverhead, p);
  for (size_t k = 0; k < lit.rgb.size(); ++k) EXPECT_LT(shaded.rgb[k], 2e-3 * lit.rgb[k]) << k;
}

// Winding: the same box wound inwards renders the same (normals follow the volume's sign).
TEST_F(TranslucencyRender, InwardWindingIsTurnedOutwards) {
  std::vector<double> v;
  std::vector<uint32_t> t;
  slab_arrays(&v, &t);
  std::vector<uint32_t> flipped = t;
  for (size_t f = 0; f < flipped.size(); f += 3) std::swap(flipped[f + 1], flipped[f + 2]);
  MeshHandle out(ctx(), v, t), in(ctx(), v, flipped);
  auto p = looking_down(2, 0.4);
  p.gather = ARCUS_GATHER_BRUTE_FORCE;
  const Image a = render(out.mesh, test_medium(), kOverhead, p), b = render(in.mesh, test_medium(), kOverhead, p);
  for (size_t k = 0; k < a.rgb.size(); ++k) EXPECT_NEAR(b.rgb[k], a.rgb[k], 1e-6 * a.rgb[k]);
}

TEST_F(TranslucencyRender, BadInputIsRefusedNamingIt) {
  std::vector<double> v;
  std::vector<uint32_t> t;
  const double lo[3] = {-1, -1, -1}, hi[3] = {1, 1, 1};
  box(lo, hi, &v, &t);
  MeshHandle mesh(ctx(), v, t);
  const arcus_dipole good = test_medium();
  arcus_translucency_render_params base{};
  ASSERT_EQ(arcus_translucency_render_params_init(&base), ARCUS_SUCCESS);
  arcus_job_t* job = nullptr;
  auto attempt = [&](const arcus_dipole& d, const std::vector<arcus_directional_light>& lights,
                     const arcus_translucency_render_params& p, const char* argument) {
    job = nullptr;
    expect_invalid(arcus_translucency_render(ctx(), mesh.mesh, &d, lights.size(), lights.data(), &p, &job), argument,
                   argument);
    EXPECT_EQ(job, nullptr);
  };
  auto with = [&](auto change) {
    arcus_translucency_render_params p = base;
    change(p);
    return p;
  };
  arcus_dipole bad = good;
  bad.sigma_s_prime[1] = 0;
  attempt(bad, kOverhead, base, "sigma_s_prime[1]");
  bad = good;
  bad.eta = 0.5;
  attempt(bad, kOverhead, base, "eta");
  attempt(good, {}, base, "light_count");
  attempt(good, {{{0, 0, 0}, {1, 1, 1}}}, base, "lights[0].direction");
  attempt(good, {{{0, 0, 1}, {1, -1, 1}}}, base, "lights[0].irradiance[1]");
  attempt(good, {{{0, 0, 1}, {1, NAN, 1}}}, base, "lights[0].irradiance[1]");
  attempt(good, kOverhead, with([](auto& p) { p.camera.width = 0; }), "params->camera");
  attempt(good, kOverhead, with([](auto& p) { p.ortho_height = -1; }), "params->ortho_height");
  attempt(good, kOverhead, with([](auto& p) { p.mm_per_unit = 0; }), "params->mm_per_unit");
  attempt(good, kOverhead, with([](auto& p) { p.exit = 2; }), "params->exit");
  attempt(good, kOverhead, with([](auto& p) { p.profile_scale = INFINITY; }), "params->profile_scale");
  attempt(good, kOverhead, with([](auto& p) { p.profile_scaling = -1; }), "params->profile_scaling");
  attempt(good, kOverhead, with([](auto& p) { p.gather = 7; }), "params->gather");
  attempt(good, kOverhead, with([](auto& p) { p.max_solid_angle = -0.01; }), "params->max_solid_angle");
  attempt(good, kOverhead, with([](auto& p) { p.highlight_deg = 90; }), "params->highlight_deg");
  // Samples beyond 2^22 are refused before they are made, naming the spacing.
  attempt(good, kOverhead, with([](auto& p) { p.sample_spacing_mm = 1e-4; }), "params->sample_spacing_mm");
  expect_invalid(arcus_translucency_render(ctx(), nullptr, &good, 1, kOverhead.data(), &base, &job), "mesh", "mesh");
  expect_invalid(arcus_translucency_render(ctx(), mesh.mesh, nullptr, 1, kOverhead.data(), &base, &job), "dipole",
                 "dipole");
  expect_invalid(arcus_translucency_render(ctx(), mesh.mesh, &good, 1, kOverhead.data(), nullptr, &job), "params",
                 "params");
  expect_invalid(arcus_translucency_render(ctx(), mesh.mesh, &good, 1, nullptr, &base, &job), "lights", "lights");
  // A tabulated profile: each field checked by name.
  std::vector<double> values(3 * 16, 0.01);
  arcus_profile_table table{16, 5.0, values.data(), 1.3};
  auto table_attempt = [&](arcus_profile_table t, const char* argument) {
    job = nullptr;
    expect_invalid(arcus_translucency_render_table(ctx(), mesh.mesh, &t, kOverhead.size(), kOverhead.data(), &base,
                                                   &job),
                   argument, argument);
    EXPECT_EQ(job, nullptr);
  };
  table_attempt({1, 5.0, values.data(), 1.3}, "profile->count");
  table_attempt({16, 0.0, values.data(), 1.3}, "profile->reach_mm");
  table_attempt({16, 5.0, nullptr, 1.3}, "profile->values");
  table_attempt({16, 5.0, values.data(), 0.5}, "profile->eta");
  values[7] = -1;
  table_attempt(table, "profile->values[7]");
  values[7] = NAN;
  table_attempt(table, "profile->values[7]");
  std::fill(values.begin(), values.end(), 0.0);
  table_attempt(table, "profile->values");
  expect_invalid(arcus_translucency_render_table(ctx(), mesh.mesh, nullptr, 1, kOverhead.data(), &base, &job),
                 "profile", "profile");
  // A mesh file that is not there: an I/O error naming it.
  arcus_mesh_t* missing = nullptr;
  EXPECT_EQ(arcus_mesh_load(ctx(), "no/such/mesh.ply", &missing), ARCUS_ERROR_IO);
  EXPECT_TRUE(arcus_test::contains_ci(arcus_context_last_error(ctx()), "no/such/mesh.ply"));
  EXPECT_EQ(missing, nullptr);
  // Another context's mesh.
  arcus_context_t* other = nullptr;
  ASSERT_EQ(arcus_context_create(ARCUS_DEVICE_DEFAULT, &other), ARCUS_SUCCESS);
  {
    MeshHandle foreign(other, v, t);
    expect_invalid(arcus_translucency_render(ctx(), foreign.mesh, &good, 1, kOverhead.data(), &base, &job), "mesh",
                   "another context's mesh");
  }
  arcus_context_release(other);
}

}  // namespace
