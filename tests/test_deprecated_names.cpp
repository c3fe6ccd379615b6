// The spellings renamed in arcus 0.10 (arcus_core.h, "Names") still resolve, for one
// release: every old function is exported and answers exactly as its new name, every
// old feature macro is the new bit.  A determinism test by nature: old against new.
#include <dlfcn.h>

#include <cmath>
#include <fstream>

#include "test_util.h"

// Calling the old names is the point here.
#pragma GCC diagnostic ignored "-Wdeprecated-declarations"

using namespace arcus_test;

namespace {

class DeprecatedNames : public ArcusTest {};

TEST_F(DeprecatedNames, EveryOldSymbolIsExported) {
  for (const char* name :
       {"arcus_advance", "arcus_scene_advance", "arcus_job_get_end_states", "arcus_job_get_failures",
        "arcus_job_get_path_size", "arcus_job_get_paths", "arcus_job_get_image_size", "arcus_job_get_image",
        "arcus_job_get_hits", "arcus_job_write_image", "arcus_refractive_index", "arcus_job_rainbow_phase",
        "arcus_job_rainbow_phasors", "arcus_mie", "arcus_mie_debye"})
    EXPECT_NE(dlsym(RTLD_DEFAULT, name), nullptr) << name;
}

TEST_F(DeprecatedNames, OldFeatureMacrosAreTheNewBits) {
  EXPECT_EQ(ARCUS_FEATURE_DP45, ARCUS_FEATURE_CURVED_DP45);
  EXPECT_EQ(ARCUS_FEATURE_FIELD_GRID, ARCUS_FEATURE_CURVED_FIELD_GRID);
  EXPECT_EQ(ARCUS_FEATURE_RECORD_PATH, ARCUS_FEATURE_CURVED_RECORD_PATH);
  EXPECT_EQ(ARCUS_FEATURE_GEOMETRY, ARCUS_FEATURE_RENDER_GEOMETRY);
  EXPECT_EQ(ARCUS_FEATURE_RECORD_STATE, ARCUS_FEATURE_RENDER_RECORD_STATE);
  char names[64];
  ASSERT_EQ(arcus_features_to_string(ARCUS_FEATURE_DP45, names, sizeof names), ARCUS_SUCCESS);
  EXPECT_STREQ(names, "CURVED_DP45");
}

TEST_F(DeprecatedNames, CurvedCallsAnswerAsTheirNewNames) {
  const FieldPtr field = linear(1.0, {0, 0.1, 0});
  arcus_advance_params p;
  ASSERT_EQ(arcus_advance_params_init(&p), ARCUS_SUCCESS);
  p.length = 10;
  p.record_path = 1;
  const double origins[6] = {0, 0, 0, 0, 1, 0}, directions[6] = {1, 0, 0, 1, 0.1, 0};
  arcus_job_t *old_job = nullptr, *new_job = nullptr;
  ASSERT_EQ(arcus_advance(ctx(), field.get(), &p, 2, origins, directions, nullptr, &old_job), ARCUS_SUCCESS);
  JobPtr old_owner(old_job);
  ASSERT_EQ(arcus_curved_advance(ctx(), field.get(), &p, 2, origins, directions, nullptr, &new_job), ARCUS_SUCCESS);
  JobPtr new_owner(new_job);
  double old_end[6], new_end[6];
  ASSERT_EQ(arcus_job_get_end_states(old_job, old_end, nullptr, nullptr, nullptr, nullptr), ARCUS_SUCCESS);
  ASSERT_EQ(arcus_job_get_curved_end_states(new_job, new_end, nullptr, nullptr, nullptr, nullptr), ARCUS_SUCCESS);
  for (int i = 0; i < 6; ++i) EXPECT_EQ(old_end[i], new_end[i]) << i;
  int32_t old_fail[2], new_fail[2];
  ASSERT_EQ(arcus_job_get_failures(old_job, old_fail), ARCUS_SUCCESS);
  ASSERT_EQ(arcus_job_get_curved_failures(new_job, new_fail), ARCUS_SUCCESS);
  EXPECT_EQ(old_fail[0], new_fail[0]);
  size_t old_points = 0, new_points = 0;
  ASSERT_EQ(arcus_job_get_path_size(old_job, &old_points), ARCUS_SUCCESS);
  ASSERT_EQ(arcus_job_get_curved_path_size(new_job, &new_points), ARCUS_SUCCESS);
  ASSERT_EQ(old_points, new_points);
  std::vector<uint64_t> offsets(3);
  std::vector<double> old_path(3 * old_points), new_path(3 * new_points);
  ASSERT_EQ(arcus_job_get_paths(old_job, offsets.data(), old_path.data(), nullptr), ARCUS_SUCCESS);
  ASSERT_EQ(arcus_job_get_curved_paths(new_job, offsets.data(), new_path.data(), nullptr), ARCUS_SUCCESS);
  EXPECT_EQ(old_path, new_path);
}

TEST_F(DeprecatedNames, SceneAndRenderCallsAnswerAsTheirNewNames) {
  const std::string path = temp_path("deprecated_render") + ".json";
  std::ofstream(path) << R"({"name": "t", "medium": {"type": "constant", "n": 1.0},
      "integrator": {"method": "dp45", "rtol": 1e-12, "atol": 1e-6, "length": 1000},
      "camera": {"position": [0, 0, 0], "look_at": [1, 0, 0], "vfov_deg": 40, "width": 4, "height": 3},
      "materials": {"m": {"diffuse": [0.5, 0.5, 0.5]}},
      "objects": [{"type": "sphere", "center": [5, 0, 0], "radius": 1, "material": "m"}],
      "sky": {"type": "constant", "color": [0.2, 0.3, 0.4]}})";
  arcus_scene_t* scene = nullptr;
  ASSERT_EQ(arcus_scene_load(ctx(), path.c_str(), &scene), ARCUS_SUCCESS) << last_error();
  arcus_renderer_t* renderer = nullptr;
  ASSERT_EQ(arcus_renderer_create(scene, &renderer), ARCUS_SUCCESS) << last_error();
  arcus_job_t* job = nullptr;
  ASSERT_EQ(arcus_render_frame(renderer, nullptr, nullptr, &job), ARCUS_SUCCESS) << last_error();
  uint32_t w = 0, h = 0, w2 = 0, h2 = 0;
  ASSERT_EQ(arcus_job_get_image_size(job, &w, &h), ARCUS_SUCCESS);
  ASSERT_EQ(arcus_job_get_render_image_size(job, &w2, &h2), ARCUS_SUCCESS);
  EXPECT_EQ(w, 4u);
  EXPECT_EQ(h, 3u);
  EXPECT_EQ(w2, w);
  EXPECT_EQ(h2, h);
  std::vector<float> old_rgb(3 * w * h), new_rgb(3 * w * h);
  ASSERT_EQ(arcus_job_get_image(job, old_rgb.data()), ARCUS_SUCCESS);
  ASSERT_EQ(arcus_job_get_render_image(job, new_rgb.data()), ARCUS_SUCCESS);
  EXPECT_EQ(old_rgb, new_rgb);
  std::vector<int32_t> old_objects(w * h), new_objects(w * h);
  ASSERT_EQ(arcus_job_get_hits(job, nullptr, old_objects.data(), nullptr, nullptr, nullptr, nullptr), ARCUS_SUCCESS);
  ASSERT_EQ(arcus_job_get_render_hits(job, nullptr, new_objects.data(), nullptr, nullptr, nullptr, nullptr),
            ARCUS_SUCCESS);
  EXPECT_EQ(old_objects, new_objects);
  const std::string png = temp_path("deprecated_render") + ".png";
  EXPECT_EQ(arcus_job_write_image(job, nullptr, png.c_str()), ARCUS_SUCCESS) << last_error();
  EXPECT_TRUE(std::ifstream(png).good());
  arcus_job_release(job);
  arcus_renderer_release(renderer);
  // A render scene is not a curved one: both spellings refuse it alike.
  job = nullptr;
  EXPECT_EQ(arcus_scene_advance(scene, nullptr, nullptr, &job), arcus_curved_advance_scene(scene, nullptr, nullptr, &job));
  arcus_scene_release(scene);
}

TEST_F(DeprecatedNames, RainbowCallsAnswerAsTheirNewNamesInTheirOwnUnits) {
  double old_n = 0, new_n = 0;
  ASSERT_EQ(arcus_refractive_index(ARCUS_MATERIAL_WATER, 589.3, 20.0, &old_n), ARCUS_SUCCESS);  // °C
  ASSERT_EQ(arcus_rainbow_refractive_index(ARCUS_MATERIAL_WATER, 589.3, 293.15, &new_n), ARCUS_SUCCESS);
  EXPECT_EQ(old_n, new_n);

  const double theta[3] = {30, 90, 138};
  double old_par[3], new_par[3], old_perp[3], new_perp[3];
  ASSERT_EQ(arcus_mie(1e-6, 550, 1.333, 0, 3, theta, nullptr, nullptr, old_par, old_perp, nullptr), ARCUS_SUCCESS);
  ASSERT_EQ(arcus_rainbow_mie(1e-6, 550, 1.333, 0, 3, theta, nullptr, nullptr, new_par, new_perp, nullptr),
            ARCUS_SUCCESS);
  double old_debye[6], new_debye[6];
  ASSERT_EQ(arcus_mie_debye(1e-6, 550, 1.333, 0, 1, 3, theta, nullptr, nullptr, old_debye, nullptr), ARCUS_SUCCESS);
  ASSERT_EQ(arcus_rainbow_mie_debye(1e-6, 550, 1.333, 0, 1, 3, theta, nullptr, nullptr, new_debye, nullptr),
            ARCUS_SUCCESS);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(old_par[i], new_par[i]) << i;
  for (int i = 0; i < 6; ++i) EXPECT_EQ(old_debye[i], new_debye[i]) << i;

  arcus_particle_t* sphere = nullptr;
  ASSERT_EQ(arcus_particle_create_sphere(ctx(), 1e-4, &sphere), ARCUS_SUCCESS);
  arcus_rainbow_params params;
  arcus_rainbow_params_init(&params);
  params.grid = 64;
  arcus_job_t *old_job = nullptr, *new_job = nullptr;
  params.temperature_c = 10;  // the deprecated °C field of 0.9 ...
  ASSERT_EQ(arcus_rainbow_cast(ctx(), sphere, &params, &old_job), ARCUS_SUCCESS) << last_error();
  arcus_rainbow_params_init(&params);
  params.grid = 64;
  params.temperature_k = 283.15;  // ... is the same water as 283.15 K
  ASSERT_EQ(arcus_rainbow_cast(ctx(), sphere, &params, &new_job), ARCUS_SUCCESS) << last_error();
  arcus_rainbow_stats old_stats, new_stats;
  ASSERT_EQ(arcus_job_get_rainbow_stats(old_job, &old_stats), ARCUS_SUCCESS);
  ASSERT_EQ(arcus_job_get_rainbow_stats(new_job, &new_stats), ARCUS_SUCCESS);
  EXPECT_DOUBLE_EQ(old_stats.refractive_index, new_stats.refractive_index);  // °C → K rounds in the last bit
  double old_phase[3], new_phase[3], old_phasors[3 * 4 * 2 * 4], new_phasors[3 * 4 * 2 * 4];
  ASSERT_EQ(arcus_job_rainbow_phase(new_job, 3, theta, nullptr, 1, old_phase, nullptr, nullptr), ARCUS_SUCCESS);
  ASSERT_EQ(arcus_job_get_rainbow_phase(new_job, 3, theta, nullptr, 1, new_phase, nullptr, nullptr), ARCUS_SUCCESS);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(old_phase[i], new_phase[i]) << i;
  ASSERT_EQ(arcus_job_rainbow_phasors(new_job, 3, theta, nullptr, old_phasors), ARCUS_SUCCESS) << last_error();
  ASSERT_EQ(arcus_job_get_rainbow_phasors(new_job, 3, theta, nullptr, new_phasors), ARCUS_SUCCESS);
  for (int i = 0; i < 3 * 4 * 2 * 4; ++i) EXPECT_EQ(old_phasors[i], new_phasors[i]) << i;
  arcus_job_release(old_job);
  arcus_job_release(new_job);
  arcus_particle_release(sphere);
}

}  // namespace
