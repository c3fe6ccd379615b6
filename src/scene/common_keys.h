// What every engine's scene file reads alike: its "name", directions, and the pinhole
// camera (arcus_camera, arcus_scene.h) of the engines that make a view (render,
// ocean).  Written once here so that one camera has one set of checks and messages.
#pragma once

#include <cstdint>
#include <string>

#include "arcus/arcus_scene.h"
#include "geometry/vec3.h"
#include "scene/json_reader.h"
#include "sky/atmosphere.h"

namespace arcus::scene {

// Pixels a side of any view, as the scene files and the C API accept them.
constexpr uint32_t kMaxSide = 16384;

// A scene's "name": tools name their output directory after it, so it must be a plain
// one (letters, digits, '_', '-', '.'; not "." or "..").
std::string parse_name(const json::Node& node);

// A scene's "atmosphere" (the shared sun and sky, arcus_daylight.h): an object of
// arcus_daylight_desc's numbers, each optional over the clear day's, checked as the C
// API checks them.
sky::Atmosphere parse_atmosphere(const json::Node& node);

// A non-zero direction, normalized.
Vec3 parse_direction(const json::Node& node);

struct CameraDesc {
  Vec3 position{0, 0, 0}, look_at{0, 0, -1}, up{0, 1, 0};
  double vfov_deg = 45;
  uint32_t width = 64, height = 64;
};

// Checks a camera: finite, look_at != position, up not along the view, 0 < vfov < 180,
// 1..kMaxSide pixels a side.  Throws INVALID_ARGUMENT naming `what`'s member.
void check_camera(const CameraDesc& camera, const std::string& what);

// The C API's camera and its description, both ways.
CameraDesc camera_desc(const arcus_camera& camera);
arcus_camera camera_struct(const CameraDesc& camera);

// The camera's frame: forward, right and true up.
struct Frame {
  Vec3 origin, forward, right, up;
  double tan_half, aspect;
};
Frame camera_frame(const CameraDesc& c);

// Pixel (i, j)'s direction through its centre, rows top to bottom: the pinhole's ray.
Vec3 pixel_direction(const Frame& f, const CameraDesc& c, uint32_t i, uint32_t j);

// Pixel (i, j)'s ray of an orthographic camera whose view is `height` (> 0, the scene's
// units) tall and as wide as the image's aspect makes it: every ray runs along forward,
// from the plane through `position` square to it (vfov_deg is not used).
void orthographic_ray(const Frame& f, const CameraDesc& c, double height, uint32_t i, uint32_t j, Vec3* origin,
                      Vec3* direction);

// A scene's "camera" object (position, look_at, up, vfov_deg, width, height), checked;
// `default_up` is the engine's world up (render: +y; ocean, whose surface is z = 0: +z).
CameraDesc parse_camera(const json::Node& node, Vec3 default_up);

}  // namespace arcus::scene
