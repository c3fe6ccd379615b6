// What the passes of a frame share (renderer.cpp traces and walks the primary rays,
// shading.cpp the light they see): the camera's frame and pixel directions, batches of
// rays with where their results go, every pixel's primary result, and what smart step
// selection and recorded paths take from a trace.  Internal to the renderer.
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "render/scene.h"
#include "render/trace.h"
#include "geometry/vec3.h"

namespace arcus::render {

// The 99.9th percentile of the rays' step counts (0 for none): recorded paths get room
// for it (recorded step by step, the room past a region's longest path is never touched).
uint64_t percentile999(std::vector<uint64_t> steps);

using scene::camera_frame;
using scene::Frame;
using scene::pixel_direction;

// A batch of rays to trace and where their results go.
struct Batch {
  std::vector<double> origins, directions;
  std::vector<int32_t> predictions;
  std::vector<size_t> pixels;
  void add(Vec3 o, Vec3 d, size_t pixel, int32_t prediction) {
    origins.insert(origins.end(), {o.x, o.y, o.z});
    directions.insert(directions.end(), {d.x, d.y, d.z});
    predictions.push_back(prediction);
    pixels.push_back(pixel);
  }
  size_t size() const { return pixels.size(); }
  // The trace's input, predicting with `predictions` if asked.
  TraceInput input(bool predict) const {
    TraceInput in;
    in.count = size();
    in.origins = origins.data();
    in.directions = directions.data();
    in.predictions = predict ? predictions.data() : nullptr;
    return in;
  }
};

// The 99.9th percentile of the steps of a probe's rays, traced directly (time into *seconds).
uint64_t probe_steps(arcus_context_t* ctx, RenderScene* scene, const arcus_advance_params& params, const Batch& probe,
                     double* seconds);

// A predicted "end step" for a ray that hits nothing: beyond any path.
constexpr int32_t kNoHit = std::numeric_limits<int32_t>::max();

// What smart step selection predicts from a ray's result: the step that hit, kNoHit for
// a ray that left the scene, -1 for a failed ray.
int32_t end_step_of(int32_t status, int32_t hit_step);

// Room for recorded paths: all but the longest few of paths whose 99.9th percentile of
// steps is `steps`, and a quarter more (a percentile from a sample, or from the last
// frame, is only an estimate).  The memory is count × room, and a path cut short only
// sends the few rays that walk past its end to be traced.
uint32_t path_room(uint64_t steps);

// Every pixel's primary result.
struct Primary {
  std::vector<int32_t> status, object, primitive, kind, index, hit_step, tests;
  // What smart step selection predicts from: the step that hit, kNoHit for a ray that
  // left the scene (a neighbour expecting no hit skips its tests to its end and proves
  // the steps empty), -1 for a failed ray.
  std::vector<int32_t> end_step;
  std::vector<double> position, direction, length;
  std::vector<double> start;  // the primary ray's initial direction
  arcus_features features = 0;  // compiled by the programs that traced or walked them
  std::vector<uint64_t> steps;
  explicit Primary(size_t n)
      : status(n, ARCUS_STATUS_FAILED), object(n, -1), primitive(n, -1), kind(n, 0), index(n, -1), hit_step(n, -1),
        tests(n, 0), end_step(n, -1), position(3 * n, NAN), direction(3 * n, 0), length(n, 0), start(3 * n, 0),
        steps(n, 0) {}
};

// Every kCoarse-th pixel (each direction) probes recorded paths' room.
constexpr uint32_t kCoarse = 4;

}  // namespace arcus::render
