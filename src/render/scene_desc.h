// A render scene file (schema: scenes/README.md, "Render scenes") read into plain
// data: no OpenCL, no files opened beyond the scene itself, so it is checked whole
// before any mesh is loaded or device work starts.  Errors: "<file>: <$.path>: <what>".
#pragma once

#include <array>
#include <string>
#include <vector>

#include "arcus/arcus.h"
#include "curved/scene_desc.h"
#include "scene/common_keys.h"

namespace arcus::render {

using scene::CameraDesc;

struct MaterialDesc {
  std::string name;
  Vec3 diffuse{0.8, 0.8, 0.8};  // reflectance, multiplied by the texture if any
  std::string texture;          // absolute path, or empty
  std::array<double, 2> uv_scale{1, 1};
  Vec3 emission{0, 0, 0};  // radiance emitted (W·m⁻²·sr⁻¹ per channel)
  double blackbody_k = 0;  // spectral scenes: emits Planck's spectrum at this temperature
                           // (scaled to the emission's mean at 555 nm); 0: RGB bands
};

enum class ObjectKind { Mesh, Sphere, Disc };

struct ObjectDesc {
  ObjectKind kind = ObjectKind::Mesh;
  std::string file;       // mesh: absolute path, or empty for
  std::string mesh_name;  // a mesh given in memory (arcus_scene_load_with_meshes)
  Vec3 translate{0, 0, 0}, scale{1, 1, 1}, rotate_deg{0, 0, 0};  // mesh: scale, then rotate x, y, z, then move
  Vec3 center{0, 0, 0}, normal{0, 1, 0};                        // sphere, disc
  double radius = 1;
  int material = 0;  // index into RenderDesc::materials
};

enum class LightKind { Sun, Point };

struct LightDesc {
  LightKind kind = LightKind::Sun;
  Vec3 direction{0, 1, 0};  // sun: unit vector toward it
  Vec3 position{0, 0, 0};   // point
  Vec3 power{1, 1, 1};      // sun: irradiance on a surface facing it; point: intensity (W/sr)
  bool daylight = false;    // the shared sun ("daylight_sun"): its colour is the atmosphere's
  double elevation_deg = 0, azimuth_deg = 0;  // daylight: where it is (azimuth from +z toward +x)
};

// Daylight: the shared single-scattering sky (arcus_daylight.h) under the scene's
// daylight sun, made into an image when the scene is loaded.
enum class SkyKind { Constant, Gradient, Image, Daylight };

struct SkyDesc {
  SkyKind kind = SkyKind::Constant;
  Vec3 color{0, 0, 0};                         // constant
  Vec3 horizon{0, 0, 0}, zenith{0, 0, 0};      // gradient, by the direction's height
  std::string file;                            // image: equirectangular, absolute path
  double intensity = 1;                        // image, daylight: scale
};

struct PhotonDesc {
  uint64_t count = 0;  // 0: no photon map
  uint32_t estimate = 100;
  double max_radius = 1;
};

struct RenderDesc {
  std::string file, name, description, document;
  curved::MediumDesc medium;
  arcus_advance_params params{};  // integrator; the box is the scene's bounds
  bool has_bounds = false;        // else: the geometry's and the camera's box, grown
  CameraDesc camera;
  std::vector<MaterialDesc> materials;
  std::vector<ObjectDesc> objects;
  std::vector<LightDesc> lights;
  SkyDesc sky;
  sky::Atmosphere atmosphere;  // the daylight sun's and sky's air
  std::vector<double> wavelengths;  // spectral scenes: nm; empty: RGB
  PhotonDesc photons;
  uint32_t techniques = 0;  // the scene's default arcus_render techniques
  double exposure = 1;
};

RenderDesc parse_render_text(const std::string& text, const std::string& file_name, const std::string& base_dir);
RenderDesc parse_render_file(const std::string& path);

// "smart_step,symmetry" -> bits; throws INVALID_ARGUMENT naming an unknown one.
uint32_t parse_techniques(const std::string& list);
std::string technique_names(uint32_t techniques);

}  // namespace arcus::render
