// A scene whose medium is a field (curved-light and render scenes): the medium and the
// integrator checked and built while the file is read, the field made under the
// context's lock, and the scene's reference to it, dropped with the scene.
#pragma once

#include <string>

#include "curved/fields.h"
#include "curved/scene_desc.h"
#include "scene/scene.h"

namespace arcus::curved {

// The field of a scene file's medium, built, with its integrator settings checked;
// throws naming the file and the key ("<path>: $.field: ...", "$.integrator").
FieldBuild build_scene_medium(const MediumDesc& medium, const arcus_advance_params& params, const std::string& path);

struct FieldScene : arcus_scene_s {
  FieldScene(arcus_context_t* ctx, const char* engine) : arcus_scene_s(ctx, engine) {}
  // Deleted under the context's lock (release_object): the field goes the same way.
  ~FieldScene() override;

  // Makes the field of `built` (inside `locked`, the only part of loading under the
  // context's lock) and takes the context references of the field and of this scene.
  void attach_field(FieldBuild built, const scene::Locked& locked);

  arcus_field_s* field = nullptr;  // the scene's reference
};

}  // namespace arcus::curved
