// A second peer: fixed-step classical RK4 on the same problem in plain C++ with
// OpenMP (threads over blocks of rays, a SIMD loop over the rays of a block), compiled
// -O3 -march=native -fopenmp: what a user gets from the compiler without OpenCL, for
// arcus' RK4 kernel to be set against.
#pragma once

#include <cstddef>

#include "odeint_peer.hpp"  // PeerRun
#include "problem.hpp"

namespace bench {

// RK4 with steps of `step`, the last one shortened so every ray ends exactly at arc
// length `length` (the step count and last step chosen as arcus' host chooses them),
// through n = n0 + g·y, for the first `count` rays, on `threads` OpenMP threads.
// steps: the step count of each ray (all equal).
PeerRun run_native_rk4(const RaySet& rays, std::size_t count, double n0, double g, double length, double step,
                       unsigned threads);

}  // namespace bench
