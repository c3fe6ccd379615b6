// Bounding volume hierarchies in the layout of kernels/bvh/bvh_desc.h, built with
// Embree's builder API (rtcBuildBVH, SAH) and flattened for the kernels.  One generic
// builder over boxes (triangles, photons as zero-size boxes, patches) and the triangle
// BVH the renderer and the rainbow engine traverse.
#pragma once

#include <cstdint>
#include <vector>

#include "bvh/bvh_desc.h"
#include "geometry/mesh.h"

namespace arcus::bvh {

struct Bounds {
  double lo[3], hi[3];
};

// How far from the origin geometry may lie: 1e18 m (about 100 light years).  Embree's
// builder bins boxes in single precision and weighs splits by their surface areas, which
// overflow beyond ~1e19 m (an assertion in its binning killed the process for a mesh at
// 3e38 m); every build refuses primitives beyond this, with a message.
constexpr double kMaxCoordinate = 1e18;

// Whether every coordinate of the point is finite and within ±kMaxCoordinate.
bool representable(const double p[3]);

// A flattened tree: nodes[0] is the root, nodes in depth-first order with the two
// children of an inner node adjacent; leaf slots [first, first + count) index `order`.
// No primitives: one node with count 0 and first -1, which traversals never enter.
struct Flat {
  std::vector<arcus_bvh_node_d> nodes;
  std::vector<uint32_t> order;  // slot -> primitive index (each primitive exactly once)
  int depth;                    // levels: 1 for a root that is a leaf
};

// SAH BVH over `prims` (finite, within ±kMaxCoordinate, lo <= hi; zero-size boxes allowed) with at most
// `max_leaf` (1..32) primitives per leaf, and at least `min_leaf` (1..max_leaf) where a
// node has that many: larger leaves mean fewer nodes to visit where a search looks at
// every primitive near a point anyway (the photon map's).  Node boxes are the exact double union of
// their primitives' boxes.  A tree deeper than ARCUS_BVH_MAX_DEPTH levels (which the
// kernels' fixed stacks could not traverse) is ARCUS_ERROR_INVALID_ARGUMENT.
Flat build(const std::vector<Bounds>& prims, int max_leaf = 4, int min_leaf = 1);

// The nodes in float for the float kernels, boxes rounded outwards so that they still
// contain everything the double boxes did.
std::vector<arcus_bvh_node_f> to_float(const std::vector<arcus_bvh_node_d>& nodes);

// Triangles of one or several meshes under one BVH.  Triangle indices run over the
// meshes concatenated: mesh g's triangle i is triangle mesh_first[g] + i.
struct TriangleBvh {
  Flat tree;                        // order: slot -> triangle index
  std::vector<double> triangles;    // 9 per slot, in leaf order: v0, v1, v2
  std::vector<uint32_t> geometry;   // per triangle index: the mesh it came from
  std::vector<uint32_t> mesh_first; // per mesh: its first triangle index
  // Zero-area triangles (|e1 × e2| within rounding of 0) are stored as their first
  // vertex three times, so the watertight test's determinant is exactly 0: never hit.
  size_t triangle_count() const { return tree.order.size(); }
};

TriangleBvh build_triangles(const std::vector<const geometry::Mesh*>& meshes, int max_leaf = 4);
TriangleBvh build_triangles(const geometry::Mesh& mesh, int max_leaf = 4);

// A segment o + t·d, t in [0, t_max] (d need not be unit: t_max = 1 with d = end − o
// is a step from o to the end).
struct Segment {
  double origin[3], direction[3], t_max;
};

// The closest hit of a segment: slot -1 and primitive -1 on a miss.  u, v: barycentric
// weights of v1 and v2 (the hit is (1−u−v)·v0 + u·v1 + v·v2), as Embree reports them.
struct Hit {
  int32_t slot = -1, primitive = -1;
  double t = 0, u = 0, v = 0;
  int32_t tests = 0;  // nodes visited + triangles tested (the OpenCL traversal only)
};

}  // namespace arcus::bvh
