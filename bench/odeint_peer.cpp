#include "odeint_peer.hpp"

#include <array>
#include <chrono>
#include <thread>

#include <boost/numeric/odeint.hpp>

namespace bench {
namespace {

using State = std::array<double, 6>;  // r, v = n·dr/ds

// dr/ds = v/n, dv/ds = ∇n for n = n0 + g·y (the state and equation arcus integrates).
struct LinearRayOde {
  double n0, g;
  void operator()(const State& x, State& dxds, double /*s*/) const {
    const double inv_n = 1.0 / (n0 + g * x[1]);
    dxds = {x[3] * inv_n, x[4] * inv_n, x[5] * inv_n, 0.0, g, 0.0};
  }
};

void integrate_range(const RaySet& rays, std::size_t begin, std::size_t end, const LinearRayOde& ode,
                     double length, double rtol, double atol, PeerRun& out) {
  namespace odeint = boost::numeric::odeint;
  // The first trial step; the controller adapts it within a few steps either way.
  constexpr double kInitialStep = 1e-3;
  for (std::size_t i = begin; i < end; ++i) {
    const double* o = &rays.origins[3 * i];
    const double* d = &rays.directions[3 * i];
    const double n = ode.n0 + ode.g * o[1];
    State x{o[0], o[1], o[2], n * d[0], n * d[1], n * d[2]};
    auto stepper = odeint::make_controlled<odeint::runge_kutta_dopri5<State>>(atol, rtol);
    // integrate_adaptive shortens the last step so the ray ends exactly at s = length.
    out.steps[i] = odeint::integrate_adaptive(stepper, ode, x, 0.0, length, kInitialStep);
    for (int k = 0; k < 3; ++k) out.positions[3 * i + k] = x[k];
  }
}

}  // namespace

PeerRun run_odeint_dopri5(const RaySet& rays, std::size_t count, double n0, double g, double length,
                          double rtol, double atol, unsigned threads) {
  PeerRun run;
  run.positions.resize(3 * count);
  run.steps.resize(count);
  const LinearRayOde ode{n0, g};
  threads = threads == 0 ? 1 : threads;

  const auto start = std::chrono::steady_clock::now();
  std::vector<std::thread> workers;
  for (unsigned t = 0; t < threads; ++t) {
    const std::size_t begin = count * t / threads, end = count * (t + 1) / threads;
    workers.emplace_back(integrate_range, std::cref(rays), begin, end, std::cref(ode), length, rtol, atol,
                         std::ref(run));
  }
  for (auto& w : workers) w.join();
  run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return run;
}

}  // namespace bench
