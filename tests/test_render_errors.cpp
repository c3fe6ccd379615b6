// Rendering through curved light (arcus_render.h), bad input: a status and a message
// naming the file and the key, and nothing changed.
#include "render_fixture.h"
#include "scoped_env.h"

using namespace arcus_test;

namespace {

// ---- bad input: a status and a message naming the file and the key -----------------

TEST_F(Render, AMissingMeshFileIsAnIoErrorNamingTheSceneTheKeyAndTheFile) {
  const std::string text = scene_text(
      R"({"type": "constant", "n": 1.0})",
      R"({"position": [0, 0, 0], "look_at": [1, 0, 0], "vfov_deg": 40, "width": 4, "height": 4})",
      R"([{"type": "mesh", "file": "/nonexistent/ship.obj", "material": "m"}])");
  const auto [status, message] = load_error(temp_file("missing", ".json", text));
  EXPECT_EQ(status, ARCUS_ERROR_IO);
  EXPECT_NE(message.find("$.objects[0].file"), std::string::npos) << message;
  EXPECT_NE(message.find("/nonexistent/ship.obj"), std::string::npos) << message;
}

TEST_F(Render, AMeshWithoutFacesIsRefused) {
  const std::string obj = temp_file("nofaces", ".obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
  const std::string text = scene_text(
      R"({"type": "constant", "n": 1.0})",
      R"({"position": [0, 0, 0], "look_at": [1, 0, 0], "vfov_deg": 40, "width": 4, "height": 4})",
      R"([{"type": "mesh", "file": ")" + obj + R"(", "material": "m"}])");
  const auto [status, message] = load_error(temp_file("nofaces", ".json", text));
  EXPECT_EQ(status, ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(message.find(obj), std::string::npos) << message;
}

TEST_F(Render, GeometryTooFarForTheBvhIsRefusedNamingTheMesh) {
  // A mesh moved 3e38 m or scaled by 1e300: Embree's binning overflowed single precision
  // and an assertion aborted the process.
  const std::string camera = R"({"position": [0, 0, 0], "look_at": [1, 0, 0], "vfov_deg": 40, "width": 4, "height": 4})";
  for (const char* placement : {R"("translate": [3e38, 0, 0])", R"("scale": 1e300)"}) {
    const std::string text = scene_text(R"({"type": "constant", "n": 1.0})", camera,
                                        R"([{"type": "mesh", "file": ")" + mesh("icosphere.obj") +
                                            R"(", "material": "m", )" + placement + "}]");
    const auto [status, message] = load_error(temp_file("far", ".json", text));
    EXPECT_EQ(status, ARCUS_ERROR_INVALID_ARGUMENT) << placement;
    EXPECT_NE(message.find("icosphere.obj: vertex"), std::string::npos) << message;
    EXPECT_NE(message.find("1e+18 m from the origin"), std::string::npos) << message;
  }
}

TEST_F(Render, AnImageThatComesOutInfiniteIsAnErrorNotAPicture) {
  // A sky of 1e308 is a finite number in the scene, but radiance sums over it overflow:
  // the job reported success with an infinite image.
  const std::string text =
      R"({"name": "t", "medium": {"type": "constant", "n": 1.0},
          "integrator": {"method": "dp45", "rtol": 1e-9, "atol": 1e-6, "length": 100},
          "camera": {"position": [0, 0, 0], "look_at": [1, 0, 0], "vfov_deg": 40, "width": 4, "height": 4},
          "materials": {"m": {"diffuse": [0.5, 0.5, 0.5]}}, "objects": [],
          "sky": {"type": "constant", "color": [1e308, 1e308, 1e308]}})";
  arcus_scene_t* scene = load(text, "infinite");
  ASSERT_NE(scene, nullptr);
  arcus_renderer_t* r = nullptr;
  ASSERT_EQ(arcus_renderer_create(scene, &r), ARCUS_SUCCESS) << last_error();
  arcus_job_t* job = nullptr;
  EXPECT_EQ(arcus_render_frame(r, nullptr, nullptr, &job), ARCUS_ERROR_NOT_FINITE);
  EXPECT_EQ(job, nullptr);
  EXPECT_NE(last_error().find("pixels are not finite"), std::string::npos) << last_error();
  arcus_renderer_release(r);
  arcus_scene_release(scene);
}

TEST_F(Render, AFrameBeyondTheHostsMemoryIsRefusedBeforeAllocating) {
  // 16384 x 16384 pixels (the schema's largest) took 4-4.8 GB before "out of host
  // memory"; now the frame's needs are held to the memory available (here a bound of
  // 1 GiB, ARCUS_MEMORY_LIMIT) before anything is allocated.
  const std::string text = scene_text(
      R"({"type": "constant", "n": 1.0})",
      R"({"position": [0, 0, 0], "look_at": [1, 0, 0], "vfov_deg": 40, "width": 16384, "height": 16384})", "[]");
  arcus_scene_t* scene = load(text, "huge_frame");
  ASSERT_NE(scene, nullptr);
  arcus_renderer_t* r = nullptr;
  ASSERT_EQ(arcus_renderer_create(scene, &r), ARCUS_SUCCESS) << last_error();
  ScopedEnv limit("ARCUS_MEMORY_LIMIT", "1G");
  arcus_job_t* job = nullptr;
  EXPECT_EQ(arcus_render_frame(r, nullptr, nullptr, &job), ARCUS_ERROR_OUT_OF_MEMORY);
  EXPECT_EQ(job, nullptr);
  EXPECT_NE(last_error().find("a 16384 x 16384 frame needs 128 GiB of host memory; 1 GiB are allowed"),
            std::string::npos)
      << last_error();
  arcus_renderer_release(r);
  arcus_scene_release(scene);
}

TEST_F(Render, MalformedScenesNameTheFileAndTheKey) {
  const std::string cam =
      R"({"position": [0, 0, 0], "look_at": [1, 0, 0], "vfov_deg": 40, "width": 0, "height": 4})";
  auto [status, message] = load_error(temp_file("zero", ".json", scene_text(R"({"type": "constant", "n": 1.0})", cam, "[]")));
  EXPECT_EQ(status, ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(message.find("$.camera"), std::string::npos) << message;
  const std::string bad_material = scene_text(
      R"({"type": "constant", "n": 1.0})",
      R"({"position": [0, 0, 0], "look_at": [1, 0, 0], "vfov_deg": 40, "width": 4, "height": 4})",
      R"([{"type": "sphere", "center": [5, 0, 0], "radius": 1, "material": "gold"}])");
  std::tie(status, message) = load_error(temp_file("material", ".json", bad_material));
  EXPECT_EQ(status, ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(message.find("$.objects[0].material"), std::string::npos) << message;
  std::tie(status, message) = load_error(temp_file("json", ".json", R"({"name": "x", "camera": {)"));
  EXPECT_EQ(status, ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(message.find("arcus_render_json"), std::string::npos) << message;
}

TEST_F(Render, ANanCameraAndSymmetryOfAnAsymmetricMediumAreRefusedAndChangeNothing) {
  // The camera looks along x, so its vertical plane is z = 0; a gradient along z breaks
  // the mirror symmetry about it.
  arcus_scene_t* scene = load(scene_text(R"({"type": "linear", "n0": 1.0, "gradient": [0, 0, 0.01]})",
                                         R"({"position": [0, 0, 0], "look_at": [1, 0, 0], "vfov_deg": 40,
                                             "width": 4, "height": 4})",
                                         "[]", R"(, "bounds": {"min": [-1, -1, -1], "max": [1, 1, 1]})"),
                              "nan");
  ASSERT_NE(scene, nullptr);
  arcus_renderer_t* r = nullptr;
  ASSERT_EQ(arcus_renderer_create(scene, &r), ARCUS_SUCCESS);
  arcus_camera cam;
  ASSERT_EQ(arcus_renderer_get_camera(r, &cam), ARCUS_SUCCESS);
  arcus_camera bad = cam;
  bad.position[1] = NAN;
  EXPECT_EQ(arcus_renderer_set_camera(r, &bad), ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("finite"), std::string::npos) << last_error();
  arcus_camera now;
  ASSERT_EQ(arcus_renderer_get_camera(r, &now), ARCUS_SUCCESS);
  EXPECT_EQ(now.position[1], cam.position[1]);
  EXPECT_EQ(arcus_renderer_set_techniques(r, ARCUS_TECHNIQUE_SYMMETRY), ARCUS_ERROR_UNSUPPORTED);
  EXPECT_NE(last_error().find("gradient is not parallel"), std::string::npos) << last_error();
  uint32_t t = 99;
  ASSERT_EQ(arcus_renderer_get_techniques(r, &t), ARCUS_SUCCESS);
  EXPECT_EQ(t, 0u);
  arcus_renderer_release(r);
  arcus_scene_release(scene);
}

}  // namespace
