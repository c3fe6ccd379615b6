// Scene files read by the library (arcus_scene_load): the bundled scenes load and run,
// what a scene says comes back through the API, and bad files fail with messages that
// name the file and the key path — through the API and through arcus_trace.
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "scoped_env.h"
#include "test_util.h"

using namespace arcus_test;

namespace {

class Scenes : public ArcusTest {
 protected:
  static std::string scene_path(const char* name) { return std::string(ARCUS_SOURCE_DIR) + "/scenes/" + name; }
  static std::string temp_file(const char* tag, const std::string& text) {
    const std::string path = ::testing::TempDir() + "arcus_scene_" + tag + "_" + std::to_string(getpid()) + ".json";
    std::ofstream(path) << text;
    return path;
  }
  // The status and context message of loading `path`.
  std::pair<arcus_status, std::string> load_error(const std::string& path) {
    arcus_scene_t* scene = reinterpret_cast<arcus_scene_t*>(0x1);
    const arcus_status st = arcus_scene_load(ctx(), path.c_str(), &scene);
    EXPECT_EQ(scene, nullptr);
    if (st == ARCUS_SUCCESS && scene) arcus_scene_release(scene);
    return {st, last_error()};
  }
};

struct SceneDeleter {
  void operator()(arcus_scene_t* s) const { arcus_scene_release(s); }
};
using ScenePtr = std::unique_ptr<arcus_scene_t, SceneDeleter>;

TEST_F(Scenes, TheLuneburgSceneLoadsAndFocusesItsRays) {
  arcus_scene_t* raw = nullptr;
  ASSERT_EQ(arcus_scene_load(ctx(), scene_path("luneburg.json").c_str(), &raw), ARCUS_SUCCESS) << last_error();
  ScenePtr scene(raw);
  const char *name = nullptr, *engine = nullptr, *document = nullptr, *description = nullptr;
  ASSERT_EQ(arcus_scene_get_name(scene.get(), &name), ARCUS_SUCCESS);
  ASSERT_EQ(arcus_scene_get_engine(scene.get(), &engine), ARCUS_SUCCESS);
  ASSERT_EQ(arcus_scene_get_document(scene.get(), &document), ARCUS_SUCCESS);
  ASSERT_EQ(arcus_scene_get_description(scene.get(), &description), ARCUS_SUCCESS);
  EXPECT_STREQ(name, "luneburg");
  EXPECT_STREQ(engine, "curved");
  EXPECT_TRUE(contains_ci(document, "\"luneburg\"")) << document;
  arcus_field_t* field = nullptr;
  ASSERT_EQ(arcus_scene_get_field(scene.get(), &field), ARCUS_SUCCESS);
  FieldPtr field_guard(field);
  arcus_field_kind kind;
  ASSERT_EQ(arcus_field_get_kind(field, &kind), ARCUS_SUCCESS);
  EXPECT_EQ(kind, ARCUS_FIELD_LUNEBURG);
  size_t count = 0;
  ASSERT_EQ(arcus_scene_get_ray_count(scene.get(), &count), ARCUS_SUCCESS);
  ASSERT_GT(count, 2u);
  std::vector<double> origins(3 * count), directions(3 * count), wavelengths(count, -1.0);
  int32_t has_wavelengths = -1;
  ASSERT_EQ(arcus_scene_get_rays(scene.get(), origins.data(), directions.data(), wavelengths.data(), &has_wavelengths),
            ARCUS_SUCCESS);
  EXPECT_EQ(has_wavelengths, 0);
  EXPECT_EQ(wavelengths[0], -1.0) << "left untouched without wavelengths";
  arcus_advance_params p;
  ASSERT_EQ(arcus_scene_get_advance_params(scene.get(), &p), ARCUS_SUCCESS);
  EXPECT_EQ(p.progress, nullptr);
  // Determinism: the scene's job is arcus_curved_advance with the scene's rays and settings.
  // (The lens' physics is checked against its closed form in test_curved_closed_forms.)
  arcus_job_t* job = nullptr;
  ASSERT_EQ(arcus_curved_advance_scene(scene.get(), nullptr, nullptr, &job), ARCUS_SUCCESS) << last_error();
  JobPtr job_guard(job);
  Rays rays;
  for (size_t i = 0; i < count; ++i)
    rays.add({origins[3 * i], origins[3 * i + 1], origins[3 * i + 2]},
             {directions[3 * i], directions[3 * i + 1], directions[3 * i + 2]});
  const Trace direct = trace(ctx(), field, p, rays);
  ASSERT_EQ(direct.status, ARCUS_SUCCESS);
  std::vector<double> pos(3 * count);
  ASSERT_EQ(arcus_job_get_curved_end_states(job, pos.data(), nullptr, nullptr, nullptr, nullptr), ARCUS_SUCCESS);
  EXPECT_EQ(pos, direct.positions);
}

TEST_F(Scenes, BadFilesFailWithTheFileAndTheKeyPath) {
  const auto missing = load_error("/no/such/scene.json");
  EXPECT_EQ(missing.first, ARCUS_ERROR_IO);
  EXPECT_TRUE(contains_ci(missing.second.c_str(), "/no/such/scene.json")) << missing.second;
  const auto directory = load_error("/tmp");
  EXPECT_EQ(directory.first, ARCUS_ERROR_IO);
  EXPECT_TRUE(contains_ci(directory.second.c_str(), "directory")) << directory.second;
  // A wrong value, with its path.
  std::ifstream in(scene_path("luneburg.json"));
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string radius = "\"radius\": 1";
  const size_t at = text.find(radius);
  ASSERT_NE(at, std::string::npos);
  auto with_radius = [&](const std::string& value) { return text.substr(0, at) + value + text.substr(at + radius.size()); };
  const std::string bad_radius = with_radius("\"radius\": \"big\"");
  const std::string file = temp_file("radius", bad_radius);
  const auto wrong = load_error(file);
  EXPECT_EQ(wrong.first, ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_TRUE(contains_ci(wrong.second.c_str(), file.c_str())) << wrong.second;
  EXPECT_TRUE(contains_ci(wrong.second.c_str(), "$.field.radius")) << wrong.second;
  // A value the medium refuses (a negative radius passes the reader, not the field).
  const std::string negative = with_radius("\"radius\": -1");
  const auto refused = load_error(temp_file("negative", negative));
  EXPECT_EQ(refused.first, ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_TRUE(contains_ci(refused.second.c_str(), "$.field")) << refused.second;
  EXPECT_TRUE(contains_ci(refused.second.c_str(), "radius")) << refused.second;
  // Deep nesting is refused before it can overflow the stack.
  const std::string deep = "{\"a\": " + std::string(100000, '[') + std::string(100000, ']') + ", \"b\": 1}";
  const auto nested = load_error(temp_file("deep", deep));
  EXPECT_EQ(nested.first, ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_TRUE(contains_ci(nested.second.c_str(), "nesting")) << nested.second;
  // A number beyond double: the file and the path, not an internal exception's text.
  const auto huge = load_error(temp_file("huge", "{\"name\": \"x\", \"medium\": {\"type\": \"constant\", \"n\": 1e400}}"));
  EXPECT_EQ(huge.first, ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_TRUE(contains_ci(huge.second.c_str(), "$.medium.n")) << huge.second;
  EXPECT_FALSE(contains_ci(huge.second.c_str(), "out_of_range.406")) << huge.second;
  // A scene handle is checked like every other.
  const char* name = nullptr;
  EXPECT_EQ(arcus_scene_get_name(reinterpret_cast<arcus_scene_t*>(ctx()), &name), ARCUS_ERROR_INVALID_ARGUMENT);
}

TEST_F(Scenes, MediumIsTheDeprecatedSpellingOfField) {
  // arcus 0.10 names a scene's index field "field", as the C API does; 0.9's "medium"
  // is still read, for one release, and giving both is refused, naming them.
  const std::string rest = R"(, "rays": {"origins": [[0, 0, 0]], "directions": [[1, 0, 0]]},
      "integrator": {"method": "dp45", "length": 1}})";
  for (const char* key : {"field", "medium"}) {
    arcus_scene_t* scene = nullptr;
    const std::string text = std::string(R"({"name": "k", ")") + key + R"(": {"type": "constant", "n": 1.5})" + rest;
    ASSERT_EQ(arcus_scene_load(ctx(), temp_file(key, text).c_str(), &scene), ARCUS_SUCCESS) << key << ": " << last_error();
    arcus_field_t* field = nullptr;
    ASSERT_EQ(arcus_scene_get_field(scene, &field), ARCUS_SUCCESS);
    const double origin[3] = {0, 0, 0};
    double n = 0;
    ASSERT_EQ(arcus_field_evaluate(field, 1, origin, &n, nullptr), ARCUS_SUCCESS);
    EXPECT_EQ(n, 1.5) << key;
    arcus_field_release(field);
    arcus_scene_release(scene);
  }
  const auto both = load_error(temp_file(
      "both_keys", R"({"name": "k", "field": {"type": "constant", "n": 1}, "medium": {"type": "constant", "n": 1})" + rest));
  EXPECT_EQ(both.first, ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_TRUE(contains_ci(both.second.c_str(), "\"medium\" is the arcus 0.9 spelling of \"field\"")) << both.second;
}

TEST_F(Scenes, ADocumentWithTwoEnginesMarkersIsRefusedNotGuessed) {
#ifndef ARCUS_TEST_ALL_ENGINES
  GTEST_SKIP() << "needs the render, ocean and rainbow engines (ARCUS_WITH_<ENGINE>)";
#endif
  // Which engine read it depended on the order the engines registered in.
  const auto both = load_error(temp_file("both", R"({"name": "x", "camera": {}, "water": {}})"));
  EXPECT_EQ(both.first, ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_TRUE(contains_ci(both.second.c_str(), "which kind of scene is it")) << both.second;
  // A rainbow scene has a camera too: "rain" decides.
  arcus_scene_t* scene = nullptr;
  ASSERT_EQ(arcus_scene_load(ctx(), scene_path("rainbow/double_bow.json").c_str(), &scene), ARCUS_SUCCESS)
      << last_error();
  ScenePtr guard(scene);
  const char* engine = nullptr;
  ASSERT_EQ(arcus_scene_get_engine(scene, &engine), ARCUS_SUCCESS);
  EXPECT_STREQ(engine, "rainbow");
}

TEST_F(Scenes, ScenesAndRequestsBeyondTheBoundsAreRefusedBeforeAllocating) {
  // A scene file is read whole: 1.5 GB of NUL bytes took 1.7 GB and 5 s.  Now its size is
  // held to ARCUS_MAX_SCENE_BYTES (64 MiB) first; a sparse file stands in for a big one.
  const std::string big = ::testing::TempDir() + "arcus_scene_big_" + std::to_string(getpid()) + ".json";
  { std::ofstream(big) << "{}"; }
  std::filesystem::resize_file(big, uint64_t(3) << 29);
  const auto huge = load_error(big);
  EXPECT_EQ(huge.first, ARCUS_ERROR_IO);
  EXPECT_TRUE(contains_ci(huge.second.c_str(), "1.5 GiB is more than the 64 MiB allowed (ARCUS_MAX_SCENE_BYTES"))
      << huge.second;
  std::filesystem::remove(big);
  // 2^26 rays (the schema's limit) are 3 GiB of origins and directions: within a
  // host limit of 256 MiB they are refused, naming the rays.
  ScopedEnv limit("ARCUS_MEMORY_LIMIT", "256M");
  const auto fan = load_error(temp_file("fan", R"({"name": "f", "medium": {"type": "constant", "n": 1.0},
      "rays": {"origin": [0, 0, 0], "fan": {"direction": [1, 0, 0], "plane_normal": [0, 0, 1],
               "min_deg": -10, "max_deg": 10, "count": 67108864}},
      "integrator": {"method": "rk4", "step": 0.1, "length": 1}})"));
  EXPECT_EQ(fan.first, ARCUS_ERROR_OUT_OF_MEMORY);
  EXPECT_TRUE(contains_ci(fan.second.c_str(), "$.rays: 67108864 rays needs 3 GiB of host memory; 256 MiB are allowed"))
      << fan.second;
  // The same bound on a call: 4 million rays need about 0.7 GiB while they are advanced.
  const size_t count = size_t(1) << 22;
  std::vector<double> origins(3 * count, 0.0), directions(3 * count, 0.0);
  for (size_t i = 0; i < count; ++i) directions[3 * i] = 1;
  auto field = constant(1.0);
  arcus_advance_params p = fixed(ARCUS_METHOD_RK4, 0.1, 1.0);
  arcus_job_t* job = nullptr;
  EXPECT_EQ(arcus_curved_advance(ctx(), field.get(), &p, count, origins.data(), directions.data(), nullptr, &job),
                                 ARCUS_ERROR_OUT_OF_MEMORY);
  EXPECT_EQ(job, nullptr);
  EXPECT_TRUE(contains_ci(last_error().c_str(), "4194304 rays needs")) << last_error();
  // A malformed bound is said to be one.
  ScopedEnv bad("ARCUS_MEMORY_LIMIT", "lots");
  EXPECT_EQ(arcus_curved_advance(ctx(), field.get(), &p, 1, origins.data(), directions.data(), nullptr, &job),
                                 ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_TRUE(contains_ci(last_error().c_str(), "ARCUS_MEMORY_LIMIT = 'lots' is not a positive size")) << last_error();
}

#ifdef ARCUS_TRACE
// arcus_trace on a deeply nested scene: a clear error and exit status 2, not a crash
// (it overflowed the stack: exit 139).
TEST(Trace, ADeeplyNestedSceneIsAnErrorNotACrash) {
  const std::string path = ::testing::TempDir() + "arcus_trace_deep_" + std::to_string(getpid()) + ".json";
  std::ofstream(path) << "{\"a\": " << std::string(100000, '[') << std::string(100000, ']') << ", \"b\": 1}";
  const std::string command = std::string(ARCUS_TRACE) + " " + path + " --out " + ::testing::TempDir() + " 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::string output;
  char buf[512];
  while (std::fgets(buf, sizeof buf, pipe)) output += buf;
  const int status = pclose(pipe);
  ASSERT_TRUE(WIFEXITED(status)) << "arcus_trace died: " << output;
  EXPECT_EQ(WEXITSTATUS(status), 2) << output;
  EXPECT_TRUE(contains_ci(output.c_str(), path.c_str())) << output;
  EXPECT_TRUE(contains_ci(output.c_str(), "nesting")) << output;
  std::remove(path.c_str());
}
#endif

}  // namespace
