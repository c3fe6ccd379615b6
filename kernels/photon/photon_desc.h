/* What the photon map's kernels and the host share, declared once for both (a macro per
 * precision, as curved/advance_desc.h does): the limits, the layout of the photon
 * buffer and the two descriptions passed by value.
 *
 * A photon is a position, the unit direction it travelled (so it arrived from −dir)
 * and its power in `channels` channels.  The map stores its photons as a structure of
 * arrays in the BVH's leaf order (bvh/bvh_desc.h): component c of the photon in slot s
 * is photons[c·count + s], so a leaf's photons are contiguous in every component.   */
#ifndef ARCUS_PHOTON_DESC_H
#define ARCUS_PHOTON_DESC_H

#ifndef __OPENCL_C_VERSION__
#include "common/real.h" /* the device source has it prepended */
#endif

/* Power channels per photon: 1 to 9 chosen at run time (3 for RGB; the ocean engine's
 * event and its photons' wavelengths and powers, ocean/ocean_desc.h).  The limit keeps
 * an estimate's sums in private memory; more need a raise here. */
#define ARCUS_PHOTON_CHANNELS 9
/* Largest k of a k-nearest-neighbour query: its search's arrays live in private memory
 * (2 × 512 × (8 + 4) bytes in double precision). */
#define ARCUS_PHOTON_MAX_K 512
/* The search's scratch arrays (photon_map.h, photon_knn): room for the photons within
 * a bound a little beyond the k-th before they are cut down to k. */
#define ARCUS_PHOTON_SEARCH_CAPACITY (2 * ARCUS_PHOTON_MAX_K)

/* Components of the photon buffer, each `count` reals long. */
#define ARCUS_PHOTON_POSITION 0  /* x y z                                     */
#define ARCUS_PHOTON_DIRECTION 3 /* dx dy dz: unit, the direction travelled    */
#define ARCUS_PHOTON_POWER 6     /* one per channel                           */

/* Radiance estimates (the `mode` of a query). */
#define ARCUS_PHOTON_SURFACE 0 /* irradiance: Σ Φ / (π r²), front-side photons only   */
#define ARCUS_PHOTON_VOLUME 1  /* Σ Φ / (4/3 π r³), photons from every direction     */

#define ARCUS_DECLARE_PHOTON_MAP_DESC(NAME, I)                                           \
  typedef struct NAME {                                                                  \
    I count;    /* photons (slots)                                            */         \
    I channels; /* power channels, 1..ARCUS_PHOTON_CHANNELS                   */         \
  } NAME

#define ARCUS_DECLARE_PHOTON_QUERY_DESC(NAME, R, I)                                      \
  typedef struct NAME {                                                                  \
    R max_radius; /* the search radius cap (may be +inf)                      */         \
    R cone;       /* Jensen's cone filter constant (≥ 1), 0: no filter       */          \
    I k;          /* photons wanted, 1..ARCUS_PHOTON_MAX_K                    */         \
    I mode;       /* ARCUS_PHOTON_SURFACE or ARCUS_PHOTON_VOLUME              */         \
    I count;      /* queries; the query buffers hold `count` reals per component */      \
    I pad;        /* keeps host and device sizes alike                         */        \
  } NAME

#ifdef __OPENCL_C_VERSION__
ARCUS_DECLARE_PHOTON_MAP_DESC(photon_map_desc, int);
ARCUS_DECLARE_PHOTON_QUERY_DESC(photon_query_desc, REAL, int);
#else
ARCUS_DECLARE_PHOTON_MAP_DESC(arcus_photon_map_desc, int32_t);
ARCUS_DECLARE_PHOTON_QUERY_DESC(arcus_photon_query_desc, double, int32_t); /* maps are double today */
#endif

#endif /* ARCUS_PHOTON_DESC_H */
