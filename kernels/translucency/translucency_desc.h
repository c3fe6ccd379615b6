/* The translucency engine's gather kernels (gather.cl) and their arguments, written once
 * for host and kernel (core/launch.h).  Both compute, for each exit point x_o, the
 * integral of thesis eq. 3.6 without its exit term: Σ_i R_d(|x_o − x_i|) E_i ΔA_i over
 * the irradiance samples, per channel (src/translucency/render.cpp adds (1/π)F_t).
 *
 *   exits      the exit points [mm], three planes x, y, z of `stride` REALs each
 *   samples    3 REALs per irradiance sample: its position [mm]
 *   powers     3 REALs per sample: E·ΔA per channel
 *   channels   ARCUS_DIPOLE_TERMS REALs per channel (dipole_rd.h); with a table
 *              (ARCUS_USE_PROFILE_TABLE) `table_size` samples per channel, channel-major,
 *              at r_k = reach (k / (size − 1))² (arcus_profile_table)
 *   table_size, table_reach   the table's samples per channel and reach [mm] (0 without)
 *   sums       the result, three planes R, G, B of `stride` REALs each
 *   first, count   the slice of points (brute force: of lane groups) this launch runs
 *
 * The hierarchical kernel (ARCUS_USE_HIERARCHICAL; Jensen & Buhler 2002) walks a BVH
 * over the samples (bvh/bvh_desc.h's layout; samples stored in leaf order) whose nodes
 * carry CLUSTER_SIZE REALs each in `clusters`: the node's summed powers, its centroid
 * (weighted by the summed power of the three channels), its area and the covariance of
 * its samples.  A node seen under a solid angle area/d² below `max_solid_angle` from a
 * point outside its box counts as one sample at its centroid; the dipole adds the
 * second-order term of R_d's Taylor expansion about the centroid over that covariance. */
#ifndef ARCUS_TRANSLUCENCY_DESC_H
#define ARCUS_TRANSLUCENCY_DESC_H

#define ARCUS_CLUSTER_POWER 0    /* 3: Σ E·ΔA per channel                 */
#define ARCUS_CLUSTER_CENTROID 3 /* 3: the power-weighted mean position    */
#define ARCUS_CLUSTER_AREA 6     /* Σ ΔA [mm²]                              */
#define ARCUS_CLUSTER_SPREAD 8   /* 6: the samples' covariance about the centroid, same
                                    weights [mm²]: xx, yy, zz, xy, xz, yz     */
#define ARCUS_CLUSTER_SIZE 14

#define ARCUS_TRANSLUCENCY_GATHER_ALL_ARGS(X)                                                   \
  X(__global const REAL*, exits) X(__global const REAL*, samples) X(__global const REAL*, powers) \
  X(__global const REAL*, channels) X(__global REAL*, sums) X(const uint, stride) X(const uint, sample_count) \
  X(const uint, table_size) X(const REAL, table_reach) X(const uint, first) X(const uint, count)

#define ARCUS_TRANSLUCENCY_GATHER_TREE_ARGS(X)                                                  \
  X(__global const REAL*, exits) X(__global const REAL*, samples) X(__global const REAL*, powers) \
  X(__global const REAL*, channels) X(__global REAL*, sums) X(const uint, stride)               \
  X(const uint, table_size) X(const REAL, table_reach) X(__global const bvh_node*, nodes) X(__global const REAL*, clusters) X(const REAL, max_solid_angle) \
  X(__global uint*, visits) X(const uint, first) X(const uint, count)

/* Distance histograms (histogram.cl, ARCUS_USE_HISTOGRAM): per row point (a work-item
 * each), Σ over the sources of their `weights_per_source` weights by the bin of their
 * distance r: `bins` bins up to `reach` mm, uniform in r, or in √r when `sqrt_bins`
 * (bin k covers reach·[(k/bins)², ((k+1)/bins)²)); sources beyond add nothing.
 * histograms: per row bins × weights_per_source REALs, bin-major.  The estimate's eq.
 * 3.16 (three channels) and the genetic search's cache (src/translucency/appearance.h). */
#define ARCUS_MAX_HISTOGRAM_BINS 256
#define ARCUS_MAX_HISTOGRAM_CELLS 1536 /* bins × weights_per_source, in private memory */
#define ARCUS_TRANSLUCENCY_HISTOGRAM_ARGS(X)                                                          \
  X(__global const REAL*, rows) X(__global const REAL*, sources) X(__global const REAL*, weights)      \
  X(__global REAL*, histograms) X(const uint, source_count) X(const uint, bins)                       \
  X(const uint, weights_per_source) X(const REAL, reach) X(const uint, sqrt_bins) X(const uint, first) \
  X(const uint, count)

#endif /* ARCUS_TRANSLUCENCY_DESC_H */
