// An independent Monte Carlo photograph of a translucent sphere, written for the tests and
// sharing no code with arcus (tests/python/halfspace_mc.py is its half-space sibling).
//
// A homogeneous sphere of radius R (mm) with index eta under a smooth dielectric
// boundary, lit by directional lights and seen by an orthographic camera on +z looking
// down −z (y up, x right, the image's top row first).  Photons enter at points uniform
// over the sphere's shadow disc of each light, pass the boundary with the exact Fresnel
// transmittance, fly exponential free paths, scatter isotropically (a medium given by its
// reduced coefficients: σ_s′ with g = 0) with their weight times the albedo, and at the
// boundary are reflected back with the Fresnel probability (total internal reflection
// included) or leave.
//
// The camera is reached by next-event estimation at every scattering vertex x: the exit
// point s whose refracted ray leaves along +z lies in the plane through the z axis and x
// (n(s), +z and the inner ray are coplanar), so it is one root φ of a signed distance in
// that plane (bracketed Newton).  The vertex's intensity (w/4π per sr) is carried along
// the inner ray with e^{−σ_t τ} and the Fresnel transmittance, and turned into intensity
// outside by dω_in/dω_out, the curved boundary's solid-angle magnification (η² at normal
// exit on a flat face), taken by finite differences of two neighbouring inner rays; over
// the pixel's area it is radiance.  Missed by design, and negligible here: paths that
// reach the camera after a further internal reflection (their chord runs through the
// medium: e^{−σ_t·chord}, chords of at least ~1 mm where the boundary reflects much) and
// the specular reflection of the lights off the outer surface.
//
// Units: lengths in mm, coefficients in mm⁻¹, a light's irradiance E per mm² of a surface
// facing it; the image is radiance in E per sr.
#ifndef ARCUS_TESTS_SPHERE_MC_H
#define ARCUS_TESTS_SPHERE_MC_H

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <thread>
#include <vector>

#include "mc_common.h"

namespace sphere_mc {

using namespace mc_common;

struct Medium {
  double sigma_a, sigma_s, eta;  // mm⁻¹, mm⁻¹ (isotropic: the reduced σ_s′), index
};
struct Light {
  double direction[3];  // toward the light
  double irradiance;    // on a surface facing it
};
struct View {
  double radius_mm;  // the sphere's, centred at the origin
  double frame_mm;   // the square image's side at the object
  int side;          // pixels
};

// The distance along unit `d` from `x` (inside) to the sphere of radius R.
inline double to_boundary(V3 x, V3 d, double R) {
  const double b = dot(x, d), c = dot(x, x) - R * R;
  return -b + std::sqrt(std::max(0.0, b * b - c));
}

class Tracer {
 public:
  Tracer(const Medium& m, const View& v) : m_(m), v_(v), sigma_t_(m.sigma_a + m.sigma_s) {}

  // Adds the camera's share of a scattering vertex at x carrying flux w (after the albedo).
  void next_event(V3 x, double w, std::vector<double>* image) const {
    const double R = v_.radius_mm, eta = m_.eta;
    const double rho = std::hypot(x.x, x.y);
    // The inner ray is at least this long (to the visible half's nearest point).
    const double shortest = x.z >= 0 ? R - std::sqrt(dot(x, x)) : std::hypot(R - rho, x.z);
    if (sigma_t_ * shortest > 12) return;  // e^{-12}: nothing the image can show
    const double ux = rho > 1e-12 ? x.x / rho : 1, uy = rho > 1e-12 ? x.y / rho : 0;
    // In the plane (ρ, z): the exit point s(φ) = R(sin φ, cos φ), the inner ray ω(φ) that
    // leaves along +z; f(φ) = the signed distance of x from the line s − τω.
    auto inner = [eta](double phi, double* wr, double* wz) {
      const double sn = std::sin(phi), cs = std::cos(phi);
      const double ct = std::sqrt(1 - sn * sn / (eta * eta));
      // tangential part (+z's, over η) along (cos φ, −sin φ); normal part along (sin φ, cos φ)
      const double tang = -sn / eta;
      *wr = tang * cs + ct * sn;
      *wz = -tang * sn + ct * cs;
    };
    auto f = [&](double phi) {
      double wr, wz;
      inner(phi, &wr, &wz);
      const double dr = R * std::sin(phi) - rho, dz = R * std::cos(phi) - x.z;
      return dr * wz - dz * wr;
    };
    // Newton from straight up (close for shallow x), bisection of [−π/2, π/2] where a
    // step would leave the bracket; f rises through its one root there, or x has none
    // (some points deep in the far half), which the ends' signs tell.
    double lo = -M_PI / 2 + 1e-9, hi = M_PI / 2 - 1e-9;
    double phi = std::asin(std::min(1.0, rho / R)), fx = f(phi);
    for (int it = 0; it < 100 && std::fabs(fx) > 1e-11 * R; ++it) {
      if (it == 6 && (f(lo) > 0 || f(hi) < 0)) return;
      (fx < 0 ? lo : hi) = phi;
      const double h = 1e-7, slope = (f(phi + h) - fx) / h;
      double next = phi - fx / slope;
      if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
      phi = next;
      fx = f(phi);
    }
    if (std::fabs(fx) > 1e-9 * R) return;
    double wr, wz;
    inner(phi, &wr, &wz);
    const V3 u{ux, uy, 0}, z{0, 0, 1};
    const V3 s = (R * std::sin(phi)) * u + (R * std::cos(phi)) * z;
    const V3 w_in = wr * u + wz * z;
    const double tau = dot(s - x, w_in);
    if (tau <= 0) return;
    const V3 n = (1 / R) * s;
    const double transmit = 1 - fresnel(dot(w_in, n), eta, 1);
    // dω_out/dω_in from two neighbouring inner rays.
    const V3 e1 = unit(cross(w_in, std::fabs(w_in.x) < 0.9 ? V3{1, 0, 0} : V3{0, 1, 0})), e2 = cross(w_in, e1);
    const double delta = 1e-5;
    auto out = [&](V3 d) {
      d = unit(d);
      const V3 at = x + to_boundary(x, d, R) * d;
      return refract(d, (1 / R) * at, eta, 1);
    };
    const V3 o0 = out(w_in), o1 = out(w_in + delta * e1), o2 = out(w_in + delta * e2);
    const V3 spread = cross(o1 - o0, o2 - o0);
    const double magnification = std::sqrt(dot(spread, spread)) / (delta * delta);
    if (!(magnification > 0)) return;
    const double pixel = v_.frame_mm / v_.side;
    const int col = static_cast<int>(std::floor((s.x + v_.frame_mm / 2) / pixel));
    const int row = static_cast<int>(std::floor((v_.frame_mm / 2 - s.y) / pixel));
    if (col < 0 || row < 0 || col >= v_.side || row >= v_.side) return;
    (*image)[static_cast<size_t>(row) * v_.side + col] +=
        w / (4 * M_PI) * std::exp(-sigma_t_ * tau) * transmit / magnification / (pixel * pixel);
  }

  // One photon of flux `flux` from the light toward `to_light` (unit); returns the flux
  // that leaves the sphere with it (0 when it is absorbed).
  double photon(V3 to_light, double flux, std::mt19937_64& rng, std::vector<double>* image) const {
    std::uniform_real_distribution<double> uniform(0, 1);
    const double R = v_.radius_mm, eta = m_.eta, albedo = m_.sigma_s / sigma_t_;
    const V3 e1 = unit(cross(to_light, std::fabs(to_light.x) < 0.9 ? V3{1, 0, 0} : V3{0, 1, 0}));
    const V3 e2 = cross(to_light, e1);
    const double r = R * std::sqrt(uniform(rng)), a = 2 * M_PI * uniform(rng);
    const V3 foot = (r * std::cos(a)) * e1 + (r * std::sin(a)) * e2;  // on the shadow disc
    V3 x = foot + std::sqrt(std::max(0.0, R * R - r * r)) * to_light;  // where it enters
    V3 n = unit(x);
    x = R * n;
    double w = flux * (1 - fresnel(dot(to_light, n), 1, eta));
    V3 d = refract(-1 * to_light, -1 * n, 1, eta);
    for (int event = 0; event < 1000000; ++event) {
      const double free_path = -std::log(1 - uniform(rng)) / sigma_t_;
      const double boundary = to_boundary(x, d, R);
      if (free_path < boundary) {
        x = x + free_path * d;
        w *= albedo;
        next_event(x, w, image);
        if (!scatter(rng, flux, &d, &w)) return 0;
      } else {
        n = unit(x + boundary * d);
        x = R * n;
        const double cos_i = dot(d, n);
        if (uniform(rng) >= fresnel(cos_i, eta, 1)) return w;  // it leaves
        d = d - (2 * cos_i) * n;
      }
    }
    return 0;
  }

 private:
  Medium m_;
  View v_;
  double sigma_t_;
};

// The photo: side × side radiances, top row first.  `photons` per light, split over
// `threads` streams seeded from `seed` (the same arguments give the same image).
inline std::vector<double> photo(const Medium& medium, const std::vector<Light>& lights, const View& view,
                                 uint64_t photons, uint64_t seed, int threads) {
  const Tracer tracer(medium, view);
  return threaded_photo(static_cast<size_t>(view.side) * view.side, seed, threads,
                        [&](int k, std::mt19937_64& rng, std::vector<double>* image) {
                          for (const Light& light : lights) {
                            const V3 to_light = unit({light.direction[0], light.direction[1], light.direction[2]});
                            const double flux = light.irradiance * M_PI * view.radius_mm * view.radius_mm / photons;
                            for (uint64_t p = k; p < photons; p += threads) tracer.photon(to_light, flux, rng, image);
                          }
                        });
}

}  // namespace sphere_mc

#endif
