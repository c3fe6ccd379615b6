#include "render/surface.h"

#include <algorithm>
#include <cmath>

namespace arcus::render {

Surface surface_at(const RenderScene& s, int32_t kind, int32_t index, Vec3 p, Vec3 arriving) {
  Surface out;
  if (kind == ARCUS_HIT_TRIANGLE) {
    const double* t = &s.triangles.triangles[9 * static_cast<size_t>(s.slot_of[static_cast<size_t>(index)])];
    const Vec3 a = vec3(t), e1 = vec3(t + 3) - a, e2 = vec3(t + 6) - a;
    out.normal = normalized(cross(e1, e2));
    const uint32_t mesh = s.triangles.geometry[static_cast<size_t>(index)];
    const auto& uvs = s.mesh_uvs[mesh];
    if (!uvs.empty()) {
      // Barycentric weights of p (projected onto the triangle's plane).
      const Vec3 w = p - a;
      const double d00 = dot(e1, e1), d01 = dot(e1, e2), d11 = dot(e2, e2), d20 = dot(w, e1), d21 = dot(w, e2);
      const double den = d00 * d11 - d01 * d01;
      const double b1 = (d11 * d20 - d01 * d21) / den, b2 = (d00 * d21 - d01 * d20) / den, b0 = 1 - b1 - b2;
      const size_t local = static_cast<size_t>(index) - s.triangles.mesh_first[mesh];
      const double* c = &uvs[6 * local];
      out.u = b0 * c[0] + b1 * c[2] + b2 * c[4];
      out.v = b0 * c[1] + b1 * c[3] + b2 * c[5];
      out.has_uv = true;
    }
  } else {
    const arcus_shape_d& sh = s.shapes[static_cast<size_t>(index)];
    const Vec3 c = vec3(sh.center);
    if (sh.kind == ARCUS_SHAPE_SPHERE) {
      out.normal = normalized(p - c);
      out.u = 0.5 + std::atan2(out.normal.x, -out.normal.z) / (2 * M_PI);
      out.v = std::acos(std::clamp(out.normal.y, -1.0, 1.0)) / M_PI;
    } else {
      out.normal = vec3(sh.normal);
      // Planar coordinates in metres along two axes of the disc's plane.
      const Vec3 n = out.normal;
      const Vec3 t = normalized(std::fabs(n.y) < 0.9 ? cross(n, Vec3{0, 1, 0}) : cross(n, Vec3{1, 0, 0}));
      const Vec3 b = cross(n, t);
      out.u = dot(p - c, t);
      out.v = dot(p - c, b);
    }
    out.has_uv = true;
  }
  if (dot(out.normal, arriving) > 0) out.normal = -1.0 * out.normal;
  return out;
}

Vec3 albedo(const RenderScene& s, size_t material, const Surface& surf) {
  const MaterialDesc& m = s.desc.materials[material];
  Vec3 a = m.diffuse;
  const image::MipPyramid& tex = s.textures[material];
  if (!tex.empty() && surf.has_uv) {
    const double su = m.uv_scale[0], sv = m.uv_scale[1];
    const double u = surf.u * su, v = surf.v * sv;
    const auto c = tex.sample(u - std::floor(u), v - std::floor(v), surf.du_x * su, surf.dv_x * sv, surf.du_y * su,
                              surf.dv_y * sv);
    a = {a.x * c[0], a.y * c[1], a.z * c[2]};
  }
  return a;
}

void set_footprints(const std::vector<int32_t>& object, int width, std::vector<Surface>* surfaces) {
  const auto& s = *surfaces;
  const size_t n = s.size(), w = static_cast<size_t>(width);
  // The change toward the nearer-looking of the neighbours at p − step and p + step.
  auto change = [&](size_t p, bool left_ok, bool right_ok, size_t step, double* du, double* dv) {
    double best = INFINITY;
    *du = *dv = 0;
    for (int side = -1; side <= 1; side += 2) {
      if (side < 0 ? !left_ok : !right_ok) continue;
      const size_t q = side < 0 ? p - step : p + step;
      if (object[q] != object[p] || !s[q].has_uv) continue;
      const double eu = side * (s[q].u - s[p].u), ev = side * (s[q].v - s[p].v);
      if (eu * eu + ev * ev < best) {
        best = eu * eu + ev * ev;
        *du = eu;
        *dv = ev;
      }
    }
  };
  for (size_t p = 0; p < n; ++p) {
    Surface& f = (*surfaces)[p];
    if (object[p] < 0 || !f.has_uv) continue;
    const size_t x = p % w, y = p / w;
    change(p, x > 0, x + 1 < w, 1, &f.du_x, &f.dv_x);
    change(p, y > 0, p + w < n, w, &f.du_y, &f.dv_y);
  }
}

}  // namespace arcus::render
