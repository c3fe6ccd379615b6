// Scenes: the object behind arcus_scene_t, shared by every engine, and the registry of
// the engines' scene loaders (an engine turns a scene file into its objects; the
// reader itself, scene/json_reader.h, is shared).
#pragma once

#include <functional>
#include <string>
#include <vector>

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

namespace arcus::geometry {
struct Mesh;
}  // namespace arcus::geometry

namespace arcus::scene {

// The meshes a caller handed arcus_scene_load_with_meshes, by the names its scene file
// gives them ({"type": "mesh", "mesh": "bunny"} in a render scene).  A loader looks up
// each name its file uses; the call then refuses any mesh no object used (a misspelt
// name, or a scene whose engine takes no meshes), so none is silently ignored.
class GivenMeshes {
 public:
  void add(std::string name, const geometry::Mesh* mesh) { given_.push_back({std::move(name), mesh, false}); }
  // The mesh called `name`; else ARCUS_ERROR_INVALID_ARGUMENT "<where>: no mesh named ...".
  const geometry::Mesh& get(const std::string& name, const std::string& where) const;
  // The index of the first mesh no lookup asked for, or -1.
  long first_unused() const;
  const std::string& name(size_t i) const { return given_[i].name; }

 private:
  struct Given {
    std::string name;
    const geometry::Mesh* mesh;
    mutable bool used;
  };
  std::vector<Given> given_;
};

// Reads the scene file at `path` and creates its objects on ctx, taking any mesh it
// names from `meshes`.  Runs without the context's lock (file reading may be slow)
// except inside `locked`, which a loader calls for the part that creates library
// objects; the given meshes are held alive meanwhile and never change.
using Locked = std::function<void(const std::function<void()>&)>;
using Loader = std::function<arcus_scene_s*(arcus_context_t* ctx, const std::string& path,
                                            const GivenMeshes& meshes, const Locked& locked)>;

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
