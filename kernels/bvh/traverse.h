/* Scalar BVH queries over the triangles of a TriangleBvh (src/bvh/bvh.h): one query at
 * a time, no lanes, so any kernel can call them per item from inside its own loop.
 * Prepend common/real.h and bvh/bvh_desc.h (in that order) before this file.
 *
 *   nodes  the flattened tree (bvh_desc.h), in the kernel's precision
 *   tris   9 REALs per leaf slot: v0, v1, v2 (slot s at tris + 9·s)
 *
 * bvh_segment_closest  the closest triangle the segment o + t·d, t in [0, t_max], hits
 * bvh_box_overlaps     whether any triangle's bounding box overlaps a box
 * bvh_segment_next, bvh_box_next   resumable walks over every hit (bvh_kernels.cl)
 *
 * The ray/triangle test is the watertight one of Woop, Benthin and Wald (JCGT 2013):
 * the triangle is sheared into the ray's frame, and the edge functions of an edge two
 * triangles share are computed from the same two transformed vertices, so they are
 * exact negations of each other and a segment through the edge cannot slip between
 * them.  Where an edge function is exactly 0 (the segment passes exactly through the
 * edge or a vertex), a top-left rule on the edge's direction gives the point to exactly
 * one of the triangles around it.  A zero determinant (a zero-area triangle, or a
 * segment in the triangle's plane) is never a hit.  Back faces are hit.
 *
 * The host can include this file too (tests): it is then one double at a time. */
#ifndef ARCUS_BVH_TRAVERSE_H
#define ARCUS_BVH_TRAVERSE_H

#ifndef __OPENCL_C_VERSION__
#include "bvh/bvh_desc.h"
typedef arcus_bvh_node_d bvh_node;
#endif

#ifdef ARCUS_USE_FLOAT
/* 1 + 2·γ(3) rounded up (Ize 2013, "Robust BVH ray traversal"): widening a slab
 * interval's far end by it makes the box test conservative despite rounding. */
#define ARCUS_BVH_SLACK RC(4.0e-7)
#else
#define ARCUS_BVH_SLACK RC(8.0e-16)
#endif

/* A query segment, prepared once: the origin, the reciprocals of the direction (0 where
 * the direction's component is 0, or so small that its reciprocal overflows: the
 * segment then stays in one slab of that axis) and the shear into the frame where the
 * ray runs along +kz. */
typedef struct bvh_ray {
  REAL o[3], inv[3];
  REAL okx, oky, okz; /* the origin in the sheared frame's axis order */
  REAL sx, sy, sz;
  int kx, ky, kz;
} bvh_ray;

ARCUS_INLINE void bvh_ray_init(bvh_ray* r, REAL ox, REAL oy, REAL oz, REAL dx, REAL dy, REAL dz) {
  const REAL d[3] = {dx, dy, dz};
  r->o[0] = ox;
  r->o[1] = oy;
  r->o[2] = oz;
  for (int k = 0; k < 3; ++k) {
    const REAL inv = RC(1.0) / d[k];
    r->inv[k] = isfinite(inv) ? inv : RC(0.0);
  }
  /* kz: the direction's largest component; kx, ky keep the winding when d[kz] < 0. */
  const REAL ax = fabs(dx), ay = fabs(dy), az = fabs(dz);
  int kz = ax > ay ? (ax > az ? 0 : 2) : (ay > az ? 1 : 2);
  int kx = kz == 2 ? 0 : kz + 1, ky = kx == 2 ? 0 : kx + 1;
  if (d[kz] < 0) {
    const int swap = kx;
    kx = ky;
    ky = swap;
  }
  r->kx = kx;
  r->ky = ky;
  r->kz = kz;
  r->okx = r->o[kx];
  r->oky = r->o[ky];
  r->okz = r->o[kz];
  r->sz = RC(1.0) / d[kz];
  r->sx = d[kx] * r->sz;
  r->sy = d[ky] * r->sz;
}

/* Whether an edge whose normalised edge function is e (positive inside) and whose
 * normalised direction is (ex, ey) holds the point: inside, or exactly on it and the
 * edge is a "top-left" one.  Of two triangles sharing the edge, one sees the direction
 * negated, so exactly one of them owns a point on it (and, around a shared vertex,
 * exactly one triangle of the fan). */
ARCUS_INLINE int bvh_edge_holds(REAL e, REAL ex, REAL ey) {
  return e > 0 || (e == 0 && (ey > 0 || (ey == 0 && ex < 0)));
}

/* The watertight test of one triangle: 1 with t in [0, t_max] and the barycentric
 * weights u (of v1), v (of v2) on a hit. */
ARCUS_INLINE int bvh_triangle_hit(const bvh_ray* r, ARCUS_GLOBAL const REAL* tri, REAL t_max, REAL* t, REAL* u,
                                  REAL* v) {
#ifdef __OPENCL_C_VERSION__
  /* OpenCL contracts a·b − c·d into an FMA by default, which would round an edge's two
   * products differently in its two triangles and break the exact negation. */
#pragma OPENCL FP_CONTRACT OFF
#endif
  const int kx = r->kx, ky = r->ky, kz = r->kz;
  const REAL az = tri[kz] - r->okz, bz = tri[3 + kz] - r->okz, cz = tri[6 + kz] - r->okz;
  const REAL ax = (tri[kx] - r->okx) - r->sx * az, ay = (tri[ky] - r->oky) - r->sy * az;
  const REAL bx = (tri[3 + kx] - r->okx) - r->sx * bz, by = (tri[3 + ky] - r->oky) - r->sy * bz;
  const REAL cx = (tri[6 + kx] - r->okx) - r->sx * cz, cy = (tri[6 + ky] - r->oky) - r->sy * cz;
  const REAL U = cx * by - cy * bx, V = ax * cy - ay * cx, W = bx * ay - by * ax;
  const REAL det = U + V + W;
  if (det == 0) return 0;
  /* Normalise to the orientation where the inside is positive, so both windings and
   * both sides of a shared edge follow one rule.  Each edge function cross(X, Y) goes
   * with the direction Y − X. */
  const REAL s = det > 0 ? RC(1.0) : RC(-1.0);
  if (!bvh_edge_holds(s * U, s * (bx - cx), s * (by - cy)) || !bvh_edge_holds(s * V, s * (cx - ax), s * (cy - ay)) ||
      !bvh_edge_holds(s * W, s * (ax - bx), s * (ay - by)))
    return 0;
  const REAL T = r->sz * (U * az + V * bz + W * cz);
  const REAL th = T / det;
  if (!(th >= 0 && th <= t_max)) return 0;
  *t = th;
  *u = V / det;
  *v = W / det;
  return 1;
}

/* Whether the segment's [0, t_max] meets the node's box; *t_near: where it enters. */
ARCUS_INLINE int bvh_ray_box(const bvh_ray* r, ARCUS_GLOBAL const bvh_node* n, REAL t_max, REAL* t_near) {
  REAL t_far = t_max;
  REAL near = 0;
  for (int k = 0; k < 3; ++k) {
    if (r->inv[k] == 0) {
      /* Parallel to the slab: inside it for every t or for none.  (Slab arithmetic with
       * an infinite 1/d would make 0·∞ = NaN for an origin on the box's face, and a
       * huge finite one would cut the segment off at t = 0 there.) */
      if (r->o[k] < n->lo[k] || r->o[k] > n->hi[k]) return 0;
      continue;
    }
    const REAL t0 = (n->lo[k] - r->o[k]) * r->inv[k], t1 = (n->hi[k] - r->o[k]) * r->inv[k];
    near = fmax(near, fmin(t0, t1));
    t_far = fmin(t_far, fmax(t0, t1));
  }
  *t_near = near;
  return near <= t_far + fabs(t_far) * ARCUS_BVH_SLACK;
}

/* Closed boxes [lo, hi] and the node's box overlap (touching counts). */
ARCUS_INLINE int bvh_node_overlaps(ARCUS_GLOBAL const bvh_node* n, const REAL* lo, const REAL* hi) {
  return n->lo[0] <= hi[0] && lo[0] <= n->hi[0] && n->lo[1] <= hi[1] && lo[1] <= n->hi[1] && n->lo[2] <= hi[2] &&
         lo[2] <= n->hi[2];
}

/* The bounding box of the triangle in slot `tri` overlaps [lo, hi]. */
ARCUS_INLINE int bvh_triangle_box_overlaps(ARCUS_GLOBAL const REAL* tri, const REAL* lo, const REAL* hi) {
  for (int k = 0; k < 3; ++k)
    if (fmin(fmin(tri[k], tri[3 + k]), tri[6 + k]) > hi[k] || fmax(fmax(tri[k], tri[3 + k]), tri[6 + k]) < lo[k])
      return 0;
  return 1;
}

/* A resumable depth-first walk: nodes on the stack have passed their box test (near:
 * where the segment enters them); [slot, end) is what remains of the current leaf.
 * Trees are at most ARCUS_BVH_MAX_DEPTH levels deep (the builder refuses deeper ones),
 * and a walk holds at most one pending sibling per level. */
typedef struct bvh_walk {
  int node[ARCUS_BVH_MAX_DEPTH];
  REAL near[ARCUS_BVH_MAX_DEPTH];
  int sp, slot, end;
} bvh_walk;

/* root_passes: the query meets the root's box.  The tree of no primitives (a root
 * with first −1) is never entered. */
ARCUS_INLINE void bvh_walk_start(bvh_walk* w, ARCUS_GLOBAL const bvh_node* nodes, int root_passes) {
  w->node[0] = 0;
  w->near[0] = 0;
  w->sp = root_passes && nodes[0].first >= 0 ? 1 : 0;
  w->slot = w->end = 0;
}

/* The next slot whose triangle the segment hits with t in [0, t_max] (its t, u, v
 * set), or -1 when the walk is over.  Nearer children first; a pending node that the
 * segment enters beyond t_max is skipped, so lowering t_max between calls (closest
 * hit) prunes the rest of the walk.  *tests grows by each box and triangle tested. */
ARCUS_INLINE int bvh_segment_next(ARCUS_GLOBAL const bvh_node* nodes, ARCUS_GLOBAL const REAL* tris,
                                  const bvh_ray* r, REAL t_max, bvh_walk* w, REAL* t, REAL* u, REAL* v, int* tests) {
  for (;;) {
    while (w->slot < w->end) {
      const int s = w->slot++;
      ++*tests;
      if (bvh_triangle_hit(r, tris + 9 * (size_t)s, t_max, t, u, v)) return s;
    }
    if (w->sp == 0) return -1;
    --w->sp;
    if (w->near[w->sp] > t_max) continue;
    int n = w->node[w->sp];
    for (;;) {
      const int first = nodes[n].first;
      if (nodes[n].count > 0) {
        w->slot = first;
        w->end = first + nodes[n].count;
        break;
      }
      REAL n0 = 0, n1 = 0;
      const int h0 = bvh_ray_box(r, nodes + first, t_max, &n0), h1 = bvh_ray_box(r, nodes + first + 1, t_max, &n1);
      *tests += 2;
      if (h0 && h1) {
        const int near_is_0 = n0 <= n1;
        w->node[w->sp] = near_is_0 ? first + 1 : first;
        w->near[w->sp] = near_is_0 ? n1 : n0;
        ++w->sp;
        n = near_is_0 ? first : first + 1;
      } else if (h0 || h1) {
        n = h0 ? first : first + 1;
      } else {
        break;
      }
    }
  }
}

/* The next slot whose triangle's bounding box overlaps the closed box [lo, hi], or -1. */
ARCUS_INLINE int bvh_box_next(ARCUS_GLOBAL const bvh_node* nodes, ARCUS_GLOBAL const REAL* tris, const REAL* lo,
                              const REAL* hi, bvh_walk* w) {
  for (;;) {
    while (w->slot < w->end) {
      const int s = w->slot++;
      if (bvh_triangle_box_overlaps(tris + 9 * (size_t)s, lo, hi)) return s;
    }
    if (w->sp == 0) return -1;
    int n = w->node[--w->sp];
    for (;;) {
      const int first = nodes[n].first;
      if (nodes[n].count > 0) {
        w->slot = first;
        w->end = first + nodes[n].count;
        break;
      }
      const int h0 = bvh_node_overlaps(nodes + first, lo, hi), h1 = bvh_node_overlaps(nodes + first + 1, lo, hi);
      if (h0 && h1) w->node[w->sp++] = first + 1;
      if (!h0 && !h1) break;
      n = h0 ? first : first + 1;
    }
  }
}

/* The closest hit of o + t·d, t in [0, t_max]: its leaf slot (the triangle is
 * tris + 9·slot, its original index the BVH's order[slot]) with *t, *u, *v set, or -1
 * (outputs untouched).  *tests grows by the boxes and triangles tested. */
ARCUS_INLINE int bvh_segment_closest(ARCUS_GLOBAL const bvh_node* nodes, ARCUS_GLOBAL const REAL* tris, REAL ox,
                                     REAL oy, REAL oz, REAL dx, REAL dy, REAL dz, REAL t_max, REAL* t, REAL* u,
                                     REAL* v, int* tests) {
  bvh_ray r;
  bvh_ray_init(&r, ox, oy, oz, dx, dy, dz);
  REAL near;
  bvh_walk w;
  ++*tests;
  bvh_walk_start(&w, nodes, bvh_ray_box(&r, nodes, t_max, &near));
  int hit = -1;
  REAL th, uh, vh;
  for (int s; (s = bvh_segment_next(nodes, tris, &r, t_max, &w, &th, &uh, &vh, tests)) >= 0;) {
    hit = s;
    t_max = th; /* only closer hits from now on */
    *t = th;
    *u = uh;
    *v = vh;
  }
  return hit;
}

/* Whether some triangle's bounding box overlaps the closed box [lo, hi]: 0 proves the
 * box holds no surface. */
ARCUS_INLINE int bvh_box_overlaps(ARCUS_GLOBAL const bvh_node* nodes, ARCUS_GLOBAL const REAL* tris, const REAL* lo,
                                  const REAL* hi) {
  bvh_walk w;
  bvh_walk_start(&w, nodes, bvh_node_overlaps(nodes, lo, hi));
  return bvh_box_next(nodes, tris, lo, hi, &w) >= 0;
}

#endif /* ARCUS_BVH_TRAVERSE_H */
