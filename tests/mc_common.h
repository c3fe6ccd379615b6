// What the tests' Monte Carlo tracers (sphere_mc.h, box_mc.h) share: vectors, the Fresnel
// equations, Snell's law and the threaded photo loop.  Written for the tests, sharing no
// code with arcus.
#ifndef ARCUS_TESTS_MC_COMMON_H
#define ARCUS_TESTS_MC_COMMON_H

#include <cmath>
#include <cstdint>
#include <random>
#include <thread>
#include <vector>

namespace mc_common {

struct V3 {
  double x, y, z;
};
inline V3 operator+(V3 a, V3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline V3 operator-(V3 a, V3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline V3 operator*(double s, V3 a) { return {s * a.x, s * a.y, s * a.z}; }
inline double dot(V3 a, V3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline V3 cross(V3 a, V3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
inline V3 unit(V3 a) { return (1 / std::sqrt(dot(a, a))) * a; }

// Unpolarised Fresnel reflectance from index n1 onto n2 at incidence cosine cos_i.
inline double fresnel(double cos_i, double n1, double n2) {
  const double sin_t2 = (n1 / n2) * (n1 / n2) * (1 - cos_i * cos_i);
  if (sin_t2 >= 1) return 1;
  const double cos_t = std::sqrt(1 - sin_t2);
  const double rs = (n1 * cos_i - n2 * cos_t) / (n1 * cos_i + n2 * cos_t);
  const double rp = (n2 * cos_i - n1 * cos_t) / (n2 * cos_i + n1 * cos_t);
  return 0.5 * (rs * rs + rp * rp);
}

// Snell: `d` (unit) crossing a boundary of normal `n` (unit, d·n > 0 is the side it goes
// to) from index n1 to n2, when it is not totally reflected.
inline V3 refract(V3 d, V3 n, double n1, double n2) {
  const double r = n1 / n2, cos_i = dot(d, n);
  const double cos_t = std::sqrt(1 - r * r * (1 - cos_i * cos_i));
  return r * d + (cos_t - r * cos_i) * n;
}

// After a scattering: an isotropic new direction, then Russian roulette on a weight fallen
// below 10⁻⁴ of the photon's flux (unbiased; ends long walks).  False: the photon ends.
inline bool scatter(std::mt19937_64& rng, double flux, V3* d, double* w) {
  std::uniform_real_distribution<double> uniform(0, 1);
  const double cz = 1 - 2 * uniform(rng), phi = 2 * M_PI * uniform(rng), sz = std::sqrt(1 - cz * cz);
  *d = {sz * std::cos(phi), sz * std::sin(phi), cz};
  if (*w < 1e-4 * flux) {
    if (uniform(rng) > 0.1) return false;
    *w *= 10;
  }
  return true;
}

// A photo of `pixels` values summed over `threads` streams: trace(k, rng, image) traces
// stream k's photons into its own image with its own generator, seeded from `seed` (the
// same arguments give the same image).
template <class Trace>
std::vector<double> threaded_photo(size_t pixels, uint64_t seed, int threads, const Trace& trace) {
  std::vector<std::vector<double>> parts(threads, std::vector<double>(pixels, 0.0));
  std::vector<std::thread> workers;
  for (int k = 0; k < threads; ++k)
    workers.emplace_back([&, k] {
      std::mt19937_64 rng(seed * 1000003 + k);
      trace(k, rng, &parts[k]);
    });
  for (auto& t : workers) t.join();
  std::vector<double> image(pixels, 0.0);
  for (const auto& part : parts)
    for (size_t i = 0; i < pixels; ++i) image[i] += part[i];
  return image;
}

}  // namespace mc_common

#endif
