// The ocean engine through the public C API: defaults, handles, bad input (a status
// and a message naming the argument, nothing lost), getters on the wrong job, a trace's
// books, cancellation, and an image from a scene file.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "arcus/arcus.h"

namespace {

struct Ctx {
  arcus_context_t* ctx = nullptr;
  Ctx() { EXPECT_EQ(arcus_context_create(ARCUS_DEVICE_DEFAULT, &ctx), ARCUS_SUCCESS) << arcus_last_error(); }
  ~Ctx() {
    if (ctx) arcus_context_release(ctx);
  }
};

arcus_water_t* thesis_water(arcus_context_t* ctx) {
  arcus_bio_optical bio;
  EXPECT_EQ(arcus_bio_optical_init(&bio), ARCUS_SUCCESS);
  arcus_water_t* w = nullptr;
  EXPECT_EQ(arcus_water_create(ctx, &bio, &w), ARCUS_SUCCESS) << arcus_context_last_error(ctx);
  return w;
}

// A point lamp of 1 W/nm at the origin, and a default setup and trace it lights.
struct Lamp {
  double nm = 550, value = 1;
  arcus_ocean_light light{};
  arcus_ocean_setup setup;
  arcus_ocean_trace_params params;
  Lamp() {
    light.kind = ARCUS_OCEAN_LIGHT_POINT;
    light.spectrum = {1, &nm, &value};
    light.half_angle_deg = 30;
    arcus_ocean_setup_init(&setup);
    setup.light_count = 1;
    setup.lights = &light;
    arcus_ocean_trace_params_init(&params);
  }
  Lamp(const Lamp&) = delete;  // setup points at light
};

TEST(OceanApi, DefaultsAreTheThesis) {
  arcus_bio_optical bio;
  ASSERT_EQ(arcus_bio_optical_init(&bio), ARCUS_SUCCESS);
  EXPECT_EQ(bio.s_y, 0.014);  // Table 4.3
  EXPECT_EQ(bio.s_d, 0.011);
  EXPECT_EQ(bio.chlorophyll_yield, 0.1);
  arcus_ocean_trace_params p;
  ASSERT_EQ(arcus_ocean_trace_params_init(&p), ARCUS_SUCCESS);
  EXPECT_EQ(p.photons, 400000u);
  EXPECT_EQ(p.max_interactions, 5u);  // §5.3
  EXPECT_EQ(p.wavelengths_per_photon, 4u);  // hero wavelengths: 3 on the 81-sample grid
  arcus_ocean_march m;
  ASSERT_EQ(arcus_ocean_march_init(&m), ARCUS_SUCCESS);
  EXPECT_EQ(m.steps, 200u);
  EXPECT_EQ(m.k, 250u);
  EXPECT_EQ(m.estimate_stride, 1u);  // the thesis': every pixel
  EXPECT_EQ(m.photon_tile, 0.0);     // photons through the lights' discs
  EXPECT_EQ(m.step_subsample, 1u);   // the per-step estimate at every step
  arcus_ocean_setup s;
  ASSERT_EQ(arcus_ocean_setup_init(&s), ARCUS_SUCCESS);
  EXPECT_EQ(s.grid.first_nm, 380);
  EXPECT_EQ(s.grid.count, 81u);
  EXPECT_TRUE(std::isinf(s.bottom_depth));
  EXPECT_EQ(arcus_bio_optical_preset("atlantic", &bio), ARCUS_SUCCESS);
  EXPECT_EQ(arcus_bio_optical_preset("lake", &bio), ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(std::string(arcus_last_error()).find("atlantic"), std::string::npos);
}

TEST(OceanApi, HandlesAreChecked) {
  Ctx c;
  arcus_water_t* w = thesis_water(c.ctx);
  EXPECT_EQ(arcus_water_retain(w), ARCUS_SUCCESS);
  EXPECT_EQ(arcus_water_release(w), ARCUS_SUCCESS);
  arcus_wavelength_grid g{400, 10, 31};
  std::vector<double> events(10 * 31);
  EXPECT_EQ(arcus_water_get_coefficients(w, &g, events.data(), nullptr, nullptr), ARCUS_SUCCESS);
  // A context where water is expected: the wrong type, refused with a message.
  EXPECT_EQ(arcus_water_get_coefficients(reinterpret_cast<arcus_water_t*>(c.ctx), &g, events.data(), nullptr, nullptr),
            ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(arcus_water_release(nullptr), ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(arcus_water_release(w), ARCUS_SUCCESS);
}

TEST(OceanApi, BadInputNamesTheArgumentAndLosesNothing) {
  Ctx c;
  arcus_bio_optical bio;
  arcus_bio_optical_init(&bio);
  bio.chlorophyll = -1;
  arcus_water_t* w = nullptr;
  EXPECT_EQ(arcus_water_create(c.ctx, &bio, &w), ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(w, nullptr);
  EXPECT_NE(std::string(arcus_context_last_error(c.ctx)).find("chlorophyll"), std::string::npos);

  w = thesis_water(c.ctx);
  Lamp lamp;
  arcus_ocean_setup& s = lamp.setup;
  arcus_ocean_trace_params& p = lamp.params;
  p.photons = 1000;
  arcus_job_t* job = nullptr;
  s.bottom_albedo = 1.5;
  EXPECT_EQ(arcus_ocean_trace(c.ctx, w, &s, &p, &job), ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(std::string(arcus_context_last_error(c.ctx)).find("bottom_albedo"), std::string::npos);
  EXPECT_EQ(job, nullptr);
  s.bottom_albedo = 0;
  s.grid = {200, 5, 10};  // below the grid's 300 nm
  EXPECT_EQ(arcus_ocean_trace(c.ctx, w, &s, &p, &job), ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(std::string(arcus_context_last_error(c.ctx)).find("grid"), std::string::npos);
  arcus_ocean_setup_init(&s);
  s.light_count = 1;
  s.lights = &lamp.light;  // a fresh setup: the water still works after the failures
  ASSERT_EQ(arcus_ocean_trace(c.ctx, w, &s, &p, &job), ARCUS_SUCCESS) << arcus_context_last_error(c.ctx);
  // An ocean job is no render job, and a trace has no image.
  arcus_render_stats rs;
  EXPECT_EQ(arcus_job_get_render_stats(job, &rs), ARCUS_ERROR_INVALID_ARGUMENT);
  arcus_ocean_render_stats os;
  EXPECT_EQ(arcus_job_get_ocean_render_stats(job, &os), ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(std::string(arcus_context_last_error(c.ctx)).find("not an ocean render"), std::string::npos);
  arcus_job_release(job);
  arcus_water_release(w);
}

TEST(OceanApi, ALightTooFarForThePhotonMapIsRefusedNotAnAbort) {
  // A point lamp at x = -3e38 m in an unbounded ocean: its photons' positions reached
  // Embree's builder, whose binning overflowed single precision and aborted the process.
  Ctx c;
  arcus_water_t* w = thesis_water(c.ctx);
  Lamp lamp;
  lamp.light.position[0] = -3e38;
  lamp.params.photons = 1000;
  arcus_job_t* job = nullptr;
  EXPECT_EQ(arcus_ocean_trace(c.ctx, w, &lamp.setup, &lamp.params, &job), ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(job, nullptr);
  const std::string message = arcus_context_last_error(c.ctx);
  EXPECT_NE(message.find("lights[0].position"), std::string::npos) << message;
  EXPECT_NE(message.find("1e+18"), std::string::npos) << message;
  lamp.light.position[0] = -1e17;  // within the bound: traced (it is far, and dark, but fine)
  EXPECT_EQ(arcus_ocean_trace(c.ctx, w, &lamp.setup, &lamp.params, &job), ARCUS_SUCCESS) << arcus_context_last_error(c.ctx);
  arcus_job_release(job);
  arcus_water_release(w);
}

TEST(OceanApi, ATraceBalancesItsEnergyAndReportsItsFeatures) {
  Ctx c;
  arcus_water_t* w = thesis_water(c.ctx);
  Lamp lamp;
  arcus_ocean_setup& s = lamp.setup;
  arcus_ocean_trace_params& p = lamp.params;
  p.photons = 20000;
  arcus_job_t* job = nullptr;
  ASSERT_EQ(arcus_ocean_trace(c.ctx, w, &s, &p, &job), ARCUS_SUCCESS) << arcus_context_last_error(c.ctx);
  arcus_ocean_tallies t;
  ASSERT_EQ(arcus_job_get_ocean_tallies(job, &t), ARCUS_SUCCESS);
  EXPECT_EQ(t.photons, 20000u);
  // Every photon's power is booked once: exact to rounding.
  EXPECT_NEAR(t.absorbed + t.escaped + t.past_limit + t.bottom, t.emitted, 1e-9 * t.emitted);
  std::vector<double> absorbed(t.interaction_bins + 1), escaped(t.interaction_bins + 1);
  EXPECT_EQ(arcus_job_get_ocean_by_interaction(job, absorbed.data(), escaped.data()), ARCUS_SUCCESS);
  double sum = 0;
  for (double a : absorbed) sum += a;
  EXPECT_NEAR(sum, t.absorbed, 1e-12 * t.emitted);
  arcus_features f = 0;
  ASSERT_EQ(arcus_job_get_features(job, &f), ARCUS_SUCCESS);
  EXPECT_EQ(f, ARCUS_FEATURE_OCEAN_INELASTIC);  // unbounded, no depths: nothing else
  char names[128];
  ASSERT_EQ(arcus_features_to_string(f, names, sizeof names), ARCUS_SUCCESS);
  EXPECT_STREQ(names, "OCEAN_INELASTIC");
  arcus_job_release(job);
  arcus_water_release(w);
}

int32_t cancel_at_once(void*, double fraction) { return fraction > 0 ? 1 : 0; }

TEST(OceanApi, ACancelledTraceKeepsWhatItTraced) {
  Ctx c;
  arcus_water_t* w = thesis_water(c.ctx);
  Lamp lamp;
  arcus_ocean_setup& s = lamp.setup;
  arcus_ocean_trace_params& p = lamp.params;
  p.photons = 50000000;  // far more than one slice
  p.progress = cancel_at_once;
  arcus_job_t* job = nullptr;
  ASSERT_EQ(arcus_ocean_trace(c.ctx, w, &s, &p, &job), ARCUS_ERROR_CANCELLED);
  ASSERT_NE(job, nullptr);
  arcus_ocean_tallies t;
  ASSERT_EQ(arcus_job_get_ocean_tallies(job, &t), ARCUS_SUCCESS);
  EXPECT_GT(t.photons, 0u);
  EXPECT_LT(t.photons, p.photons);
  EXPECT_NEAR(t.absorbed + t.escaped + t.past_limit + t.bottom, t.emitted, 1e-9 * t.emitted);
  arcus_job_release(job);
  arcus_water_release(w);
}

TEST(OceanApi, ASceneFileRendersAnImage) {
  Ctx c;
  arcus_scene_t* scene = nullptr;
  ASSERT_EQ(arcus_scene_load(c.ctx, ARCUS_SOURCE_DIR "/scenes/ocean/atlantic.json", &scene), ARCUS_SUCCESS)
      << arcus_context_last_error(c.ctx);
  const char* engine = nullptr;
  ASSERT_EQ(arcus_scene_get_engine(scene, &engine), ARCUS_SUCCESS);
  EXPECT_STREQ(engine, "ocean");
  arcus_scene_release(scene);

  // The same view, small and cheap, through the struct API.
  arcus_bio_optical bio;
  arcus_bio_optical_preset("atlantic", &bio);
  arcus_water_t* w = nullptr;
  ASSERT_EQ(arcus_water_create(c.ctx, &bio, &w), ARCUS_SUCCESS);
  Lamp lamp;
  lamp.light.position[0] = 4;
  lamp.light.position[2] = -10;
  arcus_ocean_setup& s = lamp.setup;
  s.grid = {400, 50, 7};
  arcus_ocean_trace_params& p = lamp.params;
  p.photons = 20000;
  arcus_camera cam{{0, 0, -10}, {1, 0, -10}, {0, 0, 1}, 50, 8, 6};
  arcus_ocean_march m;
  arcus_ocean_march_init(&m);
  m.steps = 20;
  m.k = 20;
  m.estimator = ARCUS_OCEAN_ESTIMATE_BEAM;
  arcus_job_t* job = nullptr;
  ASSERT_EQ(arcus_ocean_render(c.ctx, w, &s, &p, &cam, &m, &job), ARCUS_SUCCESS) << arcus_context_last_error(c.ctx);
  uint32_t width = 0, height = 0, samples = 0;
  ASSERT_EQ(arcus_job_get_ocean_image(job, &width, &height, &samples, nullptr, nullptr, nullptr), ARCUS_SUCCESS);
  EXPECT_EQ(width, 8u);
  EXPECT_EQ(height, 6u);
  EXPECT_EQ(samples, 7u);
  std::vector<float> rgb(width * height * 3);
  std::vector<double> nm(samples);
  ASSERT_EQ(arcus_job_get_ocean_image(job, nullptr, nullptr, nullptr, nm.data(), rgb.data(), nullptr), ARCUS_SUCCESS);
  EXPECT_EQ(nm[6], 700);
  for (float v : rgb) EXPECT_TRUE(std::isfinite(v));
  arcus_features f = 0;
  arcus_job_get_features(job, &f);
  EXPECT_TRUE(f & ARCUS_FEATURE_OCEAN_BEAM);
  EXPECT_TRUE(f & ARCUS_FEATURE_OCEAN_PHOTON_MAP);
  // A render job is a trace too: its books are there.
  arcus_ocean_tallies t;
  EXPECT_EQ(arcus_job_get_ocean_tallies(job, &t), ARCUS_SUCCESS);
  EXPECT_EQ(t.photons, 20000u);
  arcus_job_release(job);
  // A sky lights an image from above a surface, and not without one.
  lamp.light.kind = ARCUS_OCEAN_LIGHT_SKY;
  EXPECT_EQ(arcus_ocean_render(c.ctx, w, &s, &p, &cam, &m, &job), ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(std::string(arcus_context_last_error(c.ctx)).find("surface"), std::string::npos)
      << arcus_context_last_error(c.ctx);
  s.surface = 1;
  ASSERT_EQ(arcus_ocean_render(c.ctx, w, &s, &p, &cam, &m, &job), ARCUS_SUCCESS) << arcus_context_last_error(c.ctx);
  arcus_job_release(job);
  arcus_water_release(w);
}

}  // namespace
