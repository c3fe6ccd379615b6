/* Distance histograms (translucency_desc.h): per row point, the sources' weights summed
 * by the bin of their distance, `weights_per_source` sums a bin.  The estimate's eq.
 * 3.16 (three channels, bins uniform in r) and the genetic search's cache (channels ×
 * η nodes, bins uniform in √r, fine where R_d peaks).  One row a work-item, its
 * histogram in private memory. */
#ifndef ARCUS_USE_HISTOGRAM
#error "the histogram kernel is built only with its TRANSLUCENCY_HISTOGRAM feature"
#endif

kernel void arcus_translucency_histogram(ARCUS_PARAMS(ARCUS_TRANSLUCENCY_HISTOGRAM_ARGS)) {
  const uint item = (uint)get_global_id(0);
  if (item >= count) return;
  const uint row = first + item;
  const uint cells = bins * weights_per_source;
  REAL h[ARCUS_MAX_HISTOGRAM_CELLS];
  for (uint k = 0; k < cells; ++k) h[k] = RC(0.0);
  const REAL x = rows[3 * (size_t)row], y = rows[3 * (size_t)row + 1], z = rows[3 * (size_t)row + 2];
  const REAL inverse = RC(1.0) / reach;
  for (uint s = 0; s < source_count; ++s) {
    const REAL dx = x - sources[3 * (size_t)s], dy = y - sources[3 * (size_t)s + 1], dz = z - sources[3 * (size_t)s + 2];
    const REAL r = sqrt(dx * dx + dy * dy + dz * dz) * inverse;
    const REAL bin = (sqrt_bins ? sqrt(r) : r) * (REAL)bins;
    if (bin >= (REAL)bins) continue;
    const uint at = (uint)bin * weights_per_source;
    __global const REAL* w = weights + (size_t)s * weights_per_source;
    for (uint k = 0; k < weights_per_source; ++k) h[at + k] += w[k];
  }
  __global REAL* out = histograms + (size_t)row * cells;
  for (uint k = 0; k < cells; ++k) out[k] = h[k];
}
