#include "bvh/bvh.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <limits>
#include <string>

#include "bvh/embree_scene.h"
#include "core/error.h"
#include "core/format.h"

namespace arcus::bvh {
namespace {

// Embree's builder hands out nodes through these callbacks (from its worker threads,
// into its own thread-local memory); the tree lives until the RTCBVH is released,
// long enough to be flattened.
struct TempNode {
  TempNode* child[2];
  const uint32_t* prims;  // leaf: primitive indices
  uint32_t count;         // 0: inner node
};

void* create_node(RTCThreadLocalAllocator alloc, unsigned int child_count, void*) {
  if (child_count != 2) return nullptr;  // maxBranchingFactor is 2; flattening reports it
  auto* n = static_cast<TempNode*>(rtcThreadLocalAlloc(alloc, sizeof(TempNode), 16));
  *n = TempNode{{nullptr, nullptr}, nullptr, 0};
  return n;
}

void set_children(void* node, void** children, unsigned int child_count, void*) {
  auto* n = static_cast<TempNode*>(node);
  for (unsigned i = 0; i < child_count && i < 2; ++i) n->child[i] = static_cast<TempNode*>(children[i]);
}

// Node boxes come from the double primitives when flattening, not from Embree's floats.
void set_bounds(void*, const RTCBounds**, unsigned int, void*) {}

void* create_leaf(RTCThreadLocalAllocator alloc, const RTCBuildPrimitive* prims, size_t count, void*) {
  auto* n = static_cast<TempNode*>(rtcThreadLocalAlloc(alloc, sizeof(TempNode), 16));
  auto* ids = static_cast<uint32_t*>(rtcThreadLocalAlloc(alloc, count * sizeof(uint32_t), 16));
  for (size_t i = 0; i < count; ++i) ids[i] = prims[i].primID;
  *n = TempNode{{nullptr, nullptr}, ids, static_cast<uint32_t>(count)};
  return n;
}

float round_down(double x) {
  float f = static_cast<float>(std::clamp<double>(x, -FLT_MAX, FLT_MAX));
  return static_cast<double>(f) > x ? std::nextafter(f, -std::numeric_limits<float>::infinity()) : f;
}

float round_up(double x) {
  float f = static_cast<float>(std::clamp<double>(x, -FLT_MAX, FLT_MAX));
  return static_cast<double>(f) < x ? std::nextafter(f, std::numeric_limits<float>::infinity()) : f;
}

struct Flattener {
  const std::vector<Bounds>& prims;
  Flat& out;

  // Writes `n` into out.nodes[index] (its children into a fresh adjacent pair) and
  // returns its box.
  Bounds place(const TempNode* n, size_t index, int level) {
    if (!n) fail(ARCUS_ERROR_INVALID_ARGUMENT, "bvh: Embree's builder returned an incomplete tree");
    out.depth = std::max(out.depth, level);
    if (level > ARCUS_BVH_MAX_DEPTH)
      fail(ARCUS_ERROR_INVALID_ARGUMENT, "bvh: the tree is deeper than " + std::to_string(ARCUS_BVH_MAX_DEPTH) +
                                             " levels (the kernels' stack); the primitives are too unevenly spread");
    Bounds b{{HUGE_VAL, HUGE_VAL, HUGE_VAL}, {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL}};
    int32_t first, count;
    if (n->count > 0) {
      first = static_cast<int32_t>(out.order.size());
      count = static_cast<int32_t>(n->count);
      for (uint32_t i = 0; i < n->count; ++i) {
        const Bounds& p = prims[n->prims[i]];
        for (int k = 0; k < 3; ++k) b.lo[k] = std::min(b.lo[k], p.lo[k]), b.hi[k] = std::max(b.hi[k], p.hi[k]);
        out.order.push_back(n->prims[i]);
      }
    } else {
      first = static_cast<int32_t>(out.nodes.size());
      count = 0;
      out.nodes.resize(out.nodes.size() + 2);
      for (int c = 0; c < 2; ++c) {
        const Bounds cb = place(n->child[c], first + c, level + 1);
        for (int k = 0; k < 3; ++k) b.lo[k] = std::min(b.lo[k], cb.lo[k]), b.hi[k] = std::max(b.hi[k], cb.hi[k]);
      }
    }
    arcus_bvh_node_d& node = out.nodes[index];
    for (int k = 0; k < 3; ++k) node.lo[k] = b.lo[k], node.hi[k] = b.hi[k];
    node.first = first;
    node.count = count;
    return b;
  }
};

}  // namespace

bool representable(const double p[3]) {
  for (int k = 0; k < 3; ++k)
    if (!(std::fabs(p[k]) <= kMaxCoordinate)) return false;
  return true;
}

Flat build(const std::vector<Bounds>& prims, int max_leaf, int min_leaf) {
  require(max_leaf >= 1 && max_leaf <= RTC_BUILD_MAX_PRIMITIVES_PER_LEAF,
          "bvh: max_leaf must be 1 to " + std::to_string(RTC_BUILD_MAX_PRIMITIVES_PER_LEAF));
  require(min_leaf >= 1 && min_leaf <= max_leaf, "bvh: min_leaf must be 1 to max_leaf");
  require(prims.size() < static_cast<size_t>(std::numeric_limits<int32_t>::max()), "bvh: too many primitives");
  Flat flat;
  flat.depth = 1;
  if (prims.empty()) {
    flat.nodes.push_back(arcus_bvh_node_d{{0, 0, 0}, {0, 0, 0}, -1, 0});
    return flat;
  }
  std::vector<RTCBuildPrimitive> in(prims.size());
  for (size_t i = 0; i < prims.size(); ++i) {
    const Bounds& p = prims[i];
    for (int k = 0; k < 3; ++k)
      require(std::isfinite(p.lo[k]) && std::isfinite(p.hi[k]) && p.lo[k] <= p.hi[k],
              "bvh: primitive " + std::to_string(i) + " has a non-finite or inverted box");
    if (!representable(p.lo) || !representable(p.hi))
      fail(ARCUS_ERROR_INVALID_ARGUMENT, "bvh: primitive " + std::to_string(i) + " reaches " +
                                             number(std::max({std::fabs(p.lo[0]), std::fabs(p.lo[1]), std::fabs(p.lo[2]),
                                                              std::fabs(p.hi[0]), std::fabs(p.hi[1]), std::fabs(p.hi[2])})) +
                                             " m from the origin, beyond the " + number(kMaxCoordinate) +
                                             " m the BVH builder can represent");
    in[i] = RTCBuildPrimitive{round_down(p.lo[0]), round_down(p.lo[1]), round_down(p.lo[2]), 0,
                              round_up(p.hi[0]),   round_up(p.hi[1]),   round_up(p.hi[2]),   static_cast<unsigned>(i)};
  }

  last_embree_error();  // clears this thread's message
  RTCBVH handle = rtcNewBVH(shared_embree_device());
  RTCBuildArguments args = rtcDefaultBuildArguments();
  args.buildQuality = RTC_BUILD_QUALITY_HIGH;  // without splitPrimitive: binned SAH, no spatial splits,
                                               // so each primitive sits in exactly one leaf
  args.maxBranchingFactor = 2;
  // Embree refuses to go deeper than this; the flattener reports our own limit first.
  args.maxDepth = 2 * ARCUS_BVH_MAX_DEPTH;
  args.minLeafSize = static_cast<unsigned>(min_leaf);
  args.maxLeafSize = static_cast<unsigned>(max_leaf);
  args.traversalCost = 1.0f;
  args.intersectionCost = 1.0f;
  args.bvh = handle;
  args.primitives = in.data();
  args.primitiveCount = in.size();
  args.primitiveArrayCapacity = in.size();
  args.createNode = create_node;
  args.setNodeChildren = set_children;
  args.setNodeBounds = set_bounds;
  args.createLeaf = create_leaf;
  const auto* root = static_cast<const TempNode*>(rtcBuildBVH(&args));
  try {
    if (!root) fail(ARCUS_ERROR_INVALID_ARGUMENT, "bvh: Embree could not build the tree (" + last_embree_error() + ")");
    flat.nodes.resize(1);
    flat.order.reserve(prims.size());
    Flattener{prims, flat}.place(root, 0, 1);
  } catch (...) {
    rtcReleaseBVH(handle);
    throw;
  }
  rtcReleaseBVH(handle);
  require(flat.order.size() == prims.size(), "bvh: Embree's tree does not hold every primitive once");
  return flat;
}

std::vector<arcus_bvh_node_f> to_float(const std::vector<arcus_bvh_node_d>& nodes) {
  std::vector<arcus_bvh_node_f> out(nodes.size());
  for (size_t i = 0; i < nodes.size(); ++i) {
    for (int k = 0; k < 3; ++k) out[i].lo[k] = round_down(nodes[i].lo[k]), out[i].hi[k] = round_up(nodes[i].hi[k]);
    out[i].first = nodes[i].first;
    out[i].count = nodes[i].count;
  }
  return out;
}

TriangleBvh build_triangles(const std::vector<const geometry::Mesh*>& meshes, int max_leaf) {
  TriangleBvh out;
  std::vector<double> corners;  // 9 per triangle index, degenerate ones collapsed
  for (size_t g = 0; g < meshes.size(); ++g) {
    require_pointer(meshes[g], "build_triangles: a mesh");
    const geometry::Mesh& m = *meshes[g];
    out.mesh_first.push_back(static_cast<uint32_t>(out.geometry.size()));
    const size_t nv = m.vertex_count();
    for (size_t v = 0; v < nv; ++v)
      if (!representable(&m.positions[3 * v]))
        fail(ARCUS_ERROR_INVALID_ARGUMENT,
             (m.source.empty() ? "mesh " + std::to_string(g) : m.source) + ": vertex " + std::to_string(v) + " at (" +
                 number(m.positions[3 * v]) + ", " + number(m.positions[3 * v + 1]) + ", " +
                 number(m.positions[3 * v + 2]) + ") lies beyond the " + number(kMaxCoordinate) +
                 " m from the origin that the BVH can represent; move or scale the mesh nearer the origin");
    for (size_t t = 0; t < m.triangle_count(); ++t) {
      double v[9];
      for (int c = 0; c < 3; ++c) {
        const uint32_t i = m.triangles[3 * t + c];
        require(i < nv, "build_triangles: " + (m.source.empty() ? "mesh " + std::to_string(g) : m.source) +
                            ": triangle " + std::to_string(t) + " names a vertex that does not exist");
        for (int k = 0; k < 3; ++k) v[3 * c + k] = m.positions[3 * i + k];
      }
      const double e1[3] = {v[3] - v[0], v[4] - v[1], v[5] - v[2]}, e2[3] = {v[6] - v[0], v[7] - v[1], v[8] - v[2]};
      const double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
      const double area2 = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
      const double scale = (e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]) * (e2[0] * e2[0] + e2[1] * e2[1] + e2[2] * e2[2]);
      const double eps = 8 * std::numeric_limits<double>::epsilon();
      if (area2 <= eps * eps * scale)
        for (int c = 1; c < 3; ++c)
          for (int k = 0; k < 3; ++k) v[3 * c + k] = v[k];
      corners.insert(corners.end(), v, v + 9);
      out.geometry.push_back(static_cast<uint32_t>(g));
    }
  }
  std::vector<Bounds> boxes(out.geometry.size());
  for (size_t t = 0; t < boxes.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const double* v = &corners[9 * t];
      boxes[t].lo[k] = std::min({v[k], v[3 + k], v[6 + k]});
      boxes[t].hi[k] = std::max({v[k], v[3 + k], v[6 + k]});
    }
  out.tree = build(boxes, max_leaf);
  out.triangles.resize(9 * boxes.size());
  for (size_t s = 0; s < out.tree.order.size(); ++s)
    std::copy_n(&corners[9 * out.tree.order[s]], 9, &out.triangles[9 * s]);
  return out;
}

TriangleBvh build_triangles(const geometry::Mesh& mesh, int max_leaf) { return build_triangles({&mesh}, max_leaf); }

}  // namespace arcus::bvh
