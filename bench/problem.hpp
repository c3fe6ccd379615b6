// The test problem of thesis §5.4.1: rays in the linear medium n = n0 + g·y, whose
// paths are catenaries with a closed form, so every integrator's end point can be
// compared with the exact one.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <vector>

namespace bench {

using Point = std::array<double, 3>;

// Rays start at (0, y0, 0) with y0 in [0, 1] and travel in the x–y plane at angles in
// [-20°, +20°].  Downward rays reach a turning point (n = A there, so n stays > 0) and
// come back up: the mirage case the closed form has to get right.
struct RaySet {
  std::vector<double> origins;     // count × 3
  std::vector<double> directions;  // count × 3, unit length
  std::size_t count() const { return origins.size() / 3; }
};

// Ray i depends on i alone (an R2 low-discrepancy sequence), so the first k rays of
// any set are the same k rays: the peer and arcus can be compared on a shared prefix.
inline RaySet make_rays(std::size_t count) {
  constexpr double kPi = 3.14159265358979323846;
  constexpr double kMaxAngle = 20.0 * kPi / 180.0;
  constexpr double kA1 = 0.7548776662466927, kA2 = 0.5698402909980532;  // 1/φ₂, 1/φ₂²
  RaySet rays;
  rays.origins.reserve(3 * count);
  rays.directions.reserve(3 * count);
  for (std::size_t i = 0; i < count; ++i) {
    const double u = std::fmod(0.5 + kA1 * static_cast<double>(i), 1.0);
    const double w = std::fmod(0.5 + kA2 * static_cast<double>(i), 1.0);
    const double angle = kMaxAngle * (2.0 * w - 1.0);
    rays.origins.insert(rays.origins.end(), {0.0, u, 0.0});
    rays.directions.insert(rays.directions.end(), {std::cos(angle), std::sin(angle), 0.0});
  }
  return rays;
}

// Exact point after arc length L along a ray in n = n0 + g·y (g > 0), the ray in the
// x–y plane.  With v = n·dr/ds, v_x = A is conserved and v_y = A·sinh(u) grows
// linearly in s, which gives
//   u(s) = asinh(sinh(u0) + g·s/A),  x = x0 + A·(u − u0)/g,  y = y0 + A·(cosh u − cosh u0)/g
// (equivalently n(y) = A·cosh(g(x − C)/A)).  asinh covers rays that first go down,
// turn (u = 0) and climb.  The cosh difference is written as a product of sinh so short
// paths do not cancel, and it runs in long double so the reference stays far below
// the smallest errors measured (≈1e-12 m).
inline Point catenary_end_point(double n0, double g, const double origin[3], const double direction[3],
                                double length) {
  using real = long double;
  const real norm = std::hypot(static_cast<real>(direction[0]), static_cast<real>(direction[1]));
  const real n_start = static_cast<real>(n0) + static_cast<real>(g) * origin[1];
  const real a = n_start * direction[0] / norm;  // v_x
  if (!(a > 0) || direction[2] != 0.0 || origin[2] != 0.0)
    throw std::invalid_argument("catenary_end_point: ray must lie in the x-y plane heading +x");
  const real u0 = std::asinh(n_start * direction[1] / norm / a);
  const real u1 = std::asinh(std::sinh(u0) + static_cast<real>(g) * length / a);
  const real scale = a / static_cast<real>(g);
  const real dy = 2 * scale * std::sinh((u1 + u0) / 2) * std::sinh((u1 - u0) / 2);
  return {static_cast<double>(origin[0] + scale * (u1 - u0)), static_cast<double>(origin[1] + dy), 0.0};
}

// Distances between computed end points (count × 3) and the exact ones, per ray.
inline std::vector<double> end_point_errors(const RaySet& rays, std::size_t count, const double* positions,
                                            double n0, double g, double length) {
  std::vector<double> errors(count);
  for (std::size_t i = 0; i < count; ++i) {
    const Point exact = catenary_end_point(n0, g, &rays.origins[3 * i], &rays.directions[3 * i], length);
    const double* p = positions + 3 * i;
    errors[i] = std::sqrt((p[0] - exact[0]) * (p[0] - exact[0]) + (p[1] - exact[1]) * (p[1] - exact[1]) +
                          (p[2] - exact[2]) * (p[2] - exact[2]));
  }
  return errors;
}

}  // namespace bench
