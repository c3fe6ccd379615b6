#include "render/photons.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

#include "common/philox.h"  // kernels/common/philox.h: the same generator on host and device
#include "core/error.h"
#include "render/trace.h"

namespace arcus::render {
namespace {

using Clock = std::chrono::steady_clock;

struct V3 {
  double x, y, z;
};
V3 operator-(V3 a, V3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
V3 operator+(V3 a, V3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
V3 operator*(double s, V3 a) { return {s * a.x, s * a.y, s * a.z}; }
double dot(V3 a, V3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
V3 cross(V3 a, V3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
double length(V3 a) { return std::sqrt(dot(a, a)); }
V3 normalized(V3 a) { return (1.0 / length(a)) * a; }
V3 v3(const double* p) { return {p[0], p[1], p[2]}; }
V3 v3(const Vec3& p) { return {p[0], p[1], p[2]}; }

constexpr uint64_t kMaxPhotons = uint64_t(1) << 26;  // the schema's limit ($.photons.count)
// Generations (trace() calls): diffuse bounces plus crossings of window primitives.
constexpr int kMaxGenerations = 2 * (kMaxPhotonBounces + 1);

// Photon `id`'s draws: 0..3 at emission, then 3 per generation (roulette, direction).
constexpr uint32_t kEmissionDraws = 4;
double draw(uint64_t seed, uint64_t id, uint32_t d) { return arcus_rng_uniform_double(seed, id, d); }
uint32_t generation_draw(int generation, uint32_t k) {
  return kEmissionDraws + 3u * static_cast<uint32_t>(generation) + k;
}

// An orthonormal pair perpendicular to the unit vector n.
void basis(V3 n, V3* t, V3* b) {
  *t = normalized(std::fabs(n.x) < 0.9 ? cross(n, V3{1, 0, 0}) : cross(n, V3{0, 1, 0}));
  *b = cross(n, *t);
}

// A photon in flight.
struct Live {
  V3 origin, direction;
  double power[3];
  uint64_t id;
  int bounces;
};

// The surface at a hit: the normal facing the arriving photon and the albedo (diffuse ×
// texture), as the renderer shades it (renderer.cpp: surface_at, albedo).
struct HitSurface {
  V3 normal;
  double albedo[3];
  bool window;
};

HitSurface surface_at(const RenderScene& s, int32_t object, int32_t kind, int32_t index, V3 p, V3 arriving) {
  const ObjectDesc& o = s.desc.objects[static_cast<size_t>(object)];
  const size_t material = static_cast<size_t>(o.material);
  const MaterialDesc& m = s.desc.materials[material];
  HitSurface out;
  out.window = m.name == kWindowMaterial;
  double u = 0, v = 0;
  bool has_uv = false;
  if (kind == ARCUS_HIT_TRIANGLE) {
    const double* t = &s.triangles.triangles[9 * static_cast<size_t>(s.slot_of[static_cast<size_t>(index)])];
    const V3 a = v3(t), e1 = v3(t + 3) - a, e2 = v3(t + 6) - a;
    out.normal = normalized(cross(e1, e2));
    const uint32_t mesh = s.triangles.geometry[static_cast<size_t>(index)];
    const auto& uvs = s.mesh_uvs[mesh];
    if (!uvs.empty() && s.textures[material].width > 0) {
      const V3 w = p - a;
      const double d00 = dot(e1, e1), d01 = dot(e1, e2), d11 = dot(e2, e2), d20 = dot(w, e1), d21 = dot(w, e2);
      const double den = d00 * d11 - d01 * d01;
      const double b1 = (d11 * d20 - d01 * d21) / den, b2 = (d00 * d21 - d01 * d20) / den, b0 = 1 - b1 - b2;
      const size_t local = static_cast<size_t>(index) - s.triangles.mesh_first[mesh];
      const double* c = &uvs[6 * local];
      u = b0 * c[0] + b1 * c[2] + b2 * c[4];
      v = b0 * c[1] + b1 * c[3] + b2 * c[5];
      has_uv = std::isfinite(u) && std::isfinite(v);
    }
  } else {
    const arcus_shape_d& sh = s.shapes[static_cast<size_t>(index)];
    const V3 c = v3(sh.center);
    if (sh.kind == ARCUS_SHAPE_SPHERE) {
      out.normal = normalized(p - c);
      u = 0.5 + std::atan2(out.normal.x, -out.normal.z) / (2 * M_PI);
      v = std::acos(std::clamp(out.normal.y, -1.0, 1.0)) / M_PI;
    } else {
      out.normal = v3(sh.normal);
      // The renderer's planar coordinates: its tangent is n × y (n × x near the poles).
      const V3 n = out.normal;
      const V3 t = normalized(std::fabs(n.y) < 0.9 ? cross(n, V3{0, 1, 0}) : cross(n, V3{1, 0, 0}));
      const V3 b = cross(n, t);
      u = dot(p - c, t);
      v = dot(p - c, b);
    }
    has_uv = true;
  }
  if (dot(out.normal, arriving) > 0) out.normal = -1.0 * out.normal;
  for (int c = 0; c < 3; ++c) out.albedo[c] = m.diffuse[c];
  const image::Image& tex = s.textures[material];
  if (tex.width > 0 && has_uv) {
    const double su = u * m.uv_scale[0], sv = v * m.uv_scale[1];
    const auto c = image::sample_bilinear(tex, su - std::floor(su), sv - std::floor(sv), true);
    for (int k = 0; k < 3; ++k) out.albedo[k] *= c[k];
  }
  return out;
}

// A sun's portal: triangles with their weight area·|n·s| (their area seen from the sun).
struct Portal {
  std::vector<V3> a, e1, e2, normal;  // corner, edges, unit normal facing the sun
  std::vector<double> cdf;            // running sum of the weights
  double area = 0;                    // A: the total
};

void add_triangle(Portal* portal, V3 a, V3 b, V3 c, V3 sun) {
  const V3 e1 = b - a, e2 = c - a, n2 = cross(e1, e2);
  const double len = length(n2);
  if (!(len > 0)) return;
  V3 n = (1.0 / len) * n2;
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
Portal sun_portal(const RenderScene& s, V3 sun) {
  Portal portal;
  for (size_t tri = 0; tri < s.triangles.triangle_count(); ++tri) {
    const int32_t object = s.mesh_object[s.triangles.geometry[tri]];
    const ObjectDesc& o = s.desc.objects[static_cast<size_t>(object)];
    if (s.desc.materials[static_cast<size_t>(o.material)].name != kWindowMaterial) continue;
    const double* t = &s.triangles.triangles[9 * static_cast<size_t>(s.slot_of[tri])];
    add_triangle(&portal, v3(t), v3(t + 3), v3(t + 6), sun);
  }
  if (!portal.cdf.empty()) return portal;
  const V3 lo = v3(s.lo.data()), hi = v3(s.hi.data());
  auto corner = [&](int i, int j, int k) { return V3{i ? hi.x : lo.x, j ? hi.y : lo.y, k ? hi.z : lo.z}; };
  const double comp[3] = {sun.x, sun.y, sun.z};
  for (int axis = 0; axis < 3; ++axis) {
    if (comp[axis] == 0) continue;
    const int side = comp[axis] > 0 ? 1 : 0;  // the face whose outward normal faces the sun
    V3 q[4];
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

bool inside(const RenderScene& s, V3 p) {
  const double c[3] = {p.x, p.y, p.z};
  for (int a = 0; a < 3; ++a)
    if (!(c[a] > s.lo[a] && c[a] < s.hi[a])) return false;
  return true;
}

}  // namespace

photon::Photons shoot_photon_list(arcus_context_t* ctx, RenderScene* scene, const arcus_advance_params& params,
                                  uint64_t count, uint64_t seed, PhotonStats* stats) {
  const auto start = Clock::now();
  require_pointer(ctx, "ctx");
  require_pointer(scene, "scene");
  require(count >= 1 && count <= kMaxPhotons, "photons: count = " + std::to_string(count) + " is outside 1.." +
                                                  std::to_string(kMaxPhotons) + " (2^26)");
  const RenderScene& s = *scene;
  const double scale = std::max({s.hi[0] - s.lo[0], s.hi[1] - s.lo[1], s.hi[2] - s.lo[2]});
  // Off a surface by a little more than the crossing tolerance (as the renderer's
  // shadow rays), so a photon does not find the surface it leaves again.
  const double offset = 1e-6 * scale + 1e-4;

  // Each light's flux (summed over the channels) and its share of the photons.
  const size_t lights = s.desc.lights.size();
  std::vector<Portal> portals(lights);
  std::vector<double> flux(lights, 0.0);
  double total = 0;
  for (size_t l = 0; l < lights; ++l) {
    const LightDesc& light = s.desc.lights[l];
    const double sum = light.power[0] + light.power[1] + light.power[2];
    if (light.kind == LightKind::Sun) {
      portals[l] = sun_portal(s, normalized(v3(light.direction)));
      flux[l] = sum * portals[l].area;
    } else {
      flux[l] = sum * 4 * M_PI;
    }
    total += flux[l];
  }

  std::vector<Live> live;
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
    double power[3];
    if (light.kind == LightKind::Sun) {
      const Portal& portal = portals[l];
      const V3 sun = normalized(v3(light.direction));
      for (int c = 0; c < 3; ++c) power[c] = light.power[c] * portal.area / static_cast<double>(n);
      for (uint64_t i = 0; i < n; ++i, ++id) {
        const double pick = draw(seed, id, 0) * portal.area;
        const size_t found = std::upper_bound(portal.cdf.begin(), portal.cdf.end(), pick) - portal.cdf.begin();
        const size_t t = std::min(found, portal.cdf.size() - 1);
        const double r1 = std::sqrt(draw(seed, id, 1)), r2 = draw(seed, id, 2);
        const V3 q = portal.a[t] + (r1 * (1 - r2)) * portal.e1[t] + (r1 * r2) * portal.e2[t];
        // Just past the portal, `offset` from its plane.
        const double cosine = std::max(dot(portal.normal[t], sun), 1e-3);
        const V3 o = q - (offset / cosine) * sun;
        if (!inside(s, o)) continue;  // the light misses the scene there
        live.push_back({o, -1.0 * sun, {power[0], power[1], power[2]}, id, 0});
      }
    } else {
      for (int c = 0; c < 3; ++c) power[c] = 4 * M_PI * light.power[c] / static_cast<double>(n);
      const V3 o = v3(light.position);
      for (uint64_t i = 0; i < n; ++i, ++id) {
        const double z = 1 - 2 * draw(seed, id, 0), phi = 2 * M_PI * draw(seed, id, 1);
        const double r = std::sqrt(std::max(0.0, 1 - z * z));
        if (!inside(s, o)) continue;
        live.push_back({o, {r * std::cos(phi), r * std::sin(phi), z}, {power[0], power[1], power[2]}, id, 0});
      }
    }
  }

  photon::Photons out;
  out.channels = 3;
  for (int generation = 0; generation < kMaxGenerations && !live.empty(); ++generation) {
    std::vector<double> origins(3 * live.size()), directions(3 * live.size());
    for (size_t k = 0; k < live.size(); ++k) {
      const Live& p = live[k];
      origins[3 * k] = p.origin.x;
      origins[3 * k + 1] = p.origin.y;
      origins[3 * k + 2] = p.origin.z;
      directions[3 * k] = p.direction.x;
      directions[3 * k + 1] = p.direction.y;
      directions[3 * k + 2] = p.direction.z;
    }
    TraceInput in;
    in.count = live.size();
    in.origins = origins.data();
    in.directions = directions.data();
    const TraceOutput t = trace(ctx, scene, params, in);
    std::vector<Live> next;
    for (size_t k = 0; k < live.size(); ++k) {
      if (t.status[k] != ARCUS_STATUS_HIT || t.object[k] < 0) continue;  // left, failed: gone
      const Live& p = live[k];
      const V3 hit = v3(&t.positions[3 * k]), d = normalized(v3(&t.directions[3 * k]));
      const HitSurface surf = surface_at(s, t.object[k], t.hit_kind[k], t.hit_index[k], hit, d);
      if (surf.window) {  // an opening: on through it, unchanged
        next.push_back({hit - offset * surf.normal, d, {p.power[0], p.power[1], p.power[2]}, p.id, p.bounces});
        continue;
      }
      out.positions.insert(out.positions.end(), {hit.x, hit.y, hit.z});
      out.directions.insert(out.directions.end(), {d.x, d.y, d.z});
      out.powers.insert(out.powers.end(), {p.power[0], p.power[1], p.power[2]});
      if (p.bounces >= kMaxPhotonBounces) continue;
      const double survive = std::min(1.0, (surf.albedo[0] + surf.albedo[1] + surf.albedo[2]) / 3);
      if (!(draw(seed, p.id, generation_draw(generation, 0)) < survive)) continue;  // absorbed
      // Cosine-weighted about the normal on the side the photon came from.
      const double phi = 2 * M_PI * draw(seed, p.id, generation_draw(generation, 1));
      const double r2 = draw(seed, p.id, generation_draw(generation, 2));
      const double sin_t = std::sqrt(r2), cos_t = std::sqrt(1 - r2);
      V3 tu, tv;
      basis(surf.normal, &tu, &tv);
      const V3 dir = (sin_t * std::cos(phi)) * tu + (sin_t * std::sin(phi)) * tv + cos_t * surf.normal;
      Live n{hit + offset * surf.normal, dir, {0, 0, 0}, p.id, p.bounces + 1};
      for (int c = 0; c < 3; ++c) n.power[c] = p.power[c] * surf.albedo[c] / survive;
      next.push_back(n);
    }
    live = std::move(next);
  }

  if (stats) {
    stats->shot = count;
    stats->stored = out.positions.size() / 3;
    stats->seconds = std::chrono::duration<double>(Clock::now() - start).count();
  }
  return out;
}

std::unique_ptr<photon::PhotonMap> shoot_photons(arcus_context_t* ctx, RenderScene* scene,
                                                 const arcus_advance_params& params, uint64_t count, uint64_t seed,
                                                 PhotonStats* stats) {
  const auto start = Clock::now();
  const photon::Photons photons = shoot_photon_list(ctx, scene, params, count, seed, stats);
  auto map = std::make_unique<photon::PhotonMap>(ctx, photons);
  if (stats) stats->seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return map;
}

std::vector<double> photon_irradiance(arcus_context_t* ctx, const photon::PhotonMap& map, const RenderScene& scene,
                                      const std::vector<double>& points, const std::vector<double>& normals) {
  require_pointer(ctx, "ctx");
  require(map.channels() == 3, "photons: the map holds " + std::to_string(map.channels()) + " channels, not RGB");
  photon::Query q;
  q.k = static_cast<int32_t>(std::clamp<uint32_t>(scene.desc.photons.estimate, 1, ARCUS_PHOTON_MAX_K));
  q.max_radius = scene.desc.photons.max_radius;
  q.mode = photon::Mode::surface;
  return photon::estimate(ctx, map, points, normals, q).values;
}

}  // namespace arcus::render
