// Rainbow skies (thesis §4.1.4, §5.5.2): the single scattering of a box of drops lit by
// the sun, marched along each camera ray with a table of the drops' volume scattering
// function averaged over the sun's disc, to CIE XYZ and sRGB.  kernels/rainbow/sky.cl
// has the device side; the table itself (phase functions × sizes × number densities)
// is the caller's (bindings/python/arcus/sky.py builds it from the phase-table sweeps).
#pragma once

#include <memory>
#include <vector>

#include "arcus/arcus_rainbow.h"
#include "core/job.h"

namespace arcus::rainbow {

struct SkyJob : arcus_job_s {
  explicit SkyJob(arcus_context_t* ctx) : arcus_job_s(ctx, "rainbow sky") {}
  uint32_t width = 0, height = 0;
  std::vector<float> xyz, rgb, theta;  // 3, 3 and 1 per pixel, top row first
  double exposure = 1;
};

// Throws INVALID_ARGUMENT naming the bad member.
void check_sky(const arcus_rainbow_table& table, const arcus_rainbow_sky& sky);

// β averaged over the sun's disc, [wavelengths × phis × thetas] like the table: at each
// sample, the mean of β over `samples` directions spread evenly over a disc of angular
// diameter `diameter_deg` about it (a sunflower pattern; 1: the centre alone).  θ to a
// disc point is exact (the spherical law of cosines), φ to first order in the disc's
// radius (a 0.27° radius errs by ~1e-5 rad).
std::vector<double> disc_average(const arcus_rainbow_table& table, double diameter_deg, uint32_t samples);

// Whether β depends on the azimuth: the AZIMUTH feature.
arcus_features sky_features(const arcus_rainbow_table& table);

std::unique_ptr<SkyJob> render_sky(arcus_context_t* ctx, const arcus_rainbow_table& table,
                                   const arcus_rainbow_sky& sky, bool* cancelled);

}  // namespace arcus::rainbow
