// Scenes: the object behind arcus_scene_t, shared by every engine, and the registry of
// the engines' scene loaders (an engine turns a scene file into its objects; the
// reader itself, scene/json_reader.h, is shared).
#pragma once

#include <functional>
#include <string>

#include "arcus/arcus_scene.h"
#include "core/handle.h"
#include "scene/json_reader.h"

namespace arcus::scene {
extern const HandleKind kSceneHandle;  // "scene"
}  // namespace arcus::scene

struct arcus_scene_s : arcus::Handle {
  arcus_scene_s(arcus_context_t* ctx, const char* engine) : Handle(arcus::scene::kSceneHandle, ctx), engine(engine) {}
  const char* engine;  // "curved", ...
  std::string name, description, document;
};

namespace arcus::scene {

// Reads the scene file at `path` and creates its objects on ctx.  Runs without the
// context's lock (file reading may be slow) except inside `locked`, which a loader
// calls for the part that creates library objects.
using Locked = std::function<void(const std::function<void()>&)>;
using Loader = std::function<arcus_scene_s*(arcus_context_t* ctx, const std::string& path, const Locked& locked)>;

// `marker`: the top-level key of the engine's scene files ("camera"), or null for the
// engine that reads every other scene (the curved one).  When a document has the
// markers of several engines, the one registered with the highest `precedence` reads it;
// two of the same precedence are an error.
void register_loader(const char* engine, Loader loader, const char* marker, int precedence = 0);
struct LoaderEntry {
  LoaderEntry(const char* engine, Loader loader, const char* marker = nullptr, int precedence = 0) {
    register_loader(engine, std::move(loader), marker, precedence);
  }
};

// A loader's work for a scene whose engine makes no library objects of it (rainbow
// scenes and sweep specs: Python builds their tables and runs their tasks): reads the
// file, checks its schema with `check`, and returns a scene of `engine` holding its name
// (if any), description and document.
arcus_scene_s* document_scene(arcus_context_t* ctx, const std::string& path, const char* engine,
                              void (*check)(const json::Node& root), const Locked& locked);

// The loader of the scene at `path`, by its document's top-level keys; reads the file
// (ARCUS_ERROR_IO / INVALID_ARGUMENT for one that is unreadable or not JSON).
const Loader& loader_for(const std::string& path);

}  // namespace arcus::scene
