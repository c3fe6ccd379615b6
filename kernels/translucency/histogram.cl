/* The estimate's heavy part (thesis eq. 3.16; translucency_desc.h): per equation point,
 * the histogram over distance of the sources' irradiance × area, per channel, and the
 * bins' first moments (Σ over the channels of the weight times the distance).  One row
 * a work-item with its histogram in private memory; a basis function's column is then a
 * weighted sum of bins (src/translucency/estimate.cpp). */
#ifndef ARCUS_USE_HISTOGRAM
#error "the histogram kernel is built only with its TRANSLUCENCY_HISTOGRAM feature"
#endif

kernel void arcus_translucency_histogram(ARCUS_PARAMS(ARCUS_TRANSLUCENCY_HISTOGRAM_ARGS)) {
  const uint item = (uint)get_global_id(0);
  if (item >= count) return;
  const uint row = first + item;
  REAL h[4 * ARCUS_MAX_HISTOGRAM_BINS];
  for (uint k = 0; k < 4 * bins; ++k) h[k] = RC(0.0);
  const REAL x = rows[3 * (size_t)row], y = rows[3 * (size_t)row + 1], z = rows[3 * (size_t)row + 2];
  const REAL inverse = RC(1.0) / bin_width;
  for (uint s = 0; s < source_count; ++s) {
    const REAL dx = x - sources[3 * (size_t)s], dy = y - sources[3 * (size_t)s + 1], dz = z - sources[3 * (size_t)s + 2];
    const REAL r = sqrt(dx * dx + dy * dy + dz * dz), bin = r * inverse;
    if (bin >= (REAL)bins) continue;
    const uint b = (uint)bin;
    const REAL w0 = weights[3 * (size_t)s], w1 = weights[3 * (size_t)s + 1], w2 = weights[3 * (size_t)s + 2];
    h[4 * b] += w0;
    h[4 * b + 1] += w1;
    h[4 * b + 2] += w2;
    h[4 * b + 3] += (w0 + w1 + w2) * r;
  }
  __global REAL* out = histograms + (size_t)row * 4 * bins;
  for (uint k = 0; k < 4 * bins; ++k) out[k] = h[k];
}
