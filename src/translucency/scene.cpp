// The translucency engine's scene files (scenes/translucency/): what a genetic search
// (`arcus inverse genetic`, arcus.inverse.genetic) needs to render the target's view.
// Read by the library's strict reader like every scene; Python builds the search from
// the checked document.  Marker: "translucent_object" (ahead of the render engine's
// "camera", which these files also have).
//   {"name", "description",
//    "translucent_object": {"mesh": FILE or a bundled mesh's name, "mm_per_unit": 20},
//    "camera": {"position", "look_at", "up", "vfov_deg"}, "ortho_height": 3.2,
//    "lights": [[dx, dy, dz], [dx, dy, dz, E], [dx, dy, dz, R, G, B], ...]}
#include <string>

#include "scene/common_keys.h"
#include "scene/scene.h"

namespace arcus::translucency {
namespace {

using json::Node;

void check_scene(const Node& root) {
  root.expect_object({"name", "description", "translucent_object", "camera", "ortho_height", "lights"});
  const Node object = root.member("translucent_object");
  object.expect_object({"mesh", "mm_per_unit"});
  object.member("mesh").string();
  object.check_numbers({"mm_per_unit"});
  if (auto camera = root.find("camera")) {
    camera->expect_object({"position", "look_at", "up", "vfov_deg"});
    for (const char* key : {"position", "look_at", "up"})
      if (auto v = camera->find(key)) v->vec3();
    camera->check_numbers({"vfov_deg"});
  }
  root.check_numbers({"ortho_height"});
  const Node lights = root.member("lights");
  if (lights.array_size() < 1 || lights.array_size() > 64) lights.fail("expected 1..64 lights");
  for (const Node& light : lights.elements()) {
    const size_t n = light.array_size();
    if (n != 3 && n != 4 && n != 6) light.fail("expected [dx, dy, dz], then nothing, E or R G B");
    for (const Node& v : light.elements()) v.number();
  }
  if (auto v = root.find("name")) scene::parse_name(*v);
  if (auto v = root.find("description")) v->string();
}

arcus_scene_s* load(arcus_context_t* ctx, const std::string& path, const scene::GivenMeshes&,
                    const scene::Locked& locked) {
  return scene::document_scene(ctx, path, "translucency", check_scene, locked);
}

const scene::LoaderEntry kLoader("translucency", load, "translucent_object", /*precedence=*/1);

}  // namespace
}  // namespace arcus::translucency
