// An independent Monte Carlo photograph of a translucent box, written for the tests and
// sharing no code with arcus (sphere_mc.h is its sibling for a sphere; both take their
// optics from mc_common.h).
//
// An axis-aligned box of a homogeneous medium with index eta under a smooth dielectric
// boundary, lit by directional lights and seen by an orthographic camera from any
// direction.  Photons enter uniformly over the faces that face each light (a convex box
// shadows none of them), in proportion to their projected areas, pass the boundary with
// the exact Fresnel transmittance, fly exponential free paths, scatter isotropically (the
// reduced coefficients: σ_s′ with g = 0) with their weight times the albedo, and at the
// boundary are reflected back with the Fresnel probability (total internal reflection
// included) or leave.
//
// The camera is reached by next-event estimation at every scattering vertex x, through
// each face that faces it: on a flat face the inner ray that leaves along the view is one
// direction for every point (Snell backwards), so the exit point is where that ray from x
// meets the face, when it meets that face first.  The vertex's intensity (w/4π per sr) is
// carried along it with e^{−σ_t τ} and the Fresnel transmittance, and turned into the
// intensity outside by dω_in/dω_out = cos θ_out/(η² cos θ_in) (étendue on a flat face);
// over the pixel's area it is radiance.  Missed by design: paths that reach the camera
// after a further internal reflection, and the specular reflection of the lights.
//
// Units: lengths in mm, coefficients in mm⁻¹, a light's irradiance E per mm² of a surface
// facing it; the image is radiance in E per sr, top row first.
#ifndef ARCUS_TESTS_BOX_MC_H
#define ARCUS_TESTS_BOX_MC_H

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <thread>
#include <vector>

#include "mc_common.h"

namespace box_mc {

using namespace mc_common;

struct Medium {
  double sigma_a, sigma_s, eta;  // mm⁻¹, mm⁻¹ (isotropic: the reduced σ_s′), index
};
struct Light {
  V3 toward;          // unit, toward the light
  double irradiance;  // on a surface facing it
};
// An orthographic camera as arcus's: looking along −toward at `centre`, `up` the image's
// up (made perpendicular), a square frame `frame_mm` across in `side` pixels.
struct Camera {
  V3 toward, up, centre;
  double frame_mm;
  int side;
};

class Tracer {
 public:
  Tracer(const Medium& m, const double lo[3], const double hi[3], const Camera& c)
      : m_(m), sigma_t_(m.sigma_a + m.sigma_s), camera_(c) {
    for (int a = 0; a < 3; ++a) lo_[a] = lo[a], hi_[a] = hi[a];
    camera_.toward = unit(c.toward);
    right_ = unit(cross(-1 * camera_.toward, c.up));
    up_ = cross(right_, -1 * camera_.toward);
    // Per face that faces the camera, the inner ray that leaves along `toward`.
    for (int f = 0; f < 6; ++f) {
      const V3 n = normal(f);
      const double cos_out = dot(n, camera_.toward);
      if (cos_out <= 0) continue;
      const V3 inner = -1 * refract(-1 * camera_.toward, -1 * n, 1, m.eta);
      faces_.push_back({f, inner, cos_out / (m.eta * m.eta * dot(inner, n))});
    }
  }

  // Face f: axis f / 2, the high side when f is odd; its outward normal.
  static V3 normal(int f) {
    double v[3] = {0, 0, 0};
    v[f / 2] = f % 2 ? 1 : -1;
    return {v[0], v[1], v[2]};
  }

  // The distance along unit d from x (inside) to the boundary; *face: where it leaves.
  double to_boundary(V3 x, V3 d, int* face) const {
    const double p[3] = {x.x, x.y, x.z}, q[3] = {d.x, d.y, d.z};
    double best = INFINITY;
    for (int a = 0; a < 3; ++a) {
      if (q[a] == 0) continue;
      const double t = ((q[a] > 0 ? hi_[a] : lo_[a]) - p[a]) / q[a];
      if (t < best) best = t, *face = 2 * a + (q[a] > 0);
    }
    return std::max(0.0, best);
  }

  // Adds the camera's share of a scattering vertex at x carrying flux w (after the albedo).
  void next_event(V3 x, double w, std::vector<double>* image) const {
    const double pixel = camera_.frame_mm / camera_.side;
    for (const Face& f : faces_) {
      int face = -1;
      const double tau = to_boundary(x, f.inner, &face);
      if (face != f.index || sigma_t_ * tau > 30) continue;  // leaves by another face first
      const V3 s = x + tau * f.inner - camera_.centre;
      const int col = static_cast<int>(std::floor((dot(s, right_) + camera_.frame_mm / 2) / pixel));
      const int row = static_cast<int>(std::floor((camera_.frame_mm / 2 - dot(s, up_)) / pixel));
      if (col < 0 || row < 0 || col >= camera_.side || row >= camera_.side) continue;
      const double transmit = 1 - fresnel(dot(f.inner, normal(f.index)), m_.eta, 1);
      (*image)[static_cast<size_t>(row) * camera_.side + col] +=
          w / (4 * M_PI) * std::exp(-sigma_t_ * tau) * transmit * f.in_per_out / (pixel * pixel);
    }
  }

  // One photon of flux `flux` entering at x through face `face` from the light toward
  // `to_light`; returns the flux that leaves with it (0 when absorbed) and its direction
  // outside in *leaving.
  double photon(V3 x, int face, V3 to_light, double flux, std::mt19937_64& rng, std::vector<double>* image,
                V3* leaving = nullptr) const {
    std::uniform_real_distribution<double> uniform(0, 1);
    const double albedo = m_.sigma_s / sigma_t_;
    V3 n = normal(face);
    double w = flux * (1 - fresnel(dot(to_light, n), 1, m_.eta));
    V3 d = refract(-1 * to_light, -1 * n, 1, m_.eta);
    for (int event = 0; event < 1000000; ++event) {
      const double free_path = -std::log(1 - uniform(rng)) / sigma_t_;
      const double boundary = to_boundary(x, d, &face);
      if (free_path < boundary) {
        x = x + free_path * d;
        w *= albedo;
        if (image) next_event(x, w, image);
        if (!scatter(rng, flux, &d, &w)) return 0;
      } else {
        x = x + boundary * d;
        n = normal(face);
        const double cos_i = dot(d, n);
        if (uniform(rng) >= fresnel(cos_i, m_.eta, 1)) {  // it leaves
          if (leaving) *leaving = refract(d, n, m_.eta, 1);
          return w;
        }
        d = d - (2 * cos_i) * n;
      }
    }
    return 0;
  }

  // A point uniform over the faces that face `to_light`, chosen by projected area; the
  // sum of those areas (mm²) in *projected.
  V3 entry(V3 to_light, std::mt19937_64& rng, int* face, double* projected) const {
    std::uniform_real_distribution<double> uniform(0, 1);
    double area[6], total = 0;
    for (int f = 0; f < 6; ++f) {
      const int a = f / 2, b = (a + 1) % 3, c = (a + 2) % 3;
      area[f] = std::max(0.0, dot(normal(f), to_light)) * (hi_[b] - lo_[b]) * (hi_[c] - lo_[c]);
      total += area[f];
    }
    *projected = total;
    double pick = uniform(rng) * total;
    *face = 0;
    while (*face < 5 && (pick >= area[*face] || area[*face] == 0)) pick -= area[(*face)++];
    const int a = *face / 2, b = (a + 1) % 3, c = (a + 2) % 3;
    double p[3];
    p[a] = *face % 2 ? hi_[a] : lo_[a];
    p[b] = lo_[b] + uniform(rng) * (hi_[b] - lo_[b]);
    p[c] = lo_[c] + uniform(rng) * (hi_[c] - lo_[c]);
    return {p[0], p[1], p[2]};
  }

 private:
  struct Face {
    int index;
    V3 inner;           // the inner ray that leaves along the view
    double in_per_out;  // dω_in/dω_out there
  };
  Medium m_;
  double sigma_t_, lo_[3], hi_[3];
  Camera camera_;
  V3 right_, up_;
  std::vector<Face> faces_;
};

// The photo: side × side radiances, top row first.  `photons` per light, split over
// `threads` streams seeded from `seed` (the same arguments give the same image).
inline std::vector<double> photo(const Medium& medium, const double lo[3], const double hi[3],
                                 const std::vector<Light>& lights, const Camera& camera, uint64_t photons,
                                 uint64_t seed, int threads) {
  const Tracer tracer(medium, lo, hi, camera);
  return threaded_photo(static_cast<size_t>(camera.side) * camera.side, seed, threads,
                        [&](int k, std::mt19937_64& rng, std::vector<double>* image) {
                          for (const Light& light : lights) {
                            const V3 to_light = unit(light.toward);
                            for (uint64_t p = k; p < photons; p += threads) {
                              int face = 0;
                              double projected = 0;
                              const V3 x = tracer.entry(to_light, rng, &face, &projected);
                              tracer.photon(x, face, to_light, light.irradiance * projected / photons, rng, image);
                            }
                          }
                        });
}

}  // namespace box_mc

#endif
