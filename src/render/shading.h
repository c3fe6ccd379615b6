// The light a frame's primary rays see (thesis §4.1.6, §4.3.4): emission, the sky, direct
// light through curved shadow rays toward each light (with smart step selection and path
// caching), or curved photon mapping; and a pixel's spectral radiance for spectral
// scenes.  Internal to the renderer (renderer.cpp calls it per frame).
#pragma once

#include "render/frame_rays.h"
#include "render/renderer.h"

namespace arcus::render {

// Direct light at every hit pixel: a curved shadow ray from the hit toward each light
// (starting along the straight direction to it), traced through the medium; the light
// counts where the ray reaches it unblocked.  Writes job->rgb.
void shade(arcus_context_t* ctx, arcus_renderer_s* r, const Primary& prim, RenderJob* job);

// Pixel p's spectral radiance at `nm` from its RGB shading `rgb`: a blackbody emitter
// gives Planck's spectrum at its temperature (scaled by its emission's mean), dimmed by
// Rayleigh extinction along the air mass of the ray's apparent elevation when it lies
// beyond the atmosphere (the sun); any other RGB value stands for the band of its
// channel (blue below 490 nm, green to 580 nm, red above).
double spectral_radiance(const RenderScene& s, const Frame& f, const Primary& prim, size_t p, const float* rgb,
                         double nm);

}  // namespace arcus::render
