// A curved-light scene file (schema: scenes/README.md) read into plain data: no OpenCL,
// no closures, so that it can be checked whole before any device work, fuzzed, and
// turned into library objects by whoever holds a context.  Errors are those of
// scene/json_reader.h: "<file>: <$.path>: <what>".
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "arcus/arcus.h"
#include "geometry/vec3.h"
#include "scene/json_reader.h"

namespace arcus::curved {

struct AtmosphereDesc {  // defaults: arcus_atmosphere_desc_init's
  bool spherical = false;
  double wavelength = 550.0;  // nm
  double sea_level_temperature = 288.15;
  double sea_level_pressure = 101325.0;
  std::vector<arcus_inversion> inversions;
};

struct GridDesc {
  std::string file;              // absolute: resolved against the scene's directory, not opened
  int32_t dtype = ARCUS_FLOAT64;  // arcus_scalar_type
  std::array<uint32_t, 3> dims{};
  Vec3 origin{}, spacing{};
};

// The parameters a kind does not use keep their defaults.
struct MediumDesc {
  arcus_field_kind kind = ARCUS_FIELD_CONSTANT;
  double n = 1.0;   // constant
  double n0 = 1.0;  // linear, fisheye
  double a = 1.0;   // linear_n2
  Vec3 gradient{};  // linear
  Vec3 k{};         // linear_n2
  Vec3 center{};    // luneburg, fisheye
  double radius = 1.0;
  AtmosphereDesc atmosphere;
  GridDesc grid;
  std::string key_path = "$.field";  // where the scene gave it ("$.medium": the 0.9 spelling)
};

struct SceneDesc {
  std::string file;  // as given, for messages
  std::string name, description;
  MediumDesc medium;
  std::vector<double> origins, directions;  // ray_count() × 3; directions as given (not unit)
  std::vector<double> wavelengths;          // empty (none given), or one per ray, nm
  arcus_advance_params params{};            // progress: NULL
  std::string document;                     // pretty printed, keys in the author's order

  size_t ray_count() const { return origins.size() / 3; }
};

// Bounds on what a scene may ask for.  The fuzzer lowers max_rays so that a 20-byte fan
// cannot allocate gigabytes.
struct SceneLimits {
  size_t max_rays = size_t(1) << 26;
};

// The parts of a scene file other engines' scenes share (a render scene has a medium
// and an integrator too): each reads one node, failing with its file and key path.
void parse_medium(const json::Node& node, const std::string& base_dir, MediumDesc* out);
// A scene's index field: its "field", or "medium", the spelling of arcus 0.9 (kept for
// one release: the C API calls it a field, so do scene files now); both is an error.
json::Node field_member(const json::Node& root);
void parse_integrator(const json::Node& node, arcus_advance_params* params);
void parse_box(const json::Node& node, arcus_advance_params* params);

// "constant", "linear", ... as in the file.
const char* medium_type_name(arcus_field_kind kind);

// `file_name` names the text in messages; relative grid files are resolved against
// `base_dir` ("" : the current directory).
SceneDesc parse_scene_text(const std::string& text, const std::string& file_name, const std::string& base_dir,
                           const SceneLimits& limits = SceneLimits());
// Reads `path` (ARCUS_ERROR_IO if it is not a readable regular file) and parses it,
// relative files against its directory.
SceneDesc parse_scene_file(const std::string& path, const SceneLimits& limits = SceneLimits());

}  // namespace arcus::curved
