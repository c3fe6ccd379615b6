#include "scene/scene.h"

#include <exception>
#include <memory>
#include <utility>
#include <vector>

#include "core/call.h"
#include "core/error.h"
#include "scene/json_reader.h"

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
  // Reading and checking the file happen before the context's lock is taken; the loader
  // takes it only to create objects.  Errors of either part are reported under the lock.
  arcus_status status;
  const arcus::HandleRef held = hold(ctx, arcus::kContextHandle, "ctx", &status);  // alive while unlocked
  if (!held) return status;
  arcus_scene_s* scene = nullptr;
  std::exception_ptr failed;
  if (out && path) {
    try {
      scene = arcus::scene::loader_for(path)(ctx, path, [&](const std::function<void()>& create) {
        arcus::ContextLock lock(ctx);
        create();
      });
    } catch (...) {
      failed = std::current_exception();
    }
  }
  return simple<arcus_context_s>(ctx, arcus::kContextHandle, "ctx", [&](arcus_context_s*) {
    require_pointer(out, "out");
    *out = nullptr;
    require_pointer(path, "path");
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
