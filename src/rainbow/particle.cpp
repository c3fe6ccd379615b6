#include "rainbow/particle.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include "core/error.h"
#include "core/format.h"

namespace arcus::rainbow {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Thesis Table 4.4: a, b [m] and k of eq. 4.21 for equivalent diameters 1..6 mm.
constexpr double kTableA[6] = {0.00050, 0.001025, 0.001555, 0.002135, 0.00275, 0.0034};
constexpr double kTableB[6] = {0.00048, 0.00093, 0.001308, 0.00165, 0.00194, 0.00220};
constexpr double kTableK[6] = {0.01, 0.15, 0.20, 0.27, 0.29, 0.32};

// The raindrop's radius about its axis at height y: eq. 4.21 solved for x² + z².
double raindrop_r2(double a, double b, double k, double y) {
  return std::max(0.0, a * a * (1 - y * y / (b * b)) / (1 - k * y / b));
}

}  // namespace

Particle sphere(double radius) {
  require(std::isfinite(radius) && radius > 0, "sphere radius must be positive and finite, got " + number(radius));
  Particle p;
  p.kind = ARCUS_RAINBOW_SHAPE_SPHERE;
  p.radius = radius;
  p.bound = radius;
  p.volume = 4.0 / 3.0 * kPi * radius * radius * radius;
  return p;
}

Particle raindrop(double diameter) {
  require(std::isfinite(diameter) && diameter >= 1e-3 - 1e-12 && diameter <= 6e-3 + 1e-12,
          "raindrop diameter must be 1-6 mm (thesis Table 4.4; smaller drops are spheres: use a sphere), got " +
              number(diameter * 1e3) + " mm");
  const double x = std::clamp(diameter * 1e3 - 1.0, 0.0, 5.0);
  const int i = std::min(4, static_cast<int>(x));
  const double f = x - i;
  Particle p;
  p.kind = ARCUS_RAINBOW_SHAPE_RAINDROP;
  p.a = kTableA[i] + f * (kTableA[i + 1] - kTableA[i]);
  p.b = kTableB[i] + f * (kTableB[i + 1] - kTableB[i]);
  p.k = kTableK[i] + f * (kTableK[i + 1] - kTableK[i]);
  // Volume and bound by quadrature over y in [−b, b] (Simpson, 4000 intervals: the
  // integrand is smooth, error far below 1e-9 relative).
  const int n = 4000;
  double volume = 0, bound = 0;
  for (int j = 0; j <= n; ++j) {
    const double y = -p.b + 2 * p.b * j / n;
    const double r2 = raindrop_r2(p.a, p.b, p.k, y);
    const double w = (j == 0 || j == n) ? 1 : (j % 2 ? 4 : 2);
    volume += w * kPi * r2;
    bound = std::max(bound, std::sqrt(r2 + y * y));
  }
  p.volume = volume * (2 * p.b / n) / 3;
  p.bound = bound * 1.001;  // the sampled maximum, widened past its sampling error
  return p;
}

Particle mesh(geometry::Mesh mesh, double scale, bool smooth) {
  require(std::isfinite(scale) && scale > 0, "mesh scale must be positive and finite, got " + number(scale));
  Particle p;
  p.kind = ARCUS_RAINBOW_SHAPE_MESH;
  p.smooth = smooth;
  p.mesh = std::move(mesh);
  const std::string name = p.mesh.source.empty() ? "the mesh" : "mesh " + p.mesh.source;
  for (double& x : p.mesh.positions) x *= scale;
  // Closed: every edge in exactly two triangles, so a ray that enters must leave.
  std::map<std::pair<uint32_t, uint32_t>, int> edges;
  const auto& t = p.mesh.triangles;
  for (size_t f = 0; f + 2 < t.size(); f += 3)
    for (int e = 0; e < 3; ++e) {
      const uint32_t u = t[f + e], v = t[f + (e + 1) % 3];
      ++edges[{std::min(u, v), std::max(u, v)}];
    }
  size_t open = 0;
  for (const auto& e : edges) open += e.second != 2;
  require(open == 0, name + " is not closed: " + std::to_string(open) + " of its " +
                         std::to_string(edges.size()) + " edges are not shared by exactly two triangles");
  double volume = 0, bound = 0;
  const auto& x = p.mesh.positions;
  for (size_t f = 0; f + 2 < t.size(); f += 3) {
    const double* a = &x[3 * t[f]];
    const double* b = &x[3 * t[f + 1]];
    const double* c = &x[3 * t[f + 2]];
    volume += (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
               a[2] * (b[0] * c[1] - b[1] * c[0])) / 6;
  }
  for (size_t v = 0; v < p.mesh.vertex_count(); ++v)
    bound = std::max(bound, std::sqrt(x[3 * v] * x[3 * v] + x[3 * v + 1] * x[3 * v + 1] + x[3 * v + 2] * x[3 * v + 2]));
  p.volume = std::fabs(volume);  // either winding
  p.bound = bound * 1.000001;
  require(p.volume > 0, name + " encloses no volume");
  return p;
}

std::vector<double> vertex_normals(const geometry::Mesh& mesh) {
  std::vector<double> n(mesh.positions.size(), 0.0);
  const auto& x = mesh.positions;
  const auto& t = mesh.triangles;
  for (size_t f = 0; f + 2 < t.size(); f += 3) {
    const double* a = &x[3 * t[f]];
    const double* b = &x[3 * t[f + 1]];
    const double* c = &x[3 * t[f + 2]];
    const double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const double cr[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
    for (int k = 0; k < 3; ++k)
      for (int a2 = 0; a2 < 3; ++a2) n[3 * t[f + k] + a2] += cr[a2];  // |cross| = 2·area: area-weighted
  }
  for (size_t v = 0; v < mesh.vertex_count(); ++v) {
    const double l = std::sqrt(n[3 * v] * n[3 * v] + n[3 * v + 1] * n[3 * v + 1] + n[3 * v + 2] * n[3 * v + 2]);
    require(l > 0, "mesh vertex " + std::to_string(v) + " has no normal (its triangles cancel)");
    for (int a = 0; a < 3; ++a) n[3 * v + a] /= l;
  }
  return n;
}

double equivalent_radius(const Particle& p) { return std::cbrt(p.volume * 3 / (4 * kPi)); }

}  // namespace arcus::rainbow
