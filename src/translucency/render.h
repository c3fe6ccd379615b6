// Rendering a translucent object (thesis eq. 3.6–3.8): irradiance samples over the
// surface (surface.h), then per pixel the gather of kernels/translucency/gather.cl —
// every sample (the reference) or a BVH over them with far nodes taken whole (Jensen &
// Buhler 2002) — times the exit term, plus a Fresnel-weighted Phong highlight.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "arcus/arcus_translucency.h"
#include "core/job.h"
#include "geometry/mesh.h"
#include "translucency/dipole.h"

namespace arcus::translucency {

struct RenderJob : arcus_job_s {
  explicit RenderJob(arcus_context_t* ctx) : arcus_job_s(ctx, "translucency render") {}
  arcus_translucency_render_stats render{};
  std::vector<float> rgb, subsurface;  // 3 per pixel
  std::vector<uint8_t> covered;        // per pixel
};

// The most irradiance samples a render takes (~200 MB of host arrays).
constexpr uint64_t kMaxSamples = uint64_t(1) << 22;

// Hierarchical gather: the bound (sr) under which a node counts as one sample, when the
// caller gives 0.  The dipole takes a node with its second-order Taylor term (gather.cl),
// a table as one sample at its centroid, hence the wider bound for the dipole: both keep
// the relative RMSE against brute force near 2e-4 or below (docs/translucency.md).
constexpr double kDefaultSolidAngleDipole = 0.1;
constexpr double kDefaultSolidAngleTable = 0.005;

// What R_d is: the dipole or a table (checked by the caller, api.cpp), one of them.
struct ProfileSource {
  const arcus_dipole* dipole = nullptr;
  const arcus_profile_table* table = nullptr;
  double eta() const { return dipole ? dipole->eta : table->eta; }
};

// Checks every parameter but the profile (the caller's: api.cpp) and the mesh, naming
// them as the C API does ("params->exit", "lights[1].direction"), and renders;
// *cancelled when the progress callback stopped it.
std::unique_ptr<RenderJob> render(arcus_context_t* ctx, const geometry::Mesh& mesh, const ProfileSource& profile,
                                  const std::vector<arcus_directional_light>& lights,
                                  const arcus_translucency_render_params& params, bool* cancelled);

// Phong's exponent for a highlight of angle b (thesis eq. 3.3): −ln 2 / ln cos b.
double phong_exponent(double b_deg);

}  // namespace arcus::translucency
