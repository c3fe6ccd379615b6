// Voxel-grid fields: trilinear values and gradients against a host reference, the
// clamped exterior (face values extend outwards, zero gradient across the face), files in
// both scalar types, rays that start outside the grid, and bad grids and grid files
// (bad values and shapes, files of the wrong size, missing, or not regular files).
#include "scoped_env.h"
#include "test_util.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <future>
#include <limits>
#include <random>

using namespace arcus_test;

namespace {

class Grid : public ArcusTest {
 public:
  struct Spec {
    uint32_t dims[3];
    V3 origin, spacing;
    std::vector<double> values;
    double at(uint32_t i, uint32_t j, uint32_t k) const { return values[(size_t(k) * dims[1] + j) * dims[0] + i]; }
  };

 protected:
  // Reference: trilinear interpolation of the clamped point; the gradient is the
  // interpolant's derivative, zero along an axis on which the point lies outside.
  static double reference(const Spec& s, const V3& p, V3* grad) {
    double t[3];
    uint32_t c[3];
    bool outside[3];
    for (int a = 0; a < 3; ++a) {
      const double f = (p[a] - s.origin[a]) / s.spacing[a];
      const double hi = double(s.dims[a] - 1);
      outside[a] = f < 0.0 || f > hi;
      const double fc = std::min(std::max(f, 0.0), hi);
      c[a] = std::min(uint32_t(std::floor(fc)), s.dims[a] - 2);
      t[a] = fc - c[a];
    }
    double n = 0.0;
    V3 g{0, 0, 0};
    for (int dk = 0; dk < 2; ++dk)
      for (int dj = 0; dj < 2; ++dj)
        for (int di = 0; di < 2; ++di) {
          const double v = s.at(c[0] + di, c[1] + dj, c[2] + dk);
          const double wx = di ? t[0] : 1 - t[0], wy = dj ? t[1] : 1 - t[1], wz = dk ? t[2] : 1 - t[2];
          n += v * wx * wy * wz;
          g[0] += v * (di ? 1 : -1) * wy * wz / s.spacing[0];
          g[1] += v * wx * (dj ? 1 : -1) * wz / s.spacing[1];
          g[2] += v * wx * wy * (dk ? 1 : -1) / s.spacing[2];
        }
    for (int a = 0; a < 3; ++a)
      if (outside[a]) g[a] = 0.0;
    if (grad) *grad = g;
    return n;
  }
  static Spec random_spec(unsigned seed) {
    Spec s{{4, 5, 3}, {-1.0, 0.5, 2.0}, {0.5, 0.25, 1.0}, {}};
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 0.2);
    s.values.resize(size_t(s.dims[0]) * s.dims[1] * s.dims[2]);
    for (double& v : s.values) v = 1.0 + u(rng);
    return s;
  }
  FieldPtr make(const Spec& s) { return grid(s.values, s.dims, s.origin, s.spacing); }
};

const double kNaN = std::numeric_limits<double>::quiet_NaN();
const double kInf = std::numeric_limits<double>::infinity();

TEST_F(Grid, TrilinearValuesAndGradientsMatchAHostReference) {
  const Spec s = random_spec(7);
  auto field = make(s);
  ASSERT_TRUE(field);
  arcus_field_kind kind;
  ASSERT_EQ(arcus_field_get_kind(field.get(), &kind), ARCUS_SUCCESS);
  EXPECT_EQ(kind, ARCUS_FIELD_GRID);
  std::mt19937 rng(11);
  // Points inside and up to one grid size outside on every side.
  std::uniform_real_distribution<double> ux(-2.5, 1.5), uy(-0.5, 2.5), uz(1.0, 5.0);
  int inside = 0, outside = 0;
  for (int i = 0; i < 400; ++i) {
    const V3 p{ux(rng), uy(rng), uz(rng)};
    V3 g, want_g;
    const double n = n_at(field.get(), p, &g);
    const double want = reference(s, p, &want_g);
    // Both are a few dozen roundings of numbers ≈ 1 (and their differences / spacing).
    EXPECT_NEAR(n, want, 1e-14) << "at " << p[0] << " " << p[1] << " " << p[2];
    EXPECT_LT(distance(g, want_g), 1e-13) << "at " << p[0] << " " << p[1] << " " << p[2];
    const bool in = p[0] >= -1.0 && p[0] <= 0.5 && p[1] >= 0.5 && p[1] <= 1.5 && p[2] >= 2.0 && p[2] <= 4.0;
    (in ? inside : outside)++;
  }
  EXPECT_GT(inside, 20);
  EXPECT_GT(outside, 20);
  // At the grid nodes the values are the data themselves.
  for (uint32_t k = 0; k < s.dims[2]; ++k)
    for (uint32_t j = 0; j < s.dims[1]; ++j)
      for (uint32_t i = 0; i < s.dims[0]; ++i) {
        const V3 p = s.origin + V3{i * s.spacing[0], j * s.spacing[1], k * s.spacing[2]};
        EXPECT_NEAR(n_at(field.get(), p), s.at(i, j, k), 1e-15);
      }
}

TEST_F(Grid, OutsideValuesAreClampedWithZeroGradientAcross) {
  // n = 1 + 0.5·x on x ∈ [0, 1] (exact in trilinear form), uniform in y and z.
  Spec s{{5, 2, 2}, {0, -0.5, -0.5}, {0.25, 1, 1}, {}};
  for (uint32_t k = 0; k < 2; ++k)
    for (uint32_t j = 0; j < 2; ++j)
      for (uint32_t i = 0; i < 5; ++i) s.values.push_back(1.0 + 0.5 * 0.25 * i);
  auto field = make(s);
  ASSERT_TRUE(field);
  struct Case {
    V3 p;
    double n;
    V3 g;
  };
  const std::vector<Case> cases{{{0.3, 0.1, 0.2}, 1.15, {0.5, 0, 0}},     // inside
                                {{-3.0, 0.0, 0.0}, 1.0, {0, 0, 0}},       // before x = 0
                                {{2.0, 0.0, 0.0}, 1.5, {0, 0, 0}},        // past x = 1
                                {{0.5, 10.0, -10.0}, 1.25, {0.5, 0, 0}},  // beside: along the face
                                {{-1.0, 7.0, 9.0}, 1.0, {0, 0, 0}}};      // off a corner
  for (const Case& c : cases) {
    V3 g;
    EXPECT_NEAR(n_at(field.get(), c.p, &g), c.n, 1e-15) << c.p[0] << " " << c.p[1] << " " << c.p[2];
    EXPECT_LT(distance(g, c.g), 1e-14) << c.p[0] << " " << c.p[1] << " " << c.p[2];
  }
}

TEST_F(Grid, DeterminismFilesInBothScalarTypesEqualTheInMemoryGrid) {
  // Determinism (the same data through two constructors gives the same numbers, bit for
  // bit), and the file's values are the data: against the test's own trilinear
  // reference() of the values written (rounded to float for the float32 file).
  const Spec s = random_spec(3);
  auto mem = make(s);
  ASSERT_TRUE(mem);
  const std::string p64 = temp_path("f64"), p32 = temp_path("f32");
  Spec s32 = s;
  {
    std::ofstream out(p64, std::ios::binary);
    out.write(reinterpret_cast<const char*>(s.values.data()), std::streamsize(s.values.size() * sizeof(double)));
    std::vector<float> f(s.values.begin(), s.values.end());
    std::ofstream out32(p32, std::ios::binary);
    out32.write(reinterpret_cast<const char*>(f.data()), std::streamsize(f.size() * sizeof(float)));
    for (size_t i = 0; i < f.size(); ++i) s32.values[i] = f[i];
  }
  arcus_field_t *f64 = nullptr, *f32 = nullptr;
  ASSERT_EQ(arcus_field_create_grid_from_file(ctx(), p64.c_str(), ARCUS_FLOAT64, s.dims, s.origin.data(),
                                              s.spacing.data(), &f64),
            ARCUS_SUCCESS)
      << last_error();
  FieldPtr g64(f64);
  ASSERT_EQ(arcus_field_create_grid_from_file(ctx(), p32.c_str(), ARCUS_FLOAT32, s.dims, s.origin.data(),
                                              s.spacing.data(), &f32),
            ARCUS_SUCCESS)
      << last_error();
  FieldPtr g32(f32);
  auto mem32 = make(s32);
  ASSERT_TRUE(mem32);
  std::remove(p64.c_str());
  std::remove(p32.c_str());
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> ux(-1.5, 1.0), uy(0.0, 2.0), uz(1.5, 4.5);
  for (int i = 0; i < 50; ++i) {
    const V3 p{ux(rng), uy(rng), uz(rng)};
    V3 ga, gb;
    // Same data, same formulas: identical numbers.
    EXPECT_EQ(n_at(g64.get(), p, &ga), n_at(mem.get(), p, &gb));
    EXPECT_EQ(ga, gb);
    EXPECT_EQ(n_at(g32.get(), p, &ga), n_at(mem32.get(), p, &gb));
    EXPECT_EQ(ga, gb);
    // A few dozen roundings of numbers ≈ 1, as in TrilinearValuesAndGradientsMatchAHostReference.
    V3 want_g;
    EXPECT_NEAR(n_at(g64.get(), p, &ga), reference(s, p, &want_g), 1e-14);
    EXPECT_LT(distance(ga, want_g), 1e-13);
    EXPECT_NEAR(n_at(g32.get(), p, &ga), reference(s32, p, &want_g), 1e-14);
    EXPECT_LT(distance(ga, want_g), 1e-13);
  }
  // The float32 file really holds floats: its grid differs from the double one.
  EXPECT_NE(n_at(g32.get(), {0.1, 1.0, 2.7}), n_at(g64.get(), {0.1, 1.0, 2.7}));
}

// n = 1 + g·x on x ∈ [0, 1] (exact in trilinear form), clamped outside: n = 1 for x < 0
// and 1 + g for x > 1, uniform in y and z everywhere.  A ray from x < 0 runs straight to
// x = 0, follows a catenary (gradient along x) to x = 1, then runs straight again.
struct Ramp {
  static constexpr double g = 0.5;
  static Grid::Spec spec() {
    Grid::Spec s{{5, 2, 2}, {0, -0.5, -0.5}, {0.25, 1, 1}, {}};
    for (uint32_t k = 0; k < 2; ++k)
      for (uint32_t j = 0; j < 2; ++j)
        for (uint32_t i = 0; i < 5; ++i) s.values.push_back(1.0 + g * 0.25 * i);
    return s;
  }
  // The end state after arc L from o (x < 0) along d, and the scale of the path for the
  // bounds: its turning, and the kinks of ∇n it crosses (the faces x = 0 and x = 1).
  static RayState end(const V3& o, const V3& dir, double L, PathScale* scale) {
    const V3 d = normalize(dir);
    *scale = PathScale{0.0, L};
    scale->n_kink = 1.0 + g;
    RayState r;
    if (d[0] <= 0) {
      r = {o + L * d, d};
    } else {
      const double s1 = -o[0] / d[0];  // straight to x = 0
      const V3 r1 = o + s1 * d;
      // Inside: v_x = n·d_x grows by g per metre; it leaves at n = 1 + g where
      // v_x = sqrt((1 + g)² − A²), A = |v across x| = 1·|d_yz| (conserved).
      const double A = std::hypot(d[1], d[2]);
      const double s2 = (std::sqrt((1 + g) * (1 + g) - A * A) - d[0]) / g;
      const RayState in = catenary_end(1.0, {g, 0, 0}, r1, d, s2);
      EXPECT_NEAR(in.pos[0], 1.0, 1e-12) << "closed form";
      r = {in.pos + (L - s1 - s2) * in.dir, in.dir};
      scale->kinks = 2;
      scale->turning = angle_between(d, in.dir);
    }
    scale->r_end = norm(r.pos);
    return r;
  }
  static Rays rays() {
    Rays r;
    r.add({-2, 0, 0}, {1, 0, 0});
    r.add({-2, 0.3, 0.1}, {1, 0.3, -0.2});
    r.add({-2, 5.0, -3.0}, {0.6, -0.8, 0});  // beside the grid in y: same field
    r.add({-2, 0, 0}, {-1, 0.5, 0.5});       // moving away: straight all the way
    return r;
  }
};

TEST_F(Grid, AGridFileBeyondTheHostsMemoryIsRefusedBeforeAllocating) {
  // A sparse file of 2^31 float32 values (8 GiB that occupy no disk) passed the size
  // check and its 16 GiB of doubles were allocated.  Now they are held to the memory
  // available (a bound of 1 GiB here) first.
  const std::string path = temp_path("huge");
  { std::ofstream(path, std::ios::binary) << ""; }
  std::filesystem::resize_file(path, (uint64_t(1) << 31) * 4);
  const uint32_t dims[3] = {65536, 16384, 2};
  const double origin[3] = {0, 0, 0}, spacing[3] = {1, 1, 1};
  ScopedEnv limit("ARCUS_MEMORY_LIMIT", "1G");
  arcus_field_t* f = nullptr;
  EXPECT_EQ(arcus_field_create_grid_from_file(ctx(), path.c_str(), ARCUS_FLOAT32, dims, origin, spacing, &f),
            ARCUS_ERROR_OUT_OF_MEMORY);
  EXPECT_EQ(f, nullptr);
  EXPECT_NE(last_error().find("2147483648 values needs 16 GiB of host memory"), std::string::npos) << last_error();
  std::filesystem::remove(path);
}

TEST_F(Grid, RayStartingOutsideTravelsStraightUntilItEnters) {
  const double L = 8.0, rtol = 1e-10, atol = 1e-13;
  auto field = make(Ramp::spec());
  ASSERT_TRUE(field);
  const Rays rays = Ramp::rays();
  const Trace t = trace(ctx(), field.get(), dp45(L, rtol, atol), rays);
  ASSERT_EQ(t.status, ARCUS_SUCCESS);
  for (size_t i = 0; i < rays.size(); ++i) {
    const V3 o = rays.origin(i), d = normalize(rays.direction(i));
    EXPECT_EQ(t.ray_status[i], ARCUS_RAY_DONE);
    PathScale scale{0.0, L};
    const RayState want = Ramp::end(o, d, L, &scale);
    if (d[0] > 0) {
      // Before it enters the ray is straight: the field outside is uniform.  Traced to
      // just before x = 0 it must sit on its line (to rounding).
      const double s1 = -o[0] / d[0];
      Rays before;
      before.add(o, d);
      const Trace b = trace(ctx(), field.get(), dp45(0.99 * s1, rtol, atol), before);
      ASSERT_EQ(b.status, ARCUS_SUCCESS);
      EXPECT_LT(distance(b.pos(0), o + (0.99 * s1) * d), 1e-13 * (norm(o) + s1)) << "ray " << i;
      EXPECT_LT(distance(b.dir(0), d), 1e-15) << "ray " << i;
    }
    // The catenary's least radius of curvature is A/g ≥ 1/g·|d_yz| — for the axial ray
    // it does not bend at all; 0.1 m bounds every ray's from below.
    const double bound = dp45_bound(rtol, atol, scale);
    const double dir_bound = dp45_direction_bound(rtol, atol, scale, 0.1);
    std::printf("ray %zu (%g kinks): error %.3e m (bound %.3e), direction %.3e rad (bound %.3e)\n", i, scale.kinks,
                distance(t.pos(i), want.pos), bound, angle_between(t.dir(i), want.dir), dir_bound);
    EXPECT_LT(distance(t.pos(i), want.pos), bound) << "ray " << i;
    EXPECT_LT(angle_between(t.dir(i), want.dir), dir_bound) << "ray " << i;
  }
  // The bending is real: the second ray ends far from its straight continuation.
  EXPECT_GT(distance(t.pos(1), rays.origin(1) + L * normalize(rays.direction(1))), 0.1);
}

TEST_F(Grid, RayThroughTheGridInFloatPrecisionFollowsTheClosedForm) {
  // The ramp in float (ARCUS_PRECISION_FLOAT): DP45 at rtol 1e-6 (above float's
  // resolution, so the controller can meet it) against the closed form, within dp45_bound
  // at that tolerance plus float's rounding (float_rounding_bound).  The grid's values
  // 1 + 0.125·i are exact in float, so the field itself is not rounded.
  const double L = 8.0, rtol = 1e-6, atol = 1e-8;
  auto field = make(Ramp::spec());
  ASSERT_TRUE(field);
  const Rays rays = Ramp::rays();
  arcus_advance_params p = dp45(L, rtol, atol);
  p.precision = ARCUS_PRECISION_FLOAT;
  const Trace t = trace(ctx(), field.get(), p, rays);
  ASSERT_EQ(t.status, ARCUS_SUCCESS) << last_error();
  ASSERT_TRUE(t.features & ARCUS_FEATURE_FLOAT);
  for (size_t i = 0; i < rays.size(); ++i) {
    PathScale scale{0.0, L};
    const RayState want = Ramp::end(rays.origin(i), rays.direction(i), L, &scale);
    const double bound = dp45_bound(rtol, atol, scale) + float_rounding_bound(scale);
    std::printf("float ray %zu: error %.3e m (bound %.3e)\n", i, distance(t.pos(i), want.pos), bound);
    EXPECT_EQ(t.ray_status[i], ARCUS_RAY_DONE) << "ray " << i;
    EXPECT_LT(distance(t.pos(i), want.pos), bound) << "ray " << i;
  }
  // The bending dwarfs the bound: a float run that lost the grid would fail.
  PathScale scale{0.0, L};
  const RayState bent = Ramp::end(rays.origin(1), rays.direction(1), L, &scale);
  EXPECT_GT(distance(bent.pos, rays.origin(1) + L * normalize(rays.direction(1))),
            10.0 * (dp45_bound(rtol, atol, scale) + float_rounding_bound(scale)));
}

// ---- bad grids and grid files ----------------------------------------------------------

TEST_F(Grid, BadGridsAreRejected) {
  const double origin[3] = {0, 0, 0}, spacing[3] = {1, 1, 1};
  arcus_field_t* f = nullptr;
  std::vector<double> values(2 * 3 * 4, 1.0);
  const uint32_t dims[3] = {2, 3, 4};
  values[7] = kNaN;
  expect_invalid(arcus_field_create_grid(ctx(), values.data(), dims, origin, spacing, &f), "values", "NaN value");
  values[7] = kInf;
  expect_invalid(arcus_field_create_grid(ctx(), values.data(), dims, origin, spacing, &f), "values", "Inf value");
  // n must be positive.
  values[7] = 0.0;
  expect_invalid(arcus_field_create_grid(ctx(), values.data(), dims, origin, spacing, &f), "values", "zero value");
  values[7] = -1.0;
  expect_invalid(arcus_field_create_grid(ctx(), values.data(), dims, origin, spacing, &f), "values", "negative value");
  values[7] = 1.0;
  for (int axis = 0; axis < 3; ++axis) {
    // Each of dims must be 2..65536 (trilinear needs two nodes per axis).
    uint32_t zero[3] = {2, 3, 4};
    zero[axis] = 0;
    expect_invalid(arcus_field_create_grid(ctx(), values.data(), zero, origin, spacing, &f), "dims", "zero dimension");
    zero[axis] = 1;
    expect_invalid(arcus_field_create_grid(ctx(), values.data(), zero, origin, spacing, &f), "dims", "dimension 1");
    double bad_spacing[3] = {1, 1, 1};
    bad_spacing[axis] = 0.0;
    expect_invalid(arcus_field_create_grid(ctx(), values.data(), dims, origin, bad_spacing, &f), "spacing",
                   "zero spacing");
    bad_spacing[axis] = -1.0;
    expect_invalid(arcus_field_create_grid(ctx(), values.data(), dims, origin, bad_spacing, &f), "spacing",
                   "negative spacing");
  }
  EXPECT_EQ(f, nullptr);
}

TEST_F(Grid, GridFilesOfTheWrongSizeOrMissingAreRejected) {
  const double origin[3] = {0, 0, 0}, spacing[3] = {1, 1, 1};
  const uint32_t dims[3] = {3, 3, 3};
  const std::string path = temp_path("wrong_size");
  {
    // 26 doubles for a 27-voxel grid.
    std::ofstream out(path, std::ios::binary);
    const std::vector<double> v(26, 1.0);
    out.write(reinterpret_cast<const char*>(v.data()), std::streamsize(v.size() * sizeof(double)));
  }
  arcus_field_t* f = nullptr;
  // arcus_curved.h: "a file of the wrong size, is ARCUS_ERROR_IO".
  arcus_status st = arcus_field_create_grid_from_file(ctx(), path.c_str(), ARCUS_FLOAT64, dims, origin, spacing, &f);
  EXPECT_EQ(st, ARCUS_ERROR_IO) << arcus_status_string(st);
  EXPECT_EQ(f, nullptr);
  EXPECT_GT(std::strlen(arcus_context_last_error(ctx())), 0u);
  // 27 doubles are 54 floats: also the wrong size for a float32 file of 27 values.
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    const std::vector<double> v(27, 1.0);
    out.write(reinterpret_cast<const char*>(v.data()), std::streamsize(v.size() * sizeof(double)));
  }
  st = arcus_field_create_grid_from_file(ctx(), path.c_str(), ARCUS_FLOAT32, dims, origin, spacing, &f);
  EXPECT_EQ(st, ARCUS_ERROR_IO) << arcus_status_string(st);
  EXPECT_EQ(f, nullptr);
  // ... and the right size for float64.
  st = arcus_field_create_grid_from_file(ctx(), path.c_str(), ARCUS_FLOAT64, dims, origin, spacing, &f);
  EXPECT_EQ(st, ARCUS_SUCCESS) << last_error();
  if (f) arcus_field_release(f);
  std::remove(path.c_str());
  // A file that does not exist.
  f = nullptr;
  st = arcus_field_create_grid_from_file(ctx(), path.c_str(), ARCUS_FLOAT64, dims, origin, spacing, &f);
  EXPECT_EQ(st, ARCUS_ERROR_IO);
  EXPECT_EQ(f, nullptr);
  EXPECT_GT(std::strlen(arcus_context_last_error(ctx())), 0u);
}

TEST_F(Grid, GridFilesThatAreNotRegularFilesAreIoErrorsAndNeverBlock) {
  const uint32_t dims[3] = {2, 2, 2};
  const double origin[3] = {0, 0, 0}, spacing[3] = {1, 1, 1};
  arcus_field_t* f = nullptr;
  EXPECT_EQ(arcus_field_create_grid_from_file(ctx(), "/tmp", ARCUS_FLOAT64, dims, origin, spacing, &f), ARCUS_ERROR_IO);
  EXPECT_TRUE(contains_ci(last_error().c_str(), "directory")) << last_error();
  EXPECT_FALSE(contains_ci(last_error().c_str(), "9223372036854775807")) << last_error();
  // A FIFO with no writer: opening it for reading would wait forever (holding the
  // context's lock, so every other call on it would hang too).
  const std::string fifo = ::testing::TempDir() + "arcus_fifo_" + std::to_string(getpid());
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  auto call = std::async(std::launch::async, [&] {
    arcus_field_t* g = nullptr;
    return arcus_field_create_grid_from_file(ctx(), fifo.c_str(), ARCUS_FLOAT64, dims, origin, spacing, &g);
  });
  if (call.wait_for(std::chrono::seconds(20)) != std::future_status::ready) {
    const int fd = open(fifo.c_str(), O_WRONLY | O_NONBLOCK);  // release the reader before failing
    if (fd >= 0) close(fd);
    FAIL() << "reading a FIFO blocked";
  }
  EXPECT_EQ(call.get(), ARCUS_ERROR_IO);
  EXPECT_TRUE(contains_ci(last_error().c_str(), "FIFO")) << last_error();
  unlink(fifo.c_str());
}

// Grid files: the shape is checked before the file is read, and a directory is an I/O
// error, not a size.
TEST_F(Grid, GridFileShapeIsCheckedFirstAndADirectoryIsAnIoError) {
  const uint32_t huge[3] = {1u << 31, 1u << 31, 4};
  const double origin[3] = {0, 0, 0}, spacing[3] = {1, 1, 1};
  arcus_field_t* f = nullptr;
  EXPECT_EQ(arcus_field_create_grid_from_file(ctx(), "/dev/null", ARCUS_FLOAT64, huge, origin, spacing, &f),
            ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_TRUE(contains_ci(arcus_context_last_error(ctx()), "dims")) << last_error();
  const uint32_t dims[3] = {2, 2, 2};
  EXPECT_EQ(arcus_field_create_grid_from_file(ctx(), "/tmp", ARCUS_FLOAT64, dims, origin, spacing, &f),
            ARCUS_ERROR_IO);
  EXPECT_EQ(f, nullptr);
}

}  // namespace
