// Estimating a BSSRDF from a photo that light transport took, not the dipole: independent
// Monte Carlo tracers (tests/sphere_mc.h, tests/box_mc.h, no code shared with arcus)
// photograph Jensen et al. 2001's apple as a sphere 40 mm across (50 × 50 pixels) and as
// a 40 × 30 × 20 mm box seen obliquely (60 × 60), under the two directional lights of
// test_translucency_estimate.cpp, and arcus_translucency_estimate reads each with exit =
// NORMALIZED (the tracers' boundary lets out all that reaches it and is not reflected, as
// the normalized exit term does).
//
// Issue 21 §6 asks for R_total within 5% of the medium's and a re-render within an RMSE
// of 5% of the photo's mean radiance.  The second holds; the first does not quite, and
// not through the estimate: the true medium's own dipole render is 4–7% darker than the
// transport photo.  The dipole starts every entering photon at depth 1/σ′_t whatever its
// angle and lets light out by F_t alone; with one light at the camera, transport is 2–3%
// brighter than it where light enters and leaves near the normal and 11–22% brighter at
// grazing angles, and these photos are mostly lit obliquely.  So the estimate, which can
// only match the photo, comes out 5.6–6.0% high.  Asserted instead: the estimate's
// R_total against the truth times what the photo shows over the truth's render, within
// 3% (the bound the issue sets for photos the dipole itself rendered).
// docs/translucency.md has the figures.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "box_mc.h"
#include "sphere_mc.h"
#include "test_util.h"
#include "translucency_fixture.h"

namespace {

using arcus_test::ArcusTest;

const std::vector<arcus_directional_light> kLights{{{0.3, 0.5, 1}, {1, 1, 1}}, {{-1, 0.2, 0.3}, {0.3, 0.3, 0.3}}};
constexpr int kSide = 50;  // 0.9 mm pixels: the photo's shot noise ~6% a pixel at 2 × 10^5 photons a light
constexpr double kRadiusMm = 20, kOrthoHeight = 2.2;  // mesh units: 20 mm each

// Per channel, the RMSE of `b` against `a` over the pixels both see, over a's mean there.
std::vector<double> relative_rmse(const std::vector<float>& a, const std::vector<float>& b,
                                  const std::vector<uint8_t>& covered) {
  std::vector<double> out;
  for (int c = 0; c < 3; ++c) {
    double squares = 0, sum = 0;
    size_t count = 0;
    for (size_t i = 0; i < covered.size(); ++i)
      if (covered[i]) squares += std::pow(b[3 * i + c] - a[3 * i + c], 2), sum += a[3 * i + c], ++count;
    out.push_back(std::sqrt(squares / count) / (sum / count));
  }
  return out;
}

// An orthographic view: the camera, its frame's height in mesh units, mm per unit.
struct Shot {
  arcus_camera camera;
  double ortho_height, mm_per_unit;
};

class TranslucencyMcPhoto : public ArcusTest {
 protected:
  static Shot sphere_shot() { return {arcus_camera{{0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 30, kSide, kSide}, kOrthoHeight, kRadiusMm}; }

  // The sphere tracer's photo, RGB floats top row first, one channel's medium at a time.
  static std::vector<float> monte_carlo_photo(const arcus_dipole& d, uint64_t photons, uint64_t seed) {
    std::vector<sphere_mc::Light> lights;
    for (const auto& l : kLights) lights.push_back({{l.direction[0], l.direction[1], l.direction[2]}, l.irradiance[0]});
    const sphere_mc::View view{kRadiusMm, kOrthoHeight * kRadiusMm, kSide};
    std::vector<float> rgb(3 * kSide * kSide);
    for (int c = 0; c < 3; ++c) {
      const sphere_mc::Medium m{d.sigma_a[c], d.sigma_s_prime[c], d.eta};
      const std::vector<double> channel = sphere_mc::photo(m, lights, view, photons, seed + c, 2);
      for (size_t i = 0; i < channel.size(); ++i) rgb[3 * i + c] = static_cast<float>(channel[i]);
    }
    return rgb;
  }

  std::vector<float> render(arcus_mesh_t* mesh, const arcus_dipole& d, const Shot& shot, std::vector<uint8_t>* covered) {
    arcus_translucency_render_params p{};
    EXPECT_EQ(arcus_translucency_render_params_init(&p), ARCUS_SUCCESS);
    p.camera = shot.camera;
    p.ortho_height = shot.ortho_height;
    p.mm_per_unit = shot.mm_per_unit;
    p.highlight_deg = 0;
    p.exit = ARCUS_EXIT_NORMALIZED;
    arcus_job_t* job = nullptr;
    EXPECT_EQ(arcus_translucency_render(ctx(), mesh, &d, kLights.size(), kLights.data(), &p, &job), ARCUS_SUCCESS)
        << last_error();
    const size_t pixels = size_t(shot.camera.width) * shot.camera.height;
    std::vector<float> rgb(3 * pixels);
    covered->assign(pixels, 0);
    if (job) {
      EXPECT_EQ(arcus_job_get_translucency_image(job, rgb.data(), nullptr, covered->data()), ARCUS_SUCCESS);
    }
    arcus_job_release(job);
    return rgb;
  }

  // What check_estimate asserts (0: printed only).
  struct Bounds {
    double total_of_shown;  // |R_total over the truth times what the photo shows over the truth's render − 1|
    double total_of_truth;  // |R_total over the truth − 1|, where α′ >= 0.99 (diffusion's regime)
    double model;           // the re-render's RMSE less the photo's noise, over the photo's mean ...
    bool model_diffusive;   // ... where α′ >= 0.99 only, or in every channel
    double noise;           // the photo's own noise (it is what the comments say it is)
  };

  // Estimates the medium from a transport photo made of two independent halves, re-renders
  // it, prints the figures and asserts `bounds`.
  void check_estimate(arcus_mesh_t* mesh, const arcus_dipole& truth, const std::vector<float>& half_a,
                      const std::vector<float>& half_b, const Shot& shot, const Bounds& bounds) {
    arcus_dipole_terms want{};
    ASSERT_EQ(arcus_translucency_dipole_get_terms(&truth, &want), ARCUS_SUCCESS);
    std::vector<float> photo(half_a.size());
    for (size_t i = 0; i < photo.size(); ++i) photo[i] = 0.5f * (half_a[i] + half_b[i]);
    std::vector<uint8_t> covered;
    const std::vector<float> truth_render = render(mesh, truth, shot, &covered);
    const std::vector<double> halves = relative_rmse(half_a, half_b, covered);

    arcus_translucency_estimate_params e{};
    ASSERT_EQ(arcus_translucency_estimate_params_init(&e), ARCUS_SUCCESS);
    e.camera = shot.camera;
    e.ortho_height = shot.ortho_height;
    e.mm_per_unit = shot.mm_per_unit;
    e.eta = truth.eta;
    e.exit = ARCUS_EXIT_NORMALIZED;
    e.subtract_minimum = 0;  // no indirect light to remove
    arcus_job_t* job = nullptr;
    ASSERT_EQ(arcus_translucency_estimate(ctx(), mesh, shot.camera.width, shot.camera.height, photo.data(), nullptr,
                                          kLights.size(), kLights.data(), &e, &job),
              ARCUS_SUCCESS)
        << last_error();
    arcus_translucency_estimate_result got{};
    ASSERT_EQ(arcus_job_get_translucency_estimate(job, &got), ARCUS_SUCCESS);
    arcus_job_release(job);

    const std::vector<float> again = render(mesh, got.dipole, shot, &covered);
    const std::vector<double> error = relative_rmse(photo, again, covered);
    for (int c = 0; c < 3; ++c) {
      double photo_sum = 0, truth_sum = 0;
      for (size_t i = 0; i < covered.size(); ++i)
        if (covered[i]) photo_sum += photo[3 * i + c], truth_sum += truth_render[3 * i + c];
      const double shown = photo_sum / truth_sum;  // transport over the true dipole
      const double total = got.terms.total_reflectance[c] / want.total_reflectance[c];
      // The photo's noise is independent of the model's error: they add in quadrature.
      const double noise = 0.5 * halves[c], model = std::sqrt(std::max(0.0, error[c] * error[c] - noise * noise));
      std::printf(
          "channel %d: the photo %.3f x the true dipole's render; R_total %+.2f%% of the truth, %+.2f%% of what the "
          "photo shows; l_d %+.0f%%; re-render RMSE %.2f%% (the photo's noise %.2f%%, the model %.2f%%)\n",
          c, shown, 100 * (total - 1), 100 * (total / shown - 1),
          100 * (got.terms.diffuse_length[c] / want.diffuse_length[c] - 1), 100 * error[c], 100 * noise, 100 * model);
      const bool diffusive = truth.sigma_s_prime[c] / (truth.sigma_a[c] + truth.sigma_s_prime[c]) >= 0.99;
      if (bounds.total_of_shown > 0) {
        EXPECT_LT(std::fabs(total / shown - 1), bounds.total_of_shown) << "channel " << c;
      }
      if (bounds.total_of_truth > 0 && diffusive) {
        EXPECT_LT(std::fabs(total - 1), bounds.total_of_truth) << "channel " << c;
      }
      if (diffusive || !bounds.model_diffusive) {
        EXPECT_LT(model, bounds.model) << "channel " << c;
      }
      EXPECT_LT(noise, bounds.noise) << "channel " << c;
    }
  }
};

// The tracer's camera against its own flux, by symmetry: a sphere lit from directions
// uniform over all of space sends the same intensity every way, so what the camera sees
// (Σ radiance × pixel area, the intensity toward +z) is the flux that leaves over 4π.
// This checks the next-event estimate (root, Fresnel, solid-angle magnification) against
// plain photon counting.  At 40 000 photons the ratio's spread over eight seeds is 0.8%
// (0.987 to 1.013), so 3% is four of those.
TEST(SphereMonteCarlo, TheCameraSeesTheFluxThatLeavesOverFourPi) {
  for (const sphere_mc::Medium m : {sphere_mc::Medium{0.003, 2.29, 1.3}, sphere_mc::Medium{0.3, 1, 1.5}}) {
    const sphere_mc::View view{kRadiusMm, kOrthoHeight * kRadiusMm, kSide};
    const sphere_mc::Tracer tracer(m, view);
    std::vector<double> image(kSide * kSide, 0.0);
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> uniform(0, 1);
    const int photons = 40000;
    double left = 0;
    for (int p = 0; p < photons; ++p) {
      const double cz = 1 - 2 * uniform(rng), phi = 2 * M_PI * uniform(rng), sz = std::sqrt(1 - cz * cz);
      left += tracer.photon({sz * std::cos(phi), sz * std::sin(phi), cz}, 1.0 / photons, rng, &image);
    }
    const double pixel = view.frame_mm / view.side;
    double intensity = 0;
    for (const double radiance : image) intensity += radiance * pixel * pixel;
    std::printf("albedo %.3f: intensity toward the camera %.5f, the flux that left / 4 pi %.5f\n",
                m.sigma_s / (m.sigma_a + m.sigma_s), intensity, left / (4 * M_PI));
    EXPECT_NEAR(intensity / (left / (4 * M_PI)), 1, 0.03);
  }
}

TEST_F(TranslucencyMcPhoto, EstimatesAppleFromAMonteCarloPhoto) {
#if defined(__SANITIZE_ADDRESS__)
  // 1.2 million photons take minutes instrumented, and the library's part of this test
  // (estimate, render) runs instrumented in test_translucency_estimate already.
  GTEST_SKIP() << "the Monte Carlo photo is too slow under AddressSanitizer";
#endif
  std::vector<double> v;
  std::vector<uint32_t> t;
  icosphere(5, &v, &t);
  MeshHandle mesh(ctx(), v, t);
  arcus_dipole truth{};
  ASSERT_EQ(arcus_translucency_dipole_from_material("apple", &truth), ARCUS_SUCCESS);
  // Two independent halves: their difference measures the photo's own noise.
  const std::vector<float> half_a = monte_carlo_photo(truth, 100000, 21), half_b = monte_carlo_photo(truth, 100000, 42);
  check_estimate(mesh.mesh, truth, half_a, half_b, sphere_shot(), {0.03, 0, 0.05, false, 0.08});

  // The same photo's lights found from it alone (thesis §3.4, Fig. 3.10 on a photo that
  // transport took, with its shot noise): the main light within Fig. 3.10's 20°
  // (measured 10.5°).  The second, 0.3 as bright and grazing (73° from the view), is not
  // told apart on these 50 × 50 pixels: apple carries light ~4 mm past the terminator on
  // a 20 mm sphere, and the contour model's wrap takes its lobe up (docs/translucency-
  // photo.md), so one light is found.
  std::vector<float> photo(half_a.size());
  for (size_t i = 0; i < photo.size(); ++i) photo[i] = 0.5f * (half_a[i] + half_b[i]);
  std::vector<uint8_t> covered;
  render(mesh.mesh, truth, sphere_shot(), &covered);
  arcus_light_detection found{};
  ASSERT_EQ(arcus_translucency_detect_lights(ctx(), kSide, kSide, photo.data(), covered.data(), &found), ARCUS_SUCCESS)
      << last_error();
  ASSERT_GE(found.count, 1u);
  const double* want = kLights[0].direction;
  const double norm = std::sqrt(want[0] * want[0] + want[1] * want[1] + want[2] * want[2]);
  const double* got = found.lights[0].direction;
  const double degrees =
      std::acos(std::min(1.0, (got[0] * want[0] + got[1] * want[1] + got[2] * want[2]) / norm)) * 180 / M_PI;
  std::printf("%u light(s); the strongest at azimuth %.1f°, zenith %.1f°: %.1f° from the main light\n", found.count,
              found.lights[0].azimuth_deg, found.lights[0].zenith_deg, degrees);
  EXPECT_LT(degrees, 20);
}

// The box tracer's camera against photon counting: under one light, the intensity its
// next-event estimate sends toward the camera (Σ radiance × pixel area) against the flux
// of the photons that leave within 10° of that direction over the cone's solid angle.
// This checks the flat faces' inner rays, the étendue factor (η² off would be 69–125%)
// and the framing.  Over six seeds at 400 000 photons the ratio spread 0.96–1.01 (albedo
// 0.999, mean 0.985) and 0.91–0.99 (0.769, mean 0.959: the cone's average sits ~2% below
// its centre there, half that at 5°), so 8% is three of those spreads' deviations.
TEST(BoxMonteCarlo, TheCameraSeesWhatLeavesTowardIt) {
  const double lo[3] = {-10, -7.5, -5}, hi[3] = {10, 7.5, 5};
  const box_mc::Camera camera{{0.5, 0.6, 0.8}, {0, 1, 0}, {0, 0, 0}, 40, 40};
  const box_mc::V3 toward = box_mc::unit(camera.toward), to_light = box_mc::unit({0.3, 0.5, 1});
  const double cone = std::cos(10 * M_PI / 180);
  for (const box_mc::Medium m : {box_mc::Medium{0.003, 2.29, 1.3}, box_mc::Medium{0.3, 1, 1.5}}) {
    const box_mc::Tracer tracer(m, lo, hi, camera);
    std::vector<double> image(40 * 40, 0.0);
    std::mt19937_64 rng(7);
    const int photons = 400000;
    double in_cone = 0;
    for (int p = 0; p < photons; ++p) {
      int face = 0;
      double projected = 0;
      const box_mc::V3 x = tracer.entry(to_light, rng, &face, &projected);
      box_mc::V3 leaving{0, 0, 0};
      const double w = tracer.photon(x, face, to_light, projected / photons, rng, &image, &leaving);
      if (w > 0 && box_mc::dot(leaving, toward) > cone) in_cone += w;
    }
    const double pixel = camera.frame_mm / camera.side;
    double intensity = 0;
    for (const double radiance : image) intensity += radiance * pixel * pixel;
    const double counted = in_cone / (2 * M_PI * (1 - cone));
    std::printf("albedo %.3f: intensity toward the camera %.5f, counted in a 10-degree cone %.5f (ratio %.4f)\n",
                m.sigma_s / (m.sigma_a + m.sigma_s), intensity, counted, intensity / counted);
    EXPECT_NEAR(intensity / counted, 1, 0.08);
  }
}

// The box, seen obliquely (three faces), under the same two lights: the bounds,
// R_total within 5% of the medium's and the re-render's model error within 5%, asserted in
// the channels diffusion describes (apple's red and green, α′ = 0.999; measured +4.9% and
// +4.7%, 4.5% and 4.3%); apple's blue (α′ = 0.977) is reported: the transport photo is 6%
// brighter than the true dipole's render there (oblique light, as on the sphere) and the
// estimate +8%.  120 × 120 pixels: at 60 × 60 the estimate from the true dipole's own
// noise-free render is already +3.5% off (+2.1% at 120², +1.0% at 200²: docs/translucency.md).
// The noise bound is this photo's (4 × 10^5 photons a light and channel over 14 400 pixels).
TEST_F(TranslucencyMcPhoto, EstimatesAppleFromAMonteCarloPhotoOfABox) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "the Monte Carlo photo is too slow under AddressSanitizer";
#endif
  constexpr int kBoxSide = 120;       // 0.42 mm pixels
  constexpr double kMmPerUnit = 10;   // the box is 40 × 30 × 20 mm
  const double lo[3] = {-2, -1.5, -1}, hi[3] = {2, 1.5, 1};
  std::vector<double> v;
  std::vector<uint32_t> t;
  box(lo, hi, &v, &t);
  MeshHandle mesh(ctx(), v, t);
  const Shot shot{arcus_camera{{4, 3, 5}, {0, 0, 0}, {0, 1, 0}, 30, kBoxSide, kBoxSide}, 5.0, kMmPerUnit};
  arcus_dipole truth{};
  ASSERT_EQ(arcus_translucency_dipole_from_material("apple", &truth), ARCUS_SUCCESS);

  const double lo_mm[3] = {lo[0] * kMmPerUnit, lo[1] * kMmPerUnit, lo[2] * kMmPerUnit};
  const double hi_mm[3] = {hi[0] * kMmPerUnit, hi[1] * kMmPerUnit, hi[2] * kMmPerUnit};
  const box_mc::Camera camera{{4, 3, 5}, {0, 1, 0}, {0, 0, 0}, shot.ortho_height * kMmPerUnit, kBoxSide};
  std::vector<box_mc::Light> lights;
  for (const auto& l : kLights) lights.push_back({{l.direction[0], l.direction[1], l.direction[2]}, l.irradiance[0]});
  auto photo = [&](uint64_t photons, uint64_t seed) {
    std::vector<float> rgb(3 * kBoxSide * kBoxSide);
    for (int c = 0; c < 3; ++c) {
      const box_mc::Medium m{truth.sigma_a[c], truth.sigma_s_prime[c], truth.eta};
      const std::vector<double> channel = box_mc::photo(m, lo_mm, hi_mm, lights, camera, photons, seed + c, 2);
      for (size_t i = 0; i < channel.size(); ++i) rgb[3 * i + c] = static_cast<float>(channel[i]);
    }
    return rgb;
  };
  check_estimate(mesh.mesh, truth, photo(200000, 21), photo(200000, 42), shot, {0, 0.05, 0.05, true, 0.09});
}

}  // namespace
