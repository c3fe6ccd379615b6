/* The photon map's batch kernels: one query per work-item (photon/photon_map.h says
 * why scalar).  Queries are a structure of arrays, q.count reals per component:
 * x y z, then (surface estimates) the unit normal nx ny nz.  The host prepends
 * common/real.h, bvh/bvh_desc.h, photon/photon_desc.h and photon/photon_map.h.      */

/* The radiance estimate of each query: values[i·channels + c], radius[i], found[i]. */
__kernel void arcus_photon_estimate(__global const bvh_node* nodes, __global const REAL* photons,
                                    const photon_map_desc map, __global const REAL* queries,
                                    const photon_query_desc q, __global REAL* values, __global REAL* radius,
                                    __global int* found) {
  const size_t i = get_global_id(0), n = (size_t)q.count;
  if (i >= n) return;
  REAL d2[ARCUS_PHOTON_SEARCH_CAPACITY];
  int slot[ARCUS_PHOTON_SEARCH_CAPACITY];
  REAL out[ARCUS_PHOTON_CHANNELS], r;
  const int surface = q.mode == ARCUS_PHOTON_SURFACE;
  const REAL nx = surface ? queries[3 * n + i] : RC(0), ny = surface ? queries[4 * n + i] : RC(0),
             nz = surface ? queries[5 * n + i] : RC(0);
  found[i] = photon_estimate(nodes, photons, map, queries[i], queries[n + i], queries[2 * n + i], nx, ny, nz, &q, d2,
                             slot, out, &r);
  radius[i] = r;
  for (int c = 0; c < map.channels; ++c) values[i * (size_t)map.channels + c] = out[c];
}

/* The k nearest photons of each query, nearest first (distance², then slot):
 * slots[i·k + j] and dist2[i·k + j]; -1 and +inf past the found[i] photons found.
 * A query with a non-zero normal (q.mode ARCUS_PHOTON_SURFACE) sees front-side photons
 * only, as the surface estimate does. */
__kernel void arcus_photon_knn(__global const bvh_node* nodes, __global const REAL* photons,
                               const photon_map_desc map, __global const REAL* queries, const photon_query_desc q,
                               __global int* slots, __global REAL* dist2, __global int* found) {
  const size_t i = get_global_id(0), n = (size_t)q.count, k = (size_t)q.k;
  if (i >= n) return;
  REAL d2[ARCUS_PHOTON_SEARCH_CAPACITY];
  int slot[ARCUS_PHOTON_SEARCH_CAPACITY];
  const int surface = q.mode == ARCUS_PHOTON_SURFACE;
  const REAL nx = surface ? queries[3 * n + i] : RC(0), ny = surface ? queries[4 * n + i] : RC(0),
             nz = surface ? queries[5 * n + i] : RC(0);
  const int m = photon_knn(nodes, photons, map, queries[i], queries[n + i], queries[2 * n + i], nx, ny, nz, q.k,
                           q.max_radius * q.max_radius, d2, slot);
  photon_sort(d2, slot, m);
  for (size_t j = 0; j < k; ++j) {
    const int in = (int)j < m;
    slots[i * k + j] = in ? slot[j] : -1;
    dist2[i * k + j] = in ? d2[j] : (REAL)INFINITY;
  }
  found[i] = m;
}

/* The k nearest photons at `steps` points `step` apart along each line, found as a
 * march finds them (photon/photon_line.h: a pool per stretch of the line, a lone search
 * where the pool cannot answer).  Line i starts at lines[i], lines[n + i],
 * lines[2n + i] and runs along the unit (lines[3n + i], lines[4n + i], lines[5n + i]),
 * n = q.count.  Per step j, at e = i·steps + j: the point searched from, points[3e ..],
 * the k-th distance radius[e] (the farthest found when fewer), and the set found as the
 * sum of its slots and of their squares, digest[2e], digest[2e + 1].  lone[i] counts
 * the line's steps searched alone. */
__kernel void arcus_photon_line_march(__global const bvh_node* nodes, __global const REAL* photons,
                                      const photon_map_desc map, __global const REAL* lines, const photon_query_desc q,
                                      const int steps, const REAL step, __global REAL* points, __global REAL* radius,
                                      __global long* digest, __global int* lone) {
  const size_t i = get_global_id(0), n = (size_t)q.count;
  if (i >= n) return;
  REAL d2[ARCUS_PHOTON_SEARCH_CAPACITY];
  int slot[ARCUS_PHOTON_SEARCH_CAPACITY];
  photon_line line;
  line.count = -1;
  const REAL ux = lines[3 * n + i], uy = lines[4 * n + i], uz = lines[5 * n + i];
  REAL r_last = (REAL)INFINITY;
  int alone = 0;
  for (int j = 0; j < steps; ++j) {
    const size_t e = i * (size_t)steps + (size_t)j;
    const REAL t = (REAL)j * step;
    const REAL x = lines[i] + t * ux, y = lines[n + i] + t * uy, z = lines[2 * n + i] + t * uz;
    points[3 * e] = x, points[3 * e + 1] = y, points[3 * e + 2] = z;
    const REAL g = step * RC(1.000001); /* the distance moved, rounding allowed for */
    int changes, fresh;
    REAL r = photon_line_query(nodes, photons, map, &line, x, y, z, ux, uy, uz, (REAL)(steps - 1 - j) * step, q.k,
                               r_last, g, d2, slot, &changes, &fresh);
    long sum = 0, sum2 = 0;
    if (r >= RC(0)) {
      for (int p = 0; p < line.count; ++p)
        if (line.in[p]) sum += line.slot[p], sum2 += (long)line.slot[p] * line.slot[p];
      r_last = r;
    } else {
      ++alone;
      const REAL limit = r_last + g;
      const int m = photon_knn(nodes, photons, map, x, y, z, RC(0), RC(0), RC(0), q.k, limit * limit, d2, slot);
      for (int p = 0; p < m; ++p) sum += slot[p], sum2 += (long)slot[p] * slot[p];
      r = m > 0 ? sqrt(d2[0]) : RC(0);
      r_last = m == q.k ? r : (REAL)INFINITY;
    }
    radius[e] = r;
    digest[2 * e] = sum;
    digest[2 * e + 1] = sum2;
  }
  lone[i] = alone;
}
