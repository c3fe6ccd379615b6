// Ocean scene files (src/ocean/scene.cpp, schema: scenes/README.md, "Ocean scenes"):
// every bundled scene loads and says what its file name says (thesis §5.3, Fig. 5.8,
// 5.10, 5.11); bad input fails at load with the file name and the JSON path, the
// library's own checks (check_water, check_trace) included; arcus_scene_load hands an
// ocean scene to the ocean engine.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "arcus/arcus.h"
#include "core/error.h"
#include "ocean/scene.h"
#include "unit_util.h"

#ifndef ARCUS_SOURCE_DIR
#define ARCUS_SOURCE_DIR "."
#endif

namespace {

namespace fs = std::filesystem;
using arcus::ocean::Light;
using arcus::ocean::MarchParams;
using arcus::ocean::OceanSceneDesc;
using arcus::ocean::read_ocean_scene;
using arcus::ocean::Water;
using arcus_unit::Context;
using arcus_unit::TempDir;

const fs::path kScenes = fs::path(ARCUS_SOURCE_DIR) / "scenes" / "ocean";
constexpr double kPi = 3.14159265358979323846;

std::vector<fs::path> bundled_scenes() {
  std::vector<fs::path> files;
  for (const auto& e : fs::recursive_directory_iterator(kScenes))
    if (e.is_regular_file() && e.path().extension() == ".json" && e.path().filename().string()[0] != '.')
      files.push_back(e.path());  // not hidden files: a run's scratch copies
  std::sort(files.begin(), files.end());
  return files;
}

const std::string kWater = R"({"preset": "atlantic"})";
const std::string kLamp = R"([{"type": "point", "position": [0, 0, -5], "spectrum": 1}])";

// A valid scene, as text, with `water`, `lights` and `rest` (more top-level members).
std::string scene_text(const std::string& water = kWater, const std::string& lights = kLamp,
                       const std::string& rest = "") {
  return R"({"name": "t", "water": )" + water + R"(, "lights": )" + lights + rest + "}";
}
// The same with the default water and lamp.
std::string with(const std::string& rest) { return scene_text(kWater, kLamp, rest); }

class OceanSceneErrors : public ::testing::Test {
 protected:
  TempDir dir;
  std::string write(const std::string& text) {
    const std::string path = (fs::path(dir.path()) / "scene.json").string();
    std::ofstream(path) << text;
    return path;
  }
  // Reading `text` fails with INVALID_ARGUMENT "<file>: <path>: ...<what>...".
  void expect_error(const std::string& text, const std::string& path, const std::string& what) {
    const std::string file = write(text);
    try {
      read_ocean_scene(file);
      ADD_FAILURE() << "no error for: " << text;
    } catch (const arcus::Error& e) {
      EXPECT_EQ(e.status(), ARCUS_ERROR_INVALID_ARGUMENT) << e.what();
      const std::string m = e.what();
      EXPECT_EQ(m.rfind(file + ": " + path + ":", 0), 0u) << m;
      EXPECT_NE(m.find(what), std::string::npos) << m;
    }
  }
};

TEST(OceanScene, EveryBundledSceneLoads) {
  const auto files = bundled_scenes();
  EXPECT_GE(files.size(), 25u);
  for (const fs::path& f : files) {
    SCOPED_TRACE(f.string());
    OceanSceneDesc d;
    ASSERT_NO_THROW(d = read_ocean_scene(f.string()));
    EXPECT_FALSE(d.description.empty());
    EXPECT_FALSE(d.lights.empty());
    if (f.filename() == "fig5_9.json") {  // Fig. 5.9's tallies: the thesis' trace, settings and all
      EXPECT_EQ(d.trace.photons, 400000u);
      EXPECT_EQ(d.trace.max_interactions, 10);
    } else if (d.trace.depths.empty() && d.march.photon_tile > 0) {
      // The waters in daylight: the photons of one 8 m tile standing for the whole sea
      // (1-2 M, radii holding 1250-5000: docs/ocean.md), the estimate at every eighth
      // pixel of 512.
      ASSERT_TRUE(d.has_camera);
      EXPECT_EQ(d.march.photon_tile, 8.0);
      EXPECT_GE(d.trace.photons, 1000000u);
      EXPECT_EQ(d.march.estimator, MarchParams::beam);
      EXPECT_EQ(d.march.estimate_stride * 64, int(d.camera.width));
    } else if (d.trace.depths.empty()) {
      // The images: 2 M photons of four wavelengths, each photon's radius holding
      // 1250 (the radius of the thesis' 250 of 400 000, §5.3), 200 steps, the photon
      // estimate at every fourth pixel of 512 (every other of 256).
      ASSERT_TRUE(d.has_camera);
      EXPECT_EQ(d.trace.photons, 2000000u);
      EXPECT_EQ(d.trace.wavelengths_per_photon, 4);
      EXPECT_EQ(d.march.k, 1250);
      EXPECT_EQ(d.march.steps, 200);
      EXPECT_EQ(d.march.estimate_stride * 128, int(d.camera.width));
    } else {
      EXPECT_TRUE(d.medium.surface);
      EXPECT_EQ(d.trace.max_interactions, 64);  // profiles follow every interaction
    }
  }
}

TEST(OceanScene, TheFig510ScenesShareOneViewAndLamp) {
  for (const char* p : {"atlantic", "mediterranean", "baltic", "north_sea", "cdom_coastal"}) {
    SCOPED_TRACE(p);
    const OceanSceneDesc d = read_ocean_scene((kScenes / (std::string(p) + ".json")).string());
    EXPECT_EQ(d.name, p);
    EXPECT_EQ(d.water.kind, Water::kBioOptical);
    EXPECT_EQ(d.water.bio.chlorophyll, arcus::ocean::preset(p).chlorophyll);
    ASSERT_EQ(d.lights.size(), 1u);
    EXPECT_EQ(d.lights[0].kind, Light::point);
    EXPECT_EQ(d.lights[0].position[2], d.camera.position[2]);  // the same depth (thesis §5.3)
    EXPECT_EQ(d.camera.width, 512u);
    EXPECT_EQ(d.camera.height, 384u);
    EXPECT_EQ(d.trace.max_interactions, 5);
    EXPECT_EQ(d.march.estimator, MarchParams::beam);  // scenes/README.md: the fast estimate
    EXPECT_EQ(d.march.k, 1250);                      // the radius of the thesis' settings (§5.3)
    EXPECT_EQ(d.march.steps, 200);
    EXPECT_EQ(d.trace.photons, 2000000u);
    EXPECT_FALSE(d.medium.surface);
    EXPECT_TRUE(std::isinf(d.medium.bottom_depth));
  }
}

TEST(OceanScene, Fig58GridMatchesItsFileNames) {
  // Columns: C over Table 4.3's range; rows: a_d(400) (row 2) and a_y(440) (row 3)
  // raised from the first row's 0 (thesis §5.3).
  int n = 0;
  for (const char* c : {"0", "0.1", "0.5", "1"})
    for (const auto& row : {std::pair<const char*, const char*>{"0", "0"}, {"0.1", "0"}, {"0", "0.1"}}) {
      const std::string name = std::string("c") + c + "_ad" + row.first + "_ay" + row.second;
      SCOPED_TRACE(name);
      const OceanSceneDesc d = read_ocean_scene((kScenes / "fig5_8" / (name + ".json")).string());
      EXPECT_DOUBLE_EQ(d.water.bio.chlorophyll, std::stod(c));
      EXPECT_DOUBLE_EQ(d.water.bio.a_d400, std::stod(row.first));
      EXPECT_DOUBLE_EQ(d.water.bio.a_y440, std::stod(row.second));
      EXPECT_EQ(d.water.bio.s_y, 0.014);  // Table 4.3
      EXPECT_EQ(d.camera.width, 256u);
      ++n;
    }
  EXPECT_EQ(n, 12);
}

TEST(OceanScene, Fig511TurnsInelasticScatteringOff) {
  const OceanSceneDesc on = read_ocean_scene((kScenes / "fig5_11" / "baltic_inelastic.json").string());
  const OceanSceneDesc off = read_ocean_scene((kScenes / "fig5_11" / "baltic_no_inelastic.json").string());
  EXPECT_EQ(on.water.bio.raman_scale, 1);
  EXPECT_EQ(off.water.bio.chlorophyll, on.water.bio.chlorophyll);
  EXPECT_EQ(off.water.bio.raman_scale, 0);
  EXPECT_EQ(off.water.bio.cdom_yield_scale, 0);
  EXPECT_EQ(off.water.bio.chlorophyll_yield, 0);
  const OceanSceneDesc stokes = read_ocean_scene((kScenes / "fig5_11" / "baltic_no_anti_stokes.json").string());
  EXPECT_TRUE(on.water.bio.anti_stokes);
  EXPECT_FALSE(stokes.water.bio.anti_stokes);
  EXPECT_EQ(stokes.water.bio.raman_scale, 1);
}

TEST(OceanScene, SunIsADirectionalLightAtItsZenith) {
  const OceanSceneDesc d = read_ocean_scene((kScenes / "profiles" / "baltic_sun.json").string());
  ASSERT_EQ(d.lights.size(), 2u);
  EXPECT_EQ(d.lights[0].kind, Light::directional);
  EXPECT_NEAR(d.lights[0].direction[0], -std::sin(30 * kPi / 180), 1e-15);
  EXPECT_NEAR(d.lights[0].direction[2], -std::cos(30 * kPi / 180), 1e-15);
  EXPECT_EQ(d.lights[1].kind, Light::sky);
  EXPECT_EQ(d.lights[1].spectrum.values[0], 0.2);
  EXPECT_EQ(d.trace.depths, (std::vector<double>{0, 1, 2, 5, 10, 20, 30}));
  EXPECT_FALSE(d.has_camera);
}

TEST_F(OceanSceneErrors, DefaultsAndIops) {
  const std::string iops = R"({"iops": {"absorption": {"nm": [400, 700], "values": [0.02, 0.6]}, "scattering": 0.1,
      "phase": {"kind": "two_term_hg", "g_forward": 0.9, "g_backward": -0.5, "forward_weight": 0.98},
      "raman": true}})";
  const OceanSceneDesc d = read_ocean_scene(write(scene_text(iops, R"([{"type": "point", "position": [0, 0, 0],
      "spectrum": 2}])", R"(, "grid": {"first_nm": 400, "last_nm": 700, "step_nm": 10},
      "medium": {"box": {"min": [null, null, -50], "max": [null, null, 0]}}, "profile": {"depths": [1, 2]})")));
  EXPECT_EQ(d.water.kind, Water::kIops);
  EXPECT_TRUE(d.water.iops.raman);
  EXPECT_EQ(d.water.iops.absorption.values[1], 0.6);
  EXPECT_EQ(d.water.iops.phase.forward_weight, 0.98);
  EXPECT_EQ(d.grid.count, 31);
  EXPECT_TRUE(std::isinf(d.medium.box_lo[0]) && d.medium.box_lo[0] < 0);
  EXPECT_EQ(d.medium.box_lo[2], -50);
  EXPECT_EQ(d.medium.box_hi[2], 0);
  EXPECT_EQ(d.trace.photons, 400000u);  // defaults
  EXPECT_EQ(d.trace.max_interactions, 5);
  EXPECT_EQ(d.trace.wavelengths_per_photon, 4);
  EXPECT_EQ(d.march.estimate_stride, 1);
  EXPECT_EQ(d.grid.first_nm, 400);
  const OceanSceneDesc e = read_ocean_scene(write(scene_text()));
  EXPECT_EQ(e.grid.count, 81);  // 380–780 nm at 5
  EXPECT_FALSE(e.has_camera);
}

TEST_F(OceanSceneErrors, NameTheFileAndThePath) {
  expect_error(scene_text(R"({"preset": "atlantic", "chlorophyl": 1})"), "$.water.chlorophyl", "unknown key");
  expect_error(scene_text(R"({"chlorophyll": -1})"), "$.water.chlorophyll", "must be finite and >= 0");
  expect_error(scene_text(R"({"preset": "pacific"})"), "$.water.preset", "atlantic");
  expect_error(scene_text(R"({"preset": "atlantic", "preset": "baltic"})"), "$.water.preset", "given twice");
  expect_error(scene_text(R"({"chlorophyll": "much"})"), "$.water.chlorophyll", "expected a number");
  expect_error(scene_text(R"({"iops": {"absorption": 0.1, "scattering": 0.1, "phase": {"kind": "hg", "g": 1.5}}})"),
               "$.water.iops.phase.g", "");
  expect_error(scene_text(R"({"preset": "baltic"})", R"([{"type": "sky", "spectrum": 1}])"), "$.lights[0]",
               "needs the surface");
  expect_error(scene_text(R"({"preset": "baltic"})", R"([{"type": "lamp", "spectrum": 1}])"), "$.lights[0].type",
               "point");
  expect_error(scene_text(R"({"preset": "baltic"})", R"([{"type": "point", "position": [0, 0, 1],
               "spectrum": {"nm": [400, 500], "values": [1, -1]}}])"), "$.lights[0].spectrum.values[1]", ">= 0");
  expect_error(scene_text(R"({"preset": "baltic"})", R"([{"type": "sun", "zenith_deg": 95, "spectrum": 1}])"),
               "$.lights[0].zenith_deg", "[0, 90)");
  expect_error(scene_text(R"({"preset": "baltic"})", "[]"), "$.lights", "at least one light");
  expect_error(with(R"(, "profile": {"depths": [0, 5]})"), "$.profile.depths",
               "plane-parallel column");
  expect_error(with(R"(, "photons": {"max_interactions": 0})"), "$.photons.max_interactions", "1..");
  expect_error(with(R"(, "medium": {"n_water": 0.5})"), "$.medium.n_water", "[1, 3]");
  expect_error(with(R"(, "grid": {"first_nm": 380, "last_nm": 781, "step_nm": 5})"), "$.grid",
               "whole number");
  expect_error(with(R"(, "grid": {"first_nm": 200})"), "$.grid.first_nm", "300-1000");
  // A camera belongs under "view": at the top level it would make the file a render scene.
  expect_error(with(R"(, "camera": {})"), "$.camera", "unknown key");
  const std::string camera = R"("camera": {"position": [0, 0, 1], "look_at": [1, 0, 1], "vfov_deg": 50,
                                           "width": 8, "height": 6})";
  expect_error(with(R"(, "medium": {"surface": true}, "view": {)" + camera + "}"),
               "$.view.camera.position", "in the water");
  expect_error(with(R"(, "view": {"camera": {"position": [0, 0, -1], "look_at": [0, 0, -1],
               "vfov_deg": 50, "width": 8, "height": 6}})"), "$.view.camera", "look_at must differ");
  expect_error(with(R"(, "view": {)" + camera + R"(, "march": {"estimator": "beams"}})"),
               "$.view.march.estimator", "per_step");
}

TEST(OceanScene, LoadsThroughTheCApiAsAnOceanScene) {
  Context ctx;
  arcus_scene_t* scene = nullptr;
  const std::string path = (kScenes / "atlantic.json").string();
  ASSERT_EQ(arcus_scene_load(ctx, path.c_str(), &scene), ARCUS_SUCCESS) << arcus_last_error();
  const char* engine = nullptr;
  const char* name = nullptr;
  const char* document = nullptr;
  ASSERT_EQ(arcus_scene_get_engine(scene, &engine), ARCUS_SUCCESS);
  EXPECT_STREQ(engine, "ocean");
  ASSERT_EQ(arcus_scene_get_name(scene, &name), ARCUS_SUCCESS);
  EXPECT_STREQ(name, "atlantic");
  ASSERT_EQ(arcus_scene_get_document(scene, &document), ARCUS_SUCCESS);
  EXPECT_NE(std::string(document).find("\"preset\": \"atlantic\""), std::string::npos);
  auto* s = arcus::ocean::ocean_scene(scene);
  EXPECT_EQ(s->desc.march.k, 1250);
  EXPECT_EQ(arcus_scene_release(scene), ARCUS_SUCCESS);

  TempDir dir;
  const std::string bad = (fs::path(dir.path()) / "bad.json").string();
  std::ofstream(bad) << scene_text(R"({"chlorophyll": -1})");
  scene = nullptr;
  EXPECT_EQ(arcus_scene_load(ctx, bad.c_str(), &scene), ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(scene, nullptr);
  EXPECT_NE(std::string(arcus_last_error()).find(bad + ": $.water.chlorophyll"), std::string::npos)
      << arcus_last_error();
}

}  // namespace
