// The particles whose phase functions the rainbow engine computes (thesis §4.4.1): a
// sphere, the thesis' falling raindrop (eq. 4.21, Table 4.4) and any closed triangle
// mesh (ice crystals, measured shapes), each in its own frame about the origin.
#pragma once

#include <string>
#include <vector>

#include "geometry/mesh.h"
#include "rainbow/rainbow_desc.h"

namespace arcus::rainbow {

struct Particle {
  int kind = ARCUS_RAINBOW_SHAPE_SPHERE;
  double radius = 0;        // sphere
  double a = 0, b = 0, k = 0;  // raindrop: eq. 4.21's half-width, half-height, deformation
  geometry::Mesh mesh;      // mesh, in metres
  bool smooth = false;      // mesh: a smooth surface (interpolated vertex normals), not flat faces
  double bound = 0;         // radius of a sphere about the origin holding the particle
  double volume = 0;
};

// radius > 0 and finite.
Particle sphere(double radius);
// Equivalent-volume diameter 1-6 mm (in metres); Table 4.4 interpolated linearly.
Particle raindrop(double diameter);
// A mesh (read from a file, or made from arrays: arcus_mesh_t) scaled by `scale`; it
// must be closed: every edge in exactly two triangles.  smooth: the triangles
// approximate a smooth surface (a measured drop), whose normals are interpolated from
// the vertices; otherwise its faces are flat (a crystal).
Particle mesh(geometry::Mesh mesh, double scale, bool smooth);

// Per vertex of `mesh`, the area-weighted mean of its triangles' normals, in the
// triangles' winding (unit; 3 per vertex).
std::vector<double> vertex_normals(const geometry::Mesh& mesh);

double equivalent_radius(const Particle& p);

}  // namespace arcus::rainbow
