#include "translucency/surface.h"

#include <algorithm>
#include <array>
#include <map>
#include <utility>
#include <cmath>
#include <limits>
#include <string>

#include "core/error.h"
#include "core/format.h"

// kernels/common/fresnel.h is scalar code the host includes after common/real.h.
#include "common/real.h"
#include "common/fresnel.h"

namespace arcus::translucency {
namespace {

Vec3 vertex(const geometry::Mesh& m, size_t t, int corner) {
  return vec3(&m.positions[3 * size_t(m.triangles[3 * t + corner])]);
}

// Shadow rays go to the device in batches of this many, so a large surface under
// several lights needs no more than ~60 MB of segments at a time.
constexpr size_t kSegmentBatch = size_t(1) << 20;

}  // namespace

Surface make_surface(const geometry::Mesh& mesh, double mm_per_unit) {
  Surface s;
  s.mesh = mesh;
  for (double& p : s.mesh.positions) p *= mm_per_unit;
  const size_t n = s.mesh.triangle_count();
  s.normals.resize(3 * n);
  s.areas.resize(n);
  double volume = 0;
  for (size_t t = 0; t < n; ++t) {
    const Vec3 a = vertex(s.mesh, t, 0), b = vertex(s.mesh, t, 1), c = vertex(s.mesh, t, 2);
    const Vec3 doubled = cross(b - a, c - a);
    const double len = length(doubled);
    s.areas[t] = 0.5 * len;
    s.area += s.areas[t];
    store(len > 0 ? (1 / len) * doubled : Vec3{}, &s.normals[3 * t]);
    volume += dot(a, cross(b, c)) / 6;
  }
  // A closed mesh wound clockwise seen from outside has a negative volume: its
  // winding normals point in.
  if (volume < 0)
    for (double& v : s.normals) v = -v;
  Vec3 lo{INFINITY, INFINITY, INFINITY}, hi = -lo;
  for (size_t v = 0; v < s.mesh.vertex_count(); ++v)
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::min(lo[a], s.mesh.positions[3 * v + a]);
      hi[a] = std::max(hi[a], s.mesh.positions[3 * v + a]);
    }
  s.diagonal = length(hi - lo);
  // Corner normals: the vertex's triangles within the crease angle, weighted by area.
  std::vector<std::vector<uint32_t>> at_vertex(s.mesh.vertex_count());
  for (size_t t = 0; t < n; ++t)
    for (int k = 0; k < 3; ++k) at_vertex[s.mesh.triangles[3 * t + k]].push_back(static_cast<uint32_t>(t));
  const double crease = std::cos(kCreaseDeg * M_PI / 180);
  s.corner_normals.resize(9 * n);
  for (size_t t = 0; t < n; ++t) {
    const Vec3 own = vec3(&s.normals[3 * t]);
    for (int k = 0; k < 3; ++k) {
      Vec3 sum{};
      for (uint32_t o : at_vertex[s.mesh.triangles[3 * t + k]]) {
        const Vec3 other = vec3(&s.normals[3 * size_t(o)]);
        if (dot(other, own) >= crease) sum = sum + s.areas[o] * other;
      }
      store(length(sum) > 0 ? normalized(sum) : own, &s.corner_normals[9 * t + 3 * size_t(k)]);
    }
  }
  return s;
}

size_t open_edges(const Surface& s) {
  std::map<std::array<double, 3>, uint32_t> ids;
  auto id = [&](uint32_t vertex) {
    const double* p = &s.mesh.positions[3 * size_t(vertex)];
    return ids.emplace(std::array<double, 3>{p[0], p[1], p[2]}, static_cast<uint32_t>(ids.size())).first->second;
  };
  std::map<std::pair<uint32_t, uint32_t>, int> uses;
  for (size_t t = 0; t < s.mesh.triangle_count(); ++t)
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = id(s.mesh.triangles[3 * t + k]), b = id(s.mesh.triangles[3 * t + (k + 1) % 3]);
      if (a != b) ++uses[{std::min(a, b), std::max(a, b)}];
    }
  size_t open = 0;
  for (const auto& [edge, count] : uses) open += count != 2;
  return open;
}

Vec3 shading_normal(const Surface& s, size_t t, double u, double v) {
  const double* c = &s.corner_normals[9 * t];
  const Vec3 n = (1 - u - v) * vec3(c) + u * vec3(c + 3) + v * vec3(c + 6);
  return length(n) > 0 ? normalized(n) : vec3(&s.normals[3 * t]);
}

namespace {

// k: the triangle's cuts per edge for `spacing` (0 for a triangle of no area).
uint64_t cuts(const Surface& s, size_t t, double spacing) {
  if (s.areas[t] == 0) return 0;
  const Vec3 a = vertex(s.mesh, t, 0), b = vertex(s.mesh, t, 1), c = vertex(s.mesh, t, 2);
  const double longest = std::max({length(b - a), length(c - b), length(a - c)});
  const double k = std::ceil(longest / spacing);
  return k < 1 ? 1 : k > 4e9 ? uint64_t(4e9) : uint64_t(k);
}

}  // namespace

uint64_t sample_count(const Surface& s, double spacing) {
  uint64_t total = 0;
  for (size_t t = 0; t < s.areas.size(); ++t) {
    const uint64_t k = cuts(s, t, spacing);
    if (k > 0 && k * k > std::numeric_limits<uint64_t>::max() - total) return std::numeric_limits<uint64_t>::max();
    total += k * k;
  }
  return total;
}

Samples make_samples(const Surface& s, double spacing) {
  Samples out;
  const uint64_t total = sample_count(s, spacing);
  out.positions.reserve(3 * total);
  out.triangle.reserve(total);
  out.normals.reserve(3 * total);
  out.areas.reserve(total);
  for (size_t t = 0; t < s.areas.size(); ++t) {
    const uint64_t k = cuts(s, t, spacing);
    if (k == 0) continue;
    const Vec3 a = vertex(s.mesh, t, 0), e1 = vertex(s.mesh, t, 1) - a, e2 = vertex(s.mesh, t, 2) - a;
    const double piece = s.areas[t] / double(k * k), inv = 1.0 / double(k);
    auto add = [&](double u, double v) {
      const Vec3 p = a + (u * inv) * e1 + (v * inv) * e2;
      out.positions.insert(out.positions.end(), {p.x, p.y, p.z});
      const Vec3 normal = shading_normal(s, t, u * inv, v * inv);
      out.normals.insert(out.normals.end(), {normal.x, normal.y, normal.z});
      out.triangle.push_back(static_cast<uint32_t>(t));
      out.areas.push_back(piece);
    };
    // Grid corners (i, j), i + j <= k: the k(k+1)/2 upright triangles' centroids and the
    // k(k−1)/2 inverted ones'.
    for (uint64_t i = 0; i < k; ++i)
      for (uint64_t j = 0; i + j < k; ++j) {
        add(double(i) + 1.0 / 3, double(j) + 1.0 / 3);
        if (i + j + 1 < k) add(double(i) + 2.0 / 3, double(j) + 2.0 / 3);
      }
  }
  return out;
}

std::vector<Light> lights_of(const std::vector<arcus_directional_light>& lights) {
  constexpr size_t kMaxLights = 64;
  require(!lights.empty() && lights.size() <= kMaxLights,
          "light_count = " + std::to_string(lights.size()) + " is not 1.." + std::to_string(kMaxLights));
  std::vector<Light> out;
  for (size_t l = 0; l < lights.size(); ++l) {
    const std::string at = "lights[" + std::to_string(l) + "].";
    const Vec3 d = vec3(lights[l].direction);
    require(std::isfinite(d.x) && std::isfinite(d.y) && std::isfinite(d.z) && length(d) > 0,
            at + "direction is not a finite direction of length > 0");
    Light light{normalized(d), {}};
    for (int c = 0; c < 3; ++c) {
      require(std::isfinite(lights[l].irradiance[c]) && lights[l].irradiance[c] >= 0,
              at + "irradiance[" + std::to_string(c) + "] = " + number(lights[l].irradiance[c]) +
                  " is not a finite irradiance >= 0");
      light.irradiance[c] = lights[l].irradiance[c];
    }
    out.push_back(light);
  }
  return out;
}

void check_view(const arcus_camera& camera, double ortho_height, double mm_per_unit, int32_t exit) {
  scene::check_camera(scene::camera_desc(camera), "params->camera");
  require(std::isfinite(ortho_height) && ortho_height >= 0,
          "params->ortho_height = " + number(ortho_height) + " is not a finite height >= 0 (0: the pinhole)");
  require(std::isfinite(mm_per_unit) && mm_per_unit > 0,
          "params->mm_per_unit = " + number(mm_per_unit) + " is not a finite length > 0 (mm per mesh unit)");
  require(exit == ARCUS_EXIT_THESIS || exit == ARCUS_EXIT_NORMALIZED,
          "params->exit = " + std::to_string(exit) + " is not ARCUS_EXIT_THESIS (0) or ARCUS_EXIT_NORMALIZED (1)");
}

void check_radiance(const float* pixels, uint32_t width, uint32_t height, const char* name) {
  for (size_t i = 0; i < 3 * size_t(width) * height; ++i)
    require(std::isfinite(pixels[i]) && pixels[i] >= 0,
            std::string(name) + "[" + std::to_string(i) + "] = " + number(pixels[i]) + " (pixel " +
                std::to_string(i / 3 % width) + ", " + std::to_string(i / 3 / width) + ") is not a finite radiance >= 0");
}

scene::CameraDesc camera_in_mm(const arcus_camera& camera, double mm_per_unit) {
  scene::CameraDesc c = scene::camera_desc(camera);
  c.position = mm_per_unit * c.position;
  c.look_at = mm_per_unit * c.look_at;
  return c;
}

std::vector<uint8_t> visibility(arcus_context_t* ctx, const bvh::DeviceBvh& bvh, const Surface& surface,
                                const std::vector<double>& points, const std::vector<uint32_t>& triangle,
                                const std::vector<Light>& lights) {
  const size_t n = triangle.size(), pairs = n * lights.size();
  std::vector<uint8_t> visible(pairs, 0);
  // Off the surface by a millionth of the object, so a ray does not hit its own triangle.
  const double offset = 1e-6 * surface.diagonal;
  std::vector<bvh::Segment> batch;
  std::vector<size_t> which;
  auto flush = [&] {
    const std::vector<bvh::Hit> hits = bvh::closest_hits(ctx, bvh, batch);
    for (size_t i = 0; i < hits.size(); ++i) visible[which[i]] = hits[i].primitive < 0;
    batch.clear();
    which.clear();
  };
  for (size_t p = 0; p < n; ++p) {
    const Vec3 normal = vec3(&surface.normals[3 * size_t(triangle[p])]);
    const Vec3 start = vec3(&points[3 * p]) + offset * normal;
    for (size_t l = 0; l < lights.size(); ++l) {
      if (dot(normal, lights[l].toward) <= 0) continue;  // faces away: unlit, no ray needed
      bvh::Segment seg{};
      store(start, seg.origin);
      store(lights[l].toward, seg.direction);
      seg.t_max = 2 * surface.diagonal;
      batch.push_back(seg);
      which.push_back(p * lights.size() + l);
      if (batch.size() == kSegmentBatch) flush();
    }
  }
  if (!batch.empty()) flush();
  return visible;
}

std::vector<double> sample_irradiance(arcus_context_t* ctx, const bvh::DeviceBvh& bvh, const Surface& surface,
                                      const Samples& samples, const std::vector<Light>& lights, double eta) {
  const std::vector<uint8_t> visible = visibility(ctx, bvh, surface, samples.positions, samples.triangle, lights);
  std::vector<double> e(3 * samples.size(), 0.0);
  for (size_t s = 0; s < samples.size(); ++s) {
    const Vec3 normal = vec3(&samples.normals[3 * s]);
    for (size_t l = 0; l < lights.size(); ++l) {
      if (!visible[s * lights.size() + l]) continue;
      const double cos_i = std::max(0.0, dot(normal, lights[l].toward));
      const double through = cos_i * (1 - arcus_fresnel_reflectance(cos_i, 1.0, eta));
      for (int c = 0; c < 3; ++c) e[3 * s + c] += through * lights[l].irradiance[c];
    }
  }
  return e;
}

Views camera_hits(arcus_context_t* ctx, const bvh::DeviceBvh& bvh, const Surface& surface,
                  const scene::CameraDesc& camera, double ortho_height) {
  const scene::Frame frame = scene::camera_frame(camera);
  const size_t pixels = size_t(camera.width) * camera.height;
  // Far enough to cross the whole object from wherever the camera is.
  Vec3 centre{};
  for (size_t v = 0; v < surface.mesh.vertex_count(); ++v) centre = centre + vec3(&surface.mesh.positions[3 * v]);
  centre = (1.0 / double(surface.mesh.vertex_count())) * centre;
  const double reach = length(camera.position - centre) + 2 * surface.diagonal + ortho_height;
  std::vector<bvh::Segment> rays(pixels);
  std::vector<Vec3> back(pixels);
  for (uint32_t j = 0; j < camera.height; ++j)
    for (uint32_t i = 0; i < camera.width; ++i) {
      Vec3 origin = frame.origin, direction;
      if (ortho_height > 0)
        scene::orthographic_ray(frame, camera, ortho_height, i, j, &origin, &direction);
      else
        direction = normalized(scene::pixel_direction(frame, camera, i, j));
      const size_t p = size_t(j) * camera.width + i;
      store(origin, rays[p].origin);
      store(direction, rays[p].direction);
      rays[p].t_max = reach;
      back[p] = -direction;
    }
  const std::vector<bvh::Hit> hits = bvh::closest_hits(ctx, bvh, rays);
  Views v;
  v.points.assign(3 * pixels, NAN);
  v.toward_eye.resize(3 * pixels);
  v.triangle.assign(pixels, -1);
  v.normals.assign(3 * pixels, NAN);
  for (size_t p = 0; p < pixels; ++p) {
    store(back[p], &v.toward_eye[3 * p]);
    if (hits[p].primitive < 0) continue;
    v.triangle[p] = hits[p].primitive;
    const Vec3 at = vec3(rays[p].origin) + hits[p].t * vec3(rays[p].direction);
    store(at, &v.points[3 * p]);
    store(shading_normal(surface, size_t(hits[p].primitive), hits[p].u, hits[p].v), &v.normals[3 * p]);
  }
  return v;
}

Views back_hits(arcus_context_t* ctx, const bvh::DeviceBvh& bvh, const Surface& surface, const Views& front) {
  const size_t pixels = front.triangle.size();
  const double reach = 2 * surface.diagonal;
  std::vector<bvh::Segment> rays;
  std::vector<size_t> which;
  for (size_t p = 0; p < pixels; ++p) {
    if (front.triangle[p] < 0) continue;
    const Vec3 back = vec3(&front.toward_eye[3 * p]);
    bvh::Segment seg{};
    store(vec3(&front.points[3 * p]) - reach * back, seg.origin);
    store(back, seg.direction);
    seg.t_max = reach;
    rays.push_back(seg);
    which.push_back(p);
  }
  const std::vector<bvh::Hit> hits = bvh::closest_hits(ctx, bvh, rays);
  Views v;
  v.points.assign(3 * pixels, NAN);
  v.normals.assign(3 * pixels, NAN);
  v.toward_eye = front.toward_eye;
  v.triangle.assign(pixels, -1);
  for (size_t i = 0; i < hits.size(); ++i) {
    const size_t p = which[i];
    // The front point itself is on the surface, so the ray always ends on something.
    if (hits[i].primitive < 0) continue;
    v.triangle[p] = hits[i].primitive;
    store(vec3(rays[i].origin) + hits[i].t * vec3(rays[i].direction), &v.points[3 * p]);
    store(shading_normal(surface, size_t(hits[i].primitive), hits[i].u, hits[i].v), &v.normals[3 * p]);
  }
  return v;
}

}  // namespace arcus::translucency
