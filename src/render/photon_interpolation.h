// Undersampling of curved photon mapping's first generation (photons.h, UNDERSAMPLE):
// the neighbours of a photon in its light's sampling coordinate (a spatial hash, also
// smart step selection's coarse set), the choice of the photons to interpolate, the
// affine weights and the interpolated hit.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "render/photon_emission.h"
#include "render/photons.h"

namespace arcus::render {

// A spatial hash of sampling coordinates (one per light), with cells of side h; `flat`
// when the coordinates lie in z = 0 (a sun's, across its beam).
struct SamplingGrid {
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
  void insert(Vec3 p, uint32_t index) { cells[mix(cell(p.x), cell(p.y), flat ? 0 : cell(p.z))].push_back(index); }
  // Calls f(index) for every point in the cells at Chebyshev distance k from p's (hash
  // collisions may add others: callers check the distance).
  template <class F>
  void shell(Vec3 p, int64_t k, F&& f) const {
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
  void nearest(const std::vector<Vec3>& keys, Vec3 p, double r, size_t n, std::vector<uint32_t>* out) const {
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

// An angle of `deg` degrees as a distance in light `light`'s sampling coordinate
// (photons.h): t·D across a sun's beam, the chord 2 sin(t/2) between a point light's
// directions.
double sampling_radius(const RenderScene& s, uint32_t light, double deg);

// UNDERSAMPLE's choice, photon by photon in order: those computed (and stored in the
// grid), and those interpolated, each with its neighbours and their affine weights.
// Mirrors (SYMMETRY's second photons) are in neither.
struct Undersampling {
  std::vector<uint32_t> computed, interpolated;
  std::vector<std::vector<uint32_t>> neighbours;  // per photon (interpolated ones only)
  std::vector<std::vector<double>> weights;
};
Undersampling choose_interpolated(const RenderScene& s, const Emission& e, const PhotonOptions& o);

// An interpolated photon's result from its neighbours' (slots of `t`), or false when
// they do not all hit one plane.
bool interpolate(const RenderScene& s, const TraceOutput& t, const std::vector<uint32_t>& nb,
                 const std::vector<double>& w, TraceOutput* out, size_t j);

}  // namespace arcus::render
