// Exact glints of a convex flat-faced particle (an ice crystal) by beam tracing.
//
// The cast (thesis §4.4.3.1) follows a grid of rays; on flat faces every ray of one
// sequence of faces leaves in one direction with one Fresnel product, so the grid only
// measures the areas of the regions of the particle's shadow that feed each sequence,
// to O(1/grid).  Here each face the light enters is followed as a polygon instead: at
// every internal reflection the beam is projected along its direction onto the faces
// ahead of it and cut by each (the particle is convex, so the pieces tile it), the
// transmitted part of each piece leaves as a glint, the reflected part goes on.  The
// areas are then exact, and one orientation costs a few hundred polygon clips instead
// of grid² traced rays.  Fresnel and polarisation are the cast's (rb_interface in
// kernels/rainbow/optics.h): a glint's power is what the cast's rays of that sequence
// carry, summed over their area.
#pragma once

#include <cstdint>
#include <vector>

#include "arcus/arcus_core.h"
#include "rainbow/cast.h"
#include "rainbow/particle.h"

namespace arcus::rainbow {

// A convex particle's faces: coplanar triangles merged into one convex polygon each.
struct ConvexFace {
  double normal[3];                // outward, unit
  double offset;                   // the plane normal · x = offset [m]
  std::vector<double> vertices;    // 3 per corner, counter-clockwise seen from outside
};

// The faces of a flat-faced mesh particle; ARCUS_ERROR_INVALID_ARGUMENT naming what is
// wrong if it is smooth, not a mesh, or not convex.
std::vector<ConvexFace> convex_faces(const Particle& particle);

struct BeamTotals {
  double intercepted = 0;          // the shadows' areas summed over orientations [m²]
  double scattered[16] = {0};      // per term p, the glints' power summed [m²]
  double remaining = 0;            // still inside after P [m²]
  double dropped = 0;              // pieces below rounding, left out [m²]
  uint64_t beams = 0;              // pieces traced
};

// The glints of the particle in each orientation (rotations: count × 9, particle →
// world, row-major; the light along +z), for refractive index n and terms p = 0..bounces,
// appended to `glints`; the books in `totals`.  progress may stop it (returns true).
bool trace_beams(const std::vector<ConvexFace>& faces, double n, int bounces, size_t count, const double* rotations,
                 std::vector<Glint>& glints, BeamTotals& totals, arcus_progress_callback progress,
                 void* progress_user);

}  // namespace arcus::rainbow
