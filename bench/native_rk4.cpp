#include "native_rk4.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include <omp.h>

namespace bench {
namespace {

// The state arcus integrates: r and v = n·dr/ds.
struct Ray {
  double x, y, z, vx, vy, vz;
};

// A general linear field n = n0 + ∇n·r, as arcus' linear kind: with ∇n = (0, g, 0)
// given at run time the compiler cannot drop the zero terms, so both sides do the same
// arithmetic per step (flops.hpp counts it once for both).
struct LinearField {
  double n0, grad[3];
};

inline Ray derivative(const LinearField& f, const Ray& s) {
  const double n = f.n0 + f.grad[0] * s.x + f.grad[1] * s.y + f.grad[2] * s.z;
  const double inv_n = 1.0 / n;
  return {s.vx * inv_n, s.vy * inv_n, s.vz * inv_n, f.grad[0], f.grad[1], f.grad[2]};
}

// y + h·k
inline Ray axpy(const Ray& y, double h, const Ray& k) {
  return {y.x + h * k.x, y.y + h * k.y, y.z + h * k.z, y.vx + h * k.vx, y.vy + h * k.vy, y.vz + h * k.vz};
}

// k1 + 2 k2 + 2 k3 + k4
inline Ray rk4_sum(const Ray& k1, const Ray& k2, const Ray& k3, const Ray& k4) {
  return {k1.x + 2 * (k2.x + k3.x) + k4.x,     k1.y + 2 * (k2.y + k3.y) + k4.y,
          k1.z + 2 * (k2.z + k3.z) + k4.z,     k1.vx + 2 * (k2.vx + k3.vx) + k4.vx,
          k1.vy + 2 * (k2.vy + k3.vy) + k4.vy, k1.vz + 2 * (k2.vz + k3.vz) + k4.vz};
}

inline Ray rk4_step(const LinearField& f, const Ray& y, double h) {
  const Ray k1 = derivative(f, y);
  const Ray k2 = derivative(f, axpy(y, 0.5 * h, k1));
  const Ray k3 = derivative(f, axpy(y, 0.5 * h, k2));
  const Ray k4 = derivative(f, axpy(y, h, k3));
  return axpy(y, h / 6, rk4_sum(k1, k2, k3, k4));
}

// Rays stepped together by one thread: 64 × 6 doubles of state (3 KiB) stay in L1 and
// give the core many independent rays to overlap (16 to 256 timed alike).
constexpr std::ptrdiff_t kBlock = 64;

}  // namespace

PeerRun run_native_rk4(const RaySet& rays, std::size_t count, double n0, double g, double length, double step,
                       unsigned threads) {
  PeerRun run;
  run.positions.resize(3 * count);
  // The least n with n·step >= length and the last step that ends at `length`: the
  // same arithmetic as arcus' host (make_advance_desc), so both take the same steps.
  std::int64_t steps = std::max<std::int64_t>(1, static_cast<std::int64_t>(std::ceil(length / step)));
  while (steps > 1 && static_cast<double>(steps - 1) * step >= length) --steps;
  while (static_cast<double>(steps) * step < length) ++steps;
  const double last_step = length - static_cast<double>(steps - 1) * step;
  run.steps.assign(count, static_cast<std::uint64_t>(steps));

  const LinearField field{n0, {0.0, g, 0.0}};
  const double* origins = rays.origins.data();
  const double* directions = rays.directions.data();
  double* out = run.positions.data();
  const std::ptrdiff_t n = static_cast<std::ptrdiff_t>(count);
  const int team = static_cast<int>(std::max(1u, threads));

  const double start = omp_get_wtime();
  // Threads take blocks of rays; each block's state (structure of arrays) stays in L1
  // while its rays step together, and the compiler vectorises the loop over the rays
  // of a block.  GCC 12 does not vectorise the plainer "omp parallel for simd" over
  // rays with the step loop inside (-fopt-info-vec: "control flow in loop").
#pragma omp parallel for num_threads(team) schedule(static)
  for (std::ptrdiff_t first = 0; first < n; first += kBlock) {
    const std::ptrdiff_t m = std::min(kBlock, n - first);
    alignas(64) double x[kBlock], y[kBlock], z[kBlock], vx[kBlock], vy[kBlock], vz[kBlock];
#pragma omp simd
    for (std::ptrdiff_t j = 0; j < m; ++j) {
      const double* o = origins + 3 * (first + j);
      const double* d = directions + 3 * (first + j);
      // v = n(r0)·d/|d|
      const double n_start = field.n0 + field.grad[0] * o[0] + field.grad[1] * o[1] + field.grad[2] * o[2];
      const double scale = n_start / std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
      x[j] = o[0];
      y[j] = o[1];
      z[j] = o[2];
      vx[j] = scale * d[0];
      vy[j] = scale * d[1];
      vz[j] = scale * d[2];
    }
    for (std::int64_t k = 0; k < steps; ++k) {
      const double h = k + 1 < steps ? step : last_step;
#pragma omp simd
      for (std::ptrdiff_t j = 0; j < m; ++j) {
        const Ray r = rk4_step(field, {x[j], y[j], z[j], vx[j], vy[j], vz[j]}, h);
        x[j] = r.x;
        y[j] = r.y;
        z[j] = r.z;
        vx[j] = r.vx;
        vy[j] = r.vy;
        vz[j] = r.vz;
      }
    }
    for (std::ptrdiff_t j = 0; j < m; ++j) {
      out[3 * (first + j)] = x[j];
      out[3 * (first + j) + 1] = y[j];
      out[3 * (first + j) + 2] = z[j];
    }
  }
  run.seconds = omp_get_wtime() - start;
  return run;
}

}  // namespace bench
