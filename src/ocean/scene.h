// Ocean scenes: a scene file whose top level has "water" (scenes/README.md, "Ocean
// scenes"), read by the library like every engine's (arcus_scene_load), made into what a
// trace and a render need: the water, the lights and the medium, the photon trace's
// parameters, and optionally a camera with the ray-marching settings.
#pragma once

#include <string>
#include <vector>

#include "arcus/arcus_render.h"  // arcus_camera: the one pinhole camera of arcus
#include "ocean/trace.h"
#include "ocean/water.h"
#include "scene/scene.h"

namespace arcus::ocean {

// How camera rays gather light (thesis §4.2, §4.1.4).
struct MarchParams {
  int steps = 200;            // ray-marching steps (thesis §5.3)
  double distance = 20;       // [m] how far a camera ray is marched
  int k = 250;                // photons per radiance estimate (thesis §5.3)
  enum Estimator : int { per_step = 0, beam = 1 } estimator = per_step;  // beam: Jarosz et al. 2008
  bool single_scattering = true;    // from the lights, elastic and inelastic (eq. 4.5)
  bool multiple_scattering = true;  // from the photon map, elastic and inelastic (eq. 4.6)
  // The photon map's estimate is made at every estimate_stride-th pixel across and
  // down and interpolated bilinearly between (1: at every pixel, the thesis').  The
  // estimate is smooth over its photons' radii, which span many pixels.
  int estimate_stride = 1;
  // > 0 [m]: a scene lit only by the sun and the sky over a flat surface is the same at
  // every horizontal place, so its photons enter through one square tile of this width
  // about the camera and stand for every copy of it across the plane: the beam estimate
  // folds each ray into the tile (render.cl).  0: they enter through the lights' discs.
  double photon_tile = 0;
  // The per-step estimate at one step of every step_subsample, jittered per pixel and
  // block and weighted by the block's steps: an unbiased estimate of the sum over every
  // step with that many times fewer searches, and more noise (1: every step).
  int step_subsample = 1;
  double exposure = 1;              // PNG: linear sRGB × exposure before encoding
};

struct OceanSceneDesc {
  std::string name, description;
  Water water;
  Grid grid;
  std::vector<Light> lights;
  std::vector<size_t> daylight_lights;  // lights whose spectrum is the shared daylight's
  Medium medium;
  TraceParams trace;   // photons, max_interactions, seed, depths, layer
  bool has_camera = false;
  arcus_camera camera{};
  MarchParams march;
};

struct OceanScene : arcus_scene_s {
  explicit OceanScene(arcus_context_t* ctx) : arcus_scene_s(ctx, "ocean") {}
  OceanSceneDesc desc;
};

// Reads and checks an ocean scene file (INVALID_ARGUMENT naming the file and the JSON
// path, "scene.json: $.water.chlorophyll: must be finite and >= 0"; IO for a file that
// cannot be read).
OceanSceneDesc read_ocean_scene(const std::string& path);

// The scene behind a handle, checked to be an ocean scene.
OceanScene* ocean_scene(arcus_scene_s* scene);

}  // namespace arcus::ocean
