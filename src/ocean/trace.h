// Spectral photon tracing through water (thesis §4.2, §5.3): the host side of
// kernels/ocean/trace.cl.  A trace shoots photons from lights into water (a
// WaterTables), runs the ten-event roulette, and returns what happened to the energy
// (per event, per interaction number, per constituent), optionally the irradiances at
// depths of a plane-parallel column and the photons stored for the photon map.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

#include "arcus/arcus_core.h"
#include "core/job.h"
#include "core/kernel_source.h"
#include "ocean/ocean_desc.h"  // kernels/ocean/ocean_desc.h
#include "ocean/water.h"

namespace arcus::ocean {

struct Light {
  enum Kind : int { point = 0, spot = 1, directional = 2, sky = 3 } kind = point;
  double position[3] = {0, 0, 0};
  double direction[3] = {0, 0, -1};  // spot's axis, the beam's direction (unit after checks)
  double half_angle_deg = 30;        // spot
  double radius = 0;                 // directional without a surface: the beam's disc (0: a line)
  // Emitted spectrum: point, spot [W/nm]; directional, sky [W/m²/nm] (per m² of the
  // surface, or of the beam's cross-section).  Interpolated linearly, 0 outside its
  // range; one value: flat.
  Spectrum spectrum{{550}, {1}};
};

// A light's spectrum at nm (Light::spectrum: linear, 0 outside, one sample flat).
double light_spectrum(const Light& light, double nm);

// Where the water is.  Default: unbounded.  Plane-parallel columns: surface (a flat
// air–water interface at z = 0, Fresnel both ways) or box_hi z = 0 (a free top, no
// interface), water below, optionally a Lambertian bottom.
struct Medium {
  bool surface = false;
  double n_water = 1.34;
  double bottom_depth = std::numeric_limits<double>::infinity();
  double bottom_albedo = 0;
  double box_lo[3] = {-std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
                      -std::numeric_limits<double>::infinity()};
  double box_hi[3] = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
                      std::numeric_limits<double>::infinity()};
};

struct TraceParams {
  uint64_t photons = 400000;
  int max_interactions = 5;  // thesis §5.3
  uint64_t seed = 1;
  bool store = false;         // keep the scattered photons (photon map)
  // Wavelengths each stored photon carries (hero-wavelength sampling, trace.cl): the
  // largest divisor of the grid's sample count not above this, 1..ARCUS_OCEAN_MAX_HEROES
  // (1: the thesis' one wavelength per photon).
  int wavelengths_per_photon = ARCUS_OCEAN_MAX_HEROES;
  std::vector<double> depths; // irradiance tallies at these depths [m] (≥ 0)
  double layer = 0.1;         // E_0's track-length layer [m]
  // Inelastic code: compiled when the water has inelastic events; `force_inelastic`
  // compiles it anyway (the ablation and the feature test).
  bool force_inelastic = false;
  // > 0 [m]: the sun's and the sky's photons enter through the square tile of this
  // width centred on tile_center (x, y) and are stored folded into it (an image's
  // periodic photons: MarchParams::photon_tile); 0: through the lights' discs.
  double tile = 0;
  double tile_center[2] = {0, 0};
};

// Checks (INVALID_ARGUMENT naming the parameter).
void check_light(const Light& light, size_t index);
void check_trace(const std::vector<Light>& lights, const Medium& medium, const TraceParams& params);

struct Tallies {
  uint64_t photons = 0, interactions = 0, stored = 0;
  double emitted = 0, past_limit = 0, bottom = 0;
  double absorbed_r2 = 0;  // Σ power·(distance from emission)² where absorbed in the water
  std::array<double, kEventCount> count{}, arriving{}, absorbed{};
  std::vector<double> absorbed_by_interaction, escaped_by_interaction;  // 0..limit
  double escaped() const;
  double absorbed_total() const;
};

struct Irradiance {  // per depth and grid sample, per nm: [j·count + k]
  std::vector<double> ed, eu, e0;
};

// Photons stored at scattering events: per event a position, the direction it
// arrived along and the event; per event ARCUS_OCEAN_MAX_HEROES powers and wavelengths
// (the wavelengths it carried; power 0 past them).
struct StoredPhotons {
  std::vector<double> positions, directions, powers, wavelengths;
  std::vector<int32_t> events;
  size_t size() const { return events.size(); }
};

// The wavelengths a stored photon carries on this grid (TraceParams::wavelengths_per_photon).
int carried_wavelengths(int requested, int grid_count);

struct TraceJob : arcus_job_s {
  explicit TraceJob(arcus_context_t* ctx, const char* kind = "ocean trace") : arcus_job_s(ctx, kind) {}
  WaterTables water;
  int limit = 5;
  Tallies tallies;
  std::vector<double> depths;
  Irradiance irradiance;
  StoredPhotons photons;
  double trace_seconds = 0;
};

// Traces params.photons photons; progress may cancel (then the tallies hold the photons
// traced so far, and TraceJob::tallies.photons says how many).
std::unique_ptr<TraceJob> trace(arcus_context_t* ctx, const WaterTables& water, const std::vector<Light>& lights,
                                const Medium& medium, const TraceParams& params, arcus_progress_callback progress,
                                void* user, bool* cancelled);

// The same into an existing job (a render job is a trace job with an image).
void trace_into(TraceJob* job, arcus_context_t* ctx, const WaterTables& water, const std::vector<Light>& lights,
                const Medium& medium, const TraceParams& params, arcus_progress_callback progress, void* user,
                bool* cancelled);

// The scatterers' phase functions for the kernels: their parameters into *phases, the
// tabulated ones (cosines, density over cosines normalised to 1, CDF) appended to *buf.
void append_phases(const WaterTables& water, std::vector<double>* buf, arcus_ocean_phases* phases);

// The kernel's water buffer (kernels/ocean/ocean_desc.h) and the desc fields it fixes
// (the active events, the inelastic tables when `inelastic`, the phases); the kernel
// source, for tests that call its device functions.
std::vector<double> water_buffer(const WaterTables& water, bool inelastic, arcus_ocean_desc* desc);
const KernelSource& trace_source();

// The features a trace compiles.
arcus_features trace_features(const WaterTables& water, const Medium& medium, const TraceParams& params);

}  // namespace arcus::ocean
