/* The flattened BVH shared by the host (which builds it with Embree's rtcBuildBVH and
 * flattens it) and the kernels (which traverse it): the rendering engine's closest-hit
 * queries, the rainbow engine's patch queries and the photon map's nearest-neighbour
 * search all read this one layout.
 *
 * nodes[0] is the root.  An inner node (count == 0) has its two children at
 * nodes[first] and nodes[first + 1]; a leaf (count > 0) holds the primitives in slots
 * [first, first + count) of the primitive arrays, which the builder stores in leaf
 * order so that a leaf's primitives are contiguous.  A tree of no primitives is one node
 * with count 0 and first −1, which traversals never enter.  Boxes are in the kernels'
 * precision, rounded outwards when that is float, so they never cut off a primitive. */
#ifndef ARCUS_BVH_DESC_H
#define ARCUS_BVH_DESC_H

#ifndef __OPENCL_C_VERSION__
#include "common/real.h" /* the device source has it prepended */
#endif

#define ARCUS_DECLARE_BVH_NODE(NAME, R, I) \
  typedef struct NAME {                    \
    R lo[3];                               \
    R hi[3];                               \
    I first;                               \
    I count; /* 0: inner node            */ \
  } NAME

#ifdef __OPENCL_C_VERSION__
ARCUS_DECLARE_BVH_NODE(bvh_node, REAL, int);
#else
ARCUS_DECLARE_BVH_NODE(arcus_bvh_node_d, double, int32_t);
ARCUS_DECLARE_BVH_NODE(arcus_bvh_node_f, float, int32_t);
#endif

/* Traversal stack depth: the builder refuses trees deeper than this. */
#define ARCUS_BVH_MAX_DEPTH 64

#endif /* ARCUS_BVH_DESC_H */
