#include "navigation.h"

#include <algorithm>
#include <cmath>

namespace arcus_view {
namespace {

struct V3 {
  double x, y, z;
};
V3 operator+(V3 a, V3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
V3 operator-(V3 a, V3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
V3 operator*(double s, V3 a) { return {s * a.x, s * a.y, s * a.z}; }
double dot(V3 a, V3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
V3 cross(V3 a, V3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
V3 normalized(V3 a) { return (1.0 / std::sqrt(dot(a, a))) * a; }
V3 load(const double* p) { return {p[0], p[1], p[2]}; }
void store(V3 a, double* p) {
  p[0] = a.x;
  p[1] = a.y;
  p[2] = a.z;
}

// Rodrigues' rotation of v by `angle` about the unit axis k.
V3 rotate(V3 v, V3 k, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  return c * v + s * cross(k, v) + (dot(k, v) * (1 - c)) * k;
}

// Rotates `arm` (a vector from the pivot) by yaw about up, then by pitch about the view's
// right axis unless that brings the view direction (`sign · arm`) within 1° of ±up.
V3 swing(V3 arm, V3 up, double yaw, double pitch, double sign) {
  arm = rotate(arm, up, yaw);
  const V3 right = normalized(cross(sign * arm, up));
  const V3 pitched = rotate(arm, right, pitch);
  const double cos_limit = std::cos(1.0 * M_PI / 180.0);
  return std::fabs(dot(normalized(pitched), up)) < cos_limit ? pitched : arm;
}

}  // namespace

void orbit(arcus_camera& camera, double yaw, double pitch) {
  const V3 pivot = load(camera.look_at), up = normalized(load(camera.up));
  // The arm runs from look_at to the camera, opposite to the view direction, so a
  // rotation about the right axis that raises the view lowers the camera: negate.
  store(pivot + swing(load(camera.position) - pivot, up, yaw, -pitch, -1.0), camera.position);
}

void turn(arcus_camera& camera, double yaw, double pitch) {
  const V3 eye = load(camera.position), up = normalized(load(camera.up));
  store(eye + swing(load(camera.look_at) - eye, up, yaw, pitch, 1.0), camera.look_at);
}

void move(arcus_camera& camera, double forward, double right) {
  const V3 eye = load(camera.position), view = load(camera.look_at) - eye;
  const V3 side = normalized(cross(view, load(camera.up)));
  const V3 shift = forward * view + (right * std::sqrt(dot(view, view))) * side;
  store(eye + shift, camera.position);
  store(load(camera.look_at) + shift, camera.look_at);
}

void look(arcus_rainbow_sky& sky, double right, double up) {
  // Azimuth from +z toward +x (the library's, which puts +x on the right of a camera
  // looking along +z) and elevation above the horizon.
  const V3 f = load(sky.camera_forward);
  const double limit = 89.0 * M_PI / 180.0;
  const double azimuth = std::atan2(f.x, f.z) + right;
  const double elevation = std::clamp(std::atan2(f.y, std::hypot(f.x, f.z)) + up, -limit, limit);
  store({std::cos(elevation) * std::sin(azimuth), std::sin(elevation), std::cos(elevation) * std::cos(azimuth)},
        sky.camera_forward);
  store({0, 1, 0}, sky.camera_up);
}

void zoom(arcus_rainbow_sky& sky, double factor) { sky.fov_deg = std::clamp(sky.fov_deg * factor, 5.0, 150.0); }

}  // namespace arcus_view
