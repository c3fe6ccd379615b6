// A particle's phase function by ray casting (thesis §4.4.3): the grid cast and traced
// on the device (kernels/rainbow/cast.cl), the rays moved onto the projected edge, the
// collecting sphere's patches normalised by eq. 4.29 under one BVH, and the queries
// (kernels/rainbow/query.cl).  The job keeps the patches on the device for queries.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "arcus/arcus_rainbow.h"
#include "bvh/device_bvh.h"
#include "core/buffer.h"
#include "core/job.h"
#include "rainbow/particle.h"

namespace arcus::rainbow {

struct CastParams {
  double wavelength_nm = 550;
  double n = 1.333;             // the particle's refractive index relative to air
  int grid = 1000;
  double alpha = 0.3;
  int bounces = 3;
  bool edge_rays = true;
  double rotation[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  double query_phi_deg = 0;     // NaN: every azimuth
};

void check_cast(const CastParams& params);
// A rotation matrix (9 reals, row-major): finite, orthonormal, determinant +1, to
// rounding; the message names it `name`.
void check_rotation(const double* rotation, const std::string& name);

// A flat-faced mesh in one orientation sends all the rays of one sequence of faces
// into one direction: a glint, which no patch can hold.  Its books: the term, the
// direction, the cast area whose rays feed it and the power it carries per unit
// irradiance [m²], unpolarised.
struct Glint {
  int p = 0;
  double direction[3] = {0, 0, 0};
  double area = 0, cross_section = 0;
};

struct RainbowJob : arcus_job_s {
  explicit RainbowJob(arcus_context_t* ctx) : arcus_job_s(ctx, "rainbow") {}
  int terms = 0;                 // P + 1
  double wave_number = 0;        // 2π/λ [1/m]
  double query_phi_deg = 0;
  arcus_rainbow_stats info{};
  double cross_section = 0;      // the scattered power of p = 0..P per unit irradiance [m²]
  size_t patch_count = 0;
  std::vector<Glint> glints;     // flat meshes only
  std::unique_ptr<bvh::DeviceBvh> bvh;
  std::unique_ptr<DeviceBuffer> corners, patches;
};

arcus_features cast_features(const Particle& particle);

// Casts, traces and builds the patches.  *cancelled: the progress callback stopped the
// cast (the job then answers nothing: every query is zero).
std::unique_ptr<RainbowJob> cast(arcus_context_t* ctx, const Particle& particle, const CastParams& params,
                                 arcus_progress_callback progress, void* progress_user, bool* cancelled);

// Per direction (unit, 3 reals each) and term: ARCUS_RAINBOW_QUERY_REALS reals.  uniform:
// the two rays of a fold caustic are summed by the uniform (Airy) approximation
// (query.cl); otherwise plainly, as eq. 4.31.
std::vector<double> query(arcus_context_t* ctx, RainbowJob& job, const std::vector<double>& directions,
                          bool uniform);

// The phase function of eq. 4.32-4.34 for unpolarised light from the query's sums,
// normalised over p = 0..P (arcus_job_get_rainbow_phase).
struct Phase {
  std::vector<double> parallel, perpendicular, per_bounce;  // per_bounce: count × terms
};
Phase phase(const RainbowJob& job, const std::vector<double>& sums, bool coherent);

// Unit directions of (θ, φ) in degrees: (sin θ cos φ, sin θ sin φ, cos θ).
std::vector<double> directions(const std::vector<double>& theta_deg, const std::vector<double>& phi_deg);

}  // namespace arcus::rainbow
