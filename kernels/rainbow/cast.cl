/* The cast (thesis §4.4.3.1): one grid ray per work-item, traced through p = 0..P by
 * rb_trace (rainbow/optics.h).  Scalar: a ray's path through the particle is short
 * and branchy, and the cast is a small part of a phase function's time (the queries
 * and the BVH build dominate: bench/README.md).
 *
 * nodes, tris, order, normals   a mesh particle (rb_mesh in optics.h); null otherwise
 * points   the rays' (u, v) on the incident plane, 2 per ray
 * records  (P + 1) × rays records: term p of ray r at (p·rays + r)·ARCUS_RAINBOW_RECORD
 * left     per ray: the power still inside after P, −1 for a ray that missed
 *
 * Host prepends: common/real.h, bvh/bvh_desc.h, bvh/traverse.h, rainbow/rainbow_desc.h,
 * rainbow/optics.h. */
__kernel void arcus_rainbow_cast(ARCUS_PARAMS(ARCUS_RAINBOW_CAST_ARGS)) {
  const int r = d.first + (int)get_global_id(0);
  if (r >= d.first + d.count) return;
  rb_mesh m;
  m.nodes = nodes;
  m.tris = tris;
  m.order = order;
  m.normals = normals;
  left[r] = rb_trace(&d, &m, points[2 * r], points[2 * r + 1], records + (size_t)r * ARCUS_RAINBOW_RECORD,
                     (size_t)rays * ARCUS_RAINBOW_RECORD);
}
