#include "curved/field_scene.h"

#include <memory>
#include <utility>

#include "core/context.h"
#include "core/error.h"
#include "curved/advance.h"

namespace arcus::curved {

FieldBuild build_scene_medium(const MediumDesc& medium, const arcus_advance_params& params, const std::string& path) {
  // The settings are checked now, so a bad scene fails where it is read, naming its file.
  try {
    check_advance_params(params, medium.kind == ARCUS_FIELD_CONSTANT);
  } catch (const Error& e) {
    fail(e.status(), path + ": $.integrator: " + e.what());
  }
  try {
    return build_field(medium);
  } catch (const Error& e) {
    fail(e.status(), path + ": " + medium.key_path + ": " + e.what());
  }
}

FieldScene::~FieldScene() {
  if (field && field->drop()) {
    delete field;
    release_context(owner());
  }
}

void FieldScene::attach_field(FieldBuild built, const scene::Locked& locked) {
  locked([&] {
    auto f = std::make_unique<arcus_field_s>(owner());
    f->desc = built.desc;
    f->data = std::move(built.data);
    retain_context(owner());  // the field's reference
    retain_context(owner());  // the scene's
    field = f.release();
  });
}

}  // namespace arcus::curved
