// Curved-light scenes: a scene file's medium, rays and integrator settings made into a
// field and the arguments of arcus_curved_advance (arcus_curved.h, "curved scenes").
#include <memory>
#include <string>

#include "core/call.h"
#include "curved/advance.h"
#include "curved/field_scene.h"
#include "curved/fields.h"
#include "curved/scene_desc.h"
#include "scene/scene.h"

using arcus::require_pointer;
using namespace arcus::api;

namespace arcus::curved {
namespace {

struct CurvedScene : FieldScene {
  CurvedScene(arcus_context_t* ctx, SceneDesc d) : FieldScene(ctx, "curved"), desc(std::move(d)) {}
  SceneDesc desc;
};

// Everything is read and built before the context's lock is taken; only the library
// objects are created under it.  A bad medium is reported with the scene file's name.
arcus_scene_s* load(arcus_context_t* ctx, const std::string& path, const scene::GivenMeshes&,
                    const scene::Locked& locked) {
  SceneDesc desc = parse_scene_file(path);
  FieldBuild built = build_scene_medium(desc.medium, desc.params, path);
  auto scene = std::make_unique<CurvedScene>(ctx, std::move(desc));
  scene->name = scene->desc.name;
  scene->description = scene->desc.description;
  scene->document = scene->desc.document;
  scene->attach_field(std::move(built), locked);
  return scene.release();
}

const scene::LoaderEntry kLoader("curved", load);

template <class Body>
arcus_status on_curved_scene(arcus_scene_t* scene, Body&& body) {
  return on<arcus_scene_s>(scene, arcus::scene::kSceneHandle, "scene", [&](arcus_scene_s* s, std::string* message) {
    auto* c = dynamic_cast<CurvedScene*>(s);
    if (!c) fail(ARCUS_ERROR_INVALID_ARGUMENT, std::string("scene is a ") + s->engine + " scene, not a curved one");
    return body(c, message);
  });
}

}  // namespace
}  // namespace arcus::curved

using arcus::curved::CurvedScene;

extern "C" {

arcus_status arcus_scene_get_field(arcus_scene_t* scene, arcus_field_t** field) {
  return arcus::curved::on_curved_scene(scene, [&](CurvedScene* s, std::string*) {
    require_pointer(field, "field");
    s->field->retain();
    *field = s->field;
    return ARCUS_SUCCESS;
  });
}

arcus_status arcus_scene_get_advance_params(arcus_scene_t* scene, arcus_advance_params* params) {
  return arcus::curved::on_curved_scene(scene, [&](CurvedScene* s, std::string*) {
    require_pointer(params, "params");
    *params = s->desc.params;
    return ARCUS_SUCCESS;
  });
}

arcus_status arcus_scene_get_ray_count(arcus_scene_t* scene, size_t* count) {
  return arcus::curved::on_curved_scene(scene, [&](CurvedScene* s, std::string*) {
    require_pointer(count, "count");
    *count = s->desc.ray_count();
    return ARCUS_SUCCESS;
  });
}

arcus_status arcus_scene_get_rays(arcus_scene_t* scene, double* origins, double* directions, double* wavelengths,
                                  int32_t* has_wavelengths) {
  return arcus::curved::on_curved_scene(scene, [&](CurvedScene* s, std::string*) {
    const arcus::curved::SceneDesc& d = s->desc;
    if (origins) std::copy(d.origins.begin(), d.origins.end(), origins);
    if (directions) std::copy(d.directions.begin(), d.directions.end(), directions);
    if (wavelengths) std::copy(d.wavelengths.begin(), d.wavelengths.end(), wavelengths);
    if (has_wavelengths) *has_wavelengths = d.wavelengths.empty() ? 0 : 1;
    return ARCUS_SUCCESS;
  });
}

arcus_status arcus_curved_advance_scene(arcus_scene_t* scene, arcus_progress_callback progress, void* user,
                                        arcus_job_t** job) {
  return arcus::curved::on_curved_scene(scene, [&](CurvedScene* s, std::string* message) {
    require_pointer(job, "job");
    *job = nullptr;
    const arcus::curved::SceneDesc& d = s->desc;
    arcus_advance_params params = d.params;
    params.progress = progress;
    params.progress_user = user;
    return arcus::curved::advance(s->owner(), s->field, params, d.ray_count(), d.origins.data(), d.directions.data(),
                                  d.wavelengths.empty() ? nullptr : d.wavelengths.data(), job, message);
  });
}

}  // extern "C"
