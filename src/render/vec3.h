// Small 3-vectors for the renderer's host code (camera, shading, photons, mirrors).
#pragma once

#include <cmath>

#include "curved/scene_desc.h"  // Vec3

namespace arcus::render {

struct V3 {
  double x, y, z;
};
inline V3 operator-(V3 a, V3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline V3 operator+(V3 a, V3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline V3 operator*(double s, V3 a) { return {s * a.x, s * a.y, s * a.z}; }
inline double dot(V3 a, V3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline V3 cross(V3 a, V3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
inline double length(V3 a) { return std::sqrt(dot(a, a)); }
inline V3 normalized(V3 a) { return (1.0 / length(a)) * a; }
inline V3 v3(const double* p) { return {p[0], p[1], p[2]}; }
inline V3 v3(const curved::Vec3& p) { return {p[0], p[1], p[2]}; }

}  // namespace arcus::render
