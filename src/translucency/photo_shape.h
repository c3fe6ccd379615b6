// Shape from one uncontrolled photograph (thesis §3.4, after Khan, Reinhard, Fleming &
// Bülthoff 2006): a depth map Z of the object as the weighted sum of a base layer (its
// global convexity: the contour at Z = 0 and the bilateral-filtered luminance reshaped
// by an "inflation" spline) and a detail layer (the filter's high-frequency residual),
// normals from Z.  The bas-relief ambiguity (Belhumeur, Kriegman & Yuille 1999) leaves
// Z's scale unknown: one parameter, `relief`.
#pragma once

#include <cstdint>
#include <vector>

#include "arcus/arcus_translucency.h"
#include "translucency/photo_lights.h"

namespace arcus::translucency {

// Checks the parameters, naming them as the C API does ("params->relief").
void check_shape_params(const arcus_photo_shape_params& p);

struct PhotoShape {
  std::vector<double> depth;    // per pixel, pixels (toward the camera); 0 outside the object
  std::vector<double> normals;  // 3 per pixel, unit, the camera's frame (x right, y up); 0 outside
};

PhotoShape estimate_shape(const PhotoObject& object, const arcus_photo_shape_params& params);

}  // namespace arcus::translucency
