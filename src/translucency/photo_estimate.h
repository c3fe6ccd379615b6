// The BSSRDF from one uncontrolled photograph (thesis §3.4, results §5.2): the lights and
// the shape estimated from the photo itself (photo_lights.h, photo_shape.h), a closed mesh
// built from the depth (the back mirrors the front, as §3.4 assumes), and then the
// estimate of §3.3.1 (estimate.h) on that mesh, seen orthographically pixel for pixel.
#pragma once

#include <memory>

#include "geometry/mesh.h"
#include "translucency/estimate.h"
#include "translucency/photo_lights.h"
#include "translucency/photo_shape.h"

namespace arcus::translucency {

// The closed mesh of a depth map at the working resolution, in the photo's pixels (x
// right, y up, the photo's centre at the origin; object.scale of them a working pixel):
// at every pixel corner the object touches, a front vertex at the mean depth of the four
// pixels (0 outside) and a back one at minus that, walls along the contour joining them;
// two triangles a pixel on each side.  The mask is first opened (3 × 3) and rid of
// pixels touching others only at a corner; *used gets it.
geometry::Mesh relief_mesh(const PhotoObject& object, const PhotoShape& shape, std::vector<uint8_t>* used);

std::unique_ptr<EstimateJob> estimate_automatic(arcus_context_t* ctx, uint32_t width, uint32_t height,
                                                const float* photo, const uint8_t* matte,
                                                const arcus_translucency_auto_params& params, bool* cancelled);

}  // namespace arcus::translucency
