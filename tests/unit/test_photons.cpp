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
#include "unit_util.h"

namespace {

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

}  // namespace
