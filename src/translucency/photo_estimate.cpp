#include "translucency/photo_estimate.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "core/error.h"
#include "core/format.h"

namespace arcus::translucency {

// The least half-thickness at a corner, pixels: front and back never meet.
constexpr double kLeastDepth = 1e-3;

geometry::Mesh relief_mesh(const PhotoObject& o, const PhotoShape& shape, std::vector<uint8_t>* used) {
  const uint32_t w = o.width, h = o.height;
  cv::Mat mask(int(h), int(w), CV_8U);
  for (size_t i = 0; i < o.mask.size(); ++i) mask.data[i] = o.mask[i] ? 255 : 0;
  cv::morphologyEx(mask, mask, cv::MORPH_OPEN, cv::getStructuringElement(cv::MORPH_RECT, cv::Size(3, 3)));
  used->assign(o.mask.size(), 0);
  for (size_t i = 0; i < o.mask.size(); ++i) (*used)[i] = mask.data[i] ? 1 : 0;
  auto inside = [&](long x, long y) {
    return x >= 0 && y >= 0 && x < long(w) && y < long(h) && (*used)[size_t(y) * w + size_t(x)];
  };
  // Two pixels touching only at a corner would pinch the rim there: the later one goes.
  for (long y = 0; y + 1 < long(h); ++y)
    for (long x = 0; x + 1 < long(w); ++x) {
      const bool a = inside(x, y), b = inside(x + 1, y), c = inside(x, y + 1), d = inside(x + 1, y + 1);
      if (a && d && !b && !c) (*used)[size_t(y + 1) * w + size_t(x + 1)] = 0;
      if (b && c && !a && !d) (*used)[size_t(y + 1) * w + size_t(x)] = 0;
    }

  // Corners (w + 1) × (h + 1): the pixels about corner (x, y) are x − 1..x, y − 1..y.
  // Every corner the object touches has a front vertex at the mean depth of the four
  // pixels (those outside at 0) and a back one at minus that, never quite 0: a corner on
  // the contour keeps a little thickness, so that where the object is two pixels thin its
  // front and back do not share an edge.  Walls along the contour's edges close it.
  const size_t corners = size_t(w + 1) * (h + 1);
  std::vector<uint32_t> front(corners, 0), back(corners, 0);
  geometry::Mesh mesh;
  for (long y = 0; y <= long(h); ++y)
    for (long x = 0; x <= long(w); ++x) {
      int touching = 0;
      double sum = 0;
      for (long dy = -1; dy <= 0; ++dy)
        for (long dx = -1; dx <= 0; ++dx)
          if (inside(x + dx, y + dy)) {
            ++touching;
            sum += shape.depth[size_t(y + dy) * w + size_t(x + dx)];
          }
      if (touching == 0) continue;
      const double z = std::max(kLeastDepth, o.scale * sum / 4);
      // In the photo's pixels (a working pixel spans `scale` of them; the last row and
      // column may span fewer), its centre at the origin.
      const double f = o.scale;
      const double px = std::min(double(x) * f, double(o.photo_width)) - 0.5 * o.photo_width;
      const double py = 0.5 * o.photo_height - std::min(double(y) * f, double(o.photo_height));
      const size_t c = size_t(y) * (w + 1) + size_t(x);
      front[c] = uint32_t(mesh.vertex_count());
      back[c] = front[c] + 1;
      mesh.positions.insert(mesh.positions.end(), {px, py, z, px, py, -z});
    }
  auto quad = [&](size_t a, size_t b, size_t c, size_t d, const std::vector<uint32_t>& v) {
    mesh.triangles.insert(mesh.triangles.end(), {v[a], v[b], v[c], v[a], v[c], v[d]});
  };
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) {
      if (!inside(x, y)) continue;
      // a: top left, b: top right, c: bottom right, d: bottom left; y up, so a, d, c
      // runs counter-clockwise seen from the camera.
      const size_t a = size_t(y) * (w + 1) + x, b = a + 1, d = a + (w + 1), c = d + 1;
      quad(a, d, c, b, front);
      quad(a, b, c, d, back);
      // The contour's edges: a wall from the front edge to the back one, wound outward.
      auto strip = [&](size_t p, size_t q) {  // p → q runs counter-clockwise about the pixel
        mesh.triangles.insert(mesh.triangles.end(), {front[q], front[p], back[p], front[q], back[p], back[q]});
      };
      if (!inside(long(x), long(y) - 1)) strip(b, a);
      if (!inside(long(x) - 1, long(y))) strip(a, d);
      if (!inside(long(x), long(y) + 1)) strip(d, c);
      if (!inside(long(x) + 1, long(y))) strip(c, b);
    }
  return mesh;
}

std::unique_ptr<EstimateJob> estimate_automatic(arcus_context_t* ctx, uint32_t width, uint32_t height,
                                                const float* photo, const uint8_t* matte,
                                                const arcus_translucency_auto_params& p, bool* cancelled) {
  const auto start = std::chrono::steady_clock::now();
  check_shape_params(p.shape);
  require(std::isfinite(p.mm_per_pixel) && p.mm_per_pixel > 0,
          "params->mm_per_pixel = " + number(p.mm_per_pixel) + " is not a finite length > 0");
  for (int c = 0; c < 3; ++c)
    require(std::isfinite(p.irradiance[c]) && p.irradiance[c] >= 0,
            "params->irradiance[" + std::to_string(c) + "] = " + number(p.irradiance[c]) + " is not finite and >= 0");
  require(p.irradiance[0] + p.irradiance[1] + p.irradiance[2] > 0, "params->irradiance is 0 in every channel");

  const PhotoObject object = find_object(width, height, photo, matte);
  const arcus_light_detection lights = detect_lights(object);
  const PhotoShape shape = estimate_shape(object, p.shape);
  std::vector<uint8_t> used;
  geometry::Mesh mesh = relief_mesh(object, shape, &used);

  // The photo seen orthographically, a mesh unit a pixel, from far along +z.
  arcus_translucency_estimate_params params = p.estimate;
  params.camera.position[0] = params.camera.position[1] = 0;
  params.camera.position[2] = 4.0 * std::max(width, height);
  params.camera.look_at[0] = params.camera.look_at[1] = params.camera.look_at[2] = 0;
  params.camera.up[0] = params.camera.up[2] = 0;
  params.camera.up[1] = 1;
  params.camera.width = width;
  params.camera.height = height;
  params.ortho_height = height;
  params.mm_per_unit = p.mm_per_pixel;
  std::vector<arcus_directional_light> directional(lights.count);
  for (uint32_t j = 0; j < lights.count; ++j) {
    std::copy(lights.lights[j].direction, lights.lights[j].direction + 3, directional[j].direction);
    for (int c = 0; c < 3; ++c) directional[j].irradiance[c] = lights.lights[j].intensity * p.irradiance[c];
  }
  std::vector<uint8_t> photo_mask = at_photo_size(object, used);
  auto job = estimate(ctx, mesh, width, height, photo, photo_mask.data(), directional, params, cancelled);
  job->automatic = true;
  job->lights = lights;
  job->depth = at_photo_size(object, shape.depth, 1, object.scale);
  job->normals = at_photo_size(object, shape.normals, 3, 1);
  job->mask = std::move(photo_mask);
  job->relief = std::move(mesh);
  job->result.geometry_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() -
                                  job->stats.total_seconds;
  job->stats.total_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return job;
}

}  // namespace arcus::translucency
