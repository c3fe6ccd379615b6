// The scene reader (src/scene/json_reader, src/curved/scene_desc): pure host code, no
// device.  The bundled scenes parse to what they say; every kind of bad input is an
// arcus::Error (INVALID_ARGUMENT, or IO for files) whose message starts with the file
// name and the exact key path; the hardening against deep nesting, out-of-range
// numbers, invalid UTF-8 and odd files has a regression test each.
//
// Standalone, from the repository root:
//   g++ -std=c++17 -Isrc -Iinclude -DARCUS_SOURCE_DIR="\"$PWD\"" tests/unit/test_scene_reader.cpp
//       src/scene/json_reader.cpp src/curved/scene_desc.cpp -lgtest -lgtest_main -pthread
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <future>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "core/error.h"
#include "curved/scene_desc.h"
#include "render/scene_desc.h"
#include "scene/json_reader.h"

#ifndef ARCUS_SOURCE_DIR
#define ARCUS_SOURCE_DIR "."
#endif

namespace {

namespace fs = std::filesystem;
using arcus::curved::parse_scene_file;
using arcus::curved::parse_scene_text;
using arcus::curved::SceneDesc;
using arcus::curved::SceneLimits;
using Json = nlohmann::ordered_json;

const std::string kSource = ARCUS_SOURCE_DIR;
constexpr double kPi = 3.14159265358979323846;

std::string read_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// A message must be printable UTF-8 whatever the input was (nlohmann refuses to dump
// invalid UTF-8, so that is the check).
bool valid_utf8(const std::string& s) {
  try {
    (void)Json(s).dump();
    return true;
  } catch (const Json::exception&) {
    return false;
  }
}

// The error that parsing `text` as "x.json" throws; fails the test if there is none.
arcus::Error error_of(const std::string& text, const SceneLimits& limits = SceneLimits()) {
  try {
    parse_scene_text(text, "x.json", "/scenes", limits);
  } catch (const arcus::Error& e) {
    return e;
  }
  ADD_FAILURE() << "no error for: " << text.substr(0, 300);
  return arcus::Error(ARCUS_SUCCESS, "");
}

// Expects INVALID_ARGUMENT with a message "x.json: <path>: ..." containing `what`.
void expect_error(const std::string& text, const std::string& path, const std::string& what,
                  const SceneLimits& limits = SceneLimits()) {
  const arcus::Error e = error_of(text, limits);
  const std::string msg = e.what();
  EXPECT_EQ(e.status(), ARCUS_ERROR_INVALID_ARGUMENT) << msg;
  EXPECT_EQ(msg.rfind("x.json: " + path + ": ", 0), 0u) << "expected path " << path << " in: " << msg;
  EXPECT_NE(msg.find(what), std::string::npos) << "expected \"" << what << "\" in: " << msg;
  EXPECT_TRUE(valid_utf8(msg)) << msg;
  EXPECT_LT(msg.size(), 1000u) << msg.substr(0, 300);
}

// A small valid scene; `edit` changes it before it is written out.
std::string scene(const std::function<void(Json&)>& edit = nullptr) {
  Json j = Json::parse(R"({
    "name": "t",
    "medium": {"type": "luneburg", "center": [0, 0, 0], "radius": 1},
    "rays": {"origin": [-1, 0, 0],
             "fan": {"direction": [1, 0, 0], "plane_normal": [0, 0, 1], "min_deg": -10, "max_deg": 10, "count": 3}},
    "integrator": {"length": 2}
  })");
  if (edit) edit(j);
  return j.dump();
}

// `text` with its one occurrence of `from` replaced: for what Json cannot write (1e400).
std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  EXPECT_EQ(text.find(from, at + 1), std::string::npos) << from;
  return at == std::string::npos ? text : text.replace(at, from.size(), to);
}

std::string nested(int depth) { return std::string(depth, '[') + std::string(depth, ']'); }

std::string repeat(const std::string& s, int n) {
  std::string out;
  for (int i = 0; i < n; ++i) out += s;
  return out;
}

// A temporary directory, removed at the end of the test.
struct TempDir {
  fs::path path;
  TempDir() {
    path = fs::path(::testing::TempDir()) / ("arcus_scene_test_" + std::to_string(getpid()) + "_" +
                                            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
  fs::path write(const std::string& name, const std::string& text) const {
    std::ofstream(path / name, std::ios::binary) << text;
    return path / name;
  }
};

// ---- the bundled scenes -------------------------------------------------------------

TEST(BundledScenes, AllParse) {
  int n = 0;
  for (const auto& entry : fs::directory_iterator(fs::path(kSource) / "scenes")) {
    if (entry.path().extension() != ".json") continue;
    ++n;
    SCOPED_TRACE(entry.path().string());
    if (Json::parse(read_text(entry.path())).contains("camera")) {
      // A render scene: its own reader (render/scene_desc.h), the same strictness.
      const arcus::render::RenderDesc r = arcus::render::parse_render_file(entry.path().string());
      EXPECT_EQ(r.name, entry.path().stem().string());
      EXPECT_FALSE(r.description.empty());
      EXPECT_EQ(Json::parse(r.document), Json::parse(read_text(entry.path())));
      continue;
    }
    const SceneDesc s = parse_scene_file(entry.path().string());
    EXPECT_EQ(s.name, entry.path().stem().string());
    EXPECT_GT(s.ray_count(), 0u);
    EXPECT_EQ(s.origins.size(), 3 * s.ray_count());
    EXPECT_EQ(s.directions.size(), 3 * s.ray_count());
    EXPECT_TRUE(s.wavelengths.empty());
    EXPECT_FALSE(s.description.empty());
    // The document is the file's, keys in the author's order.
    EXPECT_EQ(Json::parse(s.document), Json::parse(read_text(entry.path())));
    EXPECT_EQ(Json::parse(s.document).dump(), Json::parse(read_text(entry.path())).dump());
  }
  EXPECT_GE(n, 4);
}

TEST(BundledScenes, MirageReadsAsWritten) {
  const SceneDesc s = parse_scene_file(kSource + "/scenes/mirage.json");
  EXPECT_EQ(s.file, kSource + "/scenes/mirage.json");
  EXPECT_EQ(s.name, "mirage");
  EXPECT_EQ(s.medium.kind, ARCUS_FIELD_ATMOSPHERE);
  EXPECT_STREQ(arcus::curved::medium_type_name(s.medium.kind), "atmosphere");
  EXPECT_FALSE(s.medium.atmosphere.spherical);
  EXPECT_EQ(s.medium.atmosphere.wavelength, 550);
  EXPECT_EQ(s.medium.atmosphere.sea_level_temperature, 288.15);
  EXPECT_EQ(s.medium.atmosphere.sea_level_pressure, 101325);
  ASSERT_EQ(s.medium.atmosphere.inversions.size(), 1u);
  EXPECT_EQ(s.medium.atmosphere.inversions[0].base, 0);
  EXPECT_EQ(s.medium.atmosphere.inversions[0].top, 2);
  EXPECT_EQ(s.medium.atmosphere.inversions[0].delta_t, 12);
  ASSERT_EQ(s.ray_count(), 64u);
  for (size_t i = 0; i < 64; ++i) {
    EXPECT_EQ(s.origins[3 * i + 1], 1.6);
    const double a = (-0.6 + 0.7 * double(i) / 63.0) * kPi / 180.0;
    EXPECT_NEAR(s.directions[3 * i + 0], std::cos(a), 1e-15);
    EXPECT_NEAR(s.directions[3 * i + 1], std::sin(a), 1e-15);
    EXPECT_EQ(s.directions[3 * i + 2], 0.0);
  }
  EXPECT_EQ(s.params.method, ARCUS_METHOD_DP45);
  EXPECT_EQ(s.params.precision, ARCUS_PRECISION_DOUBLE);
  EXPECT_EQ(s.params.length, 2000);
  EXPECT_EQ(s.params.rtol, 1e-10);
  EXPECT_EQ(s.params.atol, 1e-12);
  EXPECT_EQ(s.params.max_step, 5);
  EXPECT_EQ(s.params.use_box, 1);
  EXPECT_EQ(s.params.box_min[1], 0);
  EXPECT_EQ(s.params.box_max[0], 2001);
  EXPECT_EQ(s.params.record_path, 1);
  EXPECT_EQ(s.params.progress, nullptr);
}

TEST(BundledScenes, EveryLeafReplacedByAnObjectIsAnErrorAtItsPath) {
  // Each scalar of mirage.json in turn becomes {}: the error must name that leaf.
  const Json original = Json::parse(read_text(kSource + "/scenes/mirage.json"));
  std::function<void(const Json&, const std::string&, Json::json_pointer)> walk =
      [&](const Json& v, const std::string& path, Json::json_pointer ptr) {
        if (v.is_object()) {
          for (const auto& item : v.items()) walk(item.value(), path + "." + item.key(), ptr / item.key());
        } else if (v.is_array()) {
          for (size_t i = 0; i < v.size(); ++i) walk(v[i], path + "[" + std::to_string(i) + "]", ptr / i);
        } else {
          SCOPED_TRACE(path);
          Json j = original;
          j[ptr] = Json::object();
          expect_error(j.dump(), path, "expected");
        }
      };
  walk(original, "$", Json::json_pointer());
}

TEST(BundledScenes, EveryTruncationIsAnError) {
  const std::string text = read_text(kSource + "/scenes/fisheye.json");
  for (size_t n = 0; n + 1 < text.size(); ++n) {
    const arcus::Error e = error_of(text.substr(0, n));
    ASSERT_EQ(e.status(), ARCUS_ERROR_INVALID_ARGUMENT) << n;
    const std::string what = e.what();
    ASSERT_TRUE(what.rfind("x.json: $", 0) == 0 || what.rfind("x.json: not valid JSON (after $", 0) == 0) << what;
  }
}

// ---- a scene's contents ---------------------------------------------------------------

TEST(SceneDesc, DefaultsAreTheLibrarys) {
  const SceneDesc s = parse_scene_text(scene(), "x.json", "/scenes");
  EXPECT_EQ(s.name, "t");
  EXPECT_EQ(s.description, "");
  EXPECT_EQ(s.params.method, ARCUS_METHOD_DP45);
  EXPECT_EQ(s.params.precision, ARCUS_PRECISION_DOUBLE);
  EXPECT_EQ(s.params.length, 2);
  EXPECT_EQ(s.params.step, 0);
  EXPECT_EQ(s.params.rtol, 1e-9);
  EXPECT_EQ(s.params.atol, 1e-12);
  EXPECT_EQ(s.params.min_step, 1e-12);
  EXPECT_EQ(s.params.max_step, 0);
  EXPECT_EQ(s.params.max_rejections, 64u);
  EXPECT_EQ(s.params.max_steps, 10000000u);
  EXPECT_EQ(s.params.use_box, 0);
  EXPECT_EQ(s.params.record_path, 0);
  EXPECT_EQ(s.params.path_capacity, 0u);
  EXPECT_EQ(s.params.progress, nullptr);
  EXPECT_EQ(s.params.progress_user, nullptr);
}

TEST(SceneDesc, IntegratorBoxAndPath) {
  const SceneDesc s = parse_scene_text(scene([](Json& j) {
                                         j["integrator"] = Json::parse(
                                             R"({"method": "rk4", "precision": "float", "step": 0.01, "rtol": 1e-6,
                                                 "atol": 1e-8, "min_step": 1e-9, "max_step": 0.5,
                                                 "max_rejections": 7, "max_steps": 18446744073709551615,
                                                 "length": 3})");
                                         j["box"] = Json::parse(R"({"min": [-1, -2, -3], "max": [1, 2, 3]})");
                                         j["record_path"] = true;
                                         j["path_capacity"] = 4096;
                                       }),
                                       "x.json", "/scenes");
  EXPECT_EQ(s.params.method, ARCUS_METHOD_RK4);
  EXPECT_EQ(s.params.precision, ARCUS_PRECISION_FLOAT);
  EXPECT_EQ(s.params.step, 0.01);
  EXPECT_EQ(s.params.rtol, 1e-6);
  EXPECT_EQ(s.params.atol, 1e-8);
  EXPECT_EQ(s.params.min_step, 1e-9);
  EXPECT_EQ(s.params.max_step, 0.5);
  EXPECT_EQ(s.params.max_rejections, 7u);
  EXPECT_EQ(s.params.max_steps, UINT64_MAX);
  EXPECT_EQ(s.params.length, 3);
  EXPECT_EQ(s.params.use_box, 1);
  EXPECT_EQ(s.params.box_min[2], -3);
  EXPECT_EQ(s.params.box_max[1], 2);
  EXPECT_EQ(s.params.record_path, 1);
  EXPECT_EQ(s.params.path_capacity, 4096u);
}

TEST(SceneDesc, EveryMedium) {
  auto medium = [](const char* m) {
    return parse_scene_text(scene([&](Json& j) { j["medium"] = Json::parse(m); }), "x.json", "/scenes").medium;
  };
  EXPECT_EQ(medium(R"({"type": "constant", "n": 1.5})").n, 1.5);
  auto lin = medium(R"({"type": "linear", "n0": 1.2, "gradient": [0, 0.1, 0]})");
  EXPECT_EQ(lin.kind, ARCUS_FIELD_LINEAR);
  EXPECT_EQ(lin.n0, 1.2);
  EXPECT_EQ(lin.gradient[1], 0.1);
  auto n2 = medium(R"({"type": "linear_n2", "a": 2, "k": [0.5, 0, 0]})");
  EXPECT_EQ(n2.kind, ARCUS_FIELD_LINEAR_N2);
  EXPECT_EQ(n2.a, 2);
  EXPECT_EQ(n2.k[0], 0.5);
  auto fe = medium(R"({"type": "fisheye", "center": [1, 2, 3], "radius": 4, "n0": 2})");
  EXPECT_EQ(fe.kind, ARCUS_FIELD_FISHEYE);
  EXPECT_EQ(fe.center[2], 3);
  EXPECT_EQ(fe.radius, 4);
  EXPECT_EQ(fe.n0, 2);
  auto atm = medium(R"({"type": "atmosphere"})");  // every key optional
  EXPECT_EQ(atm.kind, ARCUS_FIELD_ATMOSPHERE);
  EXPECT_FALSE(atm.atmosphere.spherical);
  EXPECT_EQ(atm.atmosphere.wavelength, 550);
  EXPECT_EQ(atm.atmosphere.sea_level_temperature, 288.15);
  EXPECT_EQ(atm.atmosphere.sea_level_pressure, 101325);
  EXPECT_TRUE(atm.atmosphere.inversions.empty());
  auto grid = medium(
      R"({"type": "grid", "file": "data/n.raw", "dtype": "float32", "dims": [2, 3, 4],
          "origin": [0, 0, 0], "spacing": [0.5, 0.5, 0.5]})");
  EXPECT_EQ(grid.kind, ARCUS_FIELD_GRID);
  EXPECT_EQ(grid.grid.file, "/scenes/data/n.raw");  // resolved, never opened
  EXPECT_EQ(grid.grid.dtype, ARCUS_FLOAT32);
  EXPECT_EQ(grid.grid.dims[2], 4u);
  EXPECT_EQ(grid.grid.spacing[1], 0.5);
}

TEST(SceneDesc, GridFileIsResolvedAgainstTheScenesDirectory) {
  auto file = [](const std::string& name, const std::string& base) {
    return parse_scene_text(scene([&](Json& j) {
                              j["medium"] = {{"type", "grid"},       {"file", name},
                                             {"dtype", "float64"},   {"dims", {2, 2, 2}},
                                             {"origin", {0, 0, 0}},  {"spacing", {1, 1, 1}}};
                            }),
                            "x.json", base)
        .medium.grid.file;
  };
  EXPECT_EQ(file("/abs/n.raw", "/scenes"), "/abs/n.raw");
  EXPECT_EQ(file("n.raw", "/scenes"), "/scenes/n.raw");
  EXPECT_EQ(file("n.raw", "rel"), (fs::current_path() / "rel" / "n.raw").string());
  EXPECT_EQ(file("n.raw", ""), (fs::current_path() / "n.raw").string());
  // From a file: against the file's own directory.
  TempDir dir;
  const fs::path p = dir.write("g.json", scene([](Json& j) {
    j["medium"] = Json::parse(R"({"type": "grid", "file": "n.raw", "dtype": "float64", "dims": [2, 2, 2],
                                  "origin": [0, 0, 0], "spacing": [1, 1, 1]})");
  }));
  EXPECT_EQ(parse_scene_file(p.string()).medium.grid.file, (dir.path / "n.raw").string());
}

TEST(SceneDesc, FanIsRightHanded) {
  const SceneDesc s = parse_scene_text(scene([](Json& j) {
                                         j["rays"]["fan"]["min_deg"] = -90;
                                         j["rays"]["fan"]["max_deg"] = 90;
                                       }),
                                       "x.json", "/scenes");
  ASSERT_EQ(s.ray_count(), 3u);
  const double expected[3][3] = {{0, -1, 0}, {1, 0, 0}, {0, 1, 0}};
  for (int i = 0; i < 3; ++i)
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(s.directions[3 * i + a], expected[i][a], 1e-15);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(s.origins[3 * i], -1);
}

TEST(SceneDesc, FanOfExtremeVectorsStaysUnit) {
  // v·v overflows for 1e200 and underflows for 1e-200; the directions must not.
  const SceneDesc s = parse_scene_text(scene([](Json& j) {
                                         j["rays"]["fan"]["direction"] = {1e200, 0, 0};
                                         j["rays"]["fan"]["plane_normal"] = {0, 0, 1e-200};
                                       }),
                                       "x.json", "/scenes");
  for (size_t i = 0; i < s.ray_count(); ++i) {
    const double* d = &s.directions[3 * i];
    EXPECT_NEAR(d[0] * d[0] + d[1] * d[1] + d[2] * d[2], 1.0, 1e-15);
  }
}

TEST(SceneDesc, ExplicitRays) {
  const SceneDesc s = parse_scene_text(
      scene([](Json& j) {
        j["rays"] = Json::parse(R"({"origins": [[0, 0, 0], [0, 1, 0]], "directions": [[1, 0, 0], [2, 0.1, 0]]})");
      }),
      "x.json", "/scenes");
  ASSERT_EQ(s.ray_count(), 2u);
  EXPECT_EQ(s.origins, (std::vector<double>{0, 0, 0, 0, 1, 0}));
  EXPECT_EQ(s.directions, (std::vector<double>{1, 0, 0, 2, 0.1, 0}));  // as given, not unit
  EXPECT_TRUE(s.wavelengths.empty());
}

// ---- per-ray wavelengths ----------------------------------------------------------------

TEST(Wavelengths, OnePerListedRay) {
  const SceneDesc s = parse_scene_text(scene([](Json& j) {
                                         j["rays"] = Json::parse(R"({"origins": [[0, 0, 0], [0, 1, 0]],
                                                                     "directions": [[1, 0, 0], [1, 0, 0]],
                                                                     "wavelengths": [450, 650.5]})");
                                       }),
                                       "x.json", "/scenes");
  EXPECT_EQ(s.wavelengths, (std::vector<double>{450, 650.5}));
}

TEST(Wavelengths, OneNumberForAllListedRays) {
  const SceneDesc s = parse_scene_text(scene([](Json& j) {
                                         j["rays"] = Json::parse(R"({"origins": [[0, 0, 0], [0, 1, 0]],
                                                                     "directions": [[1, 0, 0], [1, 0, 0]],
                                                                     "wavelengths": 700})");
                                       }),
                                       "x.json", "/scenes");
  EXPECT_EQ(s.wavelengths, (std::vector<double>{700, 700}));
}

TEST(Wavelengths, FanOncePerWavelengthWavelengthMajor) {
  const SceneDesc s =
      parse_scene_text(scene([](Json& j) { j["rays"]["wavelengths"] = {400, 550, 700}; }), "x.json", "/scenes");
  ASSERT_EQ(s.ray_count(), 9u);  // 3 fan rays × 3 wavelengths
  ASSERT_EQ(s.wavelengths.size(), 9u);
  const SceneDesc plain = parse_scene_text(scene(), "x.json", "/scenes");
  for (size_t w = 0; w < 3; ++w)
    for (size_t i = 0; i < 3; ++i) {
      EXPECT_EQ(s.wavelengths[w * 3 + i], 400 + 150.0 * double(w));
      for (int a = 0; a < 3; ++a) {
        EXPECT_EQ(s.directions[3 * (w * 3 + i) + a], plain.directions[3 * i + a]);
        EXPECT_EQ(s.origins[3 * (w * 3 + i) + a], plain.origins[3 * i + a]);
      }
    }
  const SceneDesc one = parse_scene_text(scene([](Json& j) { j["rays"]["wavelengths"] = 633; }), "x.json", "/scenes");
  EXPECT_EQ(one.wavelengths, (std::vector<double>{633, 633, 633}));
}

TEST(Wavelengths, Errors) {
  expect_error(scene([](Json& j) {
                 j["rays"] = Json::parse(R"({"origins": [[0, 0, 0], [0, 1, 0]], "directions": [[1, 0, 0], [1, 0, 0]],
                                             "wavelengths": [450]})");
               }),
               "$.rays.wavelengths", "has 1 entries, origins has 2");
  expect_error(scene([](Json& j) { j["rays"]["wavelengths"] = {500, -5}; }), "$.rays.wavelengths[1]",
               "expected a wavelength in nm within 300..1690, got -5");
  expect_error(scene([](Json& j) { j["rays"]["wavelengths"] = 0; }), "$.rays.wavelengths", "within 300..1690, got 0");
  expect_error(scene([](Json& j) { j["rays"]["wavelengths"] = Json::array(); }), "$.rays.wavelengths",
               "needs at least one wavelength");
  expect_error(scene([](Json& j) { j["rays"]["wavelengths"] = "red"; }), "$.rays.wavelengths", "expected an array");
  expect_error(scene([](Json& j) { j["rays"]["wavelengths"] = {500, "x"}; }), "$.rays.wavelengths[1]",
               "expected a number");
  SceneLimits small;
  small.max_rays = 8;
  expect_error(scene([](Json& j) { j["rays"]["wavelengths"] = {400, 500, 600}; }), "$.rays.wavelengths",
               "3 wavelengths times 3 fan rays exceed the limit of 8 rays", small);
}

// ---- hardening (a): deep nesting ----------------------------------------------------------

TEST(Hardening, DeepNestingIsAnErrorNotAStackOverflow) {
  // 100 000 levels overflowed the stack in nlohmann's recursive copy of the DOM.
  expect_error("{\"a\": " + nested(100000) + ", \"b\": 1}", "$.a" + repeat("[0]", 63),
               "nesting deeper than 64 levels");
  expect_error(repeat("{\"k\":", 100000) + "1" + repeat("}", 100000), repeat(".k", 64).insert(0, "$"),
               "nesting deeper than 64 levels");
  // Unterminated: the depth is refused before the input runs out.
  expect_error(std::string(1000000, '['), "$" + repeat("[0]", 64), "nesting deeper than 64 levels");
}

TEST(Hardening, SixtyFourLevelsAreAllowed) {
  EXPECT_NO_THROW(arcus::json::Document::from_text(nested(64), "x.json"));
  try {
    arcus::json::Document::from_text(nested(65), "x.json");
    ADD_FAILURE() << "65 levels accepted";
  } catch (const arcus::Error& e) {
    EXPECT_EQ(std::string(e.what()), "x.json: $" + repeat("[0]", 64) + ": nesting deeper than 64 levels");
  }
  // In a scene, deep nesting inside a value the schema would reject anyway.
  expect_error(scene([](Json& j) { j["description"] = Json::parse(nested(64)); }), "$.description" + repeat("[0]", 63),
               "nesting deeper than 64 levels");
}

TEST(Hardening, DeepNestingInAFileNamesTheFile) {
  TempDir dir;
  const fs::path p = dir.write("deep.json", "{\"a\": " + nested(100000) + ", \"b\": 1}");
  try {
    parse_scene_file(p.string());
    ADD_FAILURE() << "no error";
  } catch (const arcus::Error& e) {
    EXPECT_EQ(e.status(), ARCUS_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(std::string(e.what()).rfind(p.string() + ": $.a[0]", 0), 0u) << e.what();
  }
}

// ---- hardening (b): numbers beyond a double -----------------------------------------------

TEST(Hardening, NumberOutOfRangeNamesFileAndPath) {
  // nlohmann's own out_of_range.406 named neither the file nor the key.
  expect_error(replaced(scene([](Json& j) { j["medium"]["radius"] = 12345; }), "12345", "1e400"), "$.medium.radius",
               "number out of range");
  expect_error(R"({"name": "t", "rays": {"origins": [[0, 0, 0], [0, 0, -1e400]]}})", "$.rays.origins[1][2]",
               "number out of range");
  expect_error("1e400", "$", "number out of range");
  expect_error(R"({"a": [1, 2, 123456789e999999999]})", "$.a[2]", "number out of range");
  // Below the smallest double is zero, not an error.
  const SceneDesc s = parse_scene_text(
      replaced(scene([](Json& j) { j["rays"]["origin"] = {12345, 0, 0}; }), "12345", "1e-400"), "x.json", "/scenes");
  EXPECT_EQ(s.origins[0], 0.0);
}

// ---- hardening (c): numbers in messages --------------------------------------------------

TEST(Hardening, NumbersInMessagesAreShort) {
  expect_error(scene([](Json& j) { j["rays"]["fan"]["count"] = 1e308; }), "$.rays.fan.count",
               "expected a non-negative integer, got 1e+308");
  expect_error(scene([](Json& j) { j["rays"]["fan"]["count"] = 1.5; }), "$.rays.fan.count", "got 1.5");
  expect_error(scene([](Json& j) { j["rays"]["fan"]["count"] = -3; }), "$.rays.fan.count", "got -3");
  expect_error(scene([](Json& j) { j["rays"]["fan"]["max_deg"] = 1e308; }), "$.rays.fan.max_deg",
               "must be within -360..360 degrees, got 1e+308");
  expect_error(scene([](Json& j) { j["rays"]["wavelengths"] = -1e-9; }), "$.rays.wavelengths", "got -1e-09");
  const std::string msg = error_of("[1e400]").what();
  EXPECT_NE(msg.find("1.7976931348623157e+308"), std::string::npos) << msg;
}

// ---- hardening (d): repeated and unknown keys ------------------------------------------

TEST(Hardening, RepeatedKeys) {
  expect_error(R"({"name": "a", "name": "b"})", "$.name", "key given twice");
  expect_error(R"({"name": "t", "medium": {"type": "constant", "n": 1, "n": 2}})", "$.medium.n", "key given twice");
  expect_error(R"({"rays": {"origins": [[0, 0, 0]], "directions": [{"x": 1, "x": 1}]}})", "$.rays.directions[0].x",
               "key given twice");
  // The same key in different objects is fine.
  EXPECT_NO_THROW(arcus::json::Document::from_text(R"([{"a": 1}, {"a": 1}, {"b": {"a": 1}}])", "x.json"));
}

TEST(Hardening, UnknownKeys) {
  expect_error(scene([](Json& j) { j["colour"] = 1; }), "$.colour", "unknown key (allowed here: name, description");
  expect_error(scene([](Json& j) { j["medium"]["radiuss"] = 1; }), "$.medium.radiuss",
               "unknown key (allowed here: type, center, radius)");
  expect_error(scene([](Json& j) { j["rays"]["fan"]["cnt"] = 1; }), "$.rays.fan.cnt", "unknown key");
  expect_error(scene([](Json& j) { j["integrator"]["tol"] = 1; }), "$.integrator.tol", "unknown key");
  // A key that is no identifier is quoted, escapes and all, so the path stays one line.
  expect_error(scene([](Json& j) { j["medium"]["a b\n"] = 1; }), "$.medium[\"a b\\n\"]", "unknown key");
  expect_error(scene([](Json& j) { j[""] = 1; }), "$[\"\"]", "unknown key");
  expect_error(scene([](Json& j) { j[std::string(10000, 'k') + " "] = 1; }), "$[\"" + std::string(64, 'k') + "\"...]",
               "unknown key");
}

// ---- hardening (e): not an object, empty, invalid UTF-8 ------------------------------------

TEST(Hardening, TopLevelMustBeAnObject) {
  for (const char* text : {"[1]", "1", "\"scene\"", "null", "true", "[]"}) {
    SCOPED_TRACE(text);
    expect_error(text, "$", "expected an object");
  }
}

TEST(Hardening, EmptyInput) {
  expect_error("", "$", "empty document");
  expect_error(" \n\t\r ", "$", "empty document");
  expect_error("{}", "$", "missing key \"name\"");
}

TEST(Hardening, InvalidUtf8) {
  const std::vector<std::string> inputs = {
      "{\"name\": \"\xff\"}",             // a byte that is never UTF-8
      "{\"na\xc3\": 1}",                  // a truncated sequence in a key
      "{\"name\": \"\xc0\xaf\"}",         // an overlong '/'
      "{\"name\": \"\xed\xa0\x80\"}",     // an encoded surrogate
      "{\"name\": \"\xf4\x90\x80\x80\"}",  // above U+10FFFF
      "\xff\xfe{}",                       // a UTF-16 byte order mark
      std::string("{\"name\": \"a\0b\"}", 15),  // a raw NUL in a string
      std::string("{\"name\"\0: 1}", 12),       // a NUL between tokens
      "{\"name\": \"\x01\"}",                   // a raw control character
  };
  for (const std::string& text : inputs) {
    SCOPED_TRACE(text);
    const arcus::Error e = error_of(text);
    const std::string msg = e.what();
    EXPECT_EQ(e.status(), ARCUS_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(msg.rfind("x.json: not valid JSON (after $", 0), 0u) << msg;
    EXPECT_TRUE(valid_utf8(msg)) << msg;
    EXPECT_EQ(msg.find('\0'), std::string::npos);
  }
  // An escaped NUL is valid JSON, but not in a name or a file name.
  expect_error(R"({"name": "a\u0000b"})", "$.name", "use letters");
  expect_error(scene([](Json& j) {
                 j["medium"] = {{"type", "grid"}, {"file", std::string("a\0b", 3)}};
               }),
               "$.medium.file", "must not contain a NUL character");
  // Valid UTF-8 everywhere is fine, and a UTF-8 byte order mark is skipped.
  EXPECT_NO_THROW(parse_scene_text("\xef\xbb\xbf" + scene([](Json& j) { j["description"] = "λ = 550 nm, 25 °C"; }),
                                   "x.json", "/scenes"));
}

// Text that is no JSON: "x.json: not valid JSON (after <path>): ..." — the path is where
// the parser had got to (a file cut short fails after its last complete key).
void expect_syntax_error(const std::string& text, const std::string& path, const std::string& what = "") {
  const std::string msg = error_of(text).what();
  EXPECT_EQ(msg.rfind("x.json: not valid JSON (after " + path + "): ", 0), 0u) << msg;
  EXPECT_NE(msg.find(what), std::string::npos) << "expected \"" << what << "\" in: " << msg;
  EXPECT_TRUE(valid_utf8(msg)) << msg;
  EXPECT_LT(msg.size(), 1000u) << msg.substr(0, 300);
}

TEST(Hardening, SyntaxErrorsNameWhereTheyAre) {
  expect_syntax_error(R"({"name": "t", "medium": {"type": "constant", "n": tru}})", "$.medium.n");
  expect_syntax_error(R"({"name": "t",})", "$.name");
  expect_syntax_error(R"({"name": "t"} trailing)", "$");
  expect_syntax_error(R"({"a": [1, 2, }]})", "$.a[2]");
  expect_syntax_error(R"({"a": "\ud800"})", "$.a");  // a lone surrogate escape
  expect_syntax_error(R"({"name": "t", "descr)", "$.name", "line 1");  // cut short
  // A long bad token is not copied whole into the message.
  expect_syntax_error("{\"a\": \"" + std::string(1000000, 'x') + "\x01\"}", "$.a", "...");
}

// ---- the schema's own checks, each at its path ------------------------------------------

TEST(Schema, Name) {
  expect_error(scene([](Json& j) { j.erase("name"); }), "$", "missing key \"name\"");
  expect_error(scene([](Json& j) { j["name"] = 5; }), "$.name", "expected a string");
  for (const char* bad : {"", ".", "..", "a/b", "a b", "ü"}) {
    SCOPED_TRACE(bad);
    expect_error(scene([&](Json& j) { j["name"] = bad; }), "$.name",
                 "use letters, digits, '_', '-' and '.' only (it names the output directory)");
  }
  expect_error(scene([](Json& j) { j["description"] = 1; }), "$.description", "expected a string");
}

TEST(Schema, Medium) {
  expect_error(scene([](Json& j) { j["medium"] = 1; }), "$.medium", "expected an object");
  expect_error(scene([](Json& j) { j["medium"].erase("type"); }), "$.medium", "missing key \"type\"");
  expect_error(scene([](Json& j) { j["medium"]["type"] = "lens"; }), "$.medium.type",
               "\"lens\" is not one of constant, linear, linear_n2, luneburg, fisheye, atmosphere, grid");
  expect_error(scene([](Json& j) { j["medium"]["radius"] = "1"; }), "$.medium.radius", "expected a number");
  expect_error(scene([](Json& j) { j["medium"].erase("radius"); }), "$.medium", "missing key \"radius\"");
  expect_error(scene([](Json& j) { j["medium"]["center"] = {0, 0}; }), "$.medium.center", "expected [x, y, z]");
  expect_error(scene([](Json& j) { j["medium"]["center"] = {0, nullptr, 0}; }), "$.medium.center[1]",
               "expected a number");
  expect_error(scene([](Json& j) { j["medium"]["center"] = "origin"; }), "$.medium.center", "expected an array");
  expect_error(scene([](Json& j) { j["medium"] = {{"type", "constant"}, {"n", true}}; }), "$.medium.n",
               "expected a number");
}

TEST(Schema, Atmosphere) {
  auto atm = [](const char* m) { return scene([&](Json& j) { j["medium"] = Json::parse(m); }); };
  expect_error(atm(R"({"type": "atmosphere", "spherical": 1})"), "$.medium.spherical", "expected true or false");
  expect_error(atm(R"({"type": "atmosphere", "inversions": [{"base": 0, "top": 1, "delta_t": 1}, {"base": 0}]})"),
               "$.medium.inversions[1]", "missing key \"top\"");
  expect_error(atm(R"({"type": "atmosphere", "inversions": [{"base": 0, "top": 1, "delta_t": 1, "dt": 2}]})"),
               "$.medium.inversions[0].dt", "unknown key (allowed here: base, top, delta_t)");
  expect_error(atm(R"({"type": "atmosphere", "inversions": {}})"), "$.medium.inversions", "expected an array");
  Json many = Json::array();
  for (int i = 0; i < ARCUS_MAX_INVERSIONS + 1; ++i) many.push_back({{"base", 0}, {"top", 1}, {"delta_t", 1}});
  expect_error(scene([&](Json& j) { j["medium"] = {{"type", "atmosphere"}, {"inversions", many}}; }),
               "$.medium.inversions", "at most 1024 layers");
}

TEST(Schema, Grid) {
  auto grid = [](const std::function<void(Json&)>& edit) {
    return scene([&](Json& j) {
      j["medium"] = Json::parse(R"({"type": "grid", "file": "n.raw", "dtype": "float64", "dims": [2, 2, 2],
                                    "origin": [0, 0, 0], "spacing": [1, 1, 1]})");
      edit(j["medium"]);
    });
  };
  expect_error(grid([](Json& m) { m["dtype"] = "int8"; }), "$.medium.dtype", "\"int8\" is not one of float32, float64");
  expect_error(grid([](Json& m) { m["dims"] = {2, 2}; }), "$.medium.dims", "expected [nx, ny, nz]");
  expect_error(grid([](Json& m) { m["dims"] = {2, 2, -1}; }), "$.medium.dims[2]",
               "expected a non-negative integer, got -1");
  expect_error(grid([](Json& m) { m["dims"] = {2, 2, 4294967296}; }), "$.medium.dims[2]",
               "expected an integer no larger than 4294967295");
  expect_error(grid([](Json& m) { m["file"] = ""; }), "$.medium.file", "must not be empty");
  expect_error(grid([](Json& m) { m["file"] = 3; }), "$.medium.file", "expected a string");
  expect_error(grid([](Json& m) { m.erase("spacing"); }), "$.medium", "missing key \"spacing\"");
}

TEST(Schema, Rays) {
  expect_error(scene([](Json& j) { j["rays"]["origins"] = Json::array(); }), "$.rays",
               "give either \"origin\" and \"fan\", or \"origins\" and \"directions\"");
  expect_error(scene([](Json& j) { j["rays"] = Json::object(); }), "$.rays", "give either");
  expect_error(scene([](Json& j) { j["rays"].erase("origin"); }), "$.rays", "missing key \"origin\"");
  expect_error(scene([](Json& j) { j["rays"]["fan"]["direction"] = {0, 0, 0}; }), "$.rays.fan.direction",
               "must not be the zero vector");
  expect_error(scene([](Json& j) { j["rays"]["fan"]["plane_normal"] = {0, 0, -0.0}; }), "$.rays.fan.plane_normal",
               "must not be the zero vector");
  expect_error(scene([](Json& j) { j["rays"]["fan"]["plane_normal"] = {0.1, 0, 1}; }), "$.rays.fan.plane_normal",
               "must be perpendicular to fan.direction");
  expect_error(scene([](Json& j) { j["rays"]["fan"]["max_deg"] = -11; }), "$.rays.fan.max_deg",
               "must be at least min_deg");
  expect_error(scene([](Json& j) { j["rays"]["fan"]["min_deg"] = -360.5; }), "$.rays.fan.min_deg",
               "must be within -360..360 degrees, got -360.5");
  expect_error(scene([](Json& j) { j["rays"]["fan"]["count"] = 0; }), "$.rays.fan.count", "must be at least 1");
  expect_error(scene([](Json& j) { j["rays"]["fan"]["count"] = 67108865; }), "$.rays.fan.count",
               "expected an integer no larger than 67108864");
  expect_error(scene([](Json& j) { j["rays"] = Json::parse(R"({"origins": [], "directions": []})"); }),
               "$.rays.origins", "needs at least one ray");
  expect_error(
      scene([](Json& j) { j["rays"] = Json::parse(R"({"origins": [[0, 0, 0], [1, 1, 1]], "directions": [[1, 0, 0]]})"); }),
      "$.rays.directions", "has 1 entries, origins has 2");
  expect_error(scene([](Json& j) {
                 j["rays"] = Json::parse(R"({"origins": [[0, 0, 0], [1, 1, 1]], "directions": [[1, 0, 0], [0, 0, 0]]})");
               }),
               "$.rays.directions[1]", "must not be the zero vector");
  expect_error(scene([](Json& j) {
                 j["rays"] = Json::parse(R"({"origins": [[0, 0, 0], [1, 1]], "directions": [[1, 0, 0], [1, 0, 0]]})");
               }),
               "$.rays.origins[1]", "expected [x, y, z]");
  SceneLimits small;
  small.max_rays = 1;
  expect_error(
      scene([](Json& j) {
        j["rays"] = Json::parse(R"({"origins": [[0, 0, 0], [1, 1, 1]], "directions": [[1, 0, 0], [1, 0, 0]]})");
      }),
      "$.rays.origins", "has 2 rays, more than the limit of 1", small);
}

TEST(Schema, IntegratorBoxPath) {
  expect_error(scene([](Json& j) { j.erase("integrator"); }), "$", "missing key \"integrator\"");
  expect_error(scene([](Json& j) { j["integrator"].erase("length"); }), "$.integrator", "missing key \"length\"");
  expect_error(scene([](Json& j) { j["integrator"]["method"] = "rk5"; }), "$.integrator.method",
               "\"rk5\" is not one of dp45, rk4, rk2, euler");
  expect_error(scene([](Json& j) { j["integrator"]["precision"] = "half"; }), "$.integrator.precision",
               "\"half\" is not one of double, float");
  expect_error(scene([](Json& j) { j["integrator"]["max_rejections"] = 4294967296; }), "$.integrator.max_rejections",
               "expected an integer no larger than 4294967295");
  expect_error(scene([](Json& j) { j["integrator"]["max_steps"] = 1e19; }), "$.integrator.max_steps",
               "expected a non-negative integer, got 1e+19");
  expect_error(scene([](Json& j) { j["box"] = {{"min", {0, 0, 0}}, {"max", {1, 0, 1}}}; }), "$.box.max",
               "must exceed min on every axis");
  expect_error(scene([](Json& j) { j["box"] = {{"min", {0, 0, 0}}}; }), "$.box", "missing key \"max\"");
  expect_error(scene([](Json& j) { j["record_path"] = "yes"; }), "$.record_path", "expected true or false");
  expect_error(scene([](Json& j) { j["path_capacity"] = -1; }), "$.path_capacity", "got -1");
}

// ---- files --------------------------------------------------------------------------------

void expect_io(const std::string& path, const std::string& what) {
  try {
    parse_scene_file(path);
    ADD_FAILURE() << "no error for " << path;
  } catch (const arcus::Error& e) {
    EXPECT_EQ(e.status(), ARCUS_ERROR_IO) << e.what();
    EXPECT_EQ(std::string(e.what()), path + ": " + what);
  }
}

TEST(Files, MissingDirectoryDevice) {
  TempDir dir;
  expect_io((dir.path / "none.json").string(), "cannot read: No such file or directory");
  expect_io(dir.path.string(), "is a directory, not a regular file");
  expect_io("/dev/null", "is a character device, not a regular file");
  expect_io("", "cannot read: No such file or directory");
  try {
    parse_scene_file(std::string("a\0b", 3));
    ADD_FAILURE() << "no error";
  } catch (const arcus::Error& e) {
    EXPECT_EQ(e.status(), ARCUS_ERROR_IO);
    EXPECT_STREQ(e.what(), "a\\x00b: the file name contains a NUL character");
  }
}

TEST(Files, FifoIsRefusedWithoutBlocking) {
  TempDir dir;
  const fs::path fifo = dir.path / "scene.json";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  auto result = std::async(std::launch::async, [&] { expect_io(fifo.string(), "is a FIFO, not a regular file"); });
  if (result.wait_for(std::chrono::seconds(10)) != std::future_status::ready) {
    ADD_FAILURE() << "reading a FIFO blocked";
    const int fd = open(fifo.c_str(), O_WRONLY | O_NONBLOCK);  // lets the blocked reader go
    if (fd >= 0) close(fd);
  }
  result.wait();
}

TEST(Files, UnreadableFile) {
  if (geteuid() == 0) GTEST_SKIP() << "root reads any file";
  TempDir dir;
  const fs::path p = dir.write("locked.json", scene());
  fs::permissions(p, fs::perms::none);
  expect_io(p.string(), "cannot open: Permission denied");
}

TEST(Files, ErrorsInAFileNameTheFile) {
  TempDir dir;
  const fs::path p = dir.write("bad.json", scene([](Json& j) { j["medium"]["radius"] = "big"; }));
  try {
    parse_scene_file(p.string());
    ADD_FAILURE() << "no error";
  } catch (const arcus::Error& e) {
    EXPECT_EQ(e.status(), ARCUS_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(std::string(e.what()), p.string() + ": $.medium.radius: expected a number");
  }
}

// ---- the JSON reader on its own -------------------------------------------------------------

TEST(JsonReader, DocumentKeepsTheAuthorsOrder) {
  auto doc = arcus::json::Document::from_text(R"({"zeta": 1, "alpha": {"y": [1, 2.5], "b": "s"}})", "x.json");
  EXPECT_EQ(doc.dump(), "{\n  \"zeta\": 1,\n  \"alpha\": {\n    \"y\": [\n      1,\n      2.5\n    ],\n"
                        "    \"b\": \"s\"\n  }\n}");
  const arcus::json::Node y = doc.root().member("alpha").member("y");
  EXPECT_EQ(y.path(), "$.alpha.y");
  EXPECT_EQ(y.elements()[1].path(), "$.alpha.y[1]");
  EXPECT_EQ(y.elements()[1].number(), 2.5);
  EXPECT_FALSE(doc.root().find("beta").has_value());
  // A moved document keeps its nodes valid.
  arcus::json::Document moved = std::move(doc);
  EXPECT_EQ(y.elements()[0].integer(10), 1u);
  EXPECT_EQ(y.file_name(), "x.json");
}

TEST(JsonReader, MessageHelpers) {
  EXPECT_EQ(arcus::json::child_path("$", "medium"), "$.medium");
  EXPECT_EQ(arcus::json::child_path("$", "_a1"), "$._a1");
  EXPECT_EQ(arcus::json::child_path("$", "1a"), "$[\"1a\"]");
  EXPECT_EQ(arcus::json::child_path("$.a", "x.y"), "$.a[\"x.y\"]");
  EXPECT_EQ(arcus::json::quoted("tab\there"), "\"tab\\there\"");
  // Cut at a code point, never inside one.
  EXPECT_EQ(arcus::json::quoted("aλλ", 2), "\"a\"...");
  EXPECT_EQ(arcus::json::quoted("aλλ", 3), "\"aλ\"...");
}

// ---- the fuzzer's inputs ------------------------------------------------------------------

TEST(FuzzSeeds, AllParse) {
  // Seeds that no longer parse would start the fuzzer far from the schema.
  int n = 0;
  for (const auto& entry : fs::directory_iterator(fs::path(kSource) / "tests" / "fuzz" / "scene" / "seeds")) {
    ++n;
    SCOPED_TRACE(entry.path().string());
    EXPECT_NO_THROW(parse_scene_file(entry.path().string()));
  }
  EXPECT_GE(n, 3);
}

// Inputs that once crashed or gave a bad error (tests/fuzz/scene/regressions).

TEST(FuzzRegressions, ParseOrFailCleanly) {
  const fs::path dir = fs::path(kSource) / "tests" / "fuzz" / "scene" / "regressions";
  ASSERT_TRUE(fs::is_directory(dir)) << dir;
  int n = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (!entry.is_regular_file()) continue;
    ++n;
    SCOPED_TRACE(entry.path().string());
    const std::string name = entry.path().filename().string();
    try {
      parse_scene_text(read_text(entry.path()), name, dir.string());
    } catch (const arcus::Error& e) {
      const std::string msg = e.what();
      EXPECT_EQ(e.status(), ARCUS_ERROR_INVALID_ARGUMENT) << msg;
      EXPECT_TRUE(msg.rfind(name + ": $", 0) == 0 || msg.rfind(name + ": not valid JSON (after $", 0) == 0)
          << msg.substr(0, 300);
      EXPECT_TRUE(valid_utf8(msg)) << msg.substr(0, 300);
    }
  }
  EXPECT_GT(n, 0);
}

}  // namespace
