// Queries of a cast (rainbow/cast.h): the directions asked for, the sums of the patches
// holding each (kernels/rainbow/query.cl), and the phase function made of them.
#include <chrono>
#include <cmath>
#include <string>
#include <vector>

#include "core/context.h"
#include "core/error.h"
#include "core/format.h"
#include "core/kernel_source.h"
#include "core/launch.h"
#include "core/runtime.h"
#include "rainbow/cast.h"
#include "rainbow/rainbow_desc.h"  // kernels/rainbow: the query's description, shared with the kernel

namespace arcus::rainbow {
namespace {

constexpr double kPi = 3.14159265358979323846;

ARCUS_KERNEL_ARGS(QueryArg, "arcus_rainbow_query", ARCUS_RAINBOW_QUERY_ARGS);

const KernelSource kQuery{"rainbow/query",
                          {"common/real.h", "common/fresnel.h", "bvh/bvh_desc.h", "bvh/traverse.h",
                           "rainbow/rainbow_desc.h", "rainbow/optics.h", "rainbow/airy.h", "rainbow/query.cl"},
                          ""};

}  // namespace

std::vector<double> directions(const std::vector<double>& theta_deg, const std::vector<double>& phi_deg) {
  std::vector<double> d(3 * theta_deg.size());
  for (size_t i = 0; i < theta_deg.size(); ++i) {
    require(std::isfinite(theta_deg[i]) && theta_deg[i] >= 0 && theta_deg[i] <= 180,
            "theta[" + std::to_string(i) + "] must lie in [0, 180] degrees, got " + number(theta_deg[i]));
    require(std::isfinite(phi_deg[i]), "phi[" + std::to_string(i) + "] is not finite");
    const double t = theta_deg[i] * kPi / 180, f = phi_deg[i] * kPi / 180;
    d[3 * i] = std::sin(t) * std::cos(f);
    d[3 * i + 1] = std::sin(t) * std::sin(f);
    d[3 * i + 2] = std::cos(t);
  }
  return d;
}

std::vector<double> query(arcus_context_t* ctx, RainbowJob& job, const std::vector<double>& dirs, bool uniform) {
  const size_t count = dirs.size() / 3;
  std::vector<double> out(count * job.terms * ARCUS_RAINBOW_QUERY_REALS, 0.0);
  if (count == 0 || job.patch_count == 0) return out;
  const auto t0 = std::chrono::steady_clock::now();
  const BuiltProgram built = ctx->runtime->program(kQuery, 0, Layout{1, 1});
  DeviceBuffer dirs_dev(ctx, dirs.size() * sizeof(double), "the query directions", dirs.data());
  DeviceBuffer out_dev(ctx, out.size() * sizeof(double), "the query sums");
  Launch<QueryArg> k(ctx, built.program);
  k.bind(QueryArg::nodes, job.bvh->nodes().get());
  k.bind(QueryArg::tris, job.bvh->triangles().get());
  k.bind(QueryArg::order, job.bvh->order_buffer().get());
  k.bind(QueryArg::corners, job.corners.get());
  k.bind(QueryArg::patches, job.patches.get());
  k.bind(QueryArg::dirs, &dirs_dev);
  rainbow_query_desc q{};
  q.wave_number = job.wave_number;
  q.count = static_cast<int32_t>(count);
  q.terms = job.terms;
  q.coherent = uniform ? 1 : 0;
  k.bind_value(QueryArg::q, q);
  k.bind(QueryArg::out, &out_dev);
  k.run(count);
  out_dev.read(ctx, 0, out.size() * sizeof(double), out.data());
  job.info.query_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

Phase phase(const RainbowJob& job, const std::vector<double>& sums, bool coherent) {
  const int terms = job.terms, Q = ARCUS_RAINBOW_QUERY_REALS;
  const size_t count = sums.size() / (size_t(terms) * Q);
  Phase ph;
  ph.parallel.assign(count, 0.0);
  ph.perpendicular.assign(count, 0.0);
  ph.per_bounce.assign(count * terms, 0.0);
  const double c = job.cross_section > 0 ? job.cross_section : 1;
  for (size_t i = 0; i < count; ++i) {
    const double* s = &sums[i * terms * Q];
    double total[8] = {0};
    for (int p = 0; p < terms; ++p) {
      const double* t = s + p * Q;
      for (int e = 0; e < 8; ++e) total[e] += t[e];
      double per = 0;
      if (coherent)
        for (int e = 0; e < 8; ++e) per += t[e] * t[e];
      else
        per = t[8] + t[9] + t[10] + t[11];
      ph.per_bounce[i * terms + p] = per / 2 / c;
      if (!coherent) {
        ph.parallel[i] += (t[8] + t[10]) / 2 / c;       // E_hθ, E_vθ
        ph.perpendicular[i] += (t[9] + t[11]) / 2 / c;  // E_hφ, E_vφ
      }
    }
    if (coherent) {
      auto sq = [&](int e) { return total[2 * e] * total[2 * e] + total[2 * e + 1] * total[2 * e + 1]; };
      ph.parallel[i] = (sq(0) + sq(2)) / 2 / c;
      ph.perpendicular[i] = (sq(1) + sq(3)) / 2 / c;
    }
  }
  return ph;
}

}  // namespace arcus::rainbow
