// A daylight sky's light on diffuse surfaces (issue 22: the ground lit by the sun and
// the sky).  The irradiance a surface of normal n receives, E(n) = ∫ L(ω) max(0, ω·n) dω,
// integrated once over the sky's panorama for a grid of normals and read per hit:
// above the horizon the sky's radiance, below it a Lambertian ground of albedo ρ lit by
// the sun and the sky, L = ρ/π · (E_sun sin e + E_sky(up)), ρ the atmosphere's
// ground_albedo (the ground that lights the sky back too: sky/scattering.h).  What the scene's own
// objects hide of the sky, and light they reflect onto each other, are left out: the
// ground under a shuttle sees the whole sky.
#pragma once

#include "geometry/vec3.h"
#include "image/image_io.h"

namespace arcus::render {

// E(n) as a map over normals, 64 azimuths × 33 polar angles (poles included), from
// `sky` (an equirectangular panorama of linear sRGB radiance; rows below the horizon are
// ignored) and the sun's irradiance on a surface facing it, `sun` at `sun_elevation_deg`.
image::Image sky_irradiance_map(const image::Image& sky, Vec3 sun, double sun_elevation_deg, double ground_albedo);

// The map's E at normal n (unit), bilinear between its normals.
Vec3 sky_irradiance(const image::Image& map, Vec3 n);

}  // namespace arcus::render
