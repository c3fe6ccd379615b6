#include "render/photon_emission.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "render/photons.h"

namespace arcus::render {
namespace {

// A sun's portal: triangles with their weight area·|n·s| (their area seen from the sun).
struct Portal {
  std::vector<Vec3> a, e1, e2, normal;  // corner, edges, unit normal facing the sun
  std::vector<double> cdf;            // running sum of the weights
  double area = 0;                    // A: the total
};

void add_triangle(Portal* portal, Vec3 a, Vec3 b, Vec3 c, Vec3 sun) {
  const Vec3 e1 = b - a, e2 = c - a, n2 = cross(e1, e2);
  const double len = length(n2);
  if (!(len > 0)) return;
  Vec3 n = (1.0 / len) * n2;
  double cosine = dot(n, sun);
  if (cosine < 0) {
    n = -1.0 * n;
    cosine = -cosine;
  }
  const double w = 0.5 * len * cosine;
  if (!(w > 0)) return;
  portal->a.push_back(a);
  portal->e1.push_back(e1);
  portal->e2.push_back(e2);
  portal->normal.push_back(n);
  portal->area += w;
  portal->cdf.push_back(portal->area);
}

// The window's triangles, else the faces of the bounds that face the sun.
Portal sun_portal(const RenderScene& s, Vec3 sun) {
  Portal portal;
  for (size_t tri = 0; tri < s.triangles.triangle_count(); ++tri) {
    const int32_t object = s.mesh_object[s.triangles.geometry[tri]];
    const ObjectDesc& o = s.desc.objects[static_cast<size_t>(object)];
    if (s.desc.materials[static_cast<size_t>(o.material)].name != kWindowMaterial) continue;
    const double* t = &s.triangles.triangles[9 * static_cast<size_t>(s.slot_of[tri])];
    add_triangle(&portal, vec3(t), vec3(t + 3), vec3(t + 6), sun);
  }
  if (!portal.cdf.empty()) return portal;
  const Vec3 lo = vec3(s.lo.data()), hi = vec3(s.hi.data());
  auto corner = [&](int i, int j, int k) { return Vec3{i ? hi.x : lo.x, j ? hi.y : lo.y, k ? hi.z : lo.z}; };
  const double comp[3] = {sun.x, sun.y, sun.z};
  for (int axis = 0; axis < 3; ++axis) {
    if (comp[axis] == 0) continue;
    const int side = comp[axis] > 0 ? 1 : 0;  // the face whose outward normal faces the sun
    Vec3 q[4];
    for (int c = 0; c < 4; ++c) {
      int ijk[3];
      ijk[axis] = side;
      ijk[(axis + 1) % 3] = c == 1 || c == 2;
      ijk[(axis + 2) % 3] = c >= 2;
      q[c] = corner(ijk[0], ijk[1], ijk[2]);
    }
    add_triangle(&portal, q[0], q[1], q[2], sun);
    add_triangle(&portal, q[0], q[2], q[3], sun);
  }
  return portal;
}

bool inside(const RenderScene& s, Vec3 p) {
  const double c[3] = {p.x, p.y, p.z};
  for (int a = 0; a < 3; ++a)
    if (!(c[a] > s.lo[a] && c[a] < s.hi[a])) return false;
  return true;
}

// Whether p lies on one of the portal's triangles (within tol of its plane and inside).
bool on_portal(const Portal& portal, Vec3 p, double tol) {
  for (size_t t = 0; t < portal.a.size(); ++t) {
    const Vec3 w = p - portal.a[t];
    if (std::fabs(dot(w, portal.normal[t])) > tol) continue;
    const Vec3 e1 = portal.e1[t], e2 = portal.e2[t];
    const double d00 = dot(e1, e1), d01 = dot(e1, e2), d11 = dot(e2, e2), d20 = dot(w, e1), d21 = dot(w, e2);
    const double den = d00 * d11 - d01 * d01;
    const double b1 = (d11 * d20 - d01 * d21) / den, b2 = (d00 * d21 - d01 * d20) / den;
    const double slack = tol / std::sqrt(std::max(d00, d11));
    if (b1 >= -slack && b2 >= -slack && b1 + b2 <= 1 + slack) return true;
  }
  return false;
}

std::string plane_problem(const RenderScene& s, const MirrorPlane& plane, double scale) {
  std::string why = medium_asymmetry(s.field->desc, plane);
  if (!why.empty()) return why;
  const Vec3 n = vec3(plane.normal);
  for (size_t l = 0; l < s.desc.lights.size(); ++l) {
    const LightDesc& light = s.desc.lights[l];
    const std::string name = "light " + std::to_string(l);
    if (light.kind == LightKind::Point) {
      if (std::fabs(dot(light.position, n) - plane.offset) > 1e-12 * std::max(1.0, length(light.position)))
        return name + " (a point light) does not lie in the plane";
      continue;
    }
    const Vec3 sun = normalized(light.direction);
    if (std::fabs(dot(sun, n)) > 1e-12) return name + " (a sun) does not shine parallel to the plane";
    const Portal portal = sun_portal(s, sun);
    const double tol = 1e-9 * scale;
    for (size_t t = 0; t < portal.a.size(); ++t) {
      const Vec3 a = portal.a[t], b = a + portal.e1[t], c = a + portal.e2[t];
      for (Vec3 p : {a, b, c, 0.5 * (a + b), 0.5 * (b + c), 0.5 * (a + c), (1.0 / 3) * (a + b + c)})
        if (!on_portal(portal, reflect_point(plane, p), tol))
          return name + "'s portal (its window) is not symmetric about the plane";
    }
  }
  return "";
}

// A photon, what the photon map keys it by, its light and the photon it mirrors (-1: none).
void add_photon(Emission* e, const Live& p, Vec3 key, size_t l, int32_t mirror_of) {
  e->live.push_back(p);
  e->key.push_back(key);
  e->light.push_back(static_cast<uint32_t>(l));
  e->mirror_of.push_back(mirror_of);
}

// A sun's share of n photons through its portal, ids from `id` on.  SYMMETRY: photons in
// pairs, the second the first's mirror image (an odd share's last photon alone).
void emit_sun(const RenderScene& s, const LightDesc& light, const Portal& portal, size_t l, uint64_t n, uint64_t seed,
              double offset, const MirrorPlane* plane, uint64_t& id, Emission* e) {
  const uint64_t step = plane ? 2 : 1;
  const Vec3 sun = normalized(light.direction);
  // The sampling coordinate: the start point across the beam (z = 0).
  Vec3 b1, b2;
  photon_basis(sun, &b1, &b2);
  auto across = [&](Vec3 q) { return Vec3{dot(q, b1), dot(q, b2), 0}; };
  double power[3];
  for (int c = 0; c < 3; ++c) power[c] = light.power[c] * portal.area / static_cast<double>(n);
  for (uint64_t i = 0; i < n; i += step, id += step) {
    const double pick = photon_draw(seed, id, 0) * portal.area;
    const size_t found = std::upper_bound(portal.cdf.begin(), portal.cdf.end(), pick) - portal.cdf.begin();
    const size_t t = std::min(found, portal.cdf.size() - 1);
    const double r1 = std::sqrt(photon_draw(seed, id, 1)), r2 = photon_draw(seed, id, 2);
    Vec3 q = portal.a[t] + (r1 * (1 - r2)) * portal.e1[t] + (r1 * r2) * portal.e2[t];
    // Just past the portal, `offset` from its plane.
    const double cosine = std::max(dot(portal.normal[t], sun), 1e-3);
    Vec3 o = q - (offset / cosine) * sun;
    const bool pair = plane && i + 1 < n;
    if (pair && dot(vec3(plane->normal), q) < plane->offset) {  // folded onto the positive side
      q = reflect_point(*plane, q);
      o = reflect_point(*plane, o);
    }
    if (!inside(s, o)) {  // the light misses the scene there
      if (!pair) id -= step - 1;  // an odd share's last photon: one id
      continue;
    }
    add_photon(e, {o, -1.0 * sun, {power[0], power[1], power[2]}, id, 0}, across(q), l, -1);
    if (pair) {
      add_photon(e, {reflect_point(*plane, o), -1.0 * sun, {power[0], power[1], power[2]}, id + 1, 0},
                 across(reflect_point(*plane, q)), l, static_cast<int32_t>(e->live.size() - 1));
    } else {
      id -= step - 1;
    }
  }
}

// A point light's share of n photons, uniform over directions; pairs as emit_sun's.
void emit_point(const RenderScene& s, const LightDesc& light, size_t l, uint64_t n, uint64_t seed,
                const MirrorPlane* plane, uint64_t& id, Emission* e) {
  const uint64_t step = plane ? 2 : 1;
  double power[3];
  for (int c = 0; c < 3; ++c) power[c] = 4 * M_PI * light.power[c] / static_cast<double>(n);
  const Vec3 o = light.position;
  for (uint64_t i = 0; i < n; i += step, id += step) {
    const double z = 1 - 2 * photon_draw(seed, id, 0), phi = 2 * M_PI * photon_draw(seed, id, 1);
    const double r = std::sqrt(std::max(0.0, 1 - z * z));
    Vec3 d{r * std::cos(phi), r * std::sin(phi), z};
    const bool pair = plane && i + 1 < n;
    if (pair && dot(vec3(plane->normal), d) < 0) d = reflect_vector(*plane, d);
    if (!pair) id -= step - 1;
    if (!inside(s, o)) continue;
    add_photon(e, {o, d, {power[0], power[1], power[2]}, id, 0}, d, l, -1);
    if (pair)
      add_photon(e, {o, reflect_vector(*plane, d), {power[0], power[1], power[2]}, id + 1, 0},
                 reflect_vector(*plane, d), l, static_cast<int32_t>(e->live.size() - 1));
  }
}

}  // namespace

Emission emit(const RenderScene& s, uint64_t count, uint64_t seed, double offset, const MirrorPlane* plane) {
  // Each light's flux (summed over the channels) and its share of the photons.
  const size_t lights = s.desc.lights.size();
  std::vector<Portal> portals(lights);
  std::vector<double> flux(lights, 0.0);
  double total = 0;
  for (size_t l = 0; l < lights; ++l) {
    const LightDesc& light = s.desc.lights[l];
    const double sum = light.power[0] + light.power[1] + light.power[2];
    if (light.kind == LightKind::Sun) {
      portals[l] = sun_portal(s, normalized(light.direction));
      flux[l] = sum * portals[l].area;
    } else {
      flux[l] = sum * 4 * M_PI;
    }
    total += flux[l];
  }

  Emission e;
  uint64_t id = 0;
  double running = 0;
  for (size_t l = 0; l < lights && total > 0; ++l) {
    // Cumulative rounding: the shares add up to `count` exactly.
    const uint64_t first = static_cast<uint64_t>(std::llround(static_cast<double>(count) * running / total));
    running += flux[l];
    const uint64_t last = l + 1 == lights ? count : static_cast<uint64_t>(std::llround(count * running / total));
    const uint64_t n = last - first;
    if (n == 0 || !(flux[l] > 0)) {
      id += n;
      continue;
    }
    const LightDesc& light = s.desc.lights[l];
    if (light.kind == LightKind::Sun)
      emit_sun(s, light, portals[l], l, n, seed, offset, plane, id, &e);
    else
      emit_point(s, light, l, n, seed, plane, id, &e);
  }
  return e;
}

// ---- symmetry ------------------------------------------------------------------------------

std::string medium_asymmetry(const arcus_field_desc_d& d, const MirrorPlane& plane) {
  const Vec3 n = vec3(plane.normal);
  const double tol = 1e-12;
  auto along = [&](const double* v) { return std::fabs(dot(vec3(v), n)) <= tol * length(vec3(v)); };
  auto on_plane = [&](const double* p) {
    return std::fabs(dot(vec3(p), n) - plane.offset) <= tol * std::max(1.0, length(vec3(p)));
  };
  switch (d.kind) {
    case ARCUS_KIND_CONSTANT: return "";
    case ARCUS_KIND_LINEAR:
    case ARCUS_KIND_LINEAR_N2: return along(d.vec) ? "" : "the medium's gradient is not parallel to the plane";
    case ARCUS_KIND_LUNEBURG:
    case ARCUS_KIND_FISHEYE: return on_plane(d.origin) ? "" : "the lens's centre does not lie in the plane";
    case ARCUS_KIND_ATMOSPHERE: {
      if (d.spherical) {
        const double centre[3] = {0, 0, 0};
        return on_plane(centre) ? "" : "the Earth's centre does not lie in the plane";
      }
      const double up[3] = {0, 1, 0};
      return along(up) ? "" : "the plane is not vertical (a flat atmosphere varies with y)";
    }
    default: return "a grid medium has no symmetry arcus can check";
  }
}

std::string photon_asymmetry(const RenderScene& s, MirrorPlane* plane) {
  std::string reasons;
  const char* axes = "xyz";
  for (int axis = 0; axis < 3; ++axis) {
    MirrorPlane m;
    for (int a = 0; a < 3; ++a) m.normal[a] = a == axis ? 1 : 0;
    m.offset = 0.5 * (s.lo[axis] + s.hi[axis]);
    const std::string why = plane_problem(s, m, scene_scale(s));
    if (why.empty()) {
      if (plane) *plane = m;
      return "";
    }
    reasons += std::string(reasons.empty() ? "" : "; ") + axes[axis] + " = " + std::to_string(m.offset) + ": " + why;
  }
  return "photons: symmetry needs a plane of symmetry of the medium, the lights and the suns' windows, and no mid-plane "
         "of the scene's bounds is one (" + reasons + ")";
}

}  // namespace arcus::render
