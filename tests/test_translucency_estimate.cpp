// Estimating a BSSRDF from one photograph (arcus_translucency_estimate, thesis §3.3.1)
// against the truth behind synthetic photos: a sphere of each of Jensen et al. 2001's six
// materials of Table 3.3, 40 mm across, lit by two directional lights and rendered
// through the dipole (arcus_translucency_render), is estimated back.  The photos are the library's own
// renders, but the estimate shares none of their sampling (pixels' front and back
// points against the renderer's surface samples), so what it recovers is the medium,
// not a copy of the render.  Bad input is refused naming it.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "test_util.h"
#include "translucency_fixture.h"

namespace {

using arcus_test::ArcusTest;

const std::vector<arcus_directional_light> kLights{{{0.3, 0.5, 1}, {1, 1, 1}}, {{-1, 0.2, 0.3}, {0.3, 0.3, 0.3}}};
constexpr uint32_t kSide = 200;

class TranslucencyEstimate : public ArcusTest {
 protected:
  static arcus_translucency_render_params view() {
    arcus_translucency_render_params p{};
    EXPECT_EQ(arcus_translucency_render_params_init(&p), ARCUS_SUCCESS);
    p.camera = arcus_camera{{0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 30, kSide, kSide};
    p.ortho_height = 2.2;  // the thesis' orthographic photographs
    p.mm_per_unit = 20;    // a sphere 40 mm across
    p.highlight_deg = 0;
    return p;
  }
  std::vector<float> photo(arcus_mesh_t* mesh, const arcus_dipole& d) {
    const arcus_translucency_render_params p = view();
    arcus_job_t* job = nullptr;
    EXPECT_EQ(arcus_translucency_render(ctx(), mesh, &d, kLights.size(), kLights.data(), &p, &job), ARCUS_SUCCESS)
        << last_error();
    std::vector<float> rgb(3 * kSide * kSide);
    if (job) {
      EXPECT_EQ(arcus_job_get_translucency_image(job, rgb.data(), nullptr, nullptr), ARCUS_SUCCESS);
    }
    arcus_job_release(job);
    return rgb;
  }
  static arcus_translucency_estimate_params estimate_params(double eta) {
    arcus_translucency_estimate_params e{};
    EXPECT_EQ(arcus_translucency_estimate_params_init(&e), ARCUS_SUCCESS);
    const arcus_translucency_render_params p = view();
    e.camera = p.camera;
    e.ortho_height = p.ortho_height;
    e.mm_per_unit = p.mm_per_unit;
    e.eta = eta;
    e.subtract_minimum = 0;  // the photo has no indirect light to remove
    return e;
  }
  arcus_translucency_estimate_result estimate(arcus_mesh_t* mesh, const std::vector<float>& rgb,
                                              const arcus_translucency_estimate_params& e) {
    arcus_job_t* job = nullptr;
    arcus_translucency_estimate_result r{};
    EXPECT_EQ(arcus_translucency_estimate(ctx(), mesh, kSide, kSide, rgb.data(), nullptr, kLights.size(),
                                          kLights.data(), &e, &job),
              ARCUS_SUCCESS)
        << last_error();
    if (job) {
      EXPECT_EQ(arcus_job_get_translucency_estimate(job, &r), ARCUS_SUCCESS);
    }
    arcus_job_release(job);
    return r;
  }
};

// Issue 21 §6: R_total within 3% per channel, and ℓ_d within 15% where ℓ_d is below a
// quarter of the object's size (10 mm).  Measured: R_total within 0.6%, ℓ_d within 10%.
// Asserted for apple and skim milk only: docs/translucency.md's table of six materials
// shows cream's green and potato's and whole milk's blue missing the ℓ_d bound (the
// image hardly constrains a 2 mm profile on a 40 mm sphere), which is not hidden here.
TEST_F(TranslucencyEstimate, RecoversJensensMaterialsFromSyntheticPhotos) {
  std::vector<double> v;
  std::vector<uint32_t> t;
  icosphere(5, &v, &t);
  MeshHandle mesh(ctx(), v, t);
  // The bounds: R_total within 3%, ℓ_d within 15% where ℓ_d is below a quarter of
  // the object (10 mm) — cream's green and potato's and whole milk's blue (2–5 mm) are
  // the hard ones: a profile a few pixels long.
  for (const char* name : {"apple", "cream", "marble", "potato", "skimmilk", "wholemilk"}) {
    arcus_dipole truth{};
    ASSERT_EQ(arcus_translucency_dipole_from_material(name, &truth), ARCUS_SUCCESS);
    arcus_dipole_terms want{};
    ASSERT_EQ(arcus_translucency_dipole_get_terms(&truth, &want), ARCUS_SUCCESS);
    const arcus_translucency_estimate_result got = estimate(mesh.mesh, photo(mesh.mesh, truth), estimate_params(truth.eta));
    EXPECT_EQ(got.width, kSide);
    EXPECT_GT(got.equation_pixels, 20000u);
    EXPECT_NEAR(got.r_max_mm, 40, 0.01);  // the sphere's diameter
    for (int c = 0; c < 3; ++c) {
      const double total = got.terms.total_reflectance[c] / want.total_reflectance[c] - 1;
      const double length = got.terms.diffuse_length[c] / want.diffuse_length[c] - 1;
      std::printf("%s channel %d: R_total %+.2f%%, l_d %+.1f%% (true %.2f mm); condition %.2e, %d QMR steps\n", name,
                  c, 100 * total, 100 * length, want.diffuse_length[c], got.condition_a[c], got.iterations[c]);
      EXPECT_LT(std::fabs(total), 0.03) << name << " channel " << c;
      if (want.diffuse_length[c] < 10) {
        EXPECT_LT(std::fabs(length), 0.15) << name << " channel " << c;
      }
      EXPECT_TRUE(got.residual[c] < 1e-8) << got.residual[c];
      EXPECT_GT(got.condition_a[c], 1);
    }
  }
}

// A determinism test: the same photo estimated twice gives the same numbers bit for bit.
TEST_F(TranslucencyEstimate, TheSameInputGivesTheSameEstimate) {
  std::vector<double> v;
  std::vector<uint32_t> t;
  icosphere(3, &v, &t);
  MeshHandle mesh(ctx(), v, t);
  arcus_dipole d{};
  ASSERT_EQ(arcus_translucency_dipole_from_material("skimmilk", &d), ARCUS_SUCCESS);
  const std::vector<float> rgb = photo(mesh.mesh, d);
  auto e = estimate_params(1.3);
  e.max_side = 64;
  const auto a = estimate(mesh.mesh, rgb, e), b = estimate(mesh.mesh, rgb, e);
  for (int c = 0; c < 3; ++c) {
    EXPECT_EQ(a.dipole.sigma_a[c], b.dipole.sigma_a[c]);
    EXPECT_EQ(a.dipole.sigma_s_prime[c], b.dipole.sigma_s_prime[c]);
  }
  EXPECT_EQ(a.width, 50u);  // 200 / 4: box-filtered down by a whole factor to at most 64
}

// The system and its sources are read back per channel (tests/python/test_translucency_system.py
// checks their values against NumPy); a fourth channel is refused naming it.
TEST_F(TranslucencyEstimate, TheSystemIsReadBackPerChannel) {
  std::vector<double> v;
  std::vector<uint32_t> t;
  icosphere(2, &v, &t);
  MeshHandle mesh(ctx(), v, t);
  arcus_dipole d{};
  ASSERT_EQ(arcus_translucency_dipole_from_material("skimmilk", &d), ARCUS_SUCCESS);
  const std::vector<float> rgb = photo(mesh.mesh, d);
  auto e = estimate_params(1.3);
  e.max_side = 32;
  e.basis_count = 8;
  arcus_job_t* job = nullptr;
  ASSERT_EQ(arcus_translucency_estimate(ctx(), mesh.mesh, kSide, kSide, rgb.data(), nullptr, kLights.size(),
                                        kLights.data(), &e, &job),
            ARCUS_SUCCESS)
      << last_error();
  arcus_translucency_estimate_result r{};
  ASSERT_EQ(arcus_job_get_translucency_estimate(job, &r), ARCUS_SUCCESS);
  const size_t n = r.equation_pixels, s = 2 * size_t(r.object_pixels);
  std::vector<double> a(n * 8), b(n), x(8), rows(3 * n), sources(3 * s), weights(3 * s), near(3 * n);
  for (uint32_t c = 0; c < 3; ++c) {
    ASSERT_EQ(arcus_job_get_translucency_system(job, c, a.data(), b.data(), x.data()), ARCUS_SUCCESS);
    double predicted = 0, measured = 0;  // A x against b: the image error the result reports
    for (size_t i = 0; i < n; ++i) {
      double p = 0;
      for (size_t h = 0; h < 8; ++h) p += a[i * 8 + h] * x[h];
      predicted += std::fabs(p - b[i]);
      measured += std::fabs(b[i]);
    }
    EXPECT_NEAR(predicted / measured, r.image_error[c], 1e-12);
  }
  ASSERT_EQ(arcus_job_get_translucency_sources(job, rows.data(), sources.data(), weights.data(), near.data()),
            ARCUS_SUCCESS);
  EXPECT_EQ(r.basis, ARCUS_BASIS_PIECEWISE_CONSTANT);
  EXPECT_GT(r.near_radius_mm, 0);
  expect_invalid(arcus_job_get_translucency_system(job, 3, a.data(), nullptr, nullptr), "channel", "channel 3");
  arcus_job_release(job);
}

TEST_F(TranslucencyEstimate, BadInputIsRefusedNamingIt) {
  std::vector<double> v;
  std::vector<uint32_t> t;
  icosphere(2, &v, &t);
  MeshHandle mesh(ctx(), v, t);
  std::vector<float> rgb(3 * kSide * kSide);
  for (size_t i = 0; i < rgb.size(); ++i) rgb[i] = 0.1f + 1e-6f * float(i);  // no two alike: nothing clipped
  const arcus_translucency_estimate_params good = estimate_params(1.3);
  arcus_job_t* job = nullptr;
  auto attempt = [&](const std::vector<float>& photo, const uint8_t* matte,
                     const std::vector<arcus_directional_light>& lights, const arcus_translucency_estimate_params& e,
                     const char* argument) {
    job = nullptr;
    expect_invalid(arcus_translucency_estimate(ctx(), mesh.mesh, kSide, kSide, photo.data(), matte, lights.size(),
                                               lights.data(), &e, &job),
                   argument, argument);
    EXPECT_EQ(job, nullptr);
  };
  std::vector<float> bad = rgb;
  bad[3 * (kSide * 7 + 5) + 1] = NAN;
  attempt(bad, nullptr, kLights, good, "pixel 5, 7");
  bad[3 * (kSide * 7 + 5) + 1] = -1;
  attempt(bad, nullptr, kLights, good, "photo[");
  const std::vector<uint8_t> empty(kSide * kSide, 0);
  attempt(rgb, empty.data(), kLights, good, "matte");
  attempt(rgb, nullptr, {{{0, 0, 1}, {0, 0, 0}}}, good, "no light");
  attempt(rgb, nullptr, {}, good, "light_count");
  auto e = good;
  e.basis_count = 1;
  attempt(rgb, nullptr, kLights, e, "params->basis_count");
  e = good;
  e.basis = ARCUS_BASIS_LEGENDRE + 1;
  attempt(rgb, nullptr, kLights, e, "params->basis");
  e = good;
  e.tikhonov = -1e-3;
  attempt(rgb, nullptr, kLights, e, "params->tikhonov");
  e.tikhonov = NAN;
  attempt(rgb, nullptr, kLights, e, "params->tikhonov");
  e = good;
  e.nonnegative = 2;
  attempt(rgb, nullptr, kLights, e, "params->nonnegative");
  e = good;
  e.eta = 0.9;
  attempt(rgb, nullptr, kLights, e, "params->eta");
  e = good;
  e.fit = 5;
  attempt(rgb, nullptr, kLights, e, "params->fit");
  e = good;
  e.camera.width = 100;  // the photo is 200 wide
  attempt(rgb, nullptr, kLights, e, "params->camera");
  e = good;
  e.camera.look_at[0] = 200;  // the view turned away: the mesh is not seen
  attempt(rgb, nullptr, kLights, e, "camera");
  expect_invalid(arcus_translucency_estimate(ctx(), mesh.mesh, kSide, kSide, nullptr, nullptr, kLights.size(),
                                             kLights.data(), &good, &job),
                 "photo", "photo");
  // Clipped: every pixel at one value.
  attempt(std::vector<float>(rgb.size(), 0.5f), nullptr, kLights, good, "clipped");
  // A matte off the mesh's projection: the left half of the image only.
  std::vector<uint8_t> left(kSide * kSide, 0);
  for (uint32_t y = 0; y < kSide; ++y)
    for (uint32_t x = 0; x < kSide / 2; ++x) left[y * kSide + x] = 1;
  attempt(rgb, left.data(), kLights, good, "IoU");
  // An open mesh: the sphere less one triangle.
  std::vector<uint32_t> holed(t.begin() + 3, t.end());
  MeshHandle open(ctx(), v, holed);
  expect_invalid(arcus_translucency_estimate(ctx(), open.mesh, kSide, kSide, rgb.data(), nullptr, kLights.size(),
                                             kLights.data(), &good, &job),
                 "closed", "an open mesh");
}

}  // namespace
