#include "scene/scene.h"

#include <cstring>
#include <exception>
#include <memory>
#include <utility>
#include <vector>

#include "core/call.h"
#include "core/error.h"
#include "geometry/mesh_handle.h"
#include "scene/json_reader.h"

using arcus::require;
using arcus::require_pointer;
using namespace arcus::api;

namespace arcus::scene {

const HandleKind kSceneHandle("scene");

namespace {

struct Registered {
  const char* engine;
  const char* marker;  // the top-level key that marks the engine's scenes; null: the default
  int precedence;      // among several markers present, the highest wins
  Loader loader;
};

std::vector<Registered>& loaders() {
  static std::vector<Registered> all;
  return all;
}

}  // namespace

const geometry::Mesh& GivenMeshes::get(const std::string& name, const std::string& where) const {
  for (const Given& g : given_)
    if (g.name == name) {
      g.used = true;
      return *g.mesh;
    }
  std::string names;
  for (const Given& g : given_) names += (names.empty() ? "" : ", ") + json::quoted(g.name);
  fail(ARCUS_ERROR_INVALID_ARGUMENT, where + ": no mesh named " + json::quoted(name) +
                                         " was given (arcus_scene_load_with_meshes; given: " +
                                         (names.empty() ? "none" : names) + ")");
}

long GivenMeshes::first_unused() const {
  for (size_t i = 0; i < given_.size(); ++i)
    if (!given_[i].used) return static_cast<long>(i);
  return -1;
}

void register_loader(const char* engine, Loader loader, const char* marker, int precedence) {
  loaders().push_back({engine, marker, precedence, std::move(loader)});
}

arcus_scene_s* document_scene(arcus_context_t* ctx, const std::string& path, const char* engine,
                              void (*check)(const json::Node& root), const Locked& locked) {
  const json::Document doc = json::Document::from_file(path);
  check(doc.root());
  auto scene = std::make_unique<arcus_scene_s>(ctx, engine);
  if (auto v = doc.root().find("name")) scene->name = v->string();
  if (auto v = doc.root().find("description")) scene->description = v->string();
  scene->document = doc.dump();
  locked([&] { retain_context(ctx); });  // the scene's reference
  return scene.release();
}

const Loader& loader_for(const std::string& path) {
  // The document's top-level keys say whose scene it is (a render scene has a
  // "camera"); a document that is not an object falls to the default, which reports it.
  const json::Document doc = json::Document::from_file(path);
  const json::Node root = doc.root();
  const Registered *fallback = nullptr, *marked = nullptr, *tied = nullptr;
  for (const Registered& r : loaders()) {
    if (!r.marker) {
      fallback = &r;
    } else if (root.is_object() && root.find(r.marker)) {
      if (!marked || r.precedence > marked->precedence)
        marked = &r, tied = nullptr;
      else if (r.precedence == marked->precedence)
        tied = &r;
    }
  }
  // Two engines' markers of the same precedence: which reads it must not depend on the
  // order the engines registered in.
  if (marked && tied)
    fail(ARCUS_ERROR_INVALID_ARGUMENT, path + ": $: has both \"" + marked->marker + "\" (a " + marked->engine +
                                           " scene) and \"" + tied->marker + "\" (a " + tied->engine +
                                           " scene) at the top level; which kind of scene is it?");
  if (marked) return marked->loader;
  if (!fallback) fail(ARCUS_ERROR_UNSUPPORTED, path + ": no engine reads scene files");
  return fallback->loader;
}

}  // namespace arcus::scene

namespace {

// Bounds on arcus_scene_load_with_meshes' arguments, so that a wrong count is refused
// before anything is read from the arrays.
constexpr size_t kMaxGivenMeshes = 1 << 16;
constexpr size_t kMaxMeshName = 1024;

template <class Body>
arcus_status on_scene(arcus_scene_t* scene, Body&& body) {
  return simple<arcus_scene_s>(scene, arcus::scene::kSceneHandle, "scene", body);
}

// A string of the scene, valid while it lives.
arcus_status get_string(arcus_scene_t* scene, const char** out, const char* name,
                        const std::string arcus_scene_s::*member) {
  return on_scene(scene, [&](arcus_scene_s* s) {
    require_pointer(out, name);
    *out = (s->*member).c_str();
  });
}

}  // namespace

extern "C" {

arcus_status arcus_scene_load(arcus_context_t* ctx, const char* path, arcus_scene_t** out) {
  return arcus_scene_load_with_meshes(ctx, path, 0, nullptr, nullptr, out);
}

arcus_status arcus_scene_load_with_meshes(arcus_context_t* ctx, const char* path, size_t mesh_count,
                                          const char* const* mesh_names, arcus_mesh_t* const* meshes,
                                          arcus_scene_t** out) {
  // Reading and checking the file happen before the context's lock is taken; the loader
  // takes it only to create objects.  Errors of either part are reported under the lock.
  arcus_status status;
  const arcus::HandleRef held = hold(ctx, arcus::kContextHandle, "ctx", &status);  // alive while unlocked
  if (!held) return status;
  // The arguments, checked under the lock; each mesh is held (not copied) while the file
  // is read unlocked: its geometry never changes once made.
  std::vector<arcus::HandleRef> held_meshes;
  arcus::scene::GivenMeshes given;
  status = simple<arcus_context_s>(ctx, arcus::kContextHandle, "ctx", [&](arcus_context_s*) {
    require_pointer(out, "out");
    *out = nullptr;
    require_pointer(path, "path");
    if (mesh_count == 0) return;
    require(mesh_count <= kMaxGivenMeshes, "mesh_count " + std::to_string(mesh_count) + " is over " +
                                               std::to_string(kMaxGivenMeshes));
    require_pointer(mesh_names, "mesh_names");
    require_pointer(meshes, "meshes");
    for (size_t i = 0; i < mesh_count; ++i) {
      const std::string at = "[" + std::to_string(i) + "]";
      require_pointer(mesh_names[i], ("mesh_names" + at).c_str());
      const size_t length = strnlen(mesh_names[i], kMaxMeshName + 1);
      require(length > 0 && length <= kMaxMeshName, "mesh_names" + at + " must have 1 to " +
                                                         std::to_string(kMaxMeshName) + " bytes");
      for (size_t j = 0; j < i; ++j)
        require(std::strcmp(mesh_names[i], mesh_names[j]) != 0,
                "mesh_names" + at + " = " + arcus::json::quoted(mesh_names[i]) + " is also mesh_names[" +
                    std::to_string(j) + "]");
      auto* mesh = object_of<arcus_mesh_s>(ctx, meshes[i], arcus::geometry::kMeshHandle,
                                                  ("meshes" + at).c_str());
      mesh->retain();
      held_meshes.emplace_back(mesh);
      given.add(mesh_names[i], &mesh->mesh);
    }
  });
  if (status != ARCUS_SUCCESS) return status;
  arcus_scene_s* scene = nullptr;
  std::exception_ptr failed;
  try {
    scene = arcus::scene::loader_for(path)(ctx, path, given, [&](const std::function<void()>& create) {
      arcus::ContextLock lock(ctx);
      create();
    });
  } catch (...) {
    failed = std::current_exception();
  }
  // A given mesh the scene did not use is an error too (released unlocked, as
  // arcus_scene_release does).
  const long unused = failed ? -1 : given.first_unused();
  if (unused >= 0) {
    arcus::release_handle(scene);
    failed = std::make_exception_ptr(
        arcus::Error(ARCUS_ERROR_INVALID_ARGUMENT, std::string(path) + ": uses no mesh named " +
                                                       arcus::json::quoted(given.name(unused)) + " (mesh_names[" +
                                                       std::to_string(unused) + "])"));
  }
  return simple<arcus_context_s>(ctx, arcus::kContextHandle, "ctx", [&](arcus_context_s*) {
    if (failed) std::rethrow_exception(failed);
    *out = scene;
  });
}

arcus_status arcus_scene_retain(arcus_scene_t* scene) { return retain(scene, arcus::scene::kSceneHandle, "scene"); }

arcus_status arcus_scene_release(arcus_scene_t* scene) { return release(scene, arcus::scene::kSceneHandle, "scene"); }

arcus_status arcus_scene_get_name(arcus_scene_t* scene, const char** name) {
  return get_string(scene, name, "name", &arcus_scene_s::name);
}

arcus_status arcus_scene_get_description(arcus_scene_t* scene, const char** description) {
  return get_string(scene, description, "description", &arcus_scene_s::description);
}

arcus_status arcus_scene_get_document(arcus_scene_t* scene, const char** json) {
  return get_string(scene, json, "json", &arcus_scene_s::document);
}

arcus_status arcus_scene_get_engine(arcus_scene_t* scene, const char** engine) {
  return on_scene(scene, [&](arcus_scene_s* s) {
    require_pointer(engine, "engine");
    *engine = s->engine;
  });
}

}  // extern "C"
