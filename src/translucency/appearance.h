// What a render of one object under known lights and camera owes to the geometry
// alone, cached once so that the genetic search (genetic.h; thesis §3.2) costs a
// matrix–vector product per individual instead of a render.
//
// Per covered pixel p, the renderer's image (render.h, eq. 3.6–3.8) is
//   (1/π) F_t(η, cos_o,p) Σ_i R_d(|x_p − x_i|) E_i(η) ΔA_i  +  the Phong highlight,
// where only R_d and η depend on the medium.  The cache holds, per pixel:
//   * the samples' E_i(η_j)·ΔA_i summed by distance bin (uniform in √r: fine where R_d
//     peaks) at five η nodes η_j (Chebyshev over the η gene's range) — E depends on η
//     only through F_t(η, cos θ), smooth in η, so degree-4 interpolation between the
//     nodes stands for it;
//   * within ρ (two sample spacings) the pixel's own E_p(η_j) over a flat disc, whose
//     ∫₀^ρ 2πr R_d dr is closed-form (as the estimate's near field, estimate.cpp);
//   * per light: whether it is seen, cos θ_i and cos α (for the highlight and Phong).
// For a medium, R_d is averaged over each bin's area (fit.h's bin_average); the image is
// then Σ_bins Σ_nodes cache × R_d(bin) × λ_j(η).  tests/python/test_translucency_genetic.py
// holds it against the renderer.
#pragma once

#include <cstdint>
#include <vector>

#include "arcus/arcus_translucency.h"
#include "core/job.h"
#include "geometry/mesh.h"
#include "translucency/surface.h"

namespace arcus::translucency {

constexpr uint32_t kEtaNodes = 5;
constexpr uint32_t kCacheBins = 96;  // √r bins: with 15 weights each, 1440 of the kernel's 1536 cells

struct AppearanceCache {
  uint32_t width = 0, height = 0;
  std::vector<size_t> pixels;       // the covered pixels (y · width + x)
  std::vector<double> cos_out;      // per pixel: |n·ω_o|
  std::vector<float> bins;          // per pixel kCacheBins × kEtaNodes × 3: Σ E ΔA
  std::vector<double> own;          // per pixel kEtaNodes × 3: E at the pixel's point
  std::vector<double> edges;        // kCacheBins + 1 distances [mm]
  uint32_t near_bins = 0;           // bins inside ρ, left to the disc
  double near_radius = 0;           // ρ [mm]
  double eta_nodes[kEtaNodes] = {};
  std::vector<Light> lights;
  std::vector<double> light_cos;    // per pixel per light: cos θ_i where lit, else 0
  std::vector<double> mirror_cos;   // per pixel per light: cos α (0 when facing away)
  size_t samples = 0;
  double spacing = 0;               // the samples' [mm]
};

// The cache for `mesh` seen by `camera` (mesh units; ortho_height > 0: orthographic)
// under `lights`, with η nodes over [eta_low, eta_high].  Samples every `spacing` mm
// (0: half a pixel at the object).  *cancelled when the progress callback stopped it.
AppearanceCache appearance_cache(arcus_context_t* ctx, arcus_job_s& job, const geometry::Mesh& mesh,
                                 const arcus_camera& camera, double ortho_height, double mm_per_unit,
                                 const std::vector<Light>& lights, double eta_low, double eta_high,
                                 arcus_progress_callback progress, void* progress_user, bool* cancelled);

// The image through the dipole (thesis exit term) with a Fresnel-weighted Phong
// highlight of angle b (degrees; 0: none), as render.h renders it: 3 per cache pixel.
std::vector<double> dipole_image(const AppearanceCache& cache, const arcus_dipole& dipole, double highlight_deg);

// The image of an opaque Phong surface (thesis eq. 3.2–3.3): k_d/π + k_s (n + 2)/(2π)
// cos^n α, n from b; 3 per cache pixel.
std::vector<double> phong_image(const AppearanceCache& cache, const double k_d[3], double k_s, double b_deg);

}  // namespace arcus::translucency
