// The host's one 3-vector, for every engine's host code: scene descriptions, cameras,
// shading, photons, mirrors.  (Kernels have OpenCL's double3; the *_desc.h structs
// shared with them carry plain double[3].)  Indexable as v[0..2] for code that loops
// over axes, named x, y, z for code that reads as geometry.
#pragma once

#include <array>
#include <cmath>

namespace arcus {

struct Vec3 {
  double x = 0, y = 0, z = 0;

  double operator[](int axis) const { return axis == 0 ? x : axis == 1 ? y : z; }
  double& operator[](int axis) { return axis == 0 ? x : axis == 1 ? y : z; }
  // As a double[3] for a C call (`v.array().data()` lives to the end of the call).
  std::array<double, 3> array() const { return {x, y, z}; }
};

inline Vec3 operator-(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline Vec3 operator+(Vec3 a, Vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline Vec3 operator-(Vec3 a) { return {-a.x, -a.y, -a.z}; }
inline Vec3 operator*(double s, Vec3 a) { return {s * a.x, s * a.y, s * a.z}; }
inline bool operator==(Vec3 a, Vec3 b) { return a.x == b.x && a.y == b.y && a.z == b.z; }
inline bool operator!=(Vec3 a, Vec3 b) { return !(a == b); }
inline double dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Vec3 cross(Vec3 a, Vec3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
inline double length(Vec3 a) { return std::sqrt(dot(a, a)); }
inline Vec3 normalized(Vec3 a) { return (1.0 / length(a)) * a; }
// From a C struct's double[3] (arcus_camera, the kernels' descriptions).
inline Vec3 vec3(const double* p) { return {p[0], p[1], p[2]}; }
inline void store(Vec3 v, double* p) {
  p[0] = v.x;
  p[1] = v.y;
  p[2] = v.z;
}

}  // namespace arcus
