// Underwater images (thesis §4.2, §5.3): photons traced through the water and stored
// from their second interaction on (trace.h), a photon map over them, and camera rays
// marched through the water gathering single scattering from the lights (eq. 4.5) and
// multiple scattering from the map (eq. 4.6: the per-step k-nearest estimate, or the
// beam estimate of Jarosz et al. 2008), per grid wavelength, then CIE XYZ and sRGB.
// kernels/ocean/render.cl has the device side.
#pragma once

#include <memory>
#include <vector>

#include "arcus/arcus_ocean.h"
#include "ocean/scene.h"
#include "ocean/trace.h"

namespace arcus::ocean {

struct RenderStats {
  double trace_seconds = 0, map_seconds = 0, estimate_seconds = 0, total_seconds = 0;
  uint64_t photons_stored = 0;
};

struct RenderJob : TraceJob {
  explicit RenderJob(arcus_context_t* ctx) : TraceJob(ctx, "ocean render") {}
  uint32_t width = 0, height = 0;
  std::vector<double> wavelengths;
  std::vector<double> spectral;  // width × height × samples [W/m²/sr/nm], top row first
  std::vector<float> rgb;        // linear sRGB (CIE 1931 2°: data/spectra), width × height × 3
  double exposure = 1;
  RenderStats render_stats;
};

// Throws INVALID_ARGUMENT naming the bad member (the camera: scene::check_camera).
void check_march(const MarchParams& march);

std::unique_ptr<RenderJob> render(arcus_context_t* ctx, const WaterTables& water, const std::vector<Light>& lights,
                                  const Medium& medium, const TraceParams& trace, const arcus_camera& camera,
                                  const MarchParams& march, arcus_progress_callback progress, void* user,
                                  bool* cancelled);

// The features a render compiles (besides its trace's).
arcus_features render_features(const WaterTables& water, const MarchParams& march);

}  // namespace arcus::ocean
