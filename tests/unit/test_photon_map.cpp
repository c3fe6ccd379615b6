// The photon map: its k-nearest-neighbour search is the brute-force one (same photons,
// same distances), its estimates reproduce closed forms within the statistical bound of
// the k-nearest-neighbour density estimator, and it fails cleanly on bad input and
// degenerate maps (none, fewer than k, all at one point, queries far away).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "common/philox.h"
#include "core/context.h"
#include "core/error.h"
#include "core/format.h"
#include "photon/photon_map.h"
#include "unit_util.h"

namespace {

using arcus::photon::Mode;
using arcus::photon::Photons;
using arcus::photon::PhotonMap;
using arcus::photon::Query;
using arcus_unit::Context;

constexpr double kPi = 3.14159265358979323846;

double u01(uint64_t seed, uint64_t index, uint32_t draw) { return arcus_rng_uniform_double(seed, index, draw); }

// n photons uniform in the unit cube, random unit directions, powers (1, 2, 3)·(1 + u).
Photons random_photons(size_t n, uint64_t seed) {
  Photons p;
  for (size_t i = 0; i < n; ++i) {
    for (uint32_t a = 0; a < 3; ++a) p.positions.push_back(u01(seed, i, a));
    const double z = 2 * u01(seed, i, 3) - 1, phi = 2 * kPi * u01(seed, i, 4), s = std::sqrt(1 - z * z);
    p.directions.insert(p.directions.end(), {s * std::cos(phi), s * std::sin(phi), z});
    const double w = 1 + u01(seed, i, 5);
    p.powers.insert(p.powers.end(), {w, 2 * w, 3 * w});
  }
  return p;
}

// Query points in [-0.1, 1.1]³ (some outside the photons' cube) and random normals.
void random_queries(size_t n, uint64_t seed, std::vector<double>* points, std::vector<double>* normals) {
  for (size_t i = 0; i < n; ++i) {
    for (uint32_t a = 0; a < 3; ++a) points->push_back(-0.1 + 1.2 * u01(seed, i, a));
    for (uint32_t a = 0; a < 3; ++a) normals->push_back(u01(seed, i, 3 + a) - 0.5);  // normalised by the map
  }
}

struct Brute {
  std::vector<int64_t> index;  // nearest first, ties by index
  std::vector<double> d2;
};

// The k nearest photons to q within max_radius, the front-side ones only when n is given.
Brute brute_knn(const Photons& p, const double* q, const double* n, int k, double max_radius) {
  std::vector<std::pair<double, int64_t>> all;
  const size_t count = p.positions.size() / 3;
  for (size_t i = 0; i < count; ++i) {
    const double* x = &p.positions[3 * i];
    const double dx = x[0] - q[0], dy = x[1] - q[1], dz = x[2] - q[2], d = dx * dx + dy * dy + dz * dz;
    if (d > max_radius * max_radius) continue;
    if (n) {
      const double* w = &p.directions[3 * i];
      if (n[0] * w[0] + n[1] * w[1] + n[2] * w[2] >= 0) continue;
    }
    all.emplace_back(d, static_cast<int64_t>(i));
  }
  const size_t m = std::min<size_t>(k, all.size());
  std::partial_sort(all.begin(), all.begin() + m, all.end());
  Brute b;
  for (size_t j = 0; j < m; ++j) {
    b.d2.push_back(all[j].first);
    b.index.push_back(all[j].second);
  }
  return b;
}

void expect_relative(double got, double want, double tol, const std::string& what) {
  EXPECT_LE(std::fabs(got - want), tol * std::fabs(want)) << what << ": " << got << " vs " << want;
}

// The search and the estimate of every query against brute force: the same photons in
// the same order, the same distances, and the estimate's sum over exactly them.
void check_against_brute_force(arcus_context_t* ctx, const Photons& p, const PhotonMap& map, int k,
                               double max_radius, Mode mode) {
  std::vector<double> points, normals;
  random_queries(200, 77, &points, &normals);
  if (mode == Mode::volume) normals.clear();
  Query q;
  q.k = k;
  q.max_radius = max_radius;
  q.mode = mode;
  const arcus::photon::Neighbours nb = arcus::photon::nearest(ctx, map, points, normals, q);
  const arcus::photon::Estimates est = arcus::photon::estimate(ctx, map, points, normals, q);
  const size_t queries = points.size() / 3;
  ASSERT_EQ(nb.found.size(), queries);
  ASSERT_EQ(est.values.size(), queries * 3);
  for (size_t i = 0; i < queries; ++i) {
    double unit_n[3] = {};
    if (mode == Mode::surface) {
      const double* n = &normals[3 * i];
      const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
      for (int a = 0; a < 3; ++a) unit_n[a] = n[a] / len;
    }
    const Brute b = brute_knn(p, &points[3 * i], mode == Mode::surface ? unit_n : nullptr, k, max_radius);
    const std::string at = "k = " + std::to_string(k) + ", query " + std::to_string(i);
    ASSERT_EQ(nb.found[i], static_cast<int32_t>(b.index.size())) << at;
    ASSERT_EQ(est.found[i], nb.found[i]) << at;
    double sum[3] = {};
    for (size_t j = 0; j < static_cast<size_t>(k); ++j) {
      const size_t e = i * k + j;
      if (j >= b.index.size()) {
        EXPECT_EQ(nb.index[e], -1) << at;
        EXPECT_TRUE(std::isinf(nb.distance[e])) << at;
        continue;
      }
      ASSERT_EQ(nb.index[e], b.index[j]) << at << ", neighbour " << j;
      expect_relative(nb.distance[e], std::sqrt(b.d2[j]), 1e-12, at);
      for (int c = 0; c < 3; ++c) sum[c] += p.powers[3 * b.index[j] + c];
    }
    if (b.index.empty()) {
      EXPECT_EQ(est.radius[i], 0) << at;
      for (int c = 0; c < 3; ++c) EXPECT_EQ(est.values[3 * i + c], 0) << at;
      continue;
    }
    const double r = static_cast<int>(b.index.size()) == k || std::isinf(max_radius) ? std::sqrt(b.d2.back())
                                                                                     : max_radius;
    expect_relative(est.radius[i], r, 1e-12, at + " radius");
    const double norm = mode == Mode::volume ? 4.0 / 3.0 * kPi * r * r * r : kPi * r * r;
    for (int c = 0; c < 3; ++c) expect_relative(est.values[3 * i + c], sum[c] / norm, 1e-11, at + " estimate");
  }
}

TEST(PhotonMap, NearestNeighboursAreTheBruteForceOnes) {
  Context ctx;
  const Photons p = random_photons(20000, 1);
  const PhotonMap map(ctx, p);
  EXPECT_EQ(map.size(), 20000u);
  EXPECT_EQ(map.bytes(), static_cast<size_t>(map.nodes()->bytes() + 20000 * (6 + 3) * sizeof(double)));
  // Unbounded searches fill the search's arrays (ARCUS_PHOTON_SEARCH_CAPACITY) and cut
  // them down to k on the way (photon_map.h); k = ARCUS_PHOTON_MAX_K, half of them, fills
  // them again soonest after each cut.
  for (int k : {1, 8, 300, 512}) {
    check_against_brute_force(ctx, p, map, k, INFINITY, Mode::volume);
    check_against_brute_force(ctx, p, map, k, INFINITY, Mode::surface);
  }
  // Leaves of at least 16 photons (the ocean's per-step estimate): the same neighbours.
  const PhotonMap wide(ctx, p, 16);
  check_against_brute_force(ctx, p, wide, 250, INFINITY, Mode::volume);
  // A radius cap that leaves many queries with fewer than k photons.
  check_against_brute_force(ctx, p, map, 300, 0.05, Mode::volume);
  check_against_brute_force(ctx, p, map, 8, 0.02, Mode::surface);
}

TEST(PhotonMap, FewerPhotonsThanK) {
  Context ctx;
  const Photons p = random_photons(5, 2);
  const PhotonMap map(ctx, p);
  check_against_brute_force(ctx, p, map, 8, INFINITY, Mode::volume);
  check_against_brute_force(ctx, p, map, 8, 10.0, Mode::volume);  // r = max_radius: the whole ball searched
  check_against_brute_force(ctx, p, map, 512, 10.0, Mode::surface);
}

TEST(PhotonMap, NoPhotons) {
  Context ctx;
  Photons none;
  const PhotonMap map(ctx, none);
  EXPECT_EQ(map.size(), 0u);
  EXPECT_EQ(map.bytes(), 0u);
  Query q;
  q.k = 16;
  const std::vector<double> points{0, 0, 0, 1, 2, 3}, normals{0, 0, 1, 1, 0, 0};
  const auto e = arcus::photon::estimate(ctx, map, points, normals, q);
  EXPECT_EQ(e.found, (std::vector<int32_t>{0, 0}));
  EXPECT_EQ(e.radius, (std::vector<double>{0, 0}));
  EXPECT_EQ(e.values, std::vector<double>(6, 0.0));
  const auto nb = arcus::photon::nearest(ctx, map, points, normals, q);
  EXPECT_EQ(nb.index, std::vector<int64_t>(32, -1));
  // No queries either.
  EXPECT_TRUE(arcus::photon::estimate(ctx, map, {}, {}, q).found.empty());
}

TEST(PhotonMap, AllPhotonsAtOnePoint) {
  Context ctx;
  Photons p;
  p.channels = 1;
  const size_t n = 1000;
  for (size_t i = 0; i < n; ++i) {
    p.positions.insert(p.positions.end(), {1, 2, 3});
    p.directions.insert(p.directions.end(), {0, 0, -2});  // normalised by the map
    p.powers.push_back(0.5);
  }
  const PhotonMap map(ctx, p);
  Query q;
  q.k = 8;
  q.mode = Mode::volume;
  // One unit away: k photons, all at r = 1.
  auto e = arcus::photon::estimate(ctx, map, {1, 2, 4}, {}, q);
  EXPECT_EQ(e.found[0], 8);
  EXPECT_EQ(e.radius[0], 1.0);
  expect_relative(e.values[0], 8 * 0.5 / (4.0 / 3.0 * kPi), 1e-14, "volume");
  const auto nb = arcus::photon::nearest(ctx, map, {1, 2, 4}, {}, q);
  std::vector<int64_t> idx(nb.index.begin(), nb.index.end());
  std::sort(idx.begin(), idx.end());
  EXPECT_TRUE(std::adjacent_find(idx.begin(), idx.end()) == idx.end()) << "a photon found twice";
  for (int64_t i : idx) EXPECT_TRUE(i >= 0 && i < static_cast<int64_t>(n));
  // Surface: in front of a surface facing +z the photons (travelling −z) count ...
  q.mode = Mode::surface;
  e = arcus::photon::estimate(ctx, map, {1, 2, 4}, {0, 0, 1}, q);
  EXPECT_EQ(e.found[0], 8);
  expect_relative(e.values[0], 8 * 0.5 / kPi, 1e-14, "surface");
  // ... behind one facing −z they do not.
  e = arcus::photon::estimate(ctx, map, {1, 2, 4}, {0, 0, -1}, q);
  EXPECT_EQ(e.found[0], 0);
  EXPECT_EQ(e.values[0], 0);
  // At the point itself the density is a delta: r = 0 and an infinite estimate.
  e = arcus::photon::estimate(ctx, map, {1, 2, 3}, {0, 0, 1}, q);
  EXPECT_EQ(e.found[0], 8);
  EXPECT_EQ(e.radius[0], 0);
  EXPECT_TRUE(std::isinf(e.values[0]));
  // Fewer photons than k: every one of them, over the capped disc.
  q.k = 512;
  q.max_radius = 2;
  Photons few = p;
  few.positions.resize(3 * 300);
  few.directions.resize(3 * 300);
  few.powers.resize(300);
  e = arcus::photon::estimate(ctx, PhotonMap(ctx, few), {1, 2, 3}, {0, 0, 1}, q);
  EXPECT_EQ(e.found[0], 300);
  EXPECT_EQ(e.radius[0], 2);
  expect_relative(e.values[0], 300 * 0.5 / (kPi * 4), 1e-14, "fewer than k");
}

TEST(PhotonMap, QueryFarOutside) {
  Context ctx;
  const Photons p = random_photons(1000, 3);
  const PhotonMap map(ctx, p);
  Query q;
  q.k = 10;
  q.mode = Mode::volume;
  const std::vector<double> far{1e6, -2e6, 5e5};
  auto e = arcus::photon::estimate(ctx, map, far, {}, q);  // uncapped: still the 10 nearest
  EXPECT_EQ(e.found[0], 10);
  const Brute b = brute_knn(p, far.data(), nullptr, 10, INFINITY);
  expect_relative(e.radius[0], std::sqrt(b.d2.back()), 1e-12, "radius");
  q.max_radius = 1;  // capped: nothing, and no division by a zero radius
  e = arcus::photon::estimate(ctx, map, far, {}, q);
  EXPECT_EQ(e.found[0], 0);
  EXPECT_EQ(e.values, std::vector<double>(3, 0.0));
}

// The k nearest photons along lines, found as the ocean's per-step estimate marches
// (photon_line.h: a pool of the photons about a stretch, each step's set updated from
// the last): at every step the brute-force set (compared as the sums of its slots and
// of their squares) and k-th distance.  *lone: the steps searched without the pool.
void check_march(arcus_context_t* ctx, const Photons& p, const PhotonMap& map, int k, int steps, double step,
                 int* lone) {
  std::vector<double> starts, dirs;
  const size_t lines = 10;
  for (size_t i = 0; i < lines; ++i) {
    for (uint32_t a = 0; a < 3; ++a) starts.push_back(-0.1 + 1.2 * u01(91, i, a));
    const double z = 2 * u01(91, i, 3) - 1, phi = 2 * kPi * u01(91, i, 4), s = std::sqrt(1 - z * z);
    if (i == 0) dirs.insert(dirs.end(), {1, 0, 0});  // along an axis: no crossing of the other two
    else if (i == 1) dirs.insert(dirs.end(), {0, -1, 1});
    else dirs.insert(dirs.end(), {s * std::cos(phi), s * std::sin(phi), z});
  }
  const arcus::photon::LineMarch m = arcus::photon::march_lines(ctx, map, starts, dirs, steps, step, k);
  std::vector<int64_t> slot_of(map.size());
  for (size_t s = 0; s < map.size(); ++s) slot_of[map.order()[s]] = static_cast<int64_t>(s);
  for (size_t e = 0; e < m.radius.size(); ++e) {
    const Brute b = brute_knn(p, &m.points[3 * e], nullptr, k, INFINITY);
    int64_t sum = 0, sum2 = 0;
    for (int64_t i : b.index) sum += slot_of[i], sum2 += slot_of[i] * slot_of[i];
    const std::string at = "k = " + std::to_string(k) + ", line " + std::to_string(e / steps) + ", step " +
                           std::to_string(e % steps);
    ASSERT_EQ(m.digest[2 * e], sum) << at;
    ASSERT_EQ(m.digest[2 * e + 1], sum2) << at;
    expect_relative(m.radius[e], std::sqrt(b.d2.back()), 1e-12, at);
  }
  *lone = 0;
  for (int32_t l : m.lone) *lone += l;
}

TEST(PhotonMap, MarchAlongLinesFindsTheBruteForceNeighbours) {
  Context ctx;
  // Uniform photons and a dense ball of them, so that r_k shrinks and grows along a line
  // (and past the cube's faces) and stretches are gathered anew.
  Photons p = random_photons(20000, 4);
  const Photons ball = random_photons(6000, 5);
  for (size_t i = 0; i < 6000; ++i)
    for (int a = 0; a < 3; ++a) p.positions.push_back(0.45 + 0.1 * ball.positions[3 * i + a]);
  p.directions.insert(p.directions.end(), ball.directions.begin(), ball.directions.end());
  p.powers.insert(p.powers.end(), ball.powers.begin(), ball.powers.end());
  const int steps = 70;
  for (int min_leaf : {1, 32}) {
    const PhotonMap map(ctx, p, min_leaf);
    // Steps of 0.04 to 0.14 r_k in the uniform photons (r_k = 0.023, 0.079, 0.145, 0.184);
    // several r_k in the ball, where points that far apart are searched alone
    // (ARCUS_PHOTON_LINE_MOVE).
    for (auto [k, step] : {std::pair{1, 0.003}, {40, 0.01}, {250, 0.02}, {512, 0.008}}) {
      int lone = 0;
      check_march(ctx, p, map, k, steps, step, &lone);
      // The pool answers most steps.  Lone searches: each line's first (no r_k known yet),
      // in the dense ball, and where a stretch's pool overflows entering it (24 to 66 of
      // the 700 steps here).
      EXPECT_LE(lone, 10 * steps * 15 / 100) << "k = " << k << ", min_leaf " << min_leaf;
    }
  }
}

TEST(PhotonMap, MarchWithFewerPhotonsThanK) {
  Context ctx;
  const Photons p = random_photons(5, 6);
  const PhotonMap map(ctx, p);
  int lone = 0;
  check_march(ctx, p, map, 8, 12, 0.1, &lone);
  EXPECT_EQ(lone, 10 * 12);  // no k-th: every step searches the whole map
}

// The k-nearest-neighbour density estimate of a Poisson process of intensity λ (per
// area or volume): the measure (area π r_k² or volume 4/3 π r_k³) of the ball reaching
// the k-th point, times λ, is Gamma(k, 1) distributed, so the estimate
// k·Φ_p/measure has mean λ·Φ_p·k/(k − 1) and relative standard deviation
// 1/√(k − 2) (≈ 1/√k).  Queries whose balls do not overlap are independent, so the mean
// of m of them is within 5/√((k − 2)·m) of its expectation but once in ~10⁶ runs.  A
// fixed number of uniform photons is a binomial process, which differs from Poisson by
// O(k/N): negligible here.
struct Bound {
  double mean, sigma;  // relative to the exact density
};
Bound knn_bound(int k, size_t queries) {
  return {k / (k - 1.0), 1.0 / std::sqrt((k - 2.0) * static_cast<double>(queries))};
}

void check_mean(const std::vector<double>& values, int channels, const double* exact, Bound b,
                const std::string& what) {
  const size_t m = values.size() / channels;
  for (int c = 0; c < channels; ++c) {
    double sum = 0, sum2 = 0;
    for (size_t i = 0; i < m; ++i) {
      const double v = values[i * channels + c] / exact[c];
      sum += v;
      sum2 += v * v;
    }
    const double mean = sum / m, sd = std::sqrt(sum2 / m - mean * mean);
    EXPECT_NEAR(mean, b.mean, 5 * b.sigma) << what << ", channel " << c;
    // The spread itself is the estimator's 1/√(k − 2) (loosely: its distribution is skewed).
    EXPECT_NEAR(sd, b.sigma * std::sqrt(static_cast<double>(m)), 0.2 * b.sigma * std::sqrt(static_cast<double>(m)))
        << what << ", channel " << c;
  }
}

TEST(PhotonMap, SurfaceEstimateIsTheIrradianceOfUniformPhotons) {
  Context ctx;
  // N photons uniform on the square [0, 2]² of the plane z = 1, travelling down (−z,
  // tilted at random) with a total flux Φ = (1, 2, 3) W: E = Φ / A.
  const size_t n = 200000;
  const double side = 2, area = side * side, flux[3] = {1, 2, 3};
  Photons front;
  for (size_t i = 0; i < n; ++i) {
    front.positions.insert(front.positions.end(), {side * u01(9, i, 0), side * u01(9, i, 1), 1.0});
    front.directions.insert(front.directions.end(), {u01(9, i, 2) - 0.5, u01(9, i, 3) - 0.5, -1.0});
    for (double f : flux) front.powers.push_back(f / n);
  }
  // 30 × 30 queries 1/16 apart (k = 64: r_k ≈ √(k/(πλ)) ≈ 0.02 at λ = N/A, so their
  // discs do not overlap), at least 0.1 from the edges.
  const int k = 64, grid = 30;
  std::vector<double> points, normals;
  for (int i = 0; i < grid; ++i)
    for (int j = 0; j < grid; ++j) {
      points.insert(points.end(), {0.1 + i / 16.0, 0.1 + j / 16.0, 1.0});
      normals.insert(normals.end(), {0, 0, 1});
    }
  const double exact[3] = {flux[0] / area, flux[1] / area, flux[2] / area};
  Query q;
  q.k = k;
  const PhotonMap map(ctx, front);
  const auto e = arcus::photon::estimate(ctx, map, points, normals, q);
  for (double r : e.radius) EXPECT_LT(r, 0.5 / 16) << "discs overlap";
  check_mean(e.values, 3, exact, knn_bound(k, grid * grid), "surface");

  // Photons arriving from behind (travelling +z), ten times as bright, change nothing.
  Photons both = front;
  for (size_t i = 0; i < n; ++i) {
    both.positions.insert(both.positions.end(), {side * u01(10, i, 0), side * u01(10, i, 1), 1.0});
    both.directions.insert(both.directions.end(), {u01(10, i, 2) - 0.5, u01(10, i, 3) - 0.5, 1.0});
    for (double f : flux) both.powers.push_back(10 * f / n);
  }
  const auto e2 = arcus::photon::estimate(ctx, PhotonMap(ctx, both), points, normals, q);
  for (size_t i = 0; i < e.values.size(); ++i) expect_relative(e2.values[i], e.values[i], 1e-12, "back photons");

  // Jensen's cone filter (constant c): given r_k the k − 1 inner photons are uniform in
  // the disc, so their mean weight 1 − 2/(3c) is the normalisation, and the k-th (on the
  // rim) weighs 1 − 1/c: the mean is λ·((k − 1) + (1 − 1/c)/(1 − 2/(3c)))/(k − 1).
  q.cone = 1.1;
  const auto ec = arcus::photon::estimate(ctx, map, points, normals, q);
  Bound cone = knn_bound(k, grid * grid);
  cone.mean = 1 + (1 - 1 / q.cone) / (1 - 2 / (3 * q.cone)) / (k - 1.0);
  const size_t m = ec.values.size() / 3;
  double mean = 0;
  for (size_t i = 0; i < m; ++i) mean += ec.values[3 * i] / exact[0] / m;
  EXPECT_NEAR(mean, cone.mean, 5 * cone.sigma) << "cone filter";
}

TEST(PhotonMap, VolumeEstimateIsTheDensityOfUniformPhotons) {
  Context ctx;
  // N photons uniform in the unit cube with a total flux Φ = (1, 2, 3): Φ / V.
  const size_t n = 200000;
  Photons p = random_photons(n, 11);
  const double flux[3] = {1, 2, 3};
  for (size_t i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) p.powers[3 * i + c] = flux[c] / n;
  // 8³ queries 0.11 apart, 0.115 from the faces (k = 64: r_k ≈ 0.042, balls apart).
  const int k = 64, grid = 8;
  std::vector<double> points;
  for (int i = 0; i < grid; ++i)
    for (int j = 0; j < grid; ++j)
      for (int l = 0; l < grid; ++l) points.insert(points.end(), {0.115 + 0.11 * i, 0.115 + 0.11 * j, 0.115 + 0.11 * l});
  Query q;
  q.k = k;
  q.mode = Mode::volume;
  const auto e = arcus::photon::estimate(ctx, PhotonMap(ctx, p), points, {}, q);
  for (double r : e.radius) EXPECT_LT(r, 0.055) << "balls overlap";
  check_mean(e.values, 3, flux, knn_bound(k, grid * grid * grid), "volume");
}

void expect_invalid(const std::function<void()>& f, const std::string& words) {
  try {
    f();
    ADD_FAILURE() << "no error; expected one about " << words;
  } catch (const arcus::Error& err) {
    EXPECT_EQ(err.status(), ARCUS_ERROR_INVALID_ARGUMENT) << err.what();
    EXPECT_NE(std::string(err.what()).find(words), std::string::npos) << err.what();
  }
}

TEST(PhotonMap, BadInputIsAnInvalidArgument) {
  Context ctx;
  const Photons p = random_photons(100, 4);
  const PhotonMap map(ctx, p);
  const std::vector<double> point{0.5, 0.5, 0.5}, normal{0, 0, 1};
  auto query = [&](Query q, std::vector<double> x, std::vector<double> n) {
    return [&ctx, &map, q, x, n] { arcus::photon::estimate(ctx, map, x, n, q); };
  };
  Query q;
  q.k = 0;
  expect_invalid(query(q, point, normal), "k = 0 is outside 1..512");
  q.k = 513;
  expect_invalid(query(q, point, normal), "k = 513 is outside 1..512");
  q.k = 8;
  expect_invalid(query(q, {NAN, 0, 0}, normal), "photon query 0: point (nan, 0, 0) is not finite");
  expect_invalid(query(q, {0, 0, INFINITY}, normal), "is not finite");
  expect_invalid(query(q, point, {0, 0, 0}), "normal (0, 0, 0) is zero or not finite");
  expect_invalid(query(q, point, {}), "needs a normal per query");
  expect_invalid(query(q, {0, 0}, {}), "not three per query");
  for (double r : {-1.0, 0.0, static_cast<double>(NAN)}) {
    Query bad = q;
    bad.max_radius = r;
    expect_invalid(query(bad, point, normal), "max_radius = " + arcus::number(r) + " must be a positive number");
  }
  Query cone = q;
  cone.cone = 0.5;
  expect_invalid(query(cone, point, normal), "cone = 0.5 must be 0");
  Query volume = q;
  volume.mode = Mode::volume;
  expect_invalid(query(volume, point, normal), "a volume estimate takes no normals");
  expect_invalid([&] { arcus::photon::nearest(ctx, map, point, normal, Query{0}); }, "k = 0");

  auto build = [&ctx](Photons bad) { return [&ctx, bad] { PhotonMap m(ctx, bad); }; };
  Photons bad = p;
  bad.channels = 10;
  expect_invalid(build(bad), "channels = 10 is outside 1..9");
  bad.channels = 0;
  expect_invalid(build(bad), "channels = 0 is outside 1..9");
  bad = p;
  bad.positions[3 * 7 + 1] = NAN;
  expect_invalid(build(bad), "photon 7: position");
  bad = p;
  std::fill(bad.directions.begin() + 6, bad.directions.begin() + 9, 0.0);
  expect_invalid(build(bad), "photon 2: direction (0, 0, 0) is zero or not finite");
  bad = p;
  bad.powers[3 * 4 + 2] = -1;
  expect_invalid(build(bad), "photon 4: power[2] = -1 is not a finite number >= 0");
  bad = p;
  bad.powers.pop_back();
  expect_invalid(build(bad), "need 300 powers, not 299");
  bad = p;
  bad.directions.pop_back();
  expect_invalid(build(bad), "100 positions but 299 direction components");
}

}  // namespace
