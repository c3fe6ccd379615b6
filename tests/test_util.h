// Shared helpers for the arcus C++ test suites: vector math, RAII handles, a fixture
// holding one context per test suite, a tracing wrapper, and the closed-form ray paths
// the physics tests compare against (each derivation is in its comment).
#ifndef ARCUS_TESTS_TEST_UTIL_H
#define ARCUS_TESTS_TEST_UTIL_H

#include <arcus/arcus.h>
#include <gtest/gtest.h>
#include <unistd.h>  // getpid

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace arcus_test {

// ---- vector math -----------------------------------------------------------------
using V3 = std::array<double, 3>;

inline V3 operator+(const V3& a, const V3& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
inline V3 operator-(const V3& a, const V3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
inline V3 operator-(const V3& a) { return {-a[0], -a[1], -a[2]}; }
inline V3 operator*(double s, const V3& a) { return {s * a[0], s * a[1], s * a[2]}; }
inline V3 operator*(const V3& a, double s) { return s * a; }
inline V3 operator/(const V3& a, double s) { return {a[0] / s, a[1] / s, a[2] / s}; }
inline double dot(const V3& a, const V3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline V3 cross(const V3& a, const V3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline double norm(const V3& a) { return std::sqrt(dot(a, a)); }
inline V3 normalize(const V3& a) { return a / norm(a); }
inline double distance(const V3& a, const V3& b) { return norm(a - b); }
inline bool finite(const V3& a) { return std::isfinite(a[0]) && std::isfinite(a[1]) && std::isfinite(a[2]); }
// Angle between two directions, accurate for tiny and near-π angles alike.
inline double angle_between(const V3& a, const V3& b) { return std::atan2(norm(cross(a, b)), dot(a, b)); }
// Rodrigues' rotation of v about the unit axis k by angle t.
inline V3 rotate(const V3& v, const V3& axis, double t) {
  const V3 k = normalize(axis);
  return std::cos(t) * v + std::sin(t) * cross(k, v) + (1.0 - std::cos(t)) * dot(k, v) * k;
}
constexpr double kPi = 3.14159265358979323846;
inline double deg(double radians) { return radians * 180.0 / kPi; }
inline double rad(double degrees) { return degrees * kPi / 180.0; }

inline std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}
inline bool contains_ci(const char* haystack, const char* needle) {
  return haystack && lower(haystack).find(lower(needle)) != std::string::npos;
}

// ---- RAII handles ------------------------------------------------------------------
struct ContextDeleter {
  void operator()(arcus_context_t* c) const { arcus_context_release(c); }
};
struct FieldDeleter {
  void operator()(arcus_field_t* f) const { arcus_field_release(f); }
};
struct JobDeleter {
  void operator()(arcus_job_t* j) const { arcus_job_release(j); }
};
struct MeshDeleter {
  void operator()(arcus_mesh_t* m) const { arcus_mesh_release(m); }
};
struct ParticleDeleter {
  void operator()(arcus_particle_t* p) const { arcus_particle_release(p); }
};
using ContextPtr = std::unique_ptr<arcus_context_t, ContextDeleter>;
using FieldPtr = std::unique_ptr<arcus_field_t, FieldDeleter>;
using JobPtr = std::unique_ptr<arcus_job_t, JobDeleter>;
using MeshPtr = std::unique_ptr<arcus_mesh_t, MeshDeleter>;
using ParticlePtr = std::unique_ptr<arcus_particle_t, ParticleDeleter>;

// ---- fixture: one context per test suite ------------------------------------------
class ArcusTest : public ::testing::Test {
 public:
  static void SetUpTestSuite() {
    if (ctx_) return;
    const arcus_status st = arcus_context_create(ARCUS_DEVICE_DEFAULT, &ctx_);
    if (st != ARCUS_SUCCESS) {
      std::fprintf(stderr, "arcus_context_create failed: %s: %s\n", arcus_status_string(st), arcus_last_error());
      ctx_ = nullptr;
    }
  }
  static void TearDownTestSuite() {
    if (ctx_) arcus_context_release(ctx_);
    ctx_ = nullptr;
  }

 protected:
  void SetUp() override { ASSERT_NE(ctx_, nullptr) << "no arcus context: " << arcus_last_error(); }
  static arcus_context_t* ctx() { return ctx_; }
  static std::string last_error() { return ctx_ ? arcus_context_last_error(ctx_) : arcus_last_error(); }
  // Expects `st` to be INVALID_ARGUMENT with a context message naming `argument`.
  // A null `argument` (a one-letter name like n or k, which any message contains) only
  // requires a message.
  static void expect_invalid(arcus_status st, const char* argument, const char* what) {
    EXPECT_EQ(st, ARCUS_ERROR_INVALID_ARGUMENT) << what;
    const std::string msg = arcus_context_last_error(ctx_);
    EXPECT_FALSE(msg.empty()) << what;
    if (argument) {
      EXPECT_TRUE(contains_ci(msg.c_str(), argument))
          << what << ": message \"" << msg << "\" does not name " << argument;
    }
  }
  // A file name of this process's own in the test's temporary directory.
  static std::string temp_path(const char* tag) {
    return ::testing::TempDir() + "arcus_test_" + tag + "_" + std::to_string(getpid()) + ".raw";
  }

  // Field factories: a failure is reported (with the library's message) and gives null.
  // (f is read through a pointer: argument evaluation order is unspecified.)
  static FieldPtr check(arcus_status st, arcus_field_t* const* f, const char* what) {
    EXPECT_EQ(st, ARCUS_SUCCESS) << what << ": " << arcus_status_string(st) << ": " << last_error();
    return FieldPtr(st == ARCUS_SUCCESS ? *f : nullptr);
  }
  static FieldPtr constant(double n) {
    arcus_field_t* f = nullptr;
    return check(arcus_field_create_constant(ctx_, n, &f), &f, "constant field");
  }
  static FieldPtr linear(double n0, const V3& g) {
    arcus_field_t* f = nullptr;
    return check(arcus_field_create_linear(ctx_, n0, g.data(), &f), &f, "linear field");
  }
  static FieldPtr linear_n2(double a, const V3& k) {
    arcus_field_t* f = nullptr;
    return check(arcus_field_create_linear_n2(ctx_, a, k.data(), &f), &f, "linear n^2 field");
  }
  static FieldPtr luneburg(const V3& c, double radius) {
    arcus_field_t* f = nullptr;
    return check(arcus_field_create_luneburg(ctx_, c.data(), radius, &f), &f, "Luneburg field");
  }
  static FieldPtr fisheye(const V3& c, double radius, double n0) {
    arcus_field_t* f = nullptr;
    return check(arcus_field_create_fisheye(ctx_, c.data(), radius, n0, &f), &f, "fish-eye field");
  }
  // The standard atmosphere (flat or spherical) with inversion layers; `inv` must
  // outlive the field's creation.
  static arcus_atmosphere_desc atmosphere_desc(int spherical, const std::vector<arcus_inversion>& inv) {
    arcus_atmosphere_desc d;
    EXPECT_EQ(arcus_atmosphere_desc_init(&d), ARCUS_SUCCESS);
    d.spherical = spherical;
    d.inversion_count = static_cast<uint32_t>(inv.size());
    d.inversions = inv.empty() ? nullptr : inv.data();
    return d;
  }
  static FieldPtr atmosphere(const arcus_atmosphere_desc& d) {
    arcus_field_t* f = nullptr;
    return check(arcus_field_create_atmosphere(ctx_, &d, &f), &f, "atmosphere field");
  }
  static FieldPtr grid(const std::vector<double>& values, const uint32_t dims[3], const V3& origin, const V3& spacing) {
    arcus_field_t* f = nullptr;
    return check(arcus_field_create_grid(ctx_, values.data(), dims, origin.data(), spacing.data(), &f), &f,
                 "grid field");
  }
  // n and ∇n of a field at one point (host evaluation, the kernels' formulas).
  static double n_at(arcus_field_t* f, const V3& p, V3* grad = nullptr) {
    double n = std::numeric_limits<double>::quiet_NaN();
    V3 g{};
    const arcus_status st = arcus_field_evaluate(f, 1, p.data(), &n, g.data());
    EXPECT_EQ(st, ARCUS_SUCCESS) << last_error();
    if (grad) *grad = g;
    return n;
  }

 private:
  static inline arcus_context_t* ctx_ = nullptr;
};

// ---- advance parameters ------------------------------------------------------------
inline arcus_advance_params dp45(double length, double rtol, double atol) {
  arcus_advance_params p;
  arcus_advance_params_init(&p);
  p.method = ARCUS_METHOD_DP45;
  p.length = length;
  p.rtol = rtol;
  p.atol = atol;
  return p;
}
inline arcus_advance_params fixed(arcus_method method, double step, double length) {
  arcus_advance_params p;
  arcus_advance_params_init(&p);
  p.method = method;
  p.step = step;
  p.length = length;
  return p;
}

// Stops rays on leaving the box [lo, hi].
inline void set_box(arcus_advance_params* p, const V3& lo, const V3& hi) {
  p->use_box = 1;
  std::copy(lo.begin(), lo.end(), p->box_min);
  std::copy(hi.begin(), hi.end(), p->box_max);
}

// ---- rays in, results out ----------------------------------------------------------
struct Rays {
  std::vector<double> origins, directions;
  void add(const V3& o, const V3& d) {
    origins.insert(origins.end(), o.begin(), o.end());
    directions.insert(directions.end(), d.begin(), d.end());
  }
  size_t size() const { return origins.size() / 3; }
  V3 origin(size_t i) const { return {origins[3 * i], origins[3 * i + 1], origins[3 * i + 2]}; }
  V3 direction(size_t i) const { return {directions[3 * i], directions[3 * i + 1], directions[3 * i + 2]}; }
};

struct Trace {
  arcus_status status = ARCUS_ERROR_INVALID_ARGUMENT;
  JobPtr job;
  std::vector<double> positions, directions, lengths;
  std::vector<uint64_t> steps;
  std::vector<int32_t> ray_status;
  arcus_features features = 0;

  size_t size() const { return lengths.size(); }
  V3 pos(size_t i) const { return {positions[3 * i], positions[3 * i + 1], positions[3 * i + 2]}; }
  V3 dir(size_t i) const { return {directions[3 * i], directions[3 * i + 1], directions[3 * i + 2]}; }
};

// Runs arcus_curved_advance and reads back every end state (when a job came back).
inline Trace trace(arcus_context_t* ctx, arcus_field_t* field, const arcus_advance_params& params, const Rays& rays) {
  Trace t;
  arcus_job_t* job = nullptr;
  t.status = arcus_curved_advance(ctx, field, &params, rays.size(), rays.origins.data(), rays.directions.data(), nullptr, &job);
  t.job.reset(job);
  if (!job) return t;
  size_t count = 0;
  EXPECT_EQ(arcus_job_get_count(job, &count), ARCUS_SUCCESS);
  EXPECT_EQ(count, rays.size());
  t.positions.assign(3 * count, 0.0);
  t.directions.assign(3 * count, 0.0);
  t.lengths.assign(count, 0.0);
  t.steps.assign(count, 0);
  t.ray_status.assign(count, -1);
  EXPECT_EQ(arcus_job_get_curved_end_states(job, t.positions.data(), t.directions.data(), t.steps.data(),
                                            t.ray_status.data(), t.lengths.data()),
                                            ARCUS_SUCCESS);
  EXPECT_EQ(arcus_job_get_features(job, &t.features), ARCUS_SUCCESS);
  return t;
}

// ---- error bounds ----------------------------------------------------------------------
// Bounds come from the tolerances and the closed form alone, never from what a run
// reports (its step count): a bound that grows with the implementation's output cannot
// catch an implementation that takes too many steps or errs on each.
//
// DP45's end-point error.  The controller accepts a step when its embedded estimate
// |y5 − y4| is within atol + rtol·|y| in each component of y = (r, v).  Along the path
// |r| ≤ |r_end| + L (no point lies farther than L from the end), and an error δv in
// v = n·dr/ds moves the end by ≤ δv·L/n with |v| = n, so one step's tolerance moves the
// end by at most  tol = rtol·(|r_end| + L) + atol·(1 + L/n_min).  The fifth-order
// solution the controller keeps errs by O(h⁶) a step, ≈ h/ℓ of the O(h⁵) estimate (ℓ:
// the path's radius of curvature, or the medium's length scale if shorter), so the
// steps add up to tol·∫ds/ℓ (`turning`: the path's total turning where it curves on its
// own scale) however many there are: the error is proportional to the tolerance (Hairer,
// Nørsett & Wanner I, §II.4).  kDp45Safety: error / ((1 + turning)·tol) stayed below 1.6
// for rtol 1e-5..1e-12 on every smooth closed form of these suites, below 1 for rtol ≤
// 1e-7 (the worst: the fish-eye arcs of test_curved_orders.cpp; catenaries stay below 0.03).
//
// Where ∇n jumps (a lens surface, an atmosphere's layer boundary, a grid's face) the
// estimate and the kept solution weigh the stages on either side of the jump
// differently, and their ratio is fixed by the tableau: dp45_kink_factor().  Each such
// kink may leave an error of that factor times v's tolerance in v, carried ≤ L to the end.
constexpr double kDp45Safety = 10.0;

// max over the place θ ∈ (0, 1) of a jump of dv/ds inside a step of |B(θ)|/|E(θ)|: B the
// fifth-order solution's error (Σ_{c_i > θ} b_i − (1 − θ)), E the estimate (Σ_{c_i > θ}
// e_i), from the published Dormand–Prince weights (stage 7 is the next step's first).
// ≈ 170, for a jump just before 3/10 of the step.
inline double dp45_kink_factor() {
  const double c[7] = {0.0, 1.0 / 5, 3.0 / 10, 4.0 / 5, 8.0 / 9, 1.0, 1.0};
  const double b[7] = {35.0 / 384, 0.0, 500.0 / 1113, 125.0 / 192, -2187.0 / 6784, 11.0 / 84, 0.0};
  const double e[7] = {71.0 / 57600, 0.0, -71.0 / 16695, 71.0 / 1920, -17253.0 / 339200, 22.0 / 525, -1.0 / 40};
  double worst = 0.0;
  for (int k = 1; k < 7; ++k) {  // θ between c[k−1] and c[k]: stages k.. see the jump
    if (c[k] == c[k - 1]) continue;
    double B = 0.0, E = 0.0;
    for (int i = k; i < 7; ++i) {
      B += b[i];
      E += e[i];
    }
    for (double theta : {c[k - 1], c[k]}) worst = std::max(worst, std::fabs(B - (1.0 - theta)) / std::fabs(E));
  }
  return worst;
}

// What a closed form says about a path, for the bounds below.
struct PathScale {
  double r_end;          // |r| at the end
  double length;         // L
  double turning = 0.0;  // ∫ds/ℓ (see above)
  double kinks = 0.0;    // jumps of ∇n crossed
  double n_min = 1.0;    // least n along the path
  double n_kink = 1.0;   // the largest n at a kink (v's tolerance there is rtol·n)
};
inline double dp45_bound(double rtol, double atol, const PathScale& p) {
  const double tol = rtol * (p.r_end + p.length) + atol * (1.0 + p.length / p.n_min);
  const double kink_v = (rtol * p.n_kink + atol) * p.length / p.n_min;
  return kDp45Safety * (1.0 + p.turning) * tol + dp45_kink_factor() * p.kinks * kink_v;
}
// DP45's error in v = n·dr/ds at the end (n ≤ n_max on the path): its tolerance
// atol + rtol·n a step, summed as in dp45_bound, plus what each kink leaves.
inline double dp45_v_bound(double rtol, double atol, const PathScale& p, double n_max) {
  return (kDp45Safety * (1.0 + p.turning) + dp45_kink_factor() * p.kinks) * (rtol * n_max + atol);
}
// End-direction error (radians): v's own tolerance (rtol + atol/n a step) summed as
// above, plus the turn a position error δr gives the path, ≤ δr/ℓ with ℓ the path's
// smallest radius of curvature (or the medium's length scale).
inline double dp45_direction_bound(double rtol, double atol, const PathScale& p, double ell) {
  return kDp45Safety * (1.0 + p.turning) * (rtol + atol / p.n_min) +
         dp45_kink_factor() * p.kinks * (rtol * p.n_kink + atol) / p.n_min + dp45_bound(rtol, atol, p) / ell;
}

// Float rounding of a run (ARCUS_PRECISION_FLOAT): float resolves a coordinate to
// ε_f = 2⁻²⁴ ≈ 6e-8 of its size.  The kernels carry each step's update with Kahan
// compensation, so the state's own rounding does not pile up with the step count
// (uncompensated it would grow as N·ε_f·|r|); what remains are the stages' roundings,
// a few ε_f of each increment (≤ L in all) and of each stage point (|r| ≤ |r_end| + L,
// which moves ∇n), propagated like any error along the path (1 + turning).  4: "a few";
// the measured differences between float and double runs of the same fixed steps stayed
// below 1.1 ε_f·(|r_end| + L)·(1 + turning) (the most: 2000 steps through 20 km of air).
constexpr double kFloatEps = 5.9604644775390625e-8;  // 2⁻²⁴
inline double float_rounding_bound(const PathScale& p) {
  return 4.0 * kFloatEps * (p.r_end + p.length) * (1.0 + p.turning);
}

// Observed order of convergence between two errors whose steps differ by `ratio`.
inline double observed_order(double error_coarse, double error_fine, double ratio = 2.0) {
  return std::log(error_coarse / error_fine) / std::log(ratio);
}

// ---- closed-form ray paths -------------------------------------------------------------
struct RayState {
  V3 pos, dir;
};

// Catenary: n = n0 + G·r.  Write ĝ = G/|G|, g = |G| and "height" y = ĝ·r.  With
// v = n dr/ds the ray equation is dv/ds = G, so the component of v across ĝ is constant
// (A, along the unit ĥ) and v·ĝ = v_y0 + g·s.  Parametrise v·ĝ = A sinh u, n = A cosh u:
// du/ds = g/(A cosh u), hence the horizontal coordinate is C + A u/g and the height is
// (A cosh u − n0)/g.  With u0 = asinh(v_y0/A), u_end = asinh(sinh u0 + g L/A):
//   x_end − x0 = A (u_end − u0)/g,  y_end = (A cosh u_end − n0)/g.
// A ray along ±ĝ (A = 0) stays straight.
inline RayState catenary_end(double n0, const V3& G, const V3& r0, const V3& d, double L) {
  const V3 dh = normalize(d);
  const double g = norm(G);
  const V3 gh = G / g;
  const double n_start = n0 + dot(G, r0);
  const V3 v = n_start * dh;
  const double vy = dot(v, gh);
  const V3 vh = v - vy * gh;
  const double A = norm(vh);
  if (A == 0.0) return {r0 + L * dh, dh};
  const V3 hh = vh / A;
  const double u0 = std::asinh(vy / A);
  const double u1 = std::asinh((vy + g * L) / A);
  const double y0 = dot(r0, gh);
  const double y1 = (A * std::cosh(u1) - n0) / g;
  const V3 pos = r0 + (A * (u1 - u0) / g) * hh + (y1 - y0) * gh;
  const V3 dir = normalize(A * hh + (vy + g * L) * gh);
  return {pos, dir};
}

// Linear n²: n² = a + K·r.  With dτ = ds/n the ray equation becomes d²r/dτ² = ∇(n²)/2 =
// K/2, so v(τ) = v0 + Kτ/2 and r(τ) = r0 + v0 τ + K τ²/4 (a parabola), and
// s(τ) = ∫0^τ |v| dτ' = ∫0^τ sqrt(α t² + β t + γ) dt with α = |K|²/4, β = v0·K, γ = |v0|².
// Completing the square (w = t + β/2α, m = |K × v0|·2/|K|²):
//   ∫ sqrt(α (w² + m²)) dw = √α/2 · [w sqrt(w² + m²) + m² asinh(w/m)].
struct Parabola {
  double a;
  V3 K, r0, v0;
  Parabola(double a_, const V3& K_, const V3& r0_, const V3& d) : a(a_), K(K_), r0(r0_) {
    v0 = std::sqrt(a + dot(K, r0)) * normalize(d);
  }
  V3 position(double tau) const { return r0 + tau * v0 + (tau * tau / 4.0) * K; }
  V3 direction(double tau) const { return normalize(v0 + (tau / 2.0) * K); }
  double arc_length(double tau) const {
    const double K2 = dot(K, K), alpha = K2 / 4.0;
    const double m = 2.0 * norm(cross(K, v0)) / K2, w0 = 2.0 * dot(v0, K) / K2;
    auto F = [&](double w) {
      const double body = m > 0.0 ? w * std::sqrt(w * w + m * m) + m * m * std::asinh(w / m) : w * std::fabs(w);
      return std::sqrt(alpha) / 2.0 * body;
    };
    return F(tau + w0) - F(w0);
  }
  // The τ where the arc length is L: Newton (s' = |v| > 0, s convex enough that it
  // converges from τ = L/n0).
  double tau_at(double L) const {
    double tau = L / norm(v0);
    for (int i = 0; i < 100; ++i) {
      const double dt = (arc_length(tau) - L) / norm(v0 + (tau / 2.0) * K);
      tau -= dt;
      if (std::fabs(dt) <= 1e-16 * std::fabs(tau)) break;
    }
    return tau;
  }
};

inline RayState linear_n2_end(double a, const V3& K, const V3& r0, const V3& d, double L) {
  const Parabola p(a, K, r0, d);
  const double tau = p.tau_at(L);
  return {p.position(tau), p.direction(tau)};
}

// Maxwell's fish-eye n = n0/(1 + |r − c|²/R²): every ray is a circle, and every ray
// through a point p (relative to c) also passes through p' = −R² p/|p|².  The circle
// through p tangent to d lies in the plane of p and d (the field is central); its centre
// is q = p + ρ m with m the unit normal of d in that plane and the signed radius ρ fixed
// by |q − p'| = |ρ|:  ρ = −|p − p'|² / (2 m·(p − p')).  After arc L (angle φ = L/|ρ|):
//   r = q + cos φ (p − q) + |ρ| sin φ d,   d_end = cos φ d − sin φ (p − q)/|ρ|.
// p must not be parallel to d (a ray through the centre is a straight line).
struct Circle {
  V3 centre;  // absolute
  double radius;
};
inline Circle fisheye_circle(const V3& c, double R, const V3& P, const V3& d) {
  const V3 dh = normalize(d);
  const V3 p = P - c;
  const V3 pp = (-R * R / dot(p, p)) * p;
  const V3 m = normalize(p - dot(p, dh) * dh);
  const double rho = -dot(p - pp, p - pp) / (2.0 * dot(m, p - pp));
  return {c + p + rho * m, std::fabs(rho)};
}
inline RayState fisheye_end(const V3& c, double R, const V3& P, const V3& d, double L) {
  const V3 dh = normalize(d);
  const Circle k = fisheye_circle(c, R, P, d);
  const V3 a = P - k.centre;
  const double phi = L / k.radius;
  return {k.centre + std::cos(phi) * a + (k.radius * std::sin(phi)) * dh,
          normalize(std::cos(phi) * dh - (std::sin(phi) / k.radius) * a)};
}

// Luneburg lens, inside: n² = 2 − |r − c|²/R².  With dτ = ds/n the ray equation becomes
// d²r/dτ² = ∇(n²)/2 = −(r − c)/R², a harmonic oscillator: p = r − c runs on the ellipse
// p(τ) = p0 cos(τ/R) + R v0 sin(τ/R) centred on c (v0 = n(P)·d̂), with |dp/dτ| = n.  The
// arc length s(τ) = ∫0^τ |dp/dτ| dτ' is elliptic: composite 8-point Gauss–Legendre (the
// integrand is smooth on the scale R: panels of R/10 leave ~1e-16 relative), and Newton
// for the τ where s = L.  Valid while the path stays inside the lens (inside_radius).
struct LuneburgEllipse {
  V3 c, p0, v0;
  double R;
  LuneburgEllipse(const V3& c_, double R_, const V3& P, const V3& d) : c(c_), p0(P - c_), R(R_) {
    v0 = std::sqrt(2.0 - dot(p0, p0) / (R * R)) * normalize(d);
  }
  V3 position(double tau) const { return c + std::cos(tau / R) * p0 + (R * std::sin(tau / R)) * v0; }
  V3 velocity(double tau) const { return (-std::sin(tau / R) / R) * p0 + std::cos(tau / R) * v0; }
  double arc_length(double tau) const {
    static const double x[4] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267, 0.9602898564975363};
    static const double w[4] = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763};
    const int panels = 1 + int(std::fabs(tau) / (0.1 * R));
    const double width = tau / panels;
    double s = 0.0;
    for (int k = 0; k < panels; ++k) {
      const double mid = (k + 0.5) * width;
      for (int j = 0; j < 4; ++j)
        s += w[j] * (norm(velocity(mid - 0.5 * width * x[j])) + norm(velocity(mid + 0.5 * width * x[j])));
    }
    return 0.5 * width * s;
  }
  double tau_at(double L) const {
    double tau = L / norm(v0);
    for (int i = 0; i < 50; ++i) {
      const double dt = (arc_length(tau) - L) / norm(velocity(tau));
      tau -= dt;
      if (std::fabs(dt) <= 1e-15 * std::fabs(tau)) break;
    }
    return tau;
  }
  // The largest |r − c| on the path up to arc L (sampled finely: a precondition check).
  double inside_radius(double L) const {
    const double tau = tau_at(L);
    double r = 0.0;
    for (int k = 0; k <= 1000; ++k) r = std::max(r, norm(position(tau * k / 1000.0) - c));
    return r;
  }
};
inline RayState luneburg_end(const V3& c, double R, const V3& P, const V3& d, double L) {
  const LuneburgEllipse e(c, R, P, d);
  const double tau = e.tau_at(L);
  return {e.position(tau), normalize(e.velocity(tau))};
}

}  // namespace arcus_test

#endif  // ARCUS_TESTS_TEST_UTIL_H
