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
