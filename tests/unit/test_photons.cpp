// Curved photon mapping (src/render/photons.h, thesis §4.3.4): photons shot from a sun
// through a window carry exactly the flux that enters, their irradiance estimate is the
// sun's irradiance within the k-nearest estimate's statistical bound, a medium whose
// index grows upward bends the beam where the ray equation (integrated here with RK4)
// says, the thesis' cross room shows the cross displaced on its floor, the photons are
// reproducible from their seed, and bad input is refused.
#include <gtest/gtest.h>

#include <array>
#include <chrono>
#include <cstdio>
#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "core/error.h"
#include "render/photons.h"
#include "render/scene.h"
#include "render/trace.h"
#include "unit_util.h"

namespace {

using arcus::render::PhotonOptions;
using arcus::render::PhotonStats;
using arcus::render::RenderScene;
using arcus_unit::Context;
using arcus_unit::TempDir;

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180;

// An OBJ of axis-aligned horizontal rectangles at height y: {x0, x1, z0, z1} each.
void write_rectangles(const std::string& path, double y, const std::vector<std::array<double, 4>>& rects) {
  std::ofstream f(path);
  int v = 1;
  for (const auto& r : rects) {
    f << "v " << r[0] << ' ' << y << ' ' << r[2] << "\nv " << r[1] << ' ' << y << ' ' << r[2] << "\nv " << r[1] << ' '
      << y << ' ' << r[3] << "\nv " << r[0] << ' ' << y << ' ' << r[3] << '\n';
    f << "f " << v << ' ' << v + 3 << ' ' << v + 2 << "\nf " << v << ' ' << v + 2 << ' ' << v + 1 << '\n';
    v += 4;
  }
}

// A horizontal square of half-side h centred at (cx, cz), and the rest of the square of
// half-side H around it as 4 rectangles (a ceiling with a square hole).
std::vector<std::array<double, 4>> square(double cx, double cz, double h) {
  return {{cx - h, cx + h, cz - h, cz + h}};
}
std::vector<std::array<double, 4>> frame(double h, double H) {
  return {{-H, H, -H, -h}, {-H, H, h, H}, {-H, -h, -h, h}, {h, H, -h, h}};
}

struct Loaded {
  arcus_scene_t* handle = nullptr;
  RenderScene* scene = nullptr;
  ~Loaded() {
    if (handle) arcus_scene_release(handle);
  }
};

void load(arcus_context_t* ctx, const std::string& path, Loaded* out) {
  ASSERT_EQ(arcus_scene_load(ctx, path.c_str(), &out->handle), ARCUS_SUCCESS) << arcus_context_last_error(ctx);
  out->scene = arcus::render::render_scene(out->handle);
}

// A test scene: the medium, the integrator and the objects as JSON fragments; every
// material black unless given, a sun and photon settings.
std::string scene_json(const std::string& medium, const std::string& materials, const std::string& objects,
                       const std::string& sun_direction, const std::string& bounds, const std::string& photons,
                       const std::string& lights = "") {
  const std::string sun = R"([{"type": "sun", "direction": )" + sun_direction + R"(, "irradiance": [1, 2, 3]}])";
  return R"({"name": "photons", "medium": )" + medium +
         R"(, "integrator": {"method": "dp45", "rtol": 1e-10, "atol": 1e-12, "length": 40},
  "bounds": )" + bounds + R"(,
  "camera": {"position": [0, 0.5, 0], "look_at": [0, 0, 1], "vfov_deg": 60, "width": 8, "height": 8},
  "materials": )" + materials + R"(, "objects": )" + objects + R"(,
  "lights": )" + (lights.empty() ? sun : lights) + R"(,
  "photons": )" + photons + "}";
}

std::string mesh_object(const std::string& file, const std::string& material) {
  return R"({"type": "mesh", "file": ")" + file + R"(", "material": ")" + material + R"("})";
}

// Sums with a compensation term (Kahan): the total of many equal powers to rounding.
double kahan(const std::vector<double>& powers, int channel) {
  double sum = 0, c = 0;
  for (size_t i = channel; i < powers.size(); i += 3) {
    const double y = powers[i] - c, t = sum + y;
    c = (t - sum) - y;
    sum = t;
  }
  return sum;
}

// ---- (a) energy conservation and the estimate, constant medium -----------------------

// The sun straight down through a square hole of area A = 1 m² (its opening: the
// "window") onto a black floor: every photon goes through the hole and is absorbed at
// its first hit, so the stored powers add up to E·A exactly (each is E·A/N), and the
// estimate on the floor is E inside the lit square and 0 beyond max_radius of it.
//
// The statistical bound: for photons of equal power Φ scattered uniformly with density
// ρ, π ρ r_k² is Gamma(k, 1)-distributed, so the k-nearest estimate k Φ / (π r_k²) has a
// relative standard deviation of 1/√(k − 2) ≈ 1/√k and a bias of 1/(k − 1); k = 300:
// 5.8 % and 0.3 %.  Each point is checked to
// 4 sd, and the mean over 16 points 0.2 m apart (> 2 r_k ≈ 0.044 m: independent photons)
// to 4 sd / √16.
TEST(Photons, EnergyIsConservedAndTheEstimateIsTheSunsIrradianceInsideTheLitSquare) {
  Context ctx;
  TempDir dir;
  const double h = 0.5, E[3] = {1, 2, 3};
  write_rectangles(dir.path() + "/floor.obj", 0.0, square(0, 0, 3));
  write_rectangles(dir.path() + "/ceiling.obj", 1.0, frame(h, 3));
  write_rectangles(dir.path() + "/window.obj", 1.0, square(0, 0, h));
  const std::string path = dir.path() + "/a.json";
  std::ofstream(path) << scene_json(
      R"({"type": "constant", "n": 1})",
      R"({"black": {"diffuse": [0, 0, 0]}, "window": {"diffuse": [0, 0, 0]}})",
      "[" + mesh_object(dir.path() + "/floor.obj", "black") + ", " + mesh_object(dir.path() + "/ceiling.obj", "black") +
          ", " + mesh_object(dir.path() + "/window.obj", "window") + "]",
      "[0, 1, 0]", R"({"min": [-3.5, -0.5, -3.5], "max": [3.5, 1.5, 3.5]})",
      R"({"count": 200000, "estimate": 300, "max_radius": 0.2})");
  Loaded s;
  load(ctx, path, &s);
  ASSERT_TRUE(s.scene);
  const uint64_t N = 200000;

  PhotonStats stats;
  const auto t0 = std::chrono::steady_clock::now();
  const arcus::photon::Photons p = arcus::render::shoot_photon_list(ctx, s.scene, s.scene->desc.params, N, 7, &stats);
  EXPECT_EQ(stats.shot, N);
  ASSERT_EQ(stats.stored, N) << "every photon goes through the hole and stops on the floor";
  ASSERT_EQ(p.powers.size(), 3 * N);
  for (int c = 0; c < 3; ++c) {
    const double expected = E[c] * (2 * h) * (2 * h);
    EXPECT_NEAR(kahan(p.powers, c), expected, 1e-12 * expected) << "channel " << c;
  }
  for (size_t i = 0; i < N; ++i) {
    ASSERT_NEAR(p.positions[3 * i + 1], 0.0, 1e-6) << "photon " << i << " off the floor";
    ASSERT_LE(std::fabs(p.positions[3 * i]), h + 1e-6) << "photon " << i << " outside the lit square";
    ASSERT_LE(std::fabs(p.positions[3 * i + 2]), h + 1e-6) << "photon " << i << " outside the lit square";
    ASSERT_NEAR(p.directions[3 * i + 1], -1.0, 1e-9);
  }

  // The estimate: the same photons (same seed), as a map.
  const auto map = arcus::render::shoot_photons(ctx, s.scene, s.scene->desc.params, N, 7, &stats);
  ASSERT_EQ(map->size(), N);
  std::vector<double> points, up, down;
  for (double x : {-0.3, -0.1, 0.1, 0.3})
    for (double z : {-0.3, -0.1, 0.1, 0.3}) points.insert(points.end(), {x, 0.0, z});
  const size_t inside = points.size() / 3;
  for (auto q : {std::array<double, 2>{1.5, 0}, {-1.5, 0}, {0, 1.5}, {0, -1.5}, {2, 2}, {h + 0.25, 0}})
    points.insert(points.end(), {q[0], 0.0, q[1]});
  for (size_t i = 0; i < points.size() / 3; ++i) {
    up.insert(up.end(), {0, 1, 0});
    down.insert(down.end(), {0, -1, 0});
  }
  const std::vector<double> irr = arcus::render::photon_irradiance(ctx, *map, *s.scene, points, up);
  ASSERT_EQ(irr.size(), points.size());
  const double sd = 1 / std::sqrt(300.0);
  for (int c = 0; c < 3; ++c) {
    double mean = 0;
    for (size_t i = 0; i < inside; ++i) {
      EXPECT_NEAR(irr[3 * i + c] / E[c], 1.0, 4 * sd) << "point " << i << " channel " << c;
      mean += irr[3 * i + c] / E[c] / inside;
    }
    EXPECT_NEAR(mean, 1.0, 4 * sd / std::sqrt(double(inside))) << "channel " << c;
    for (size_t i = inside; i < points.size() / 3; ++i)
      EXPECT_EQ(irr[3 * i + c], 0.0) << "point " << i << " is beyond max_radius of the lit square";
  }
  // Seen from below the floor no photon arrived: nothing.
  const std::vector<double> back = arcus::render::photon_irradiance(ctx, *map, *s.scene, points, down);
  for (double v : back) EXPECT_EQ(v, 0.0);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("[ timing   ] 2 x %llu photons shot and stored, 2 x %zu estimates: %.2f s\n",
              static_cast<unsigned long long>(N), points.size() / 3, seconds);
}

// ---- (b) curved light bends ----------------------------------------------------------

struct Landing {
  double x, z;
};

// The ray equation d/ds (n dr/ds) = ∇n for n = n0 + g·y, integrated with classical RK4
// in arc length (state r and v = n dr/ds) from r0 along d until y = 0, where the last
// step is cut by linear interpolation: the beam's central ray, independently of the
// library.
Landing rk4_landing(double n0, double g, const double r0[3], const double d[3]) {
  auto n_at = [&](double y) { return n0 + g * y; };
  double r[3] = {r0[0], r0[1], r0[2]};
  const double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  double v[3];
  for (int a = 0; a < 3; ++a) v[a] = n_at(r0[1]) * d[a] / len;
  const double step = 1e-3;
  auto deriv = [&](const double* rr, const double* vv, double* dr, double* dv) {
    const double n = n_at(rr[1]);
    for (int a = 0; a < 3; ++a) dr[a] = vv[a] / n;
    dv[0] = 0;
    dv[1] = g;
    dv[2] = 0;
  };
  for (int i = 0; i < 1000000; ++i) {
    double k1r[3], k1v[3], k2r[3], k2v[3], k3r[3], k3v[3], k4r[3], k4v[3], tr[3], tv[3];
    deriv(r, v, k1r, k1v);
    for (int a = 0; a < 3; ++a) tr[a] = r[a] + 0.5 * step * k1r[a], tv[a] = v[a] + 0.5 * step * k1v[a];
    deriv(tr, tv, k2r, k2v);
    for (int a = 0; a < 3; ++a) tr[a] = r[a] + 0.5 * step * k2r[a], tv[a] = v[a] + 0.5 * step * k2v[a];
    deriv(tr, tv, k3r, k3v);
    for (int a = 0; a < 3; ++a) tr[a] = r[a] + step * k3r[a], tv[a] = v[a] + step * k3v[a];
    deriv(tr, tv, k4r, k4v);
    double next[3];
    for (int a = 0; a < 3; ++a) {
      next[a] = r[a] + step / 6 * (k1r[a] + 2 * k2r[a] + 2 * k3r[a] + k4r[a]);
      v[a] += step / 6 * (k1v[a] + 2 * k2v[a] + 2 * k3v[a] + k4v[a]);
    }
    if (next[1] <= 0) {
      const double f = r[1] / (r[1] - next[1]);
      return {r[0] + f * (next[0] - r[0]), r[2] + f * (next[2] - r[2])};
    }
    for (int a = 0; a < 3; ++a) r[a] = next[a];
  }
  ADD_FAILURE() << "the reference ray never reached the floor";
  return {NAN, NAN};
}

struct Patch {
  double cx = 0, cz = 0, min_x = INFINITY, max_x = -INFINITY;
  size_t count = 0;
};

// The sun at 65° elevation, light travelling +x and down, through a 0.4 m square window
// at y = 5 onto a black floor at y = 0: in n = 1 + 0.1·y (n = 1.5 at the window, 1 on
// the floor) the rays bend toward higher n, upward, so the beam flattens and lands
// farther along +x than the straight one (which it is in n = 1).  Every ray of the beam
// starts at the same height in the same direction and n depends on y only, so the lit
// patch is the window translated by the central ray's displacement: the photons'
// centroid is the central ray's landing (within the sampling error, window side / √12
// / √N = 0.6 mm for N = 40 000), and the patch keeps the window's 0.4 m width.
TEST(Photons, AGradientUpwardBendsTheBeamFartherAsTheRayEquationSays) {
  Context ctx;
  TempDir dir;
  const double h = 0.2, elevation = 65 * kDeg;
  const double sun[3] = {-std::cos(elevation), std::sin(elevation), 0};
  write_rectangles(dir.path() + "/floor.obj", 0.0, {{-2, 9, -3, 3}});
  write_rectangles(dir.path() + "/window.obj", 5.0, square(0, 0, h));
  const std::string objects = "[" + mesh_object(dir.path() + "/floor.obj", "black") + ", " +
                              mesh_object(dir.path() + "/window.obj", "window") + "]";
  const std::string sun_json = "[" + std::to_string(sun[0]) + ", " + std::to_string(sun[1]) + ", 0]";
  const uint64_t N = 40000;

  auto patch = [&](const std::string& medium, const char* tag) {
    const std::string path = dir.path() + "/" + tag + ".json";
    std::ofstream(path) << scene_json(medium, R"({"black": {"diffuse": [0, 0, 0]}, "window": {}})", objects, sun_json,
                                      R"({"min": [-3, -0.5, -4], "max": [10, 5.5, 4]})",
                                      R"({"count": 40000, "estimate": 50, "max_radius": 0.1})");
    Loaded s;
    Patch out;
    load(ctx, path, &s);
    if (!s.scene) return out;
    PhotonStats stats;
    const arcus::photon::Photons p = arcus::render::shoot_photon_list(ctx, s.scene, s.scene->desc.params, N, 3, &stats);
    EXPECT_EQ(stats.stored, N) << tag;
    for (size_t i = 0; i < p.positions.size() / 3; ++i) {
      EXPECT_NEAR(p.positions[3 * i + 1], 0.0, 1e-6) << tag;
      out.cx += p.positions[3 * i];
      out.cz += p.positions[3 * i + 2];
      out.min_x = std::min(out.min_x, p.positions[3 * i]);
      out.max_x = std::max(out.max_x, p.positions[3 * i]);
    }
    out.count = p.positions.size() / 3;
    out.cx /= out.count;
    out.cz /= out.count;
    return out;
  };
  const Patch straight = patch(R"({"type": "constant", "n": 1})", "straight");
  const Patch curved = patch(R"({"type": "linear", "n0": 1, "gradient": [0, 0.1, 0]})", "curved");

  const double r0[3] = {0, 5, 0}, d[3] = {-sun[0], -sun[1], -sun[2]};
  const Landing ref_straight = rk4_landing(1.0, 0.0, r0, d);
  const Landing ref_curved = rk4_landing(1.0, 0.1, r0, d);
  EXPECT_NEAR(ref_straight.x, 5 / std::tan(elevation), 1e-9) << "the reference itself, in a constant medium";
  // Along +x n·cos α is conserved: 1.5 cos 65° at the window, so the ray reaches the
  // floor at cos α = 0.634 — it does not turn back — after ≈ 3.03 m.
  EXPECT_GT(ref_curved.x, ref_straight.x + 0.5);

  const double tolerance = 5 * (2 * h) / std::sqrt(12.0 * N) + 1e-4;  // 5 sd of the centroid + the path's own error
  EXPECT_NEAR(straight.cx, ref_straight.x, tolerance);
  EXPECT_NEAR(curved.cx, ref_curved.x, tolerance);
  EXPECT_NEAR(straight.cz, 0.0, tolerance);
  EXPECT_NEAR(curved.cz, 0.0, tolerance);
  EXPECT_GT(curved.cx - straight.cx, 0.5) << "the curved beam lands farther along +x";
  // The patch is the window translated: 0.4 m wide along x in both media.
  EXPECT_NEAR(straight.max_x - straight.min_x, 2 * h, 0.01);
  EXPECT_NEAR(curved.max_x - curved.min_x, 2 * h, 0.01);
  std::printf("[ landing  ] straight %.4f m (ray %.4f), curved %.4f m (ray %.4f)\n", straight.cx, ref_straight.x,
              curved.cx, ref_curved.x);
}

// ---- the thesis' cross room ----------------------------------------------------------

// scenes/cross_room.json with fewer photons: the cross's image on the floor is where
// the curved light puts it — lit (the sun's E·sin 65° plus the room's indirect light)
// on the curved image's arm, and only indirectly lit where straight light would have
// put the same arm.
TEST(Photons, TheCrossRoomShowsTheCrossWhereTheCurvedLightPutsIt) {
  Context ctx;
  Loaded s;
  load(ctx, ARCUS_SOURCE_DIR "/scenes/cross_room.json", &s);
  ASSERT_TRUE(s.scene);
  ASSERT_EQ(s.scene->desc.lights.size(), 1u);
  const auto& sun = s.scene->desc.lights[0];
  const double elevation = std::asin(sun.direction[1]);
  PhotonStats stats;
  const auto t0 = std::chrono::steady_clock::now();
  const auto map = arcus::render::shoot_photons(ctx, s.scene, s.scene->desc.params, 100000, 1, &stats);
  const double shoot = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_EQ(stats.shot, 100000u);
  EXPECT_GT(stats.stored, 100000u) << "every photon enters through the window; some bounce";

  // The window's cross: centre (1, 5, 2.5), arms 1.6 × 0.4 m (data/meshes/make_cross_room.py).
  const double d[3] = {-sun.direction[0], -sun.direction[1], -sun.direction[2]};
  const double r0[3] = {1.0, 5.0, 2.5};
  const Landing curved = rk4_landing(1.0, 0.1, r0, d);
  const Landing straight = rk4_landing(1.0, 0.0, r0, d);
  ASSERT_GT(curved.x - straight.x, 0.5);
  // Points on the cross's arm along z, 0.6 m from the centre: lit in the curved image,
  // not in the straight one (x more than 0.2 m off the arm).
  const std::vector<double> points = {curved.x, 0, curved.z - 0.6, curved.x, 0, curved.z + 0.6,
                                      straight.x, 0, straight.z - 0.6, straight.x, 0, straight.z + 0.6};
  const std::vector<double> normals = {0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0};
  const std::vector<double> irr = arcus::render::photon_irradiance(ctx, *map, *s.scene, points, normals);
  const double direct = sun.power[0] * std::sin(elevation);
  for (int i = 0; i < 2; ++i) {
    EXPECT_GT(irr[3 * i], 0.7 * direct) << "curved image point " << i;
    EXPECT_LT(irr[3 * (i + 2)], 0.3 * direct) << "straight image point " << i;
  }
  std::printf("[ cross    ] direct E sin(elevation) = %.3f; curved arm %.3f %.3f, straight arm %.3f %.3f; "
              "%llu stored, %.2f s\n",
              direct, irr[0], irr[3], irr[6], irr[9], static_cast<unsigned long long>(stats.stored), shoot);
}

// ---- reproducibility -------------------------------------------------------------------

// Grey floor and ceiling: photons bounce (Russian roulette), some leave through the
// window again (crossing it; none is stored in the opening).  The same seed gives the
// same photons bit for bit; another seed other ones.
TEST(Photons, TheSeedDeterminesThePhotonsAndBouncedOnesLeaveThroughTheWindow) {
  Context ctx;
  TempDir dir;
  const double h = 0.5;
  write_rectangles(dir.path() + "/floor.obj", 0.0, square(0, 0, 3));
  write_rectangles(dir.path() + "/ceiling.obj", 1.0, frame(h, 3));
  write_rectangles(dir.path() + "/window.obj", 1.0, square(0, 0, h));
  const std::string path = dir.path() + "/d.json";
  std::ofstream(path) << scene_json(
      R"({"type": "linear", "n0": 1, "gradient": [0, 0.1, 0]})",
      R"({"grey": {"diffuse": [0.5, 0.6, 0.7]}, "window": {"diffuse": [0, 0, 0], "emission": [1, 1, 1]}})",
      "[" + mesh_object(dir.path() + "/floor.obj", "grey") + ", " + mesh_object(dir.path() + "/ceiling.obj", "grey") +
          ", " + mesh_object(dir.path() + "/window.obj", "window") + "]",
      "[0.3, 1, 0.2]", R"({"min": [-3.5, -0.5, -3.5], "max": [3.5, 1.5, 3.5]})", R"({"count": 1000})");
  Loaded s;
  load(ctx, path, &s);
  ASSERT_TRUE(s.scene);
  PhotonStats a_stats, b_stats, c_stats;
  const auto a = arcus::render::shoot_photon_list(ctx, s.scene, s.scene->desc.params, 20000, 11, &a_stats);
  const auto b = arcus::render::shoot_photon_list(ctx, s.scene, s.scene->desc.params, 20000, 11, &b_stats);
  const auto c = arcus::render::shoot_photon_list(ctx, s.scene, s.scene->desc.params, 20000, 12, &c_stats);
  EXPECT_GT(a_stats.stored, 25000u) << "bounces are stored too";
  EXPECT_EQ(a.positions, b.positions);
  EXPECT_EQ(a.directions, b.directions);
  EXPECT_EQ(a.powers, b.powers);
  EXPECT_NE(a.positions, c.positions);
  size_t on_ceiling = 0;
  for (size_t i = 0; i < a.positions.size() / 3; ++i) {
    const double* p = &a.positions[3 * i];
    if (p[1] > 0.5) {
      ++on_ceiling;
      EXPECT_GT(a.directions[3 * i + 1], 0) << "a photon on the ceiling's underside came from below";
      EXPECT_FALSE(std::fabs(p[0]) < h - 1e-6 && std::fabs(p[2]) < h - 1e-6) << "stored in the opening";
    }
  }
  EXPECT_GT(on_ceiling, 1000u);
}

// ---- (c) bad input -------------------------------------------------------------------

TEST(Photons, ZeroPhotonsIsAnInvalidArgumentWithAMessageAndASceneWithoutLightsHasNone) {
  Context ctx;
  TempDir dir;
  write_rectangles(dir.path() + "/floor.obj", 0.0, square(0, 0, 3));
  const std::string path = dir.path() + "/c.json";
  auto text = [&](const std::string& lights) {
    return scene_json(R"({"type": "constant", "n": 1})", R"({"grey": {}})",
                      "[" + mesh_object(dir.path() + "/floor.obj", "grey") + "]", "[0, 1, 0]",
                      R"({"min": [-3.5, -0.5, -3.5], "max": [3.5, 1.5, 3.5]})", R"({"count": 10})", lights);
  };
  std::ofstream(path) << text("");
  Loaded s;
  load(ctx, path, &s);
  ASSERT_TRUE(s.scene);
  PhotonStats stats;
  try {
    arcus::render::shoot_photons(ctx, s.scene, s.scene->desc.params, 0, 1, &stats);
    ADD_FAILURE() << "0 photons were accepted";
  } catch (const arcus::Error& e) {
    EXPECT_EQ(e.status(), ARCUS_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(e.what()).find("count = 0"), std::string::npos) << e.what();
  }
  try {
    arcus::render::shoot_photons(ctx, nullptr, s.scene->desc.params, 10, 1, &stats);
    ADD_FAILURE() << "a null scene was accepted";
  } catch (const arcus::Error& e) {
    EXPECT_EQ(e.status(), ARCUS_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(e.what()).find("scene"), std::string::npos) << e.what();
  }

  // Without lights: an empty map, whose estimate is 0 everywhere.
  const std::string dark = dir.path() + "/dark.json";
  std::ofstream(dark) << text("[]");
  Loaded d;
  load(ctx, dark, &d);
  ASSERT_TRUE(d.scene);
  const auto map = arcus::render::shoot_photons(ctx, d.scene, d.scene->desc.params, 10, 1, &stats);
  EXPECT_EQ(map->size(), 0u);
  EXPECT_EQ(stats.stored, 0u);
  const std::vector<double> irr =
      arcus::render::photon_irradiance(ctx, *map, *d.scene, {0, 0, 0, 1, 0, 1}, {0, 1, 0, 0, 1, 0});
  EXPECT_EQ(irr, std::vector<double>(6, 0.0));
}

// ---- the techniques (thesis §4.3.4) ------------------------------------------------------

const std::string kCrossRoom = ARCUS_SOURCE_DIR "/scenes/cross_room.json";

void expect_same(const arcus::photon::Photons& a, const arcus::photon::Photons& b, const char* what) {
  ASSERT_EQ(a.positions.size(), b.positions.size()) << what;
  EXPECT_TRUE(a.positions == b.positions) << what << ": positions differ";
  EXPECT_TRUE(a.directions == b.directions) << what << ": directions differ";
  EXPECT_TRUE(a.powers == b.powers) << what << ": powers differ";
}

// Smart step selection only changes which steps are tested first: trace() proves the
// steps it skips empty, so the photons are the exhaustive scan's bit for bit, with
// fewer tests — spatially (a coarse first pass) and, in the next frame, temporally
// (each photon's own end step in the last frame).
TEST(PhotonTechniques, SmartStepGivesTheSamePhotonsWithFewerTests) {
  Context ctx;
  Loaded s;
  load(ctx, kCrossRoom, &s);
  ASSERT_TRUE(s.scene);
  const uint64_t N = 60000;
  PhotonStats plain, spatial, temporal;
  const auto a = arcus::render::shoot_photon_list(ctx, s.scene, s.scene->desc.params, N, 5, &plain);
  arcus::render::PhotonCache cache;
  PhotonOptions o;
  o.techniques = ARCUS_TECHNIQUE_SMART_STEP;
  o.cache = &cache;
  const auto b = arcus::render::shoot_photon_list(ctx, s.scene, s.scene->desc.params, N, 5, &spatial, o);
  const auto c = arcus::render::shoot_photon_list(ctx, s.scene, s.scene->desc.params, N, 5, &temporal, o);
  expect_same(a, b, "spatial smart step");
  expect_same(a, c, "temporal smart step");
  EXPECT_EQ(plain.traced, spatial.traced);
  EXPECT_EQ(plain.steps, spatial.steps) << "the same integration";
  EXPECT_LT(spatial.tests, plain.tests);
  EXPECT_LT(temporal.tests, plain.tests);
  // The first generation alone (what the technique predicts).
  PhotonStats f_plain, f_smart;
  arcus::render::first_generation(ctx, s.scene, s.scene->desc.params, N, 5, &f_plain);
  PhotonOptions spatial_only;
  spatial_only.techniques = ARCUS_TECHNIQUE_SMART_STEP;
  arcus::render::first_generation(ctx, s.scene, s.scene->desc.params, N, 5, &f_smart, spatial_only);
  EXPECT_LT(f_smart.tests, f_plain.tests);
  std::printf("[ smart    ] first generation: %.2f tests per photon plain, %.2f smart\n",
              double(f_plain.tests) / N, double(f_smart.tests) / N);
  std::printf("[ smart    ] tests per traced path: %.2f plain, %.2f spatial, %.2f temporal; %.2f / %.2f / %.2f s\n",
              double(plain.tests) / plain.traced, double(spatial.tests) / spatial.traced,
              double(temporal.tests) / temporal.traced, plain.seconds, spatial.seconds, temporal.seconds);
}

// The path cache keeps the first generation: the next frame traces only the bounces and
// gives the same photons; another seed (or count) is another first generation.
TEST(PhotonTechniques, ThePathCachedSecondFrameIsTheSame) {
  Context ctx;
  Loaded s;
  load(ctx, kCrossRoom, &s);
  ASSERT_TRUE(s.scene);
  const uint64_t N = 60000;
  arcus::render::PhotonCache cache;
  PhotonOptions o;
  o.techniques = ARCUS_TECHNIQUE_PATH_CACHE;
  o.cache = &cache;
  PhotonStats first, second, other;
  const auto a = arcus::render::shoot_photon_list(ctx, s.scene, s.scene->desc.params, N, 5, &first, o);
  EXPECT_EQ(first.cached, 0u);
  EXPECT_GT(cache.bytes(), N * 50);
  const auto b = arcus::render::shoot_photon_list(ctx, s.scene, s.scene->desc.params, N, 5, &second, o);
  expect_same(a, b, "path-cached frame");
  EXPECT_EQ(second.cached, N) << "every photon enters through the window";
  EXPECT_EQ(second.traced, first.traced - N) << "only the bounces are traced";
  const auto c = arcus::render::shoot_photon_list(ctx, s.scene, s.scene->desc.params, N, 6, &other, o);
  EXPECT_EQ(other.cached, 0u) << "another seed";
  EXPECT_NE(a.positions, c.positions);
  std::printf("[ cache    ] first frame %.2f s, cached frame %.2f s, %zu bytes held\n", first.seconds, second.seconds,
              cache.bytes());
}

// Symmetry in the cross room (n varies with y, the sun shines in the xy plane, the
// cross is symmetric about z = 2.5, the bounds' mid-plane): half the photons walk their
// twin's path mirrored.  Such a photon lands on the mirror image of its twin's hit
// (the same path, mirrored: to rounding), and where tracing it directly puts it — to
// the integrator's tolerance, since a direct trace is another numerical solution (its
// step control sees other coordinates).  With the integrator at rtol 1e-12 both
// solutions are the exact path to well within 1e-9 m.
TEST(PhotonTechniques, MirroredPhotonsLandWhereTracingThemPutsThem) {
  Context ctx;
  Loaded s;
  load(ctx, kCrossRoom, &s);
  ASSERT_TRUE(s.scene);
  arcus::render::MirrorPlane plane;
  ASSERT_EQ(arcus::render::photon_asymmetry(*s.scene, &plane), "");
  EXPECT_EQ(plane.normal[2], 1.0);
  EXPECT_EQ(plane.offset, 2.5);
  PhotonOptions o;
  o.techniques = ARCUS_TECHNIQUE_SYMMETRY;
  auto check = [&](const arcus_advance_params& params, uint64_t N, double to_twin, double to_trace, const char* tag) {
    PhotonStats st;
    const auto g = arcus::render::first_generation(ctx, s.scene, params, N, 5, &st, o);
    std::vector<double> origins, directions;
    std::vector<size_t> which;
    size_t fallback = 0;
    double twin = 0;
    for (size_t i = 0; i < g.how.size(); ++i) {
      fallback += g.how[i] == arcus::render::kFirstFallback;
      if (g.how[i] != arcus::render::kFirstMirrored) continue;
      origins.insert(origins.end(), &g.origins[3 * i], &g.origins[3 * i] + 3);
      directions.insert(directions.end(), &g.directions[3 * i], &g.directions[3 * i] + 3);
      which.push_back(i);
      // Its twin (the photon before it) is its mirror image about z = 2.5.
      EXPECT_EQ(g.ids[i], g.ids[i - 1] + 1);
      EXPECT_NEAR(g.origins[3 * i + 2], 5.0 - g.origins[3 * (i - 1) + 2], 1e-12);
      twin = std::max({twin, std::fabs(g.hits[3 * i] - g.hits[3 * (i - 1)]),
                       std::fabs(g.hits[3 * i + 1] - g.hits[3 * (i - 1) + 1]),
                       std::fabs(g.hits[3 * i + 2] - (5.0 - g.hits[3 * (i - 1) + 2]))});
    }
    EXPECT_EQ(st.mirrored + fallback, N / 2) << tag << ": every twin mirrored, or traced when unresolved";
    EXPECT_GT(st.mirrored, N / 2 - N / 1000) << tag;
    EXPECT_LE(twin, to_twin) << tag;
    arcus::render::TraceInput in;
    in.count = which.size();
    in.origins = origins.data();
    in.directions = directions.data();
    const auto t = arcus::render::trace(ctx, s.scene, params, in);
    double worst = 0;
    for (size_t k = 0; k < which.size(); ++k) {
      ASSERT_EQ(t.status[k], g.status[which[k]]) << tag;
      ASSERT_EQ(t.object[k], g.object[which[k]]) << tag;
      for (int a = 0; a < 3; ++a) worst = std::max(worst, std::fabs(t.positions[3 * k + a] - g.hits[3 * which[k] + a]));
    }
    EXPECT_LE(worst, to_trace) << tag;
    std::printf("[ symmetry ] %s: %llu mirrored, %zu traced after all; largest difference from the twin's mirror "
                "image %.3g m, from tracing them %.3g m\n",
                tag, static_cast<unsigned long long>(st.mirrored), fallback, twin, worst);
  };
  // The scene's integrator (rtol 1e-7 over ~6 m of path): ~1e-6 m.
  check(s.scene->desc.params, 40000, 1e-9, 5e-6, "rtol 1e-7");
  arcus_advance_params tight = s.scene->desc.params;
  tight.rtol = 1e-12;
  tight.atol = 1e-14;
  check(tight, 4000, 1e-9, 1e-9, "rtol 1e-12");

  // The whole shot.
  PhotonStats full;
  const auto p = arcus::render::shoot_photon_list(ctx, s.scene, s.scene->desc.params, 40000, 5, &full, o);
  EXPECT_GT(full.mirrored, 19900u);
  EXPECT_GT(full.stored, 40000u);
}

// Symmetry with asymmetric geometry: an obstacle on one side of the plane.  The photons
// that hit it have mirrors whose mirrored path ends at its mirror image, where nothing
// is: unresolved, they are traced — so every first hit is still the traced one.  And a
// scene whose medium or light is not symmetric is refused with the reason.
TEST(PhotonTechniques, SymmetryTracesWhatTheMirrorCannotResolveAndRefusesAsymmetricScenes) {
  Context ctx;
  TempDir dir;
  write_rectangles(dir.path() + "/floor.obj", 0.0, square(0, 0, 3));
  write_rectangles(dir.path() + "/ceiling.obj", 1.0, frame(0.5, 3));
  write_rectangles(dir.path() + "/window.obj", 1.0, square(0, 0, 0.5));
  write_rectangles(dir.path() + "/box.obj", 0.5, {{0.1, 0.4, 0.1, 0.4}});
  const std::string objects = "[" + mesh_object(dir.path() + "/floor.obj", "grey") + ", " +
                              mesh_object(dir.path() + "/ceiling.obj", "grey") + ", " +
                              mesh_object(dir.path() + "/box.obj", "grey") + ", " +
                              mesh_object(dir.path() + "/window.obj", "window") + "]";
  const std::string materials = R"({"grey": {"diffuse": [0.5, 0.5, 0.5]}, "window": {"diffuse": [0, 0, 0]}})";
  const std::string bounds = R"({"min": [-3.5, -0.5, -3.5], "max": [3.5, 1.5, 3.5]})";
  const std::string medium = R"({"type": "linear", "n0": 1, "gradient": [0, 0.1, 0]})";
  std::ofstream(dir.path() + "/sym.json") << scene_json(medium, materials, objects, "[0.2, 1, 0]", bounds,
                                                         R"({"count": 1000})");
  std::ofstream(dir.path() + "/asym.json") << scene_json(medium, materials, objects, "[0.3, 1, 0.2]", bounds,
                                                          R"({"count": 1000})");
  Loaded s, bad;
  load(ctx, dir.path() + "/sym.json", &s);
  load(ctx, dir.path() + "/asym.json", &bad);
  ASSERT_TRUE(s.scene && bad.scene);
  arcus::render::MirrorPlane plane;
  ASSERT_EQ(arcus::render::photon_asymmetry(*s.scene, &plane), "");
  EXPECT_EQ(plane.normal[2], 1.0) << "z = 0: the sun shines along x";
  PhotonOptions o;
  o.techniques = ARCUS_TECHNIQUE_SYMMETRY;
  PhotonStats st;
  const uint64_t N = 20000;
  const auto g = arcus::render::first_generation(ctx, s.scene, s.scene->desc.params, N, 3, &st, o);
  size_t fallback = 0;
  for (int32_t h : g.how) fallback += h == arcus::render::kFirstFallback;
  EXPECT_GT(fallback, 100u) << "the box's mirror image is empty";
  EXPECT_EQ(st.mirrored + fallback, N / 2);
  arcus::render::TraceInput in;
  in.count = g.ids.size();
  in.origins = g.origins.data();
  in.directions = g.directions.data();
  const auto t = arcus::render::trace(ctx, s.scene, s.scene->desc.params, in);
  double worst = 0;
  for (size_t k = 0; k < in.count; ++k) {
    ASSERT_EQ(t.status[k], g.status[k]) << k;
    ASSERT_EQ(t.object[k], g.object[k]) << k;
    if (t.status[k] == ARCUS_STATUS_HIT)
      for (int a = 0; a < 3; ++a) worst = std::max(worst, std::fabs(t.positions[3 * k + a] - g.hits[3 * k + a]));
  }
  EXPECT_LE(worst, 1e-9);

  const std::string why = arcus::render::photon_asymmetry(*bad.scene, &plane);
  EXPECT_NE(why.find("symmetry"), std::string::npos) << why;
  EXPECT_NE(why.find("does not shine parallel"), std::string::npos) << why;
  try {
    arcus::render::shoot_photon_list(ctx, bad.scene, bad.scene->desc.params, 100, 1, &st, o);
    ADD_FAILURE() << "symmetry was accepted for an asymmetric scene";
  } catch (const arcus::Error& e) {
    EXPECT_EQ(e.status(), ARCUS_ERROR_UNSUPPORTED);
    EXPECT_EQ(std::string(e.what()), why);
  }
}

// Undersampling (t = 2° ↔ 0.178 m across the beam, n = 3) in the cross room: the medium
// varies with y only and every sun photon starts at y = 5 going the same way, so a
// photon's path is its neighbours' translated and its hit on the (flat) floor an affine
// function of its start point, which the weights of three neighbours reproduce; what
// remains is each traced path's own error — DP45 at rtol 1e-7 over ~6 m of path, and
// where on its last chord the crossing is placed: ~1e-6 m — and rounding.  The bound,
// 1e-5 m mean and 1e-4 m for any photon, is that error with room (a wrong neighbour
// set would be off by centimetres: photons 0.1 m apart land 0.1 m apart); a photon
// whose neighbours land on different surfaces is traced.
TEST(PhotonTechniques, UndersampledHitsAreTheTracedOnesToTheIntegratorsError) {
  Context ctx;
  Loaded s;
  load(ctx, kCrossRoom, &s);
  ASSERT_TRUE(s.scene);
  const uint64_t N = 60000;
  PhotonOptions o;
  o.techniques = ARCUS_TECHNIQUE_UNDERSAMPLE;
  o.measure_interpolation = true;
  PhotonStats st, plain;
  const auto p = arcus::render::shoot_photon_list(ctx, s.scene, s.scene->desc.params, N, 5, &st, o);
  const auto q = arcus::render::shoot_photon_list(ctx, s.scene, s.scene->desc.params, N, 5, &plain);
  EXPECT_GT(st.interpolated, N * 99 / 100) << "a few photons per 0.178 m disc are traced";
  EXPECT_EQ(st.interpolation_measured, st.interpolated);
  EXPECT_LT(st.interpolation_error_mean, 1e-5);
  EXPECT_LT(st.interpolation_error_max, 1e-4);
  EXPECT_EQ(st.traced + st.interpolated, plain.traced) << "every photon is traced or interpolated";
  std::printf("[ under    ] %llu of %llu first hits interpolated: error mean %.3g m, max %.3g m; %.2f s (plain %.2f s)\n",
              static_cast<unsigned long long>(st.interpolated), static_cast<unsigned long long>(N),
              st.interpolation_error_mean, st.interpolation_error_max, st.seconds, plain.seconds);
}

// All four at once, and each alone, on the whole cross room (500 000 photons): timings
// (run with --gtest_also_run_disabled_tests).
TEST(PhotonTechniques, DISABLED_CrossRoomTimings) {
  Context ctx;
  Loaded s;
  load(ctx, kCrossRoom, &s);
  ASSERT_TRUE(s.scene);
  const uint64_t N = s.scene->desc.photons.count;
  const std::pair<const char*, uint32_t> runs[] = {
      {"none", 0u},
      {"smart_step", ARCUS_TECHNIQUE_SMART_STEP},
      {"symmetry", ARCUS_TECHNIQUE_SYMMETRY},
      {"undersample", ARCUS_TECHNIQUE_UNDERSAMPLE},
      {"path_cache", ARCUS_TECHNIQUE_PATH_CACHE},
      {"all", ARCUS_TECHNIQUE_ALL}};
  for (const auto& [name, bits] : runs) {
    arcus::render::PhotonCache cache;
    PhotonOptions o;
    o.techniques = bits;
    o.cache = &cache;
    for (int frame = 0; frame < 2; ++frame) {
      PhotonStats st;
      arcus::render::shoot_photon_list(ctx, s.scene, s.scene->desc.params, N, 1, &st, o);
      std::printf("[ timing   ] %-11s frame %d: %6.2f s  stored %llu traced %llu mirrored %llu interpolated %llu "
                  "cached %llu tests %llu steps %llu\n",
                  name, frame + 1, st.seconds, (unsigned long long)st.stored, (unsigned long long)st.traced,
                  (unsigned long long)st.mirrored, (unsigned long long)st.interpolated,
                  (unsigned long long)st.cached, (unsigned long long)st.tests, (unsigned long long)st.steps);
    }
  }
}

}  // namespace
