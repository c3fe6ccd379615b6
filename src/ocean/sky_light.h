// The sky's light in ocean images (thesis §4.2 with a sky over the surface): the tables
// kernels/ocean/render.cl reads for the first scattering of a uniform sky and for
// Snell's window (kernels/ocean/ocean_desc.h, "sky tables").
#pragma once

#include <vector>

#include "ocean/trace.h"
#include "ocean/water.h"

namespace arcus::ocean {

// The sky's light in an image (kernels/ocean/ocean_desc.h, "sky tables"): a uniform sky
// of radiance L_s = E/π above the flat surface (E: the sky lights' plane irradiance)
// comes through it as n² T(μ) L_s within Snell's cone (μ_w ≥ μ_c, the n² law of radiance
// and the Fresnel transmittance), dimmed along the slant path d/μ_w to depth d.  Its
// first scattering toward a view whose direction has vertical cosine v, at depth d:
//   elastic   Σ_s σ_s(λ) ∫_cone n² T L_s e^(−σ_t d/μ) p_s(cos Θ) dω,
//   inelastic Σ_i M[λ][λ_i] E_0(d, λ_i), E_0 the sky's scalar irradiance there,
// with the azimuth integrated once per (v, μ) (the phase functions do not depend on λ).
struct SkyTables {
  int rows = 0, cosines = 0;
  double d_step = 1;
  std::vector<double> data;  // L_s (n), window n²T (cosines), elastic (rows × cosines × n), inelastic (rows × n)
};

// The sky lights' tables for rays down to depth d_max; st: σ_t per sample; M: the
// inelastic redistribution (render.cpp; empty: none).  rows = 0 when no light is a sky.
SkyTables sky_tables(const WaterTables& w, const std::vector<Light>& lights, const Medium& medium,
                     const std::vector<double>& st, const std::vector<double>& M, double d_max);

}  // namespace arcus::ocean
