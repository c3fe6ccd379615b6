// What the translucency engine knows of an object's surface: the mesh in mm with
// outward normals, irradiance samples spread evenly over it, the irradiance each gets
// from directional lights (thesis eq. 3.8) and where camera rays meet it.  Shared by
// rendering (render.cpp) and, later, estimation from a photograph.
#pragma once

#include <cstdint>
#include <vector>

#include "arcus/arcus_translucency.h"
#include "bvh/device_bvh.h"
#include "geometry/mesh.h"
#include "geometry/vec3.h"
#include "scene/common_keys.h"

namespace arcus::translucency {

// The mesh in mm and what follows from its triangles.
struct Surface {
  geometry::Mesh mesh;          // positions in mm
  std::vector<double> normals;  // 3 per triangle: unit, outward (by the sign of the volume)
  // 9 per triangle: each corner's shading normal, the area-weighted mean of the normals
  // of the triangles at that vertex within kCreaseDeg of this one's (so a cube keeps
  // flat faces and a sphere turns smooth).
  std::vector<double> corner_normals;
  std::vector<double> areas;    // per triangle [mm²]
  double area = 0;              // the whole surface [mm²]
  double diagonal = 0;          // of its bounding box [mm]
};

// Edges not shared by exactly two triangles, vertices taken as equal where their
// positions are (files often repeat a vertex per face): 0 for a closed mesh.
size_t open_edges(const Surface& s);

// Triangles meeting at a vertex at a sharper angle than this keep their own normals.
constexpr double kCreaseDeg = 45;

// The shading normal at barycentric weights (u, v) of triangle t's corners 1 and 2.
Vec3 shading_normal(const Surface& s, size_t t, double u, double v);

// `mesh` scaled by mm_per_unit, its normals turned outwards when its volume is negative.
Surface make_surface(const geometry::Mesh& mesh, double mm_per_unit);

// Irradiance samples: each triangle cut into k² congruent triangles (k = ⌈longest edge /
// spacing⌉), a sample at each one's centroid carrying its area (the midpoint rule).
struct Samples {
  std::vector<double> positions;  // 3 per sample [mm]
  std::vector<uint32_t> triangle; // the triangle each lies on
  std::vector<double> normals;    // 3 per sample: the shading normal there
  std::vector<double> areas;      // ΔA [mm²]
  size_t size() const { return areas.size(); }
};

// How many samples `spacing` gives (saturating at UINT64_MAX), and the samples.
uint64_t sample_count(const Surface& surface, double spacing);
Samples make_samples(const Surface& surface, double spacing);

struct Light {
  Vec3 toward;          // unit, toward the light
  double irradiance[3]; // on a surface facing it
};

// The caller's lights, checked (1..64; finite, non-zero directions; finite irradiances
// >= 0), messages naming them ("lights[1].irradiance[2]").
std::vector<Light> lights_of(const std::vector<arcus_directional_light>& lights);

// The view parameters renders and estimates share, checked, naming them
// ("params->camera", "params->ortho_height", "params->mm_per_unit", "params->exit").
void check_view(const arcus_camera& camera, double ortho_height, double mm_per_unit, int32_t exit);

// An image of linear radiance (width × height × 3 floats) checked: every value finite
// and >= 0, else an error naming `name`, the index and the pixel.
void check_radiance(const float* pixels, uint32_t width, uint32_t height, const char* name);

// The caller's camera (mesh units) with positions in mm, as the surface's.
scene::CameraDesc camera_in_mm(const arcus_camera& camera, double mm_per_unit);

// Whether each point (3 per point, on the surface) sees each light: a shadow ray per
// pair through the BVH, started a hair off the surface along its triangle's normal;
// a light behind the triangle is not seen.  visible[p * lights + l].
std::vector<uint8_t> visibility(arcus_context_t* ctx, const bvh::DeviceBvh& bvh, const Surface& surface,
                                const std::vector<double>& points, const std::vector<uint32_t>& triangle,
                                const std::vector<Light>& lights);

// Eq. 3.8 for directional lights: per sample and channel Σ_l F_t(η, cos θ_l) E_l cos θ_l
// over the lights it sees, θ_l from the shading normal (3 per sample).
std::vector<double> sample_irradiance(arcus_context_t* ctx, const bvh::DeviceBvh& bvh, const Surface& surface,
                                      const Samples& samples, const std::vector<Light>& lights, double eta);

// Where each pixel's camera ray first meets the surface (camera and heights in mm).
struct Views {
  std::vector<double> points;      // 3 per pixel [mm]; NaN where none
  std::vector<double> toward_eye;  // 3 per pixel: unit, back along the ray
  std::vector<double> normals;     // 3 per pixel: the shading normal where it meets the surface
  std::vector<int32_t> triangle;   // -1 where none
};
Views camera_hits(arcus_context_t* ctx, const bvh::DeviceBvh& bvh, const Surface& surface,
                  const scene::CameraDesc& camera, double ortho_height);

// Where each of those rays last leaves the surface (the thesis' back points p_b, §3.3.1):
// a ray shot back along it from beyond the object.  Pixels without a front point have
// none; toward_eye is the front's.
Views back_hits(arcus_context_t* ctx, const bvh::DeviceBvh& bvh, const Surface& surface, const Views& front);

}  // namespace arcus::translucency
