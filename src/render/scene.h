// Render scenes: a scene file with a camera (scene_desc.h) made into what a frame
// needs: the field, the meshes' triangles under one BVH, the analytic shapes, the
// materials with their textures, the lights, the sky, and the scene's bounds.  The
// device copies are made on first use and kept for every later frame.
#pragma once

#include <algorithm>
#include <array>
#include <memory>
#include <vector>

#include "bvh/bvh.h"
#include "bvh/device_bvh.h"
#include "core/buffer.h"
#include "curved/field_scene.h"
#include "image/image_io.h"
#include "image/mipmap.h"
#include "curved/advance_desc.h"  // kernels/curved/advance_desc.h: the ray status codes
#include "render/render_desc.h"   // kernels/render/render_desc.h
#include "render/scene_desc.h"
#include "scene/scene.h"

namespace arcus::render {

struct RenderScene : curved::FieldScene {
  explicit RenderScene(arcus_context_t* ctx) : FieldScene(ctx, "render") {}

  RenderDesc desc;
  bvh::TriangleBvh triangles;      // every mesh's triangles, object by object
  std::vector<uint32_t> slot_of;   // per triangle index: its slot in triangles.triangles
  std::vector<int32_t> mesh_object;  // per mesh of `triangles`: its index in desc.objects
  std::vector<std::vector<double>> mesh_uvs;  // per mesh: 6 per triangle (its corners' uv), or empty
  std::vector<arcus_shape_d> shapes;
  std::vector<int32_t> shape_object;           // per shape: its index in desc.objects
  std::vector<image::MipPyramid> textures;     // per material (empty: none)
  image::Image sky_image;
  // A daylight sky's light on surfaces: irradiance (linear sRGB, W m⁻² nm⁻¹) per
  // surface normal, an equirectangular map over normals (sky_light.h); empty otherwise.
  image::Image sky_irradiance;
  std::array<double, 3> lo{}, hi{};            // the bounds: rays that leave see the sky

  // Device copies in the kernels' precision (0: double, 1: float), made on first use.
  std::shared_ptr<bvh::DeviceBvh> device_bvh[2];
  std::shared_ptr<DeviceBuffer> device_shapes[2];
  void upload(arcus_context_t* ctx, bool single);
};

// The largest side of the scene's bounds: the scale of its tolerances.
inline double scene_scale(const RenderScene& s) {
  return std::max({s.hi[0] - s.lo[0], s.hi[1] - s.lo[1], s.hi[2] - s.lo[2]});
}

// How far a ray leaving a surface (a shadow ray, a bounced photon) starts off it: a
// little more than the crossing tolerance, so that it does not find that surface again.
inline double surface_offset(const RenderScene& s) { return 1e-6 * scene_scale(s) + 1e-4; }

// The scene behind a handle, checked to be a render scene.
RenderScene* render_scene(arcus_scene_s* scene);

}  // namespace arcus::render
