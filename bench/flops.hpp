// Floating-point operations of one step of one ray, from the method and the field kind,
// counted in the formulas of kernels/advance.cl and kernels/field.h (double path, no
// box, no path recording).  Rules:
//   - an FMA counts 2; an add, subtract, multiply, divide or sqrt 1; a float log2 or
//     exp2 (DP45's step factor) 1 like sqrt, though each is many instructions;
//   - compares, selects, fabs, fmin/fmax/clamp, negation and conversions count 0;
//   - a constant of the job or field (−inv_radius2, −2·inv_radius2) and the scalars
//     computed once per step for every ray (h/2, h/6) count 0;
//   - ray_fma(k, 1, acc) is the add k + acc: 1 per component (a literal 1 is no
//     multiplication);
//   - what the compiler may remove beyond that is NOT subtracted: the count is what
//     the formulas ask for, not what the machine code executes (see RK4 below).
// The float path's Kahan update (ray_advance) costs 42 more per step; not counted here.
#pragma once

#include <arcus/arcus.h>

#include <stdexcept>

namespace bench {

// field_eval for one point (field.h).
constexpr double field_eval_flops(arcus_field_kind kind) {
  switch (kind) {
    case ARCUS_FIELD_LINEAR:
      // n = n0 + g·r: 3 mul + 3 add (3 FMAs); ∇n = g is a field constant: 0
      return 6;
    case ARCUS_FIELD_LINEAR_N2:
      // n = sqrt(a + k·r): 6 + sqrt 1; 0.5/n: 1; ∇n = k·(0.5/n): 3
      return 6 + 1 + 1 + 3;
    case ARCUS_FIELD_LUNEBURG:
      // d = r − c: 3; ρ² = |d|²·inv_R²: 3 mul + 2 add + 1 mul; 2 − min(ρ², 1): 1;
      // sqrt: 1; s = −inv_R²/n: 1 (the negation is a constant); ∇n = s·d: 3
      return 3 + 6 + 1 + 1 + 1 + 3;
    case ARCUS_FIELD_FISHEYE:
      // d = r − c: 3; q = 1 + |d|²·inv_R²: 3 mul + 2 add + 1 mul + 1 add; 1/q: 1;
      // n = n0/q: 1; s = (−2·inv_R²)·n·(1/q): 2 (the first product is a constant);
      // ∇n = s·d: 3
      return 3 + 7 + 1 + 1 + 2 + 3;
    default:
      // constant: no work worth a count; atmosphere and grid depend on their data
      // (segments, cells) and are not analytic in this sense.
      throw std::invalid_argument("flops_per_step: only linear, linear n², Luneburg and fish-eye are counted");
  }
}

// ray_derivative: field_eval, then 1/n: 1 and dr/ds = v·(1/n): 3.
constexpr double derivative_flops(arcus_field_kind kind) { return field_eval_flops(kind) + 1 + 3; }

// One step per ray: Euler, RK2, RK4 per (fixed) step; DP45 per attempted step,
// accepted or rejected alike (both do the same work).  A ray6 operation is 6 lanes of
// state: ray_step / ray_fma 6 FMAs = 12, ray_scale / ray_times 6 mul = 6.
constexpr double flops_per_step(arcus_method method, arcus_field_kind kind) {
  const double d = derivative_flops(kind);
  switch (method) {
    case ARCUS_METHOD_EULER:
      // 1 derivative; ray_advance = ray_step(y, h, k): 12
      return d + 12;
    case ARCUS_METHOD_RK2:
      // 2 derivatives; ray_step(y, h/2, k1): 12; ray_advance: 12
      return 2 * d + 12 + 12;
    case ARCUS_METHOD_RK4:
      // 4 derivatives; 3 stage states ray_step: 36; acc += 2 k2, 2 k3 (ray_fma): 24;
      // k4 + acc (ray_fma by 1): 6; ray_advance(y, h/6, ·): 12.
      //
      // Linear field: 4 × 10 + 36 + 24 + 6 + 12 = 118.  PoCL's machine code executes
      // fewer (kRk4LinearExecutedFlops below); the other fields have a varying ∇n and no
      // such removal.
      return 4 * d + 36 + 24 + 6 + 12;
    case ARCUS_METHOD_DP45: {
      // 6 derivatives (k2..k7; k1 comes from the previous step, FSAL).
      // Stage states: ray_scale(k1) 6 + one ray_fma per further k, then ray_step 12:
      const double stages = (6 + 12) + (6 + 12 + 12) + (6 + 24 + 12) + (6 + 36 + 12) + (6 + 48 + 12);  // 210
      // y5: ray_scale(k1, B1) 6 + 4 ray_fma 48, ray_advance 12
      const double solution = 6 + 48 + 12;  // 66
      // error: ray_scale(k1, E1) 6 + 5 ray_fma 60, ray_times(e, h) 6
      const double error = 6 + 60 + 6;  // 72
      // dp_error_norm: rtol·max 1, atol + 1, |err| / that 1 for each of 6 components
      const double norm = 6 * 3;  // 18
      // remaining = length − s: 1; s + h: 1; 0.9·exp2(−0.2·log2(err)): 4 (float);
      // h·factor: 1
      const double control = 1 + 1 + 4 + 1;  // 7
      return 6 * d + stages + solution + error + norm + control;
    }
  }
  throw std::invalid_argument("flops_per_step: unknown method");
}

static_assert(flops_per_step(ARCUS_METHOD_RK4, ARCUS_FIELD_LINEAR) == 118, "see the RK4 comment");

// What PoCL's compiled RK4 step executes per ray for the linear field: 97 of the 118.
// ∇n is constant, so the v part of acc (2 ray_fma + add per component: 15) is loop
// invariant and hoisted out of the step loop, and stage 3's v equals stage 2's and is
// computed once (6): 118 − 21 = 97.  Checked in the disassembly of one step-loop
// iteration (8 groups of double8): 312 vfmadd, 96 vmulpd, 24 vaddpd and 32 vdivpd on
// zmm, per group 39 FMA + 12 mul + 3 add + 4 div = 97 (bench/README.md, "RK4 FLOPs per step",
// says how to redo it after a kernel change).
constexpr double kRk4LinearExecutedFlops = 97;

// RK4's divisions per step per ray: 1/n in each of its 4 derivatives.  A division counts
// 1 FLOP but the divider takes a new one far less often than an FMA pipe an FMA, so
// these 4 can bound the step rate before the FMAs do (fp64_peak measures both rates).
constexpr double kRk4DivisionsPerStep = 4;

}  // namespace bench
