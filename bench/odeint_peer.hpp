// The peer: Boost.Odeint's controlled Dormand–Prince 5(4) on the same ray equation,
// one ray at a time on the CPU, the way a plain C++ ray tracer would use it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "problem.hpp"

namespace bench {

struct PeerRun {
  double seconds = 0;              // wall time of the integration (threads included)
  std::vector<double> positions;   // count × 3 end points
  std::vector<std::uint64_t> steps;  // accepted steps per ray
};

// Integrates the first `count` rays over arc length `length` through n = n0 + g·y with
// make_controlled(atol, rtol) runge_kutta_dopri5, split over `threads` std::threads.
PeerRun run_odeint_dopri5(const RaySet& rays, std::size_t count, double n0, double g, double length,
                          double rtol, double atol, unsigned threads);

}  // namespace bench
