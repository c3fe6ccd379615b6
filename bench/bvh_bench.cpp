// arcus_bench_bvh: segments per second of the OpenCL BVH traversal (kernels/bvh/,
// PoCL on every core) against Embree's rtcIntersect1 on as many std::threads, on the
// same segments: short steps like a curved-ray integrator's and long rays, over the
// bundled meshes and a scene of 27 tori.  Prints a Markdown table.
//
//   arcus_bench_bvh [--segments N] [--repeats R]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "bvh/device_bvh.h"
#include "bvh/embree_scene.h"
#include "core/context.h"
#include "geometry/mesh.h"

namespace {

using arcus::bvh::Hit;
using arcus::bvh::Segment;
using arcus::geometry::Mesh;

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

// Short: 5 cm steps (the meshes are ~2 m across) from anywhere in the scene's box, in
// random directions.  Long: from a sphere around the scene towards a random point of its
// box, 10 box diagonals long.
std::vector<Segment> make_segments(const Mesh& m, size_t n, bool short_steps, uint64_t seed) {
  double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  for (size_t v = 0; v < m.vertex_count(); ++v)
    for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], m.positions[3 * v + k]), hi[k] = std::max(hi[k], m.positions[3 * v + k]);
  const double diag = std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) + (hi[2] - lo[2]) * (hi[2] - lo[2]));
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> gauss;
  std::uniform_real_distribution<double> u01(0, 1);
  auto unit = [&](double d[3]) {
    for (int k = 0; k < 3; ++k) d[k] = gauss(rng);
    const double l = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    for (int k = 0; k < 3; ++k) d[k] /= l;
  };
  std::vector<Segment> out(n);
  for (Segment& s : out) {
    double inside[3], d[3];
    for (int k = 0; k < 3; ++k) inside[k] = lo[k] + u01(rng) * (hi[k] - lo[k]);
    unit(d);
    if (short_steps) {
      for (int k = 0; k < 3; ++k) s.origin[k] = inside[k], s.direction[k] = 0.05 * d[k];
      s.t_max = 1;
    } else {
      for (int k = 0; k < 3; ++k) s.origin[k] = 0.5 * (lo[k] + hi[k]) + diag * d[k];
      double l = 0;
      for (int k = 0; k < 3; ++k) s.direction[k] = inside[k] - s.origin[k], l += s.direction[k] * s.direction[k];
      for (int k = 0; k < 3; ++k) s.direction[k] /= std::sqrt(l);
      s.t_max = 10 * diag;
    }
  }
  return out;
}

Mesh tori() {  // 3 × 3 × 3 tori, 3 m apart, turned differently
  const Mesh torus = arcus::geometry::load_mesh(ARCUS_SOURCE_DIR "/data/meshes/torus.obj");
  Mesh all;
  for (int i = 0; i < 27; ++i) {
    const double a = 0.7 * i, c = std::cos(a), s = std::sin(a);
    const double M[12] = {c, -s, 0, 3.0 * (i % 3), s, c, 0, 3.0 * (i / 3 % 3), 0, 0, 1, 3.0 * (i / 9)};
    const Mesh t = arcus::geometry::transformed(torus, M);
    const uint32_t base = static_cast<uint32_t>(all.vertex_count());
    all.positions.insert(all.positions.end(), t.positions.begin(), t.positions.end());
    for (uint32_t v : t.triangles) all.triangles.push_back(base + v);
  }
  return all;
}

}  // namespace

int main(int argc, char** argv) {
  size_t n = 1 << 19;
  int repeats = 5;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--segments")) n = std::strtoul(argv[i + 1], nullptr, 10);
    if (!std::strcmp(argv[i], "--repeats")) repeats = std::atoi(argv[i + 1]);
  }
  arcus_context_t* ctx = nullptr;
  if (arcus_context_create(ARCUS_DEVICE_DEFAULT, &ctx) != ARCUS_SUCCESS) {
    std::fprintf(stderr, "%s\n", arcus_last_error());
    return 1;
  }
  const unsigned cores = ctx->info.compute_units;
  std::printf("# BVH closest hit: OpenCL traversal (%s, %u compute units) against Embree rtcIntersect1 on %u threads\n\n",
              ctx->info.name, cores, cores);
  std::printf("%zu segments per run, median of %d runs; Mseg/s = 10^6 segments per second.  OpenCL \"kernel\": the "
              "kernel's device time; \"call\": closest_hits() with uploads and read-backs.\n\n",
              n, repeats);
  std::printf("| mesh | triangles | segments | hit | tests/seg | OpenCL double kernel | OpenCL double call | "
              "OpenCL float kernel | Embree %u threads | Embree ÷ OpenCL double kernel | same triangle |\n",
              cores);
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|\n");
  struct Case {
    const char* name;
    Mesh mesh;
  };
  std::vector<Case> cases;
  cases.push_back({"icosphere", arcus::geometry::load_mesh(ARCUS_SOURCE_DIR "/data/meshes/icosphere.obj")});
  cases.push_back({"tower", arcus::geometry::load_mesh(ARCUS_SOURCE_DIR "/data/meshes/tower.ply")});
  cases.push_back({"27 tori", tori()});
  for (const Case& c : cases) {
    const arcus::bvh::TriangleBvh bvh = arcus::bvh::build_triangles(c.mesh);
    const arcus::bvh::DeviceBvh dev_d(ctx, bvh, false), dev_f(ctx, bvh, true);
    const arcus::bvh::EmbreeScene embree(c.mesh);
    for (bool short_steps : {true, false}) {
      const std::vector<Segment> segs = make_segments(c.mesh, n, short_steps, 2024);
      std::vector<double> kd, call, kf, em;
      std::vector<Hit> got, want;
      arcus::bvh::closest_hits(ctx, dev_d, segs);  // builds the programs
      arcus::bvh::closest_hits(ctx, dev_f, segs);
      for (int r = 0; r < repeats; ++r) {
        double s = 0;
        auto t0 = std::chrono::steady_clock::now();
        got = arcus::bvh::closest_hits(ctx, dev_d, segs, &s);
        call.push_back(seconds_since(t0));
        kd.push_back(s);
        arcus::bvh::closest_hits(ctx, dev_f, segs, &s);
        kf.push_back(s);
        t0 = std::chrono::steady_clock::now();
        want = embree.closest_hits(segs, cores);
        em.push_back(seconds_since(t0));
      }
      size_t hits = 0, same = 0;
      double tests = 0;
      for (size_t i = 0; i < n; ++i) {
        hits += got[i].primitive >= 0;
        same += got[i].primitive == want[i].primitive;
        tests += got[i].tests;
      }
      const double mkd = n / median(kd) * 1e-6, mcall = n / median(call) * 1e-6, mkf = n / median(kf) * 1e-6,
                   mem = n / median(em) * 1e-6;
      std::printf("| %s | %zu | %s | %.1f %% | %.1f | %.2f | %.2f | %.2f | %.2f | %.2f× | %.3f %% |\n", c.name,
                  c.mesh.triangle_count(), short_steps ? "short steps (5 cm)" : "long rays", 100.0 * hits / n,
                  tests / n, mkd, mcall, mkf, mem, mem / mkd, 100.0 * same / n);
      std::fflush(stdout);
    }
  }
  arcus_context_release(ctx);
  return 0;
}
