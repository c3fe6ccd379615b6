// Render scenes with meshes from memory (arcus_scene_load_with_meshes, arcus_scene.h):
// a mesh handed over as arrays is placed by the scene as a mesh file is and renders the
// straight pinhole image; the same triangles from memory and from a file give the same
// image bit for bit; every misuse of the names and handles is refused, naming it.
#include "render_fixture.h"

using namespace arcus_test;

namespace {

// The icosphere, read by this test (not the library) as arrays: its triangles' corners
// one after another, so triangle k is indices 3k, 3k+1, 3k+2 as in the file.  `to_float`
// rounds the coordinates as the library's file readers do.
struct Arrays {
  std::vector<double> vertices;
  std::vector<uint32_t> indices;
};
Arrays icosphere_arrays(const std::string& path, bool to_float) {
  const double origin[3] = {0, 0, 0};
  Arrays a;
  a.vertices = read_obj_triangles(path, 1.0, origin);
  if (to_float)
    for (double& x : a.vertices) x = static_cast<float>(x);
  for (uint32_t i = 0; 3 * i < a.vertices.size(); ++i) a.indices.push_back(i);
  return a;
}

class RenderMeshes : public Render {
 protected:
  MeshPtr make_mesh(const Arrays& a) {
    arcus_mesh_t* m = nullptr;
    EXPECT_EQ(arcus_mesh_create(ctx(), a.vertices.size() / 3, a.vertices.data(), a.indices.size() / 3,
                                a.indices.data(), &m),
              ARCUS_SUCCESS)
        << last_error();
    return MeshPtr(m);
  }
  // The scene `text` with these meshes: its status, the scene (null when refused) and
  // the context's message.
  arcus_status load_with(const std::string& text, std::vector<const char*> names, std::vector<arcus_mesh_t*> meshes,
                         arcus_scene_t** scene) {
    const std::string path = temp_file("meshes", ".json", text);
    return arcus_scene_load_with_meshes(ctx(), path.c_str(), names.size(), names.data(), meshes.data(), scene);
  }
  static std::string sphere_scene(const std::string& source) {
    return scene_text(kConstantMedium, kPinholeCamera,
                      R"([{"type": "mesh", )" + source +
                          R"(, "material": "m", "translate": [0, 0, -5], "scale": 1.5}])");
  }
};

// The scene's own placement (scale, then move) applies to a mesh from memory: the image
// is the straight pinhole image of the placed triangles, found by brute force.
TEST_F(RenderMeshes, AMeshFromMemoryIsPlacedByTheSceneAndRendersTheStraightPinholeImage) {
  const MeshPtr sphere = make_mesh(icosphere_arrays(mesh("icosphere.obj"), false));
  ASSERT_TRUE(sphere);
  arcus_scene_t* scene = nullptr;
  ASSERT_EQ(load_with(sphere_scene(R"("mesh": "ball")"), {"ball"}, {sphere.get()}, &scene), ARCUS_SUCCESS)
      << last_error();
  const double at[3] = {0, 0, -5};
  const Rendered img = render(scene, 0);
  arcus_scene_release(scene);
  expect_straight_pinhole_image(img, read_obj_triangles(mesh("icosphere.obj"), 1.5, at));
}

// Determinism: the same triangles from memory and from the file give the same image,
// hits and stats bit for bit (the file's coordinates are floats, so the arrays are
// rounded alike).  The scene keeps its own copy: the handle is released before rendering.
TEST_F(RenderMeshes, DeterminismAMeshFromMemoryRendersBitForBitAsItsFile) {
  MeshPtr sphere = make_mesh(icosphere_arrays(mesh("icosphere.obj"), true));
  ASSERT_TRUE(sphere);
  arcus_scene_t* from_memory = nullptr;
  ASSERT_EQ(load_with(sphere_scene(R"("mesh": "ball")"), {"ball"}, {sphere.get()}, &from_memory), ARCUS_SUCCESS)
      << last_error();
  sphere.reset();
  arcus_scene_t* from_file = load(sphere_scene(R"("file": ")" + mesh("icosphere.obj") + "\""), "file");
  ASSERT_NE(from_file, nullptr);
  const Rendered a = render(from_memory, ARCUS_TECHNIQUE_SMART_STEP), b = render(from_file, ARCUS_TECHNIQUE_SMART_STEP);
  arcus_scene_release(from_memory);
  arcus_scene_release(from_file);
  ASSERT_FALSE(a.rgb.empty());
  EXPECT_EQ(a.rgb, b.rgb);
  EXPECT_EQ(a.points, b.points);
  EXPECT_EQ(a.objects, b.objects);
  EXPECT_EQ(a.primitives, b.primitives);
  EXPECT_EQ(a.distances, b.distances);
  EXPECT_EQ(a.steps, b.steps);
}

TEST_F(RenderMeshes, NamesAndHandlesAreCheckedAndEachMisuseIsNamed) {
  const MeshPtr sphere = make_mesh(icosphere_arrays(mesh("icosphere.obj"), false));
  ASSERT_TRUE(sphere);
  const std::string uses_ball = sphere_scene(R"("mesh": "ball")");
  struct Case {
    const char* what;
    std::string text;
    std::vector<const char*> names;
    std::vector<arcus_mesh_t*> meshes;
    const char* message;  // a part of the context's message
  };
  arcus_mesh_t* m = sphere.get();
  const std::vector<Case> cases = {
      {"a name the file uses that is not given", uses_ball, {"bowl"}, {m}, "$.objects[0].mesh: no mesh named \"ball\""},
      {"no mesh given at all", uses_ball, {}, {}, "given: none"},
      {"a given mesh the scene does not use", uses_ball, {"ball", "cube"}, {m, m}, "uses no mesh named \"cube\""},
      {"a curved scene takes no meshes", R"({"name": "c", "field": {"type": "constant", "n": 1},
                                                  "rays": {"origins": [[0, 0, 0]], "directions": [[1, 0, 0]]},
                                                  "integrator": {"method": "dp45", "length": 1}})", {"ball"}, {m},
       "uses no mesh named \"ball\" (mesh_names[0])"},
      {"a name given twice", uses_ball, {"ball", "ball"}, {m, m}, "mesh_names[1] = \"ball\" is also mesh_names[0]"},
      {"an empty name", uses_ball, {""}, {m}, "mesh_names[0] must have 1 to 1024 bytes"},
      {"a NULL name", uses_ball, {nullptr}, {m}, "mesh_names[0] is NULL"},
      {"a NULL mesh", uses_ball, {"ball"}, {nullptr}, "meshes[0] is NULL"},
      {"a scene handle for a mesh", uses_ball, {"ball"}, {reinterpret_cast<arcus_mesh_t*>(ctx())},
       "meshes[0] is a context, not a mesh"},
      {"both a file and a mesh", sphere_scene(R"("mesh": "ball", "file": "x.obj")"), {"ball"}, {m},
       "$.objects[0].mesh: give \"file\" or \"mesh\", not both"},
      {"an empty mesh name in the file", sphere_scene(R"("mesh": "")"), {"ball"}, {m},
       "$.objects[0].mesh: expected the name of a mesh"},
  };
  for (const Case& c : cases) {
    arcus_scene_t* scene = reinterpret_cast<arcus_scene_t*>(&scene);  // overwritten with NULL on failure
    EXPECT_EQ(load_with(c.text, c.names, c.meshes, &scene), ARCUS_ERROR_INVALID_ARGUMENT) << c.what;
    EXPECT_EQ(scene, nullptr) << c.what;
    EXPECT_NE(last_error().find(c.message), std::string::npos) << c.what << ": " << last_error();
  }
  // Arrays missing for a count, and a count past the bound, before either is read.
  arcus_scene_t* scene = nullptr;
  const std::string path = temp_file("meshes", ".json", uses_ball);
  EXPECT_EQ(arcus_scene_load_with_meshes(ctx(), path.c_str(), 1, nullptr, &m, &scene), ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("mesh_names is NULL"), std::string::npos) << last_error();
  const char* name = "ball";
  EXPECT_EQ(arcus_scene_load_with_meshes(ctx(), path.c_str(), 1, &name, nullptr, &scene), ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("meshes is NULL"), std::string::npos) << last_error();
  EXPECT_EQ(arcus_scene_load_with_meshes(ctx(), path.c_str(), size_t(1) << 40, &name, &m, &scene),
            ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("mesh_count 1099511627776 is over 65536"), std::string::npos) << last_error();
  // The mesh and the context are untouched by all of it: the right call still works.
  ASSERT_EQ(load_with(uses_ball, {"ball"}, {m}, &scene), ARCUS_SUCCESS) << last_error();
  arcus_scene_release(scene);
}

// A mesh belongs to its context: another context's is refused, naming it.
TEST_F(RenderMeshes, AMeshOfAnotherContextIsRefused) {
  arcus_context_t* other = nullptr;
  ASSERT_EQ(arcus_context_create(ARCUS_DEVICE_DEFAULT, &other), ARCUS_SUCCESS) << arcus_last_error();
  const ContextPtr other_ref(other);
  const Arrays a = icosphere_arrays(mesh("icosphere.obj"), false);
  arcus_mesh_t* m = nullptr;
  ASSERT_EQ(arcus_mesh_create(other, a.vertices.size() / 3, a.vertices.data(), a.indices.size() / 3, a.indices.data(),
                              &m),
            ARCUS_SUCCESS);
  const MeshPtr mesh_ref(m);
  arcus_scene_t* scene = nullptr;
  EXPECT_EQ(load_with(sphere_scene(R"("mesh": "ball")"), {"ball"}, {m}, &scene), ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(scene, nullptr);
  EXPECT_NE(last_error().find("meshes[0] belongs to another context"), std::string::npos) << last_error();
}

}  // namespace
