/* The gather of thesis eq. 3.6 (translucency_desc.h): per exit point, Σ R_d E ΔA over
 * the irradiance samples.  Two kernels, one per program (the feature decides):
 *   arcus_translucency_gather_all   every sample for every point: the reference, with
 *                                   ARCUS_LANES points side by side (PoCL runs a
 *                                   per-item loop scalar, lanes make it vector code)
 *   arcus_translucency_gather_tree  the hierarchical method (ARCUS_USE_HIERARCHICAL):
 *                                   one point a work-item, lanes 1, a stack walk */
#if defined(ARCUS_USE_DIPOLE) == defined(ARCUS_USE_PROFILE_TABLE)
#error "the gather evaluates one profile: built with TRANSLUCENCY_DIPOLE or TRANSLUCENCY_TABLE"
#endif

#ifdef ARCUS_USE_DIPOLE
/* The dipole's terms in private memory: the loop reads them for every pair. */
#define ARCUS_PROFILE_SETUP                     \
  REAL ch[3 * ARCUS_DIPOLE_TERMS];              \
  for (int k = 0; k < 3 * ARCUS_DIPOLE_TERMS; ++k) ch[k] = channels[k]
/* Σ over channels c of p_c·R_d,c(r²) into acc[c]. */
#define ARCUS_ADD_SAMPLE(acc, r2, p0, p1, p2)                                                            \
  do {                                                                                                    \
    (acc)[0] += (p0) * arcus_dipole_rd((r2), ch[0], ch[1], ch[2], ch[3]);                                  \
    (acc)[1] += (p1) * arcus_dipole_rd((r2), ch[4], ch[5], ch[6], ch[7]);                                  \
    (acc)[2] += (p2) * arcus_dipole_rd((r2), ch[8], ch[9], ch[10], ch[11]);                                \
  } while (0)
#else
#if ARCUS_LANES != 1
#error "a table is read one point a work-item (lanes 1)"
#endif
/* Position in the table, r = reach (k / (size − 1))²: k = (size − 1) √(r / reach). */
#define ARCUS_PROFILE_SETUP const REAL to_index = (REAL)(table_size - 1) / sqrt(table_reach)
#define ARCUS_ADD_SAMPLE(acc, r2, p0, p1, p2)                                 \
  do {                                                                         \
    const REAL u = sqrt(sqrt(r2)) * to_index;                                  \
    if (u < (REAL)(table_size - 1)) {                                          \
      const uint k = (uint)u;                                                  \
      const REAL f = u - (REAL)k;                                              \
      __global const REAL* t = channels + k;                                   \
      (acc)[0] += (p0) * mix(t[0], t[1], f);                                   \
      (acc)[1] += (p1) * mix(t[table_size], t[table_size + 1], f);             \
      (acc)[2] += (p2) * mix(t[2 * table_size], t[2 * table_size + 1], f);     \
    }                                                                          \
  } while (0)
#endif

#ifndef ARCUS_USE_HIERARCHICAL

kernel void arcus_translucency_gather_all(ARCUS_PARAMS(ARCUS_TRANSLUCENCY_GATHER_ALL_ARGS)) {
  const uint item = (uint)get_global_id(0);
  if (item * ARCUS_GROUPS >= count) return;
  ARCUS_PROFILE_SETUP;
  /* This item's lane groups of points; past the slice's end a group repeats its last
   * one (slices need not be whole work-items). */
  uint at[ARCUS_GROUPS];
  FOR_GROUPS(g) at[g] = min(first + item * ARCUS_GROUPS + g, first + count - 1);
  REALV x[ARCUS_GROUPS], y[ARCUS_GROUPS], z[ARCUS_GROUPS], acc[ARCUS_GROUPS][3];
  FOR_GROUPS(g) {
    x[g] = VLOAD(at[g], exits);
    y[g] = VLOAD(at[g], exits + stride);
    z[g] = VLOAD(at[g], exits + 2 * (size_t)stride);
    acc[g][0] = acc[g][1] = acc[g][2] = RC(0.0);
  }
  for (uint s = 0; s < sample_count; ++s) {
    const REAL sx = samples[3 * (size_t)s], sy = samples[3 * (size_t)s + 1], sz = samples[3 * (size_t)s + 2];
    const REAL p0 = powers[3 * (size_t)s], p1 = powers[3 * (size_t)s + 1], p2 = powers[3 * (size_t)s + 2];
    FOR_GROUPS(g) {
      const REALV dx = x[g] - sx, dy = y[g] - sy, dz = z[g] - sz;
      const REALV r2 = dx * dx + dy * dy + dz * dz;
      ARCUS_ADD_SAMPLE(acc[g], r2, p0, p1, p2);
    }
  }
  FOR_GROUPS(g) {
    VSTORE(acc[g][0], at[g], sums);
    VSTORE(acc[g][1], at[g], sums + stride);
    VSTORE(acc[g][2], at[g], sums + 2 * (size_t)stride);
  }
}

#else

#ifdef ARCUS_USE_DIPOLE
/* The tree walk holds one point a work-item, which PoCL runs as scalar code: a sample's
 * six exponentials (three channels, two sources) go as one 8-wide vector here, lanes 0–2
 * the real sources and 4–6 the virtual ones (3 and 7 idle: z 1, weight 0).  Measured:
 * docs/translucency.md ("Speed"). */
#define REAL8 ARCUS_CAT(REAL, 8)
#define ARCUS_TREE_SETUP                                                                                  \
  const REAL8 z8 = (REAL8)(channels[0], channels[4], channels[8], RC(1.0), channels[1], channels[5],     \
                           channels[9], RC(1.0));                                                         \
  const REAL8 s8 = (REAL8)(channels[2], channels[6], channels[10], RC(0.0), channels[2], channels[6],    \
                           channels[10], RC(0.0));                                                        \
  const REAL8 w8 = (REAL8)(channels[3], channels[7], channels[11], RC(0.0), channels[3], channels[7],    \
                           channels[11], RC(0.0)) * z8
#define ARCUS_TREE_ADD(acc, r2, p0, p1, p2)                                                              \
  do {                                                                                                    \
    const REAL8 d = sqrt((REAL8)(r2) + z8 * z8);                                                          \
    const REAL8 t = w8 * (RC(1.0) + s8 * d) * exp(-s8 * d) / (d * d * d);                                 \
    (acc)[0] += (p0) * (t.s0 + t.s4);                                                                     \
    (acc)[1] += (p1) * (t.s1 + t.s5);                                                                     \
    (acc)[2] += (p2) * (t.s2 + t.s6);                                                                     \
  } while (0)
/* A node taken whole: R_d's Taylor expansion in the sample's position y about the
 * centroid c to second order, averaged over the node's samples (covariance Σ, mean c):
 * R(u) + R′(u)·tr Σ + 2R″(u)·aᵀΣa, with u = |a|², a = x − c and, per source (s = σ_tr d,
 * d = √(u + z²)), R = C(1 + s), R′ = −C(s² + 3s + 3)/(2d²), R″ = C(s³ + 6s² + 15s + 15)/(4d⁴),
 * C = w z e^{−s}/d³.  The first-order term vanishes about the mean; what is left is third
 * order in the node's size over its distance (docs/translucency.md). */
#define ARCUS_TREE_ADD_NODE(acc, u, trace, quad, p0, p1, p2)                                             \
  do {                                                                                                    \
    const REAL8 d2 = (REAL8)(u) + z8 * z8, d = sqrt(d2), s = s8 * d;                                      \
    const REAL8 c = w8 * exp(-s) / (d2 * d);                                                              \
    const REAL8 t = c * (RC(1.0) + s - (REAL8)(trace) * (s * s + RC(3.0) * s + RC(3.0)) / (RC(2.0) * d2) + \
                         (REAL8)(quad) * (((s + RC(6.0)) * s + RC(15.0)) * s + RC(15.0)) / (RC(2.0) * d2 * d2)); \
    (acc)[0] += (p0) * (t.s0 + t.s4);                                                                     \
    (acc)[1] += (p1) * (t.s1 + t.s5);                                                                     \
    (acc)[2] += (p2) * (t.s2 + t.s6);                                                                     \
  } while (0)
#else
#define ARCUS_TREE_SETUP ARCUS_PROFILE_SETUP
#define ARCUS_TREE_ADD ARCUS_ADD_SAMPLE
/* A table has no derivatives here: a node is one sample at its centroid. */
#define ARCUS_TREE_ADD_NODE(acc, u, trace, quad, p0, p1, p2) ARCUS_ADD_SAMPLE(acc, u, p0, p1, p2)
#endif

/* Squared distance from p to the box (0 inside). */
ARCUS_INLINE REAL box_distance2(__global const bvh_node* n, REAL px, REAL py, REAL pz) {
  const REAL p[3] = {px, py, pz};
  REAL d2 = RC(0.0);
  for (int a = 0; a < 3; ++a) {
    const REAL below = n->lo[a] - p[a], above = p[a] - n->hi[a];
    const REAL d = fmax(RC(0.0), fmax(below, above));
    d2 += d * d;
  }
  return d2;
}

kernel void arcus_translucency_gather_tree(ARCUS_PARAMS(ARCUS_TRANSLUCENCY_GATHER_TREE_ARGS)) {
  const uint item = (uint)get_global_id(0);
  if (item >= count) return;
  const uint point = first + item;
  ARCUS_TREE_SETUP;
  const REAL x = exits[point], y = exits[stride + point], z = exits[2 * (size_t)stride + point];
  REAL acc[3] = {RC(0.0), RC(0.0), RC(0.0)};
  uint visited = 0;
  int stack[ARCUS_BVH_MAX_DEPTH + 1];
  int top = 0;
  if (nodes[0].first >= 0) stack[top++] = 0;
  while (top > 0) {
    const int at = stack[--top];
    __global const bvh_node* n = nodes + at;
    __global const REAL* c = clusters + (size_t)at * ARCUS_CLUSTER_SIZE;
    ++visited;
    const REAL p0 = c[ARCUS_CLUSTER_POWER], p1 = c[ARCUS_CLUSTER_POWER + 1], p2 = c[ARCUS_CLUSTER_POWER + 2];
    if (p0 == RC(0.0) && p1 == RC(0.0) && p2 == RC(0.0)) continue; /* unlit: adds nothing */
    const REAL dx = x - c[ARCUS_CLUSTER_CENTROID], dy = y - c[ARCUS_CLUSTER_CENTROID + 1],
               dz = z - c[ARCUS_CLUSTER_CENTROID + 2];
    const REAL r2 = dx * dx + dy * dy + dz * dz;
    /* Far enough: the node taken whole (ARCUS_TREE_ADD_NODE) when, from outside its box,
     * both its area and 6× its samples' variance (a compact node's area; a long thin one's
     * extent) over d² are below the bound (Jensen & Buhler 2002 test the area alone). */
    __global const REAL* v = c + ARCUS_CLUSTER_SPREAD; /* xx, yy, zz, xy, xz, yz */
    const REAL trace = v[0] + v[1] + v[2];
    if (box_distance2(n, x, y, z) > RC(0.0) && fmax(c[ARCUS_CLUSTER_AREA], RC(6.0) * trace) < max_solid_angle * r2) {
      const REAL quad = dx * dx * v[0] + dy * dy * v[1] + dz * dz * v[2] +
                        RC(2.0) * (dx * dy * v[3] + dx * dz * v[4] + dy * dz * v[5]);
      ARCUS_TREE_ADD_NODE(acc, r2, trace, quad, p0, p1, p2);
    } else if (n->count > 0) {
      for (int s = n->first; s < n->first + n->count; ++s) {
        const REAL ex = x - samples[3 * (size_t)s], ey = y - samples[3 * (size_t)s + 1],
                   ez = z - samples[3 * (size_t)s + 2];
        const REAL q2 = ex * ex + ey * ey + ez * ez;
        ARCUS_TREE_ADD(acc, q2, powers[3 * (size_t)s], powers[3 * (size_t)s + 1], powers[3 * (size_t)s + 2]);
      }
    } else {
      stack[top++] = n->first;
      stack[top++] = n->first + 1;
    }
  }
  sums[point] = acc[0];
  sums[stride + point] = acc[1];
  sums[2 * (size_t)stride + point] = acc[2];
  visits[point] = visited;
}

#endif
