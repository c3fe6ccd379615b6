#include "render/photons.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <unordered_map>

#include "common/philox.h"  // kernels/common/philox.h: the same generator on host and device
#include "core/error.h"
#include "render/surface.h"
#include "render/trace.h"

namespace arcus::render {
namespace {

using Clock = std::chrono::steady_clock;


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
// texture), as the renderer shades it (render/surface.h).
struct HitSurface {
  V3 normal;
  double albedo[3];
  bool window;
};

HitSurface surface_at(const RenderScene& s, int32_t object, int32_t kind, int32_t index, V3 p, V3 arriving) {
  const size_t material = static_cast<size_t>(s.desc.objects[static_cast<size_t>(object)].material);
  const Surface surface = render::surface_at(s, kind, index, p, arriving);
  const V3 a = albedo(s, material, surface);
  return {surface.normal, {a.x, a.y, a.z}, s.desc.materials[material].name == kWindowMaterial};
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

// ---- the techniques' helpers -----------------------------------------------------------

V3 reflect_point(const MirrorPlane& m, V3 p) {
  const V3 n = v3(m.normal);
  return p - (2 * (dot(n, p) - m.offset)) * n;
}
V3 reflect_vector(const MirrorPlane& m, V3 d) {
  const V3 n = v3(m.normal);
  return d - (2 * dot(n, d)) * n;
}

// A spatial hash of sampling coordinates (one per light), with cells of side h; `flat`
// when the coordinates lie in z = 0 (a sun's, across its beam).
struct Grid {
  double h = 1;
  bool flat = false;
  std::unordered_map<uint64_t, std::vector<uint32_t>> cells;
  static uint64_t mix(int64_t i, int64_t j, int64_t k) {
    uint64_t x = static_cast<uint64_t>(i) * 0x9E3779B97F4A7C15ull;
    x ^= static_cast<uint64_t>(j) * 0xC2B2AE3D27D4EB4Full + (x << 6) + (x >> 2);
    x ^= static_cast<uint64_t>(k) * 0x165667B19E3779F9ull + (x << 6) + (x >> 2);
    return x;
  }
  int64_t cell(double c) const { return static_cast<int64_t>(std::floor(c / h)); }
  void insert(V3 p, uint32_t index) { cells[mix(cell(p.x), cell(p.y), flat ? 0 : cell(p.z))].push_back(index); }
  // Calls f(index) for every point in the cells at Chebyshev distance k from p's (hash
  // collisions may add others: callers check the distance).
  template <class F>
  void shell(V3 p, int64_t k, F&& f) const {
    const int64_t i = cell(p.x), j = cell(p.y), l = flat ? 0 : cell(p.z), kz = flat ? 0 : k;
    for (int64_t a = -k; a <= k; ++a)
      for (int64_t b = -k; b <= k; ++b)
        for (int64_t c = -kz; c <= kz; ++c) {
          if (std::max({std::llabs(a), std::llabs(b), std::llabs(c)}) != k) continue;
          const auto it = cells.find(mix(i + a, j + b, l + c));
          if (it == cells.end()) continue;
          for (uint32_t index : it->second) f(index);
        }
  }
  // The (up to) n stored points nearest p within r, nearest first (ties: lower index).
  // Shell by shell: after shell k every point within k·h has been seen.
  void nearest(const std::vector<V3>& keys, V3 p, double r, size_t n, std::vector<uint32_t>* out) const {
    thread_local std::vector<std::pair<double, uint32_t>> found;
    found.clear();
    const int64_t last = static_cast<int64_t>(std::ceil(r / h));
    for (int64_t k = 0; k <= last; ++k) {
      shell(p, k, [&](uint32_t index) {
        const double d = length(keys[index] - p);
        if (d <= r) found.push_back({d, index});
      });
      size_t sure = 0;
      for (const auto& f : found) sure += f.first <= k * h;
      if (sure >= n) break;
    }
    const size_t m = std::min(n, found.size());
    std::partial_sort(found.begin(), found.begin() + m, found.end());
    out->clear();
    for (size_t k = 0; k < m; ++k) out->push_back(found[k].second);
  }
};

// The step a ray's trace ended on: the hit's, or the last for a ray that left (the
// renderer's end_step); -1 for none.
int32_t end_step(const TraceOutput& t, size_t k) {
  if (t.status[k] == ARCUS_STATUS_HIT) return t.hit_step[k];
  if (t.status[k] == ARCUS_STATUS_LEFT_BOX || t.status[k] == ARCUS_STATUS_DONE)
    return static_cast<int32_t>(std::min<uint64_t>(t.steps[k], INT32_MAX));
  return -1;
}

// A first generation's results, one entry per photon (the trace outputs' layout).
TraceOutput empty_results(size_t n) {
  TraceOutput t;
  t.positions.assign(3 * n, NAN);
  t.directions.assign(3 * n, 0);
  t.lengths.assign(n, 0);
  t.steps.assign(n, 0);
  t.status.assign(n, ARCUS_STATUS_FAILED);
  t.object.assign(n, -1);
  t.primitive.assign(n, -1);
  t.hit_kind.assign(n, ARCUS_HIT_NONE);
  t.hit_index.assign(n, -1);
  t.hit_step.assign(n, -1);
  t.tests.assign(n, 0);
  return t;
}

// The photons as they leave the lights, with what the techniques need of each.
struct Emission {
  std::vector<Live> live;
  std::vector<V3> key;              // the sampling coordinate (photons.h)
  std::vector<uint32_t> light;      // the light's index
  std::vector<int32_t> mirror_of;   // SYMMETRY: the photon this one mirrors (its index), -1
};

}  // namespace

// ---- symmetry ------------------------------------------------------------------------------

std::string medium_asymmetry(const arcus_field_desc_d& d, const MirrorPlane& plane) {
  const V3 n = v3(plane.normal);
  const double tol = 1e-12;
  auto along = [&](const double* v) { return std::fabs(dot(v3(v), n)) <= tol * length(v3(v)); };
  auto on_plane = [&](const double* p) {
    return std::fabs(dot(v3(p), n) - plane.offset) <= tol * std::max(1.0, length(v3(p)));
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

namespace {

// Whether p lies on one of the portal's triangles (within tol of its plane and inside).
bool on_portal(const Portal& portal, V3 p, double tol) {
  for (size_t t = 0; t < portal.a.size(); ++t) {
    const V3 w = p - portal.a[t];
    if (std::fabs(dot(w, portal.normal[t])) > tol) continue;
    const V3 e1 = portal.e1[t], e2 = portal.e2[t];
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
  const V3 n = v3(plane.normal);
  for (size_t l = 0; l < s.desc.lights.size(); ++l) {
    const LightDesc& light = s.desc.lights[l];
    const std::string name = "light " + std::to_string(l);
    if (light.kind == LightKind::Point) {
      if (std::fabs(dot(v3(light.position), n) - plane.offset) > 1e-12 * std::max(1.0, length(v3(light.position))))
        return name + " (a point light) does not lie in the plane";
      continue;
    }
    const V3 sun = normalized(v3(light.direction));
    if (std::fabs(dot(sun, n)) > 1e-12) return name + " (a sun) does not shine parallel to the plane";
    const Portal portal = sun_portal(s, sun);
    const double tol = 1e-9 * scale;
    for (size_t t = 0; t < portal.a.size(); ++t) {
      const V3 a = portal.a[t], b = a + portal.e1[t], c = a + portal.e2[t];
      for (V3 p : {a, b, c, 0.5 * (a + b), 0.5 * (b + c), 0.5 * (a + c), (1.0 / 3) * (a + b + c)})
        if (!on_portal(portal, reflect_point(plane, p), tol))
          return name + "'s portal (its window) is not symmetric about the plane";
    }
  }
  return "";
}

double scene_scale(const RenderScene& s) {
  return std::max({s.hi[0] - s.lo[0], s.hi[1] - s.lo[1], s.hi[2] - s.lo[2]});
}

}  // namespace

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

// ---- the cache -----------------------------------------------------------------------------

struct PhotonCache::Data {
  // What the first generation depends on.
  struct Key {
    const RenderScene* scene = nullptr;
    uint64_t count = 0, seed = 0;
    uint32_t techniques = 0;  // SYMMETRY | UNDERSAMPLE
    std::vector<double> numbers;  // the integrator, the lights, t and n
    bool operator==(const Key& o) const {
      return scene == o.scene && count == o.count && seed == o.seed && techniques == o.techniques &&
             numbers == o.numbers;
    }
  };
  Key key;
  bool has_paths = false;   // PATH_CACHE: the first generation below
  std::vector<Live> live;
  TraceOutput results;
  std::vector<int32_t> how;
  std::vector<int32_t> previous_end;  // SMART_STEP: per photon of the last frame's first generation
};

PhotonCache::PhotonCache() : data(std::make_unique<Data>()) {}
PhotonCache::~PhotonCache() = default;
size_t PhotonCache::bytes() const {
  if (!data) return 0;
  const Data& d = *data;
  const TraceOutput& t = d.results;
  return d.live.size() * sizeof(Live) + d.how.size() * 4 + d.previous_end.size() * 4 +
         (t.positions.size() + t.directions.size() + t.lengths.size()) * 8 + t.steps.size() * 8 +
         (t.status.size() + t.object.size() + t.primitive.size() + t.hit_kind.size() + t.hit_index.size() +
          t.hit_step.size() + t.tests.size()) * 4;
}

namespace {

PhotonCache::Data::Key cache_key(const RenderScene* s, const arcus_advance_params& p, uint64_t count, uint64_t seed,
                                 const PhotonOptions& o) {
  PhotonCache::Data::Key k;
  k.scene = s;
  k.count = count;
  k.seed = seed;
  k.techniques = o.techniques & (ARCUS_TECHNIQUE_SYMMETRY | ARCUS_TECHNIQUE_UNDERSAMPLE);
  k.numbers = {double(p.method), double(p.precision), p.length, p.step, p.rtol, p.atol, p.min_step, p.max_step,
               double(p.max_rejections), double(p.max_steps), o.undersample_deg, double(o.undersample_n)};
  for (const LightDesc& l : s->desc.lights) {
    k.numbers.push_back(l.kind == LightKind::Sun ? 0 : 1);
    for (int a = 0; a < 3; ++a) k.numbers.insert(k.numbers.end(), {l.direction[a], l.position[a], l.power[a]});
  }
  return k;
}

// ---- emission ------------------------------------------------------------------------------

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
      portals[l] = sun_portal(s, normalized(v3(light.direction)));
      flux[l] = sum * portals[l].area;
    } else {
      flux[l] = sum * 4 * M_PI;
    }
    total += flux[l];
  }

  Emission e;
  auto add = [&](const Live& p, V3 key, size_t l, int32_t mirror_of) {
    e.live.push_back(p);
    e.key.push_back(key);
    e.light.push_back(static_cast<uint32_t>(l));
    e.mirror_of.push_back(mirror_of);
  };
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
    // SYMMETRY: photons in pairs, the second the first's mirror image (an odd share's
    // last photon alone).
    const uint64_t step = plane ? 2 : 1;
    if (light.kind == LightKind::Sun) {
      const Portal& portal = portals[l];
      const V3 sun = normalized(v3(light.direction));
      // The sampling coordinate: the start point across the beam (z = 0).
      V3 b1, b2;
      basis(sun, &b1, &b2);
      auto across = [&](V3 q) { return V3{dot(q, b1), dot(q, b2), 0}; };
      for (int c = 0; c < 3; ++c) power[c] = light.power[c] * portal.area / static_cast<double>(n);
      for (uint64_t i = 0; i < n; i += step, id += step) {
        const double pick = draw(seed, id, 0) * portal.area;
        const size_t found = std::upper_bound(portal.cdf.begin(), portal.cdf.end(), pick) - portal.cdf.begin();
        const size_t t = std::min(found, portal.cdf.size() - 1);
        const double r1 = std::sqrt(draw(seed, id, 1)), r2 = draw(seed, id, 2);
        V3 q = portal.a[t] + (r1 * (1 - r2)) * portal.e1[t] + (r1 * r2) * portal.e2[t];
        // Just past the portal, `offset` from its plane.
        const double cosine = std::max(dot(portal.normal[t], sun), 1e-3);
        V3 o = q - (offset / cosine) * sun;
        const bool pair = plane && i + 1 < n;
        if (pair && dot(v3(plane->normal), q) < plane->offset) {  // folded onto the positive side
          q = reflect_point(*plane, q);
          o = reflect_point(*plane, o);
        }
        if (!inside(s, o)) {  // the light misses the scene there
          if (!pair) id -= step - 1;  // an odd share's last photon: one id
          continue;
        }
        add({o, -1.0 * sun, {power[0], power[1], power[2]}, id, 0}, across(q), l, -1);
        if (pair) {
          add({reflect_point(*plane, o), -1.0 * sun, {power[0], power[1], power[2]}, id + 1, 0},
              across(reflect_point(*plane, q)), l, static_cast<int32_t>(e.live.size() - 1));
        } else {
          id -= step - 1;
        }
      }
    } else {
      for (int c = 0; c < 3; ++c) power[c] = 4 * M_PI * light.power[c] / static_cast<double>(n);
      const V3 o = v3(light.position);
      for (uint64_t i = 0; i < n; i += step, id += step) {
        const double z = 1 - 2 * draw(seed, id, 0), phi = 2 * M_PI * draw(seed, id, 1);
        const double r = std::sqrt(std::max(0.0, 1 - z * z));
        V3 d{r * std::cos(phi), r * std::sin(phi), z};
        const bool pair = plane && i + 1 < n;
        if (pair && dot(v3(plane->normal), d) < 0) d = reflect_vector(*plane, d);
        if (!pair) id -= step - 1;
        if (!inside(s, o)) continue;
        add({o, d, {power[0], power[1], power[2]}, id, 0}, d, l, -1);
        if (pair)
          add({o, reflect_vector(*plane, d), {power[0], power[1], power[2]}, id + 1, 0}, reflect_vector(*plane, d), l,
              static_cast<int32_t>(e.live.size() - 1));
      }
    }
  }
  return e;
}

// ---- the first generation ------------------------------------------------------------------

struct Batch {
  std::vector<double> origins, directions;
  void add(const Live& p) {
    origins.insert(origins.end(), {p.origin.x, p.origin.y, p.origin.z});
    directions.insert(directions.end(), {p.direction.x, p.direction.y, p.direction.z});
  }
  TraceInput input(const int32_t* predictions) const {
    TraceInput in;
    in.count = origins.size() / 3;
    in.origins = origins.data();
    in.directions = directions.data();
    in.predictions = predictions;
    return in;
  }
};

void count_trace(const TraceOutput& t, bool integrated, PhotonStats* st) {
  for (size_t k = 0; k < t.status.size(); ++k) {
    st->tests += static_cast<uint64_t>(std::max(t.tests[k], 0));
    if (integrated) st->steps += t.steps[k];
  }
  if (integrated) st->traced += t.status.size();
}

// A unit vector's two perpendiculars.
void across_basis(V3 n, V3* e1, V3* e2) { basis(normalized(n), e1, e2); }

// Affine weights: w with Σ w = 1 and Σ w (key_i − key) = 0 in the plane across `axis`
// (least norm for n > 3); false when the neighbours are (nearly) collinear or the
// weights extrapolate far.
bool affine_weights(V3 key, V3 axis, const std::vector<V3>& keys, double radius, std::vector<double>* w) {
  V3 e1, e2;
  across_basis(axis, &e1, &e2);
  const size_t n = keys.size();
  w->assign(n, 0);
  if (n == 1) {
    (*w)[0] = 1;
    return true;
  }
  // Coordinates relative to the neighbours' own spread (scale-free conditioning).
  double spread = 0;
  for (size_t i = 0; i < n; ++i) spread = std::max(spread, length(keys[i] - key));
  if (!(spread > 0) || spread > radius) return false;
  std::vector<double> u(n), v(n);
  for (size_t i = 0; i < n; ++i) {
    u[i] = dot(keys[i] - key, e1) / spread;
    v[i] = dot(keys[i] - key, e2) / spread;
  }
  // M = A Aᵀ for A = [1; u; v] (3 × n); w = Aᵀ M⁻¹ (1, 0, 0).
  double m[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
  for (size_t i = 0; i < n; ++i) {
    const double r[3] = {1, u[i], v[i]};
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) m[a][b] += r[a] * r[b];
  }
  const double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                     m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                     m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  if (!(std::fabs(det) > 1e-6)) return false;
  // The first column of M⁻¹.
  const double c0 = (m[1][1] * m[2][2] - m[1][2] * m[2][1]) / det;
  const double c1 = -(m[1][0] * m[2][2] - m[1][2] * m[2][0]) / det;
  const double c2 = (m[1][0] * m[2][1] - m[1][1] * m[2][0]) / det;
  for (size_t i = 0; i < n; ++i) {
    (*w)[i] = c0 + u[i] * c1 + v[i] * c2;
    if (!(std::fabs((*w)[i]) <= 3)) return false;
  }
  return true;
}

// An interpolated photon's result from its neighbours' (slots of `t`), or false when
// they do not all hit one plane.
bool interpolate(const RenderScene& s, const TraceOutput& t, const std::vector<uint32_t>& nb,
                 const std::vector<double>& w, TraceOutput* out, size_t j) {
  const size_t first = nb[0];
  if (t.status[first] != ARCUS_STATUS_HIT) return false;
  V3 normal{0, 0, 0};
  // Coplanar: normals parallel, hits within 1e-5 of the scene's size of one plane (hits
  // lie on their triangles to the crossing tolerance, not to rounding).
  const double tol = 1e-5 * scene_scale(s);
  for (uint32_t k : nb) {
    if (t.status[k] != ARCUS_STATUS_HIT || t.object[k] != t.object[first] || t.hit_kind[k] != t.hit_kind[first])
      return false;
    if (t.hit_kind[k] == ARCUS_HIT_TRIANGLE) {
      const double* tri = &s.triangles.triangles[9 * static_cast<size_t>(s.slot_of[static_cast<size_t>(t.hit_index[k])])];
      const V3 nk = normalized(cross(v3(tri + 3) - v3(tri), v3(tri + 6) - v3(tri)));
      if (k == first) {
        normal = nk;
      } else if (length(cross(nk, normal)) > 1e-9 ||
                 std::fabs(dot(normal, v3(&t.positions[3 * k]) - v3(&t.positions[3 * first]))) > tol) {
        return false;
      }
    } else {
      const arcus_shape_d& sh = s.shapes[static_cast<size_t>(t.hit_index[k])];
      if (sh.kind == ARCUS_SHAPE_SPHERE || t.hit_index[k] != t.hit_index[first]) return false;  // a disc only
    }
  }
  V3 p{0, 0, 0}, d{0, 0, 0};
  double len = 0;
  for (size_t i = 0; i < nb.size(); ++i) {
    p = p + w[i] * v3(&t.positions[3 * nb[i]]);
    d = d + w[i] * v3(&t.directions[3 * nb[i]]);
    len += w[i] * t.lengths[nb[i]];
  }
  if (!(length(d) > 0)) return false;
  d = normalized(d);
  out->copy_ray(j, t, first);  // the nearest's surface
  for (int a = 0; a < 3; ++a) {
    out->positions[3 * j + a] = (&p.x)[a];
    out->directions[3 * j + a] = (&d.x)[a];
  }
  out->lengths[j] = len;
  out->steps[j] = 0;
  out->tests[j] = 0;
  return true;
}

// The first generation's results (every photon of e), with the techniques of `o`.
TraceOutput first_results(arcus_context_t* ctx, RenderScene* scene, const arcus_advance_params& params,
                          const Emission& e, const PhotonOptions& o, const MirrorPlane* plane,
                          const std::vector<int32_t>* previous, std::vector<int32_t>* how, PhotonStats* st) {
  const RenderScene& s = *scene;
  const size_t n = e.live.size();
  TraceOutput out = empty_results(n);
  how->assign(n, kFirstTraced);
  const bool smart = o.techniques & ARCUS_TECHNIQUE_SMART_STEP;
  const bool under = o.techniques & ARCUS_TECHNIQUE_UNDERSAMPLE;
  const double D = scene_scale(s);
  // An angle as a distance in each light's sampling coordinate (photons.h).
  auto radius = [&](uint32_t light, double deg) {
    const double t = deg * M_PI / 180;
    return s.desc.lights[light].kind == LightKind::Sun ? t * D : 2 * std::sin(t / 2);
  };
  const size_t lights = s.desc.lights.size();
  std::vector<int32_t> partner(n, -1);
  for (size_t i = 0; i < n; ++i)
    if (e.mirror_of[i] >= 0) partner[static_cast<size_t>(e.mirror_of[i])] = static_cast<int32_t>(i);

  // Undersampling: which photons (not mirrors) are computed, which interpolated.
  std::vector<uint32_t> computed;
  std::vector<uint32_t> interpolated;
  std::vector<std::vector<uint32_t>> neighbours(under ? n : 0);
  std::vector<std::vector<double>> weights(under ? n : 0);
  const uint32_t need = std::max<uint32_t>(o.undersample_n, 1);
  if (under) {
    std::vector<Grid> grids(lights);
    std::vector<double> radii(lights);
    for (size_t l = 0; l < lights; ++l) {
      radii[l] = radius(static_cast<uint32_t>(l), o.undersample_deg);
      grids[l].h = radii[l];
      grids[l].flat = s.desc.lights[l].kind == LightKind::Sun;
    }
    std::vector<uint32_t> candidates, chosen;
    std::vector<V3> keys;
    for (size_t i = 0; i < n; ++i) {
      if (e.mirror_of[i] >= 0) continue;
      Grid& g = grids[e.light[i]];
      const double r = radii[e.light[i]];
      g.nearest(e.key, e.key[i], r, SIZE_MAX, &candidates);  // every stored one within t, nearest first
      bool interpolate_it = false;
      if (candidates.size() >= need) {
        // The n closest stored ones, if their weights reproduce this photon's coordinate
        // without extrapolating far; else the closest in each of n equal sectors around
        // it (which mostly surround it); else it is computed and stored.
        const V3 axis = s.desc.lights[e.light[i]].kind == LightKind::Sun ? V3{0, 0, 1} : e.key[i];
        auto fit = [&](const std::vector<uint32_t>& nb) {
          keys.clear();
          for (uint32_t k : nb) keys.push_back(e.key[k]);
          if (!affine_weights(e.key[i], axis, keys, r, &weights[i])) return false;
          neighbours[i] = nb;
          return true;
        };
        chosen.assign(candidates.begin(), candidates.begin() + need);
        interpolate_it = fit(chosen);
        if (!interpolate_it && need >= 3) {
          V3 e1, e2;
          across_basis(axis, &e1, &e2);
          std::vector<int64_t> best(need, -1);
          for (uint32_t k : candidates) {  // nearest first: the first in a sector is its nearest
            const V3 d = e.key[k] - e.key[i];
            double angle = std::atan2(dot(d, e2), dot(d, e1));
            if (angle < 0) angle += 2 * M_PI;
            const size_t sector = std::min<size_t>(need - 1, static_cast<size_t>(angle / (2 * M_PI) * need));
            if (best[sector] < 0) best[sector] = k;
          }
          chosen.clear();
          for (int64_t k : best)
            if (k >= 0) chosen.push_back(static_cast<uint32_t>(k));
          interpolate_it = chosen.size() == need && fit(chosen);
        }
      }
      if (interpolate_it) {
        interpolated.push_back(static_cast<uint32_t>(i));
      } else {
        computed.push_back(static_cast<uint32_t>(i));
        g.insert(e.key[i], static_cast<uint32_t>(i));
      }
    }
  } else {
    for (size_t i = 0; i < n; ++i)
      if (e.mirror_of[i] < 0) computed.push_back(static_cast<uint32_t>(i));
  }

  // Smart step selection: temporal predictions (the last frame's, photon by photon), or
  // a coarse set traced first and the rest predicted from its nearest within t.
  const bool temporal = smart && previous && previous->size() == n;
  std::vector<uint32_t> coarse, rest;
  std::vector<Grid> coarse_grids(lights);
  std::vector<double> coarse_r(lights);
  std::vector<uint32_t> found;
  if (smart && !temporal) {
    for (size_t l = 0; l < lights; ++l) {
      coarse_r[l] = radius(static_cast<uint32_t>(l), o.smart_step_deg);
      coarse_grids[l].h = coarse_r[l] / 2;
      coarse_grids[l].flat = s.desc.lights[l].kind == LightKind::Sun;
    }
    for (uint32_t i : computed) {
      Grid& g = coarse_grids[e.light[i]];
      g.nearest(e.key, e.key[i], coarse_r[e.light[i]], 1, &found);
      if (!found.empty()) {
        rest.push_back(i);
      } else {
        coarse.push_back(i);
        g.insert(e.key[i], i);
      }
    }
  } else {
    coarse = computed;  // one pass
  }
  auto predict = [&](uint32_t i) -> int32_t {
    if (temporal) return (*previous)[i];
    if (!smart) return -1;
    std::vector<uint32_t> nearest;
    coarse_grids[e.light[i]].nearest(e.key, e.key[i], coarse_r[e.light[i]], 1, &nearest);
    return nearest.empty() ? -1 : end_step(out, nearest[0]);
  };

  // The computed photons: traced; with SYMMETRY traced with their paths recorded
  // (record_paths) and their mirrors walked along those mirrored, in chunks that bound
  // the recorded paths' memory.  A mirror whose walk is unresolved (the mirrored path
  // ended on a hit, the mirror image hits nothing there: the geometry is not
  // symmetric) is traced after all.
  std::vector<uint32_t> fallback;
  std::vector<int32_t> fallback_pred;
  constexpr size_t kChunk = size_t(1) << 15;
  uint32_t hint = 64;
  for (const auto* pass : {&coarse, &rest}) {
    const size_t chunk = plane ? kChunk : std::max<size_t>(pass->size(), 1);
    for (size_t c0 = 0; c0 < pass->size(); c0 += chunk) {
      const size_t c1 = std::min(pass->size(), c0 + chunk);
      Batch b;
      std::vector<int32_t> pred;
      for (size_t k = c0; k < c1; ++k) {
        b.add(e.live[(*pass)[k]]);
        pred.push_back(predict((*pass)[k]));
      }
      DevicePaths paths;
      const TraceOutput t = plane ? record_paths(ctx, scene, params, b.input(smart ? pred.data() : nullptr), hint, &paths)
                                  : trace(ctx, scene, params, b.input(smart ? pred.data() : nullptr));
      count_trace(t, true, st);
      for (size_t k = c0; k < c1; ++k) out.copy_ray((*pass)[k], t, k - c0);
      if (!plane) continue;
      hint = std::max<uint32_t>(hint, paths.capacity);
      std::vector<WalkRay> rays;
      std::vector<uint32_t> mirrors;
      pred.clear();
      for (size_t k = c0; k < c1; ++k) {
        const int32_t m = partner[(*pass)[k]];
        if (m < 0) continue;
        WalkRay w;
        w.a = static_cast<int32_t>(k - c0);
        w.mirror = 1;
        rays.push_back(w);
        mirrors.push_back(static_cast<uint32_t>(m));
        pred.push_back(temporal ? (*previous)[static_cast<size_t>(m)] : end_step(t, k - c0));  // the same steps
      }
      if (rays.empty()) continue;
      const TraceOutput mt = walk(ctx, scene, params, paths, rays, *plane, smart ? pred.data() : nullptr);
      count_trace(mt, false, st);
      for (size_t k = 0; k < rays.size(); ++k) {
        if (mt.status[k] == ARCUS_STATUS_UNRESOLVED) {
          fallback.push_back(mirrors[k]);
          fallback_pred.push_back(-1);
          continue;
        }
        out.copy_ray(mirrors[k], mt, k);
        (*how)[mirrors[k]] = kFirstMirrored;
        ++st->mirrored;
      }
    }
  }

  // The interpolated photons (and their mirrors, from their neighbours' mirrors); those
  // whose neighbours do not share a plane are traced after all.
  for (uint32_t i : interpolated) {
    std::vector<std::pair<uint32_t, std::vector<uint32_t>>> pending = {{i, neighbours[i]}};
    if (partner[i] >= 0) {
      std::vector<uint32_t> mirrored;
      for (uint32_t k : neighbours[i]) mirrored.push_back(static_cast<uint32_t>(partner[k]));
      pending.push_back({static_cast<uint32_t>(partner[i]), mirrored});
    }
    for (const auto& [j, nb] : pending) {
      if (interpolate(s, out, nb, weights[i], &out, j)) {
        (*how)[j] = kFirstInterpolated;
        ++st->interpolated;
      } else {
        fallback.push_back(j);
        fallback_pred.push_back(temporal ? (*previous)[j] : end_step(out, nb[0]));
      }
    }
  }
  if (!fallback.empty()) {
    Batch b;
    for (uint32_t i : fallback) b.add(e.live[i]);
    const TraceOutput t = trace(ctx, scene, params, b.input(smart ? fallback_pred.data() : nullptr));
    count_trace(t, true, st);
    for (size_t k = 0; k < fallback.size(); ++k) {
      out.copy_ray(fallback[k], t, k);
      (*how)[fallback[k]] = kFirstFallback;
    }
  }
  if (o.measure_interpolation && st->interpolated > 0) {
    Batch b;
    std::vector<uint32_t> which;
    for (size_t i = 0; i < n; ++i)
      if ((*how)[i] == kFirstInterpolated) {
        b.add(e.live[i]);
        which.push_back(static_cast<uint32_t>(i));
      }
    const TraceOutput t = trace(ctx, scene, params, b.input(nullptr));
    double sum = 0;
    for (size_t k = 0; k < which.size(); ++k) {
      if (t.status[k] != ARCUS_STATUS_HIT) continue;
      const double err = length(v3(&t.positions[3 * k]) - v3(&out.positions[3 * which[k]]));
      sum += err;
      st->interpolation_error_max = std::max(st->interpolation_error_max, err);
      ++st->interpolation_measured;
    }
    if (st->interpolation_measured) st->interpolation_error_mean = sum / st->interpolation_measured;
  }
  return out;
}

// The first generation: from the cache, or emitted and computed (and cached).
void first_generation_of(arcus_context_t* ctx, RenderScene* scene, const arcus_advance_params& params,
                         uint64_t count, uint64_t seed, double offset, const PhotonOptions& o,
                         std::vector<Live>* live, TraceOutput* results, std::vector<int32_t>* how, PhotonStats* st) {
  PhotonCache::Data* cache = o.cache ? o.cache->data.get() : nullptr;
  const auto key = cache_key(scene, params, count, seed, o);
  const bool same = cache && cache->key == key;
  if (cache && !same) {  // another configuration: nothing of the last frame applies
    *cache = PhotonCache::Data{};
    cache->key = key;
  }
  if ((o.techniques & ARCUS_TECHNIQUE_PATH_CACHE) && same && cache->has_paths) {
    *live = cache->live;
    *results = cache->results;
    how->assign(live->size(), kFirstCached);
    st->cached = live->size();
    return;
  }
  MirrorPlane plane;
  const bool symmetric = o.techniques & ARCUS_TECHNIQUE_SYMMETRY;
  if (symmetric) {
    const std::string why = photon_asymmetry(*scene, &plane);
    if (!why.empty()) fail(ARCUS_ERROR_UNSUPPORTED, why);
  }
  Emission e = emit(*scene, count, seed, offset, symmetric ? &plane : nullptr);
  *results = first_results(ctx, scene, params, e, o, symmetric ? &plane : nullptr,
                           same && !cache->previous_end.empty() ? &cache->previous_end : nullptr, how, st);
  *live = std::move(e.live);
  if (cache) {
    cache->previous_end.clear();
    if (o.techniques & ARCUS_TECHNIQUE_SMART_STEP)
      for (size_t k = 0; k < live->size(); ++k) cache->previous_end.push_back(end_step(*results, k));
    cache->has_paths = o.techniques & ARCUS_TECHNIQUE_PATH_CACHE;
    if (cache->has_paths) {
      cache->live = *live;
      cache->results = *results;
    } else {
      cache->live.clear();
      cache->results = TraceOutput{};
    }
  }
}

double surface_offset(const RenderScene& s) {
  // Off a surface by a little more than the crossing tolerance (as the renderer's
  // shadow rays), so a photon does not find the surface it leaves again.
  return 1e-6 * scene_scale(s) + 1e-4;
}

void check_arguments(arcus_context_t* ctx, RenderScene* scene, uint64_t count) {
  require_pointer(ctx, "ctx");
  require_pointer(scene, "scene");
  require(count >= 1 && count <= kMaxPhotons, "photons: count = " + std::to_string(count) + " is outside 1.." +
                                                  std::to_string(kMaxPhotons) + " (2^26)");
}

}  // namespace

FirstGeneration first_generation(arcus_context_t* ctx, RenderScene* scene, const arcus_advance_params& params,
                                 uint64_t count, uint64_t seed, PhotonStats* stats, const PhotonOptions& options) {
  check_arguments(ctx, scene, count);
  PhotonStats local;
  PhotonStats* st = stats ? stats : &local;
  std::vector<Live> live;
  TraceOutput t;
  FirstGeneration out;
  first_generation_of(ctx, scene, params, count, seed, surface_offset(*scene), options, &live, &t, &out.how, st);
  for (size_t k = 0; k < live.size(); ++k) {
    const Live& p = live[k];
    out.origins.insert(out.origins.end(), {p.origin.x, p.origin.y, p.origin.z});
    out.directions.insert(out.directions.end(), {p.direction.x, p.direction.y, p.direction.z});
    out.ids.push_back(p.id);
    const bool hit = t.status[k] == ARCUS_STATUS_HIT;
    for (int a = 0; a < 3; ++a) out.hits.push_back(hit ? t.positions[3 * k + a] : NAN);
  }
  out.status = t.status;
  out.object = t.object;
  return out;
}

photon::Photons shoot_photon_list(arcus_context_t* ctx, RenderScene* scene, const arcus_advance_params& params,
                                  uint64_t count, uint64_t seed, PhotonStats* stats, const PhotonOptions& options) {
  const auto start = Clock::now();
  check_arguments(ctx, scene, count);
  const RenderScene& s = *scene;
  const double offset = surface_offset(s);
  PhotonStats st;

  std::vector<Live> live;
  TraceOutput first;
  std::vector<int32_t> how;
  first_generation_of(ctx, scene, params, count, seed, offset, options, &live, &first, &how, &st);

  photon::Photons out;
  out.channels = 3;
  for (int generation = 0; generation < kMaxGenerations && !live.empty(); ++generation) {
    TraceOutput traced;
    if (generation > 0) {
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
      traced = trace(ctx, scene, params, in);
      count_trace(traced, true, &st);
    }
    const TraceOutput& t = generation == 0 ? first : traced;
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

  st.shot = count;
  st.stored = out.positions.size() / 3;
  st.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  if (stats) *stats = st;
  return out;
}


std::unique_ptr<photon::PhotonMap> shoot_photons(arcus_context_t* ctx, RenderScene* scene,
                                                 const arcus_advance_params& params, uint64_t count, uint64_t seed,
                                                 PhotonStats* stats, const PhotonOptions& options) {
  const auto start = Clock::now();
  const photon::Photons photons = shoot_photon_list(ctx, scene, params, count, seed, stats, options);
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
