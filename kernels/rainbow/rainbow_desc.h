/* What the rainbow engine's host (src/rainbow/) and kernels (kernels/rainbow/) share:
 * the particle's shape, the cast's parameters and the layout of the traced rays and of
 * the collecting sphere's patches.  Host and device both include this file.
 *
 * A traced ray leaves one record per term p = 0..P (thesis §4.4.3.1, Fig. 4.18): p = 0
 * reflected outside, p ≥ 1 out after p refractions... precisely, entered and left with
 * p − 1 internal reflections between.  A record is ARCUS_RAINBOW_RECORD reals:
 *   [0..2]  the outgoing direction (world, unit)
 *   [3..10] the phasors E_hθ, E_hφ, E_vθ, E_vφ (re, im): the field of the horizontally
 *           (x) and vertically (y) polarised incident wave, on the outgoing (θ, φ)
 *           frame, scaled so that |E|² is the ray's share of power (no spreading yet)
 *   [11]    the optical path from the incident reference plane through the particle's
 *           centre to the outgoing one (eq. 4.24-4.25, Fig. 4.14) [m]
 *   [12]    1 when the term exists (it hit, and for p ≥ 1 was not totally reflected)
 *   [13]    the sequence of faces it met (meshes; 0 otherwise): patches join only rays
 *           of one sequence, one wavefront
 *   [14]    the focal lines it passed (optics.h counts them)                            */
#ifndef ARCUS_RAINBOW_DESC_H
#define ARCUS_RAINBOW_DESC_H

#ifndef __OPENCL_C_VERSION__
#include <stdint.h>
#include "common/real.h"
#define RAINBOW_INT int32_t
#else
#define RAINBOW_INT int
#endif

#define ARCUS_RAINBOW_RECORD 15
#define ARCUS_RAINBOW_MAX_BOUNCES 15

#define ARCUS_RAINBOW_SHAPE_SPHERE 0
#define ARCUS_RAINBOW_SHAPE_RAINDROP 1
#define ARCUS_RAINBOW_SHAPE_MESH 2

/* The cast, by value to the kernel.  rotation: the particle's frame → world (row-major);
 * shape: sphere {radius}; raindrop {a, b, k, bound radius} (eq. 4.21); mesh {bound
 * radius, the offset that steps a ray off the face it starts on}. */
#define ARCUS_DECLARE_RAINBOW_CAST(NAME, R, I) \
  typedef struct NAME {                        \
    R rotation[9];                             \
    R shape[4];                                \
    R n;          /* particle / air            */ \
    R plane;      /* the incident plane: z = −plane */ \
    I kind;       /* ARCUS_RAINBOW_SHAPE_*     */ \
    I bounces;    /* P                         */ \
    I first, count;                            \
  } NAME

#ifdef __OPENCL_C_VERSION__
ARCUS_DECLARE_RAINBOW_CAST(rainbow_cast_desc, REAL, int);
#else
ARCUS_DECLARE_RAINBOW_CAST(rainbow_cast_desc, double, int32_t);
#endif

/* The cast kernel's arguments, X(type, name) (ARCUS_PARAMS; src/core/launch.h): the
 * mesh's BVH (NULL for other shapes), its vertex normals, the (u, v) grid, the cast,
 * and what each ray leaves. */
#define ARCUS_RAINBOW_CAST_ARGS(X)  \
  X(__global const bvh_node*, nodes) \
  X(__global const REAL*, tris)      \
  X(__global const int*, order)      \
  X(__global const REAL*, normals)   \
  X(__global const REAL*, points)    \
  X(const rainbow_cast_desc, d)      \
  X(const int, rays)                 \
  X(__global REAL*, records)         \
  X(__global REAL*, left)

/* A patch on the collecting sphere (thesis §4.4.3.2, Fig. 4.19): the four corner
 * records of one term p at grid corners (i, j), (i+1, j), (i+1, j+1), (i, j+1), in that
 * order.  The host has normalised the corners' amplitudes by eq. 4.29 and turned their
 * phasors by their focal lines (eq. 4.31).  The BVH holds two chord triangles per patch:
 * corners (0, 1, 2) and (0, 2, 3); triangle t belongs to patch t / 2. */
typedef struct rainbow_patch {
  RAINBOW_INT corner[4];
  RAINBOW_INT p;
} rainbow_patch;

/* The query, by value: its directions' count, the wave number 2π/λ [1/m], and whether
 * the two rays of a fold caustic are summed by the uniform approximation (query.cl). */
#define ARCUS_DECLARE_RAINBOW_QUERY(NAME, R, I) \
  typedef struct NAME {                         \
    R wave_number;                              \
    I count, terms, coherent;                   \
  } NAME

#ifdef __OPENCL_C_VERSION__
ARCUS_DECLARE_RAINBOW_QUERY(rainbow_query_desc, REAL, int);
#else
ARCUS_DECLARE_RAINBOW_QUERY(rainbow_query_desc, double, int32_t);
#endif

/* The query kernel's arguments: the patches' chord BVH, their corners, the patches,
 * the directions, the query and the sums. */
#define ARCUS_RAINBOW_QUERY_ARGS(X)          \
  X(__global const bvh_node*, nodes)         \
  X(__global const REAL*, tris)              \
  X(__global const int*, order)              \
  X(__global const REAL*, corners)           \
  X(__global const rainbow_patch*, patches)  \
  X(__global const REAL*, dirs)              \
  X(const rainbow_query_desc, q)             \
  X(__global REAL*, out)

/* A patch corner for the queries: direction (3), the four phasors (8) normalised by
 * eq. 4.29 and turned by −π/2 per focal line, optical path (1), focal lines (1). */
#define ARCUS_RAINBOW_CORNER 13

/* Per direction and term: the 8 reals of the summed phasors, then the 4 intensities
 * |E_hθ|², |E_hφ|², |E_vθ|², |E_vφ|² summed without phases. */
#define ARCUS_RAINBOW_QUERY_REALS 12

/* A sky render (sky.cl), by value: the image and camera (a pinhole: the ray through
 * pixel (i, j) is forward + u·right + v·up with u, v spanning ±half_width, ±half_height),
 * the sun's direction and the light frame of its centre (light along −sun; +x_light,
 * +y_light the table's φ = 0° and 90°), the box of rain, the table's θ samples and
 * sizes, the slice of pixels this launch does, and whether the sky is an image. */
#define ARCUS_DECLARE_RAINBOW_SKY(NAME, R, I) \
  typedef struct NAME {                       \
    R camera[3], forward[3], right[3], up[3]; \
    R half_width, half_height;                \
    R sun[3], x_light[3], y_light[3];         \
    R box_min[3], box_max[3];                 \
    R theta_first, theta_step; /* degrees */  \
    I width, height, steps;                   \
    I wavelengths, thetas, phis;              \
    I first, count;                           \
    I sky_image, padding; /* 1: sky_rgb */    \
  } NAME

#ifdef __OPENCL_C_VERSION__
ARCUS_DECLARE_RAINBOW_SKY(rainbow_sky_desc, REAL, int);
#else
ARCUS_DECLARE_RAINBOW_SKY(rainbow_sky_desc, double, int32_t);
#endif

/* The sky kernel's arguments: the disc-averaged table, the spectra (extinction, sun,
 * sky, ground), the sky image behind each pixel and its spectra, the colour weights,
 * the render, and the XYZ and θ images. */
#define ARCUS_RAINBOW_SKY_ARGS(X)        \
  X(__global const REAL*, beta)          \
  X(__global const REAL*, extinction)    \
  X(__global const REAL*, sun)           \
  X(__global const REAL*, sky)           \
  X(__global const REAL*, ground)        \
  X(__global const float*, sky_rgb)      \
  X(__global const REAL*, sky_basis)     \
  X(__global const REAL*, weights)       \
  X(const rainbow_sky_desc, s)           \
  X(__global float*, xyz)                \
  X(__global float*, theta_out)

#endif /* ARCUS_RAINBOW_DESC_H */
