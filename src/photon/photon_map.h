// The photon map (Jensen's; thesis §4.3.4 for curved photon mapping): photons stored on
// the device in a BVH (arcus::bvh::build) and kept there, so that later jobs — the
// renderer's gather, the ocean engine's volume estimate — read them without a round
// trip.  The search and the estimate are device code (kernels/photon/photon_map.h),
// callable from other kernels; estimate() and nearest() run them on a batch of queries.
// Double precision.
#pragma once

#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

#include "bvh/bvh_desc.h"      // kernels/bvh/bvh_desc.h
#include "core/buffer.h"
#include "core/kernel_source.h"
#include "photon/photon_desc.h"  // kernels/photon/photon_desc.h: shared with the kernels

namespace arcus::photon {

// Photons as the caller hands them over, one after another.
struct Photons {
  std::vector<double> positions;   // x y z per photon
  std::vector<double> directions;  // the direction each travelled (normalised on upload)
  std::vector<double> powers;      // `channels` per photon, finite and >= 0
  int channels = 3;                // 1..ARCUS_PHOTON_CHANNELS (3: RGB; spectral bins)
};

class PhotonMap {
 public:
  // Checks the photons (INVALID_ARGUMENT naming the first bad one), builds the BVH and
  // uploads nodes and photons (OUT_OF_MEMORY, checked first, when they do not fit).
  // Leaves hold up to max(4, min_leaf) photons, and at least min_leaf (1..32) where a
  // node has that many: a search visits fewer nodes and scans more photons with larger.
  PhotonMap(arcus_context_t* ctx, const Photons& photons, int min_leaf = 1);

  size_t size() const { return order_.size(); }
  int channels() const { return desc_.channels; }
  int depth() const { return depth_; }
  // Device memory held: the nodes and the photons.
  size_t bytes() const;
  // The kernels' view: bvh_node array and photon components (both null when empty).
  const DeviceBuffer* nodes() const { return nodes_.get(); }
  const DeviceBuffer* photons() const { return photons_.get(); }
  const arcus_photon_map_desc& desc() const { return desc_; }
  // Slot (leaf order, as the kernels see photons) -> index in the input.
  const std::vector<uint32_t>& order() const { return order_; }
  // Whether the map's buffers can be used by ctx's jobs (same device).
  bool usable_by(const arcus_context_t* ctx) const;

 private:
  const DeviceRuntime* runtime_;
  arcus_photon_map_desc desc_{};
  std::vector<uint32_t> order_;
  int depth_ = 0;
  std::shared_ptr<DeviceBuffer> nodes_, photons_;  // shared with the jobs that read them
};

enum class Mode : int32_t { surface = ARCUS_PHOTON_SURFACE, volume = ARCUS_PHOTON_VOLUME };

struct Query {
  int32_t k = 50;                                          // 1..ARCUS_PHOTON_MAX_K
  double max_radius = std::numeric_limits<double>::infinity();  // > 0; +inf: no cap
  Mode mode = Mode::surface;  // surface: a unit normal per query, front-side photons only
  double cone = 0;            // Jensen's cone filter constant (>= 1); 0: none
};

// Per query: values[i·channels + c] — surface: irradiance Σ Φ / (π r²) (times the BRDF
// gives radiance); volume: Σ Φ / (4/3 π r³) (times the phase function) — the radius r
// used (r_k, or max_radius when fewer than k were found; kernels/photon/photon_map.h)
// and the photons found.
struct Estimates {
  std::vector<double> values, radius;
  std::vector<int32_t> found;
  double kernel_seconds = 0;
};

// points: x y z per query; normals: x y z per query for surface queries (any length,
// normalised here), none for volume ones.  Bad arguments are INVALID_ARGUMENT.
Estimates estimate(arcus_context_t* ctx, const PhotonMap& map, const std::vector<double>& points,
                   const std::vector<double>& normals, const Query& query);

// The k nearest photons of each query (surface queries: front-side ones only), nearest
// first: index[i·k + j] in the input's numbering and their distances; -1 and +inf past
// found[i].  query.cone is not used.
struct Neighbours {
  std::vector<int64_t> index;
  std::vector<double> distance;
  std::vector<int32_t> found;
};
Neighbours nearest(arcus_context_t* ctx, const PhotonMap& map, const std::vector<double>& points,
                   const std::vector<double>& normals, const Query& query);

// The k nearest photons at `steps` points `step` apart along each line (starts and
// unit directions: x y z per line), found as a ray march finds them
// (kernels/photon/photon_line.h): per line i and step j, at e = i·steps + j, the point
// searched from (points[3e..]), the k-th distance (the farthest found when fewer) and
// the set found as the sum of its slots and of their squares (digest[2e], [2e + 1]);
// lone[i]: the steps searched alone, without the line's pool.
struct LineMarch {
  std::vector<double> points, radius;
  std::vector<int64_t> digest;
  std::vector<int32_t> lone;
};
LineMarch march_lines(arcus_context_t* ctx, const PhotonMap& map, const std::vector<double>& starts,
                      const std::vector<double>& directions, int steps, double step, int k);

// For other engines' kernels: the files to put before a kernel that calls photon_knn,
// photon_estimate or photon_line_query (in this order), and the map's three arguments
// set at first, first + 1, first + 2: (__global const bvh_node* nodes,
// __global const REAL* photons, const photon_map_desc map).
const std::vector<const char*>& device_headers();
void set_map_arguments(KernelCall& call, unsigned first, const PhotonMap& map);

}  // namespace arcus::photon
