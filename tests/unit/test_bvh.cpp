// The BVH: Embree's builder flattened, the OpenCL traversal (bvh/traverse.h) against
// Embree's rtcIntersect1 on the bundled meshes, watertightness on shared edges and
// vertices, degenerate triangles, grazing segments, the empty tree, the box-overlap
// proof and the all-hits kernel against brute force.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <random>
#include <set>

#include "bvh/device_bvh.h"
#include "bvh/embree_scene.h"
#include "core/error.h"
#include "core/layout.h"
#include "core/runtime.h"
#include "geometry/mesh.h"
#include "unit_util.h"

// The traversal's own code on the host (one double at a time), for brute-force references.
#include "bvh/traverse.h"

namespace {

using arcus::bvh::AllHits;
using arcus::bvh::Bounds;
using arcus::bvh::DeviceBvh;
using arcus::bvh::Hit;
using arcus::bvh::Segment;
using arcus::bvh::TriangleBvh;
using arcus::geometry::Mesh;
using arcus_unit::Context;

const char* const kMeshes[] = {"icosphere.obj", "torus.obj", "tower.ply"};

Mesh bundled(const char* name) { return arcus::geometry::load_mesh(std::string(ARCUS_SOURCE_DIR "/data/meshes/") + name); }

const double* vertex(const Mesh& m, size_t triangle, int corner) {
  return &m.positions[3 * m.triangles[3 * triangle + corner]];
}

// Random segments over a mesh of size ~1 (coordinates within ±3): a third long rays
// from anywhere, a third aimed at a random point of a random triangle and ending
// before or after it, a third short steps near the surface (a curved-ray integrator's).
std::vector<Segment> random_segments(const Mesh& m, size_t n, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u01(0, 1), box(-3, 3), normal(-1, 1);
  auto direction = [&](double d[3]) {
    do
      for (int k = 0; k < 3; ++k) d[k] = normal(rng);
    while (d[0] * d[0] + d[1] * d[1] + d[2] * d[2] > 1 || d[0] * d[0] + d[1] * d[1] + d[2] * d[2] < 1e-4);
    const double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    for (int k = 0; k < 3; ++k) d[k] /= len;
  };
  auto surface_point = [&](double p[3]) {
    const size_t t = std::uniform_int_distribution<size_t>(0, m.triangle_count() - 1)(rng);
    double a = u01(rng), b = u01(rng);
    if (a + b > 1) a = 1 - a, b = 1 - b;
    for (int k = 0; k < 3; ++k)
      p[k] = vertex(m, t, 0)[k] + a * (vertex(m, t, 1)[k] - vertex(m, t, 0)[k]) + b * (vertex(m, t, 2)[k] - vertex(m, t, 0)[k]);
  };
  std::vector<Segment> out(n);
  for (size_t i = 0; i < n; ++i) {
    Segment& s = out[i];
    switch (i % 3) {
      case 0:
        for (int k = 0; k < 3; ++k) s.origin[k] = box(rng);
        direction(s.direction);
        s.t_max = 8 * u01(rng);
        break;
      case 1: {
        double target[3];
        surface_point(target);
        for (int k = 0; k < 3; ++k) s.origin[k] = box(rng), s.direction[k] = target[k] - s.origin[k];
        s.t_max = 0.5 + u01(rng);  // up to 1.5 times the way to the target
        break;
      }
      default: {
        double d[3];
        surface_point(s.origin);
        direction(d);
        for (int k = 0; k < 3; ++k) s.origin[k] += 0.02 * d[k];
        direction(s.direction);
        for (int k = 0; k < 3; ++k) s.direction[k] *= 0.05;
        s.t_max = 1;
      }
    }
  }
  return out;
}

double norm(const double v[3]) { return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

// |cos| of the angle between the segment and triangle t's normal.
double incidence(const Mesh& m, size_t t, const Segment& s) {
  const double *a = vertex(m, t, 0), *b = vertex(m, t, 1), *c = vertex(m, t, 2);
  const double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  const double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
  return std::fabs(n[0] * s.direction[0] + n[1] * s.direction[1] + n[2] * s.direction[2]) / (norm(n) * norm(s.direction));
}

// How far apart Embree (float) and the double traversal may put a hit, along the
// segment, in units of length: Embree rounds the vertices, origin and direction to
// float (relative 6·10⁻⁸ at coordinates up to 3, so ~2·10⁻⁷ each) and intersects in
// float, which places the hit ~10⁻⁶ off the surface; along a segment meeting the
// surface at incidence cos θ that is 10⁻⁶ / cos θ.  cos θ is floored at 10⁻³ (the
// few nearly grazing segments get 10⁻³).
double tolerance(double cos_incidence) { return 1e-6 / std::max(cos_incidence, 1e-3); }

struct Agreement {
  size_t hits = 0, misses = 0, other_triangle = 0, at_an_end = 0;
};

// Compares the traversal with Embree: the same triangle at the same distance (to the
// tolerance), or another triangle at the same distance where the hit is within the
// tolerance of one of Embree's triangle's edges (a shared edge or vertex, where either
// triangle is right); a hit one side misses only within the tolerance of the
// segment's ends (t = 0 or t_max, where float and double round either way).
Agreement compare_with_embree(const Mesh& m, const std::vector<Segment>& segs, const std::vector<Hit>& got,
                              const std::vector<Hit>& want, const std::string& what) {
  Agreement a;
  for (size_t i = 0; i < segs.size(); ++i) {
    const Segment& s = segs[i];
    const double len = norm(s.direction);
    const Hit &g = got[i], &w = want[i];
    if (g.primitive < 0 && w.primitive < 0) {
      ++a.misses;
      continue;
    }
    if (g.primitive < 0 || w.primitive < 0) {
      const Hit& h = g.primitive >= 0 ? g : w;
      const double tol = tolerance(incidence(m, h.primitive, s));
      EXPECT_TRUE(h.t * len <= tol || (s.t_max - h.t) * len <= tol)
          << what << " segment " << i << ": only " << (g.primitive >= 0 ? "OpenCL" : "Embree") << " hits, triangle "
          << h.primitive << " at t " << h.t << " of " << s.t_max;
      ++a.at_an_end;
      continue;
    }
    const double tol = tolerance(std::min(incidence(m, g.primitive, s), incidence(m, w.primitive, s)));
    EXPECT_LE(std::fabs(g.t - w.t) * len, tol) << what << " segment " << i << ": triangles " << g.primitive << ", "
                                               << w.primitive;
    if (g.primitive == w.primitive) {
      ++a.hits;
      // The barycentric coordinates name the same point, to the same tolerance.
      const double *p0 = vertex(m, g.primitive, 0), *p1 = vertex(m, g.primitive, 1), *p2 = vertex(m, g.primitive, 2);
      double gap[3];
      for (int k = 0; k < 3; ++k)
        gap[k] = (g.u - w.u) * (p1[k] - p0[k]) + (g.v - w.v) * (p2[k] - p0[k]);
      EXPECT_LE(norm(gap), tol) << what << " segment " << i;
    } else {
      ++a.other_triangle;
      const double edge = std::min({w.u, w.v, 1 - w.u - w.v});
      EXPECT_LE(edge, 1e-4) << what << " segment " << i << ": triangles " << g.primitive << ", " << w.primitive
                            << " and Embree's hit is not on an edge";
    }
  }
  return a;
}

TEST(Bvh, BuildFlattensEveryPrimitiveOnceWithExactBoxes) {
  for (const char* name : kMeshes) {
    const Mesh m = bundled(name);
    const TriangleBvh b = arcus::bvh::build_triangles(m);
    const auto& nodes = b.tree.nodes;
    std::vector<uint32_t> sorted = b.tree.order;
    std::sort(sorted.begin(), sorted.end());
    for (size_t i = 0; i < sorted.size(); ++i) ASSERT_EQ(sorted[i], i) << name;
    EXPECT_EQ(b.triangle_count(), m.triangle_count());
    EXPECT_LE(b.tree.depth, ARCUS_BVH_MAX_DEPTH);
    // Each node's box is exactly the union of its children's / its triangles' boxes;
    // leaves hold 1 to 4 triangles and every node is reached once.
    std::vector<int> reached(nodes.size(), 0);
    reached[0] = 1;
    for (size_t n = 0; n < nodes.size(); ++n) {
      ASSERT_EQ(reached[n], 1) << name << " node " << n;
      double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
      if (nodes[n].count > 0) {
        ASSERT_LE(nodes[n].count, 4);
        for (int s = nodes[n].first; s < nodes[n].first + nodes[n].count; ++s)
          for (int c = 0; c < 3; ++c)
            for (int k = 0; k < 3; ++k)
              lo[k] = std::min(lo[k], b.triangles[9 * s + 3 * c + k]), hi[k] = std::max(hi[k], b.triangles[9 * s + 3 * c + k]);
      } else {
        ASSERT_GT(nodes[n].first, static_cast<int>(n));  // depth-first: children come later
        for (int c = 0; c < 2; ++c) {
          ++reached[nodes[n].first + c];
          for (int k = 0; k < 3; ++k)
            lo[k] = std::min(lo[k], nodes[nodes[n].first + c].lo[k]), hi[k] = std::max(hi[k], nodes[nodes[n].first + c].hi[k]);
        }
      }
      for (int k = 0; k < 3; ++k) {
        EXPECT_EQ(nodes[n].lo[k], lo[k]);
        EXPECT_EQ(nodes[n].hi[k], hi[k]);
      }
    }
    // Triangles are in leaf order: slot s holds triangle order[s].
    for (size_t s = 0; s < b.triangle_count(); ++s)
      for (int c = 0; c < 3; ++c)
        for (int k = 0; k < 3; ++k) ASSERT_EQ(b.triangles[9 * s + 3 * c + k], vertex(m, b.tree.order[s], c)[k]);
    // Float boxes contain the double ones.
    const auto f = arcus::bvh::to_float(nodes);
    for (size_t n = 0; n < nodes.size(); ++n)
      for (int k = 0; k < 3; ++k) EXPECT_TRUE(f[n].lo[k] <= nodes[n].lo[k] && f[n].hi[k] >= nodes[n].hi[k]);
  }
}

TEST(Bvh, GenericBuilderTakesPointsAndRefusesBadInput) {
  // Photons: zero-size boxes, many on the same spot.
  std::vector<arcus::bvh::Bounds> points;
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int i = 0; i < 5000; ++i) {
    const double p[3] = {i % 3 == 0 ? 0.25 : u(rng), i % 3 == 0 ? 0.5 : u(rng), u(rng) * (i % 3 != 0)};
    points.push_back({{p[0], p[1], p[2]}, {p[0], p[1], p[2]}});
  }
  const arcus::bvh::Flat flat = arcus::bvh::build(points, 8);
  EXPECT_EQ(flat.order.size(), points.size());
  EXPECT_LE(flat.depth, ARCUS_BVH_MAX_DEPTH);
  for (const auto& n : flat.nodes) EXPECT_LE(n.count, 8);
  // No primitives: one node that traversals never enter.
  const arcus::bvh::Flat empty = arcus::bvh::build({});
  ASSERT_EQ(empty.nodes.size(), 1u);
  EXPECT_EQ(empty.nodes[0].count, 0);
  EXPECT_EQ(empty.nodes[0].first, -1);
  EXPECT_TRUE(empty.order.empty());
  EXPECT_THROW(arcus::bvh::build(points, 0), arcus::Error);
  EXPECT_THROW(arcus::bvh::build(points, 33), arcus::Error);
  points[10].lo[1] = NAN;
  EXPECT_THROW(arcus::bvh::build(points), arcus::Error);
  points[10].lo[1] = 2, points[10].hi[1] = 1;  // inverted
  EXPECT_THROW(arcus::bvh::build(points), arcus::Error);
}

TEST(Bvh, PrimitivesBeyondWhatEmbreeCanBinAreRefusedNotAnAbort) {
  // Embree bins in single precision: a box at 3e38 m failed an assertion in its binning
  // and killed the process.  Beyond kMaxCoordinate the build refuses, with a message.
  for (const double far : {3e38, -1e30, 2e18}) {
    std::vector<Bounds> boxes(64);
    for (size_t i = 0; i < boxes.size(); ++i)
      for (int k = 0; k < 3; ++k) boxes[i].lo[k] = boxes[i].hi[k] = double(i) + k;
    boxes[17].lo[0] = std::min(far, boxes[17].lo[0]);
    boxes[17].hi[0] = std::max(far, boxes[17].hi[0]);
    const arcus_unit::Failure f = arcus_unit::failure_of([&] { arcus::bvh::build(boxes); });
    EXPECT_EQ(f.status, ARCUS_ERROR_INVALID_ARGUMENT) << far;
    EXPECT_NE(f.message.find("primitive 17"), std::string::npos) << f.message;
    EXPECT_NE(f.message.find("1e+18 m"), std::string::npos) << f.message;
  }
  // Up to the bound it builds, one leaf per primitive's box as always.
  std::vector<Bounds> boxes(64);
  for (size_t i = 0; i < boxes.size(); ++i)
    for (int k = 0; k < 3; ++k) boxes[i].lo[k] = boxes[i].hi[k] = (i % 2 ? 1e18 : -1e18) / double(i + 1);
  EXPECT_EQ(arcus::bvh::build(boxes).order.size(), boxes.size());
}

TEST(Bvh, OpenClTraversalAgreesWithEmbree) {
  Context ctx;
  for (const char* name : kMeshes) {
    const Mesh m = bundled(name);
    const DeviceBvh device(ctx, arcus::bvh::build_triangles(m), false);
    const arcus::bvh::EmbreeScene embree(m);
    const std::vector<Segment> segs = random_segments(m, 3000, 42);
    const std::vector<Hit> got = arcus::bvh::closest_hits(ctx, device, segs);
    const Agreement a = compare_with_embree(m, segs, got, embree.closest_hits(segs, 2), name);
    // Both outcomes are well represented, and disagreements are rare edge cases.
    EXPECT_GT(a.hits, 600u) << name;
    EXPECT_GT(a.misses, 600u) << name;
    EXPECT_LT(a.other_triangle + a.at_an_end, 30u) << name;
    for (size_t i = 0; i < got.size(); ++i)
      if (got[i].slot >= 0) {
        ASSERT_EQ(static_cast<uint32_t>(got[i].primitive), device.order()[got[i].slot]);
      }
    std::printf("%s: %zu same hits, %zu misses, %zu other triangle on an edge, %zu at an end\n", name, a.hits,
                a.misses, a.other_triangle, a.at_an_end);
  }
}

TEST(Bvh, FloatTraversalAgreesWithEmbreeToo) {
  Context ctx;
  const Mesh m = bundled("torus.obj");
  const DeviceBvh device(ctx, arcus::bvh::build_triangles(m), true);
  const std::vector<Segment> segs = random_segments(m, 3000, 43);
  const std::vector<Hit> got = arcus::bvh::closest_hits(ctx, device, segs);
  const std::vector<Hit> want = arcus::bvh::EmbreeScene(m).closest_hits(segs);
  // Float against float: the same triangle wherever neither is within 10⁻⁵ of an edge or an end.
  size_t same = 0, differ = 0;
  for (size_t i = 0; i < segs.size(); ++i) {
    if (got[i].primitive == want[i].primitive) {
      ++same;
      if (got[i].primitive >= 0) {
        EXPECT_NEAR(got[i].t * norm(segs[i].direction), want[i].t * norm(segs[i].direction), 1e-4);
      }
    } else {
      ++differ;
    }
  }
  EXPECT_LT(differ, 15u);
  EXPECT_EQ(same + differ, segs.size());
}

// A flat grid of n × n unit squares in z = 0, each split along its diagonal, with
// alternating diagonals so that vertices are shared by 4 or 8 triangles.
Mesh grid(int n) {
  Mesh m;
  for (int y = 0; y <= n; ++y)
    for (int x = 0; x <= n; ++x) m.positions.insert(m.positions.end(), {double(x), double(y), 0.0});
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const uint32_t a = y * (n + 1) + x, b = a + 1, c = a + n + 2, d = a + n + 1;
      if ((x + y) % 2)
        m.triangles.insert(m.triangles.end(), {a, b, c, a, c, d});
      else
        m.triangles.insert(m.triangles.end(), {a, b, d, b, c, d});
    }
  return m;
}

TEST(Bvh, SegmentsThroughSharedEdgesAndVerticesHitExactlyOneTriangle) {
  Context ctx;
  // Exact cases: segments through grid edges and vertices (every edge function is
  // exactly 0 there), straight down and sheared, both ways, and with the grid's
  // winding flipped.  All hits per segment: exactly one.
  for (bool flipped : {false, true}) {
    Mesh g = grid(6);
    if (flipped)
      for (size_t t = 0; t < g.triangle_count(); ++t) std::swap(g.triangles[3 * t + 1], g.triangles[3 * t + 2]);
    const DeviceBvh device(ctx, arcus::bvh::build_triangles(g), false);
    std::vector<Segment> segs;
    const double dirs[][3] = {{0, 0, 1}, {0, 0, -1}, {0.25, 0.5, 1}, {-0.5, 0.125, -1}, {0.75, -0.25, 1}};
    for (const auto& d : dirs)
      for (int i = 2; i <= 16; ++i)
        for (int j = 2; j <= 16; ++j) {  // quarter steps: vertices, edge midpoints, quarter points, interiors
          const double x = i * 0.25, y = j * 0.25;  // reached at t = 1
          segs.push_back(Segment{{x - d[0], y - d[1], -d[2]}, {d[0], d[1], d[2]}, 2});
        }
    const AllHits all = arcus::bvh::all_hits(ctx, device, segs, 10 * segs.size());
    ASSERT_FALSE(all.overflow);
    std::vector<int> per(segs.size(), 0);
    for (const auto& p : all.pairs) ++per[p.first];
    for (size_t i = 0; i < segs.size(); ++i)
      EXPECT_EQ(per[i], 1) << "flipped " << flipped << ", segment through (" << segs[i].origin[0] + segs[i].direction[0]
                           << ", " << segs[i].origin[1] + segs[i].direction[1] << ")";
    const std::vector<Hit> closest = arcus::bvh::closest_hits(ctx, device, segs);
    for (size_t i = 0; i < segs.size(); ++i) EXPECT_GE(closest[i].primitive, 0);
  }
  // Rounded cases: on each bundled mesh, segments through points on shared edges and
  // through shared vertices (the point rounded to double, so the segment passes within
  // an ulp of the edge): exactly one triangle around the point, never none, never two.
  // The segment crosses the surface there: its direction has the same side (|cos| >=
  // 0.1) against every triangle around the point; a segment grazing a ridge may
  // rightly hit both faces or neither.
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u01(0, 1), sym(-1, 1);
  for (const char* name : kMeshes) {
    const Mesh m = bundled(name);
    // Vertices by position: the torus' seam repeats its vertices for the texture.
    std::map<std::array<double, 3>, uint32_t> first_at;
    std::vector<uint32_t> same(m.vertex_count());
    for (uint32_t v = 0; v < m.vertex_count(); ++v)
      same[v] = first_at.insert({{m.positions[3 * v], m.positions[3 * v + 1], m.positions[3 * v + 2]}, v}).first->second;
    std::map<std::pair<uint32_t, uint32_t>, std::vector<uint32_t>> edges;
    std::vector<std::vector<uint32_t>> fans(m.vertex_count());
    for (uint32_t t = 0; t < m.triangle_count(); ++t)
      for (int c = 0; c < 3; ++c) {
        const uint32_t a = same[m.triangles[3 * t + c]], b = same[m.triangles[3 * t + (c + 1) % 3]];
        edges[{std::min(a, b), std::max(a, b)}].push_back(t);
        fans[a].push_back(t);
      }
    std::vector<std::pair<std::pair<uint32_t, uint32_t>, std::vector<uint32_t>>> shared;
    for (const auto& e : edges)
      if (e.second.size() == 2) shared.push_back(e);
    auto unit_normal = [&](uint32_t t, double n[3]) {
      const double *a = vertex(m, t, 0), *b = vertex(m, t, 1), *c = vertex(m, t, 2);
      const double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
      n[0] = e1[1] * e2[2] - e1[2] * e2[1], n[1] = e1[2] * e2[0] - e1[0] * e2[2], n[2] = e1[0] * e2[1] - e1[1] * e2[0];
      const double l = norm(n);
      for (int k = 0; k < 3; ++k) n[k] /= l;
    };
    // A direction crossing every triangle of `around` from the same side, or false.
    auto crossing = [&](const std::vector<uint32_t>& around, double d[3]) {
      double avg[3] = {0, 0, 0}, n[3];
      for (uint32_t t : around) {
        unit_normal(t, n);
        for (int k = 0; k < 3; ++k) avg[k] += n[k];
      }
      for (int tries = 0; tries < 20; ++tries) {
        const double sign = u01(rng) < 0.5 ? -1 : 1, len = norm(avg);
        for (int k = 0; k < 3; ++k) d[k] = sign * avg[k] / len + 0.8 * sym(rng);
        bool ok = true;
        for (uint32_t t : around) {
          unit_normal(t, n);
          ok = ok && sign * (n[0] * d[0] + n[1] * d[1] + n[2] * d[2]) >= 0.1 * norm(d);
        }
        if (ok) return true;
      }
      return false;
    };
    const DeviceBvh device(ctx, arcus::bvh::build_triangles(m), false);
    std::vector<Segment> segs;
    std::vector<std::vector<uint32_t>> around;
    while (segs.size() < 3000) {
      const auto& e = shared[std::uniform_int_distribution<size_t>(0, shared.size() - 1)(rng)];
      const bool at_vertex = segs.size() % 5 == 0;  // every fifth through the vertex itself
      const std::vector<uint32_t>& tris = at_vertex ? fans[e.first.first] : e.second;
      const double *a = &m.positions[3 * e.first.first], *b = &m.positions[3 * e.first.second];
      const double f = at_vertex ? 0.0 : u01(rng);
      double d[3];
      if (!crossing(tris, d)) continue;
      Segment s;
      for (int k = 0; k < 3; ++k) s.direction[k] = 0.01 * d[k], s.origin[k] = a[k] + f * (b[k] - a[k]) - s.direction[k];
      s.t_max = 2;
      segs.push_back(s);
      around.push_back(tris);
    }
    const AllHits all = arcus::bvh::all_hits(ctx, device, segs, 10 * segs.size());
    ASSERT_FALSE(all.overflow);
    std::vector<int> hits(segs.size(), 0);
    for (const auto& p : all.pairs)
      hits[p.first] += std::count(around[p.first].begin(), around[p.first].end(), p.second) > 0;
    for (size_t i = 0; i < segs.size(); ++i)
      EXPECT_EQ(hits[i], 1) << name << " segment " << i << (i % 5 == 0 ? " through a vertex" : " through an edge");
  }
}

TEST(Bvh, ZeroAreaTrianglesAreNeverHit) {
  Context ctx;
  Mesh m;
  // 0: a proper triangle; 1: two coincident vertices; 2: collinear, exact; 3: collinear
  // with rounded coordinates; 4: all three the same point; 5: another proper one.
  m.positions = {0, 0, 0,   1, 0, 0,   0, 1, 0,                        // 0 1 2
                 0.5, 0.25, 0.5, 0.5, 0.25, 0.5, 0.75, 0.5, 0.5,       // 3 4 5
                 -1, -1, 0, 1, 1, 0, 3, 3, 0,                          // 6 7 8
                 0.1, 0.2, 0.3, 0.2, 0.4, 0.6, 0.30000000000000004, 0.6000000000000001, 0.9,  // 9 10 11
                 2, 2, 2,                                              // 12
                 0, 0, 1, 1, 0, 1, 0, 1, 1};                           // 13 14 15
  m.triangles = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 12, 12, 13, 14, 15};
  const TriangleBvh b = arcus::bvh::build_triangles(m);
  const DeviceBvh device(ctx, b, false);
  std::vector<Segment> segs;
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> sym(-1, 1);
  // Through every vertex and edge midpoint of the degenerate ones, from random directions.
  for (uint32_t t = 1; t <= 4; ++t)
    for (int c = 0; c < 3; ++c)
      for (double f : {0.0, 0.5, 0.25})
        for (int r = 0; r < 20; ++r) {
          const double *p = vertex(m, t, c), *q = vertex(m, t, (c + 1) % 3);
          Segment s;
          for (int k = 0; k < 3; ++k) s.direction[k] = sym(rng), s.origin[k] = p[k] + f * (q[k] - p[k]) - s.direction[k];
          s.t_max = 2;
          segs.push_back(s);
        }
  const AllHits all = arcus::bvh::all_hits(ctx, device, segs, 10 * segs.size());
  ASSERT_FALSE(all.overflow);
  for (const auto& p : all.pairs) EXPECT_TRUE(p.second == 0 || p.second == 5) << "segment " << p.first << " hit " << p.second;
  for (const Hit& h : arcus::bvh::closest_hits(ctx, device, segs)) EXPECT_TRUE(h.primitive < 0 || h.primitive == 0 || h.primitive == 5);
  // The proper triangles are hit.
  const std::vector<Segment> down = {Segment{{0.25, 0.25, 2}, {0, 0, -1}, 3}};
  const std::vector<Hit> h = arcus::bvh::closest_hits(ctx, device, down);
  EXPECT_EQ(h[0].primitive, 5);
  EXPECT_DOUBLE_EQ(h[0].t, 1.0);
  EXPECT_DOUBLE_EQ(h[0].u, 0.25);
  EXPECT_DOUBLE_EQ(h[0].v, 0.25);
}

TEST(Bvh, EmptyTreeMissesEverything) {
  Context ctx;
  Mesh empty;
  const TriangleBvh b = arcus::bvh::build_triangles(empty);
  for (bool single : {false, true}) {
    const DeviceBvh device(ctx, b, single);
    const std::vector<Segment> segs = {Segment{{0, 0, 0}, {1, 0, 0}, 10}, Segment{{-1, -1, -1}, {1, 1, 1}, 5}};
    for (const Hit& h : arcus::bvh::closest_hits(ctx, device, segs)) EXPECT_EQ(h.slot, -1);
    EXPECT_EQ(arcus::bvh::all_hits(ctx, device, segs, 4).needed, 0u);
    EXPECT_EQ(arcus::bvh::all_hits(ctx, device, std::vector<double>{0, 0, 0}, 4).needed, 0u);
  }
}

// A cube [-0.5, 0.5]³ of 12 triangles.
Mesh cube() {
  Mesh m;
  for (int i = 0; i < 8; ++i) m.positions.insert(m.positions.end(), {i & 1 ? 0.5 : -0.5, i & 2 ? 0.5 : -0.5, i & 4 ? 0.5 : -0.5});
  m.triangles = {0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4, 2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5};
  return m;
}

TEST(Bvh, GrazingSegmentsParallelToAFace) {
  Context ctx;
  const Mesh m = cube();
  const DeviceBvh device(ctx, arcus::bvh::build_triangles(m), false);
  const arcus::bvh::EmbreeScene embree(m);
  std::vector<Segment> segs;
  // Parallel to the top face z = 0.5, just above, exactly in it, just below, across the cube.
  for (double z : {0.5 + 1e-9, 0.5, 0.5 - 1e-9})
    for (double y : {-0.3, 0.0, 0.1, 0.3})  // at x = -0.5 (t = 0.5): y within the cube
      segs.push_back(Segment{{-1, y, z}, {1, 0.125, 0}, 2});
  const std::vector<Hit> got = arcus::bvh::closest_hits(ctx, device, segs);
  const std::vector<Hit> want = embree.closest_hits(segs);
  auto top = [](int p) { return p == 4 || p == 5; };  // the two triangles of z = 0.5
  for (size_t i = 0; i < segs.size(); ++i) {
    const double z = segs[i].origin[2];
    EXPECT_FALSE(top(got[i].primitive)) << "segment " << i;  // in the plane: det = 0; beside it: no crossing
    if (z > 0.5) {
      EXPECT_EQ(got[i].primitive, -1) << "segment " << i;
    }
    if (z < 0.5) {  // inside the cube's slab: enters through the face x = -0.5 at t = 0.5
      EXPECT_EQ(got[i].primitive, want[i].primitive) << "segment " << i;
      EXPECT_TRUE(got[i].primitive == 8 || got[i].primitive == 9) << "segment " << i;
      EXPECT_NEAR(got[i].t, 0.5, 1e-12);
    }
  }
}

TEST(Bvh, BoxOverlapProofAgreesWithBruteForce) {
  Context ctx;
  // A kernel of a test's own calling the inline function, as the renderer will.
  const arcus::KernelSource source{"bvh/test_box_overlaps",
                                   {"common/real.h", "bvh/bvh_desc.h", "bvh/traverse.h"},
                                   "__kernel void box_overlaps(__global const bvh_node* nodes, __global const REAL* tris,\n"
                                   "                           __global const REAL* boxes, uint n, __global int* out) {\n"
                                   "  const size_t i = get_global_id(0);\n"
                                   "  if (i >= n) return;\n"
                                   "  REAL lo[3], hi[3];\n"
                                   "  for (int k = 0; k < 3; ++k) lo[k] = boxes[6 * i + k], hi[k] = boxes[6 * i + 3 + k];\n"
                                   "  out[i] = bvh_box_overlaps(nodes, tris, lo, hi);\n"
                                   "}\n"};
  const arcus::BuiltProgram program =
      ctx.ctx->runtime->program(source, 0, arcus::choose_layout(ctx.ctx->runtime->entry(), 1));
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u01(0, 1), pos(-1.8, 1.8);
  for (const char* name : kMeshes) {
    const Mesh m = bundled(name);
    const TriangleBvh b = arcus::bvh::build_triangles(m);
    const DeviceBvh device(ctx, b, false);
    const cl_uint n = 4000;
    std::vector<double> boxes;
    for (cl_uint i = 0; i < n; ++i) {
      const double size = i % 2 ? 0.02 * u01(rng) : 0.4 * u01(rng);
      for (int k = 0; k < 3; ++k) boxes.push_back(pos(rng));
      for (int k = 0; k < 3; ++k) boxes.push_back(boxes[6 * i + k] + size * u01(rng));
    }
    arcus::DeviceBuffer in(ctx, boxes.size() * sizeof(double), "boxes", boxes.data()), out(ctx, n * sizeof(cl_int), "out");
    arcus::KernelCall k(program.program, "box_overlaps");
    k.set(0, device.nodes().get());
    k.set(1, device.triangles().get());
    k.set(2, &in);
    k.set_value(3, n);
    k.set(4, &out);
    k.run(ctx, n);
    std::vector<cl_int> got(n);
    out.read(ctx, 0, n * sizeof(cl_int), got.data());
    size_t overlapping = 0;
    for (cl_uint i = 0; i < n; ++i) {
      bool any = false;
      for (size_t t = 0; t < m.triangle_count() && !any; ++t) {
        bool all = true;
        for (int k = 0; k < 3; ++k) {
          const double lo = std::min({vertex(m, t, 0)[k], vertex(m, t, 1)[k], vertex(m, t, 2)[k]});
          const double hi = std::max({vertex(m, t, 0)[k], vertex(m, t, 1)[k], vertex(m, t, 2)[k]});
          all = all && lo <= boxes[6 * i + 3 + k] && boxes[6 * i + k] <= hi;
        }
        any = all;
      }
      overlapping += any;
      ASSERT_EQ(got[i], any ? 1 : 0) << name << " box " << i;
    }
    EXPECT_GT(overlapping, 100u) << name;
    EXPECT_LT(overlapping, n - 100) << name;
  }
}

TEST(Bvh, AllHitsEqualBruteForceAndOverflowIsReported) {
  Context ctx;
  for (const char* name : kMeshes) {
    const Mesh m = bundled(name);
    const TriangleBvh b = arcus::bvh::build_triangles(m);
    const DeviceBvh device(ctx, b, false);
    const std::vector<Segment> segs = random_segments(m, 1500, 9);
    // Brute force: the same triangle test (the host instance of traverse.h) on every slot.
    std::vector<std::pair<uint32_t, uint32_t>> want;
    for (uint32_t i = 0; i < segs.size(); ++i) {
      const Segment& s = segs[i];
      bvh_ray r;
      bvh_ray_init(&r, s.origin[0], s.origin[1], s.origin[2], s.direction[0], s.direction[1], s.direction[2]);
      for (size_t slot = 0; slot < b.triangle_count(); ++slot) {
        double t, u, v;
        if (bvh_triangle_hit(&r, &b.triangles[9 * slot], s.t_max, &t, &u, &v)) want.push_back({i, b.tree.order[slot]});
      }
    }
    std::sort(want.begin(), want.end());
    ASSERT_GT(want.size(), segs.size() / 3) << name;
    AllHits got = arcus::bvh::all_hits(ctx, device, segs, want.size());
    ASSERT_FALSE(got.overflow);
    std::sort(got.pairs.begin(), got.pairs.end());
    EXPECT_EQ(got.pairs, want) << name;
    // One too few places: reported with the size needed, no partial list.
    const AllHits small = arcus::bvh::all_hits(ctx, device, segs, want.size() - 1);
    EXPECT_TRUE(small.overflow);
    EXPECT_EQ(small.needed, want.size());
    EXPECT_TRUE(small.pairs.empty());

    // Points: every triangle whose box contains the point, against brute force.
    std::vector<double> points;
    std::mt19937_64 rng(13);
    std::uniform_real_distribution<double> pos(-1.6, 1.6);
    for (int i = 0; i < 3000; ++i) points.push_back(pos(rng));
    for (int i = 0; i < 30; ++i) points.insert(points.end(), vertex(m, i, 0), vertex(m, i, 0) + 3);  // on box corners
    std::vector<std::pair<uint32_t, uint32_t>> inside;
    for (uint32_t p = 0; p < points.size() / 3; ++p)
      for (uint32_t t = 0; t < m.triangle_count(); ++t) {
        bool in = true;
        for (int k = 0; k < 3; ++k) {
          const double x = points[3 * p + k];
          in = in && std::min({vertex(m, t, 0)[k], vertex(m, t, 1)[k], vertex(m, t, 2)[k]}) <= x &&
               x <= std::max({vertex(m, t, 0)[k], vertex(m, t, 1)[k], vertex(m, t, 2)[k]});
        }
        if (in) inside.push_back({p, t});
      }
    AllHits boxes = arcus::bvh::all_hits(ctx, device, points, inside.size() + 10);
    ASSERT_FALSE(boxes.overflow);
    std::sort(boxes.pairs.begin(), boxes.pairs.end());
    EXPECT_EQ(boxes.pairs, inside) << name;
    EXPECT_GT(inside.size(), 100u) << name;
  }
}

}  // namespace
