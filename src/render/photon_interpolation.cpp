#include "render/photon_interpolation.h"

#include <cmath>

namespace arcus::render {
namespace {

// A direction's two perpendiculars.
void across_basis(Vec3 n, Vec3* e1, Vec3* e2) { photon_basis(normalized(n), e1, e2); }

// Affine weights: w with Σ w = 1 and Σ w (key_i − key) = 0 in the plane across `axis`
// (least norm for n > 3); false when the neighbours are (nearly) collinear or the
// weights extrapolate far.
bool affine_weights(Vec3 key, Vec3 axis, const std::vector<Vec3>& keys, double radius, std::vector<double>* w) {
  Vec3 e1, e2;
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

}  // namespace

double sampling_radius(const RenderScene& s, uint32_t light, double deg) {
  const double t = deg * M_PI / 180;
  return s.desc.lights[light].kind == LightKind::Sun ? t * scene_scale(s) : 2 * std::sin(t / 2);
}

Undersampling choose_interpolated(const RenderScene& s, const Emission& e, const PhotonOptions& o) {
  const size_t n = e.live.size(), lights = s.desc.lights.size();
  const uint32_t need = std::max<uint32_t>(o.undersample_n, 1);
  Undersampling u;
  u.neighbours.resize(n);
  u.weights.resize(n);
  std::vector<SamplingGrid> grids(lights);
  std::vector<double> radii(lights);
  for (size_t l = 0; l < lights; ++l) {
    radii[l] = sampling_radius(s, static_cast<uint32_t>(l), o.undersample_deg);
    grids[l].h = radii[l];
    grids[l].flat = s.desc.lights[l].kind == LightKind::Sun;
  }
  std::vector<uint32_t> candidates, chosen;
  std::vector<Vec3> keys;
  for (size_t i = 0; i < n; ++i) {
    if (e.mirror_of[i] >= 0) continue;
    SamplingGrid& g = grids[e.light[i]];
    const double r = radii[e.light[i]];
    g.nearest(e.key, e.key[i], r, SIZE_MAX, &candidates);  // every stored one within t, nearest first
    bool interpolate_it = false;
    if (candidates.size() >= need) {
      // The n closest stored ones, if their weights reproduce this photon's coordinate
      // without extrapolating far; else the closest in each of n equal sectors around
      // it (which mostly surround it); else it is computed and stored.
      const Vec3 axis = s.desc.lights[e.light[i]].kind == LightKind::Sun ? Vec3{0, 0, 1} : e.key[i];
      auto fit = [&](const std::vector<uint32_t>& nb) {
        keys.clear();
        for (uint32_t k : nb) keys.push_back(e.key[k]);
        if (!affine_weights(e.key[i], axis, keys, r, &u.weights[i])) return false;
        u.neighbours[i] = nb;
        return true;
      };
      chosen.assign(candidates.begin(), candidates.begin() + need);
      interpolate_it = fit(chosen);
      if (!interpolate_it && need >= 3) {
        Vec3 e1, e2;
        across_basis(axis, &e1, &e2);
        std::vector<int64_t> best(need, -1);
        for (uint32_t k : candidates) {  // nearest first: the first in a sector is its nearest
          const Vec3 d = e.key[k] - e.key[i];
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
      u.interpolated.push_back(static_cast<uint32_t>(i));
    } else {
      u.computed.push_back(static_cast<uint32_t>(i));
      g.insert(e.key[i], static_cast<uint32_t>(i));
    }
  }
  return u;
}

// An interpolated photon's result from its neighbours' (slots of `t`), or false when
// they do not all hit one plane.
bool interpolate(const RenderScene& s, const TraceOutput& t, const std::vector<uint32_t>& nb,
                 const std::vector<double>& w, TraceOutput* out, size_t j) {
  const size_t first = nb[0];
  if (t.status[first] != ARCUS_STATUS_HIT) return false;
  Vec3 normal{0, 0, 0};
  // Coplanar: normals parallel, hits within 1e-5 of the scene's size of one plane (hits
  // lie on their triangles to the crossing tolerance, not to rounding).
  const double tol = 1e-5 * scene_scale(s);
  for (uint32_t k : nb) {
    if (t.status[k] != ARCUS_STATUS_HIT || t.object[k] != t.object[first] || t.hit_kind[k] != t.hit_kind[first])
      return false;
    if (t.hit_kind[k] == ARCUS_HIT_TRIANGLE) {
      const double* tri = &s.triangles.triangles[9 * static_cast<size_t>(s.slot_of[static_cast<size_t>(t.hit_index[k])])];
      const Vec3 nk = normalized(cross(vec3(tri + 3) - vec3(tri), vec3(tri + 6) - vec3(tri)));
      if (k == first) {
        normal = nk;
      } else if (length(cross(nk, normal)) > 1e-9 ||
                 std::fabs(dot(normal, vec3(&t.positions[3 * k]) - vec3(&t.positions[3 * first]))) > tol) {
        return false;
      }
    } else {
      const arcus_shape_d& sh = s.shapes[static_cast<size_t>(t.hit_index[k])];
      if (sh.kind == ARCUS_SHAPE_SPHERE || t.hit_index[k] != t.hit_index[first]) return false;  // a disc only
    }
  }
  Vec3 p{0, 0, 0}, d{0, 0, 0};
  double len = 0;
  for (size_t i = 0; i < nb.size(); ++i) {
    p = p + w[i] * vec3(&t.positions[3 * nb[i]]);
    d = d + w[i] * vec3(&t.directions[3 * nb[i]]);
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

}  // namespace arcus::render
