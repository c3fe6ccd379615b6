// Flat-faced meshes (crystals) through the public C API: a glass cube's glints against
// Fresnel's closed forms, cast as a grid of rays (arcus_rainbow_cast) and traced as
// beams (arcus_rainbow_trace_beams), and what beam tracing refuses.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "arcus/arcus.h"
#include "rainbow_handles.h"

namespace {

constexpr double kPi = 3.14159265358979323846;

using rainbow_test::Ctx;
using rainbow_test::Job;
using rainbow_test::Particle;

// A cube of half-side 1 as an OBJ file; `dent` moves its corner (1, 1, 1) to (dent,
// dent, dent), which for dent < 1 makes it concave.
std::string write_cube(const std::string& name, double dent = 1) {
  const std::string path = testing::TempDir() + name;
  std::ofstream f(path);
  for (int v = 0; v < 8; ++v) {
    const double far = v == 7 ? dent : 1;
    f << "v " << (v & 1 ? far : -1) << " " << (v & 2 ? far : -1) << " " << (v & 4 ? far : -1) << "\n";
  }
  // two triangles per face, vertices numbered from 1 (bit 0: x, bit 1: y, bit 2: z)
  const int faces[6][4] = {{1, 3, 4, 2}, {5, 6, 8, 7}, {1, 2, 6, 5}, {3, 7, 8, 4}, {1, 5, 7, 3}, {2, 4, 8, 6}};
  for (const auto& q : faces) f << "f " << q[0] << " " << q[1] << " " << q[2] << "\nf " << q[0] << " " << q[2] << " " << q[3] << "\n";
  return path;
}

// A flat-faced mesh's light is glints (arcus_job_get_rainbow_glints).  A glass cube
// (n = 1.5) met face-on: the main glint of each term leaves straight back or through
// with the Fresnel closed forms R = ((n − 1)/(n + 1))² = 0.04, (1 − R)², (1 − R)² R,
// (1 − R)² R² of its cast area (every one of its rays is the same ray: 1e-12); turned
// 30° about y: p = 0 leaves at θ = 180° − 60° and p = 1 through the parallel faces
// at θ = 0 (directions to 1e-12), each with its unpolarised Fresnel product; the glints'
// books equal the cast's per term (1e-12 relative).
TEST(RainbowFlatMeshes, CastsGiveGlintsWithFresnelPowers) {
  Ctx c;
  const std::string path = write_cube("arcus_cube.obj");
  const double n = 1.5, deg30 = kPi / 6;
  for (const double turn : {0.0, deg30}) {
    Particle p;
    ASSERT_EQ(arcus_particle_create_mesh(c.ctx, path.c_str(), 1e-3, 0, &p.p), ARCUS_SUCCESS)
        << arcus_context_last_error(c.ctx);
    arcus_rainbow_params params;
    arcus_rainbow_params_init(&params);
    params.grid = 64;
    params.material = ARCUS_MATERIAL_FIXED;
    params.refractive_index = n;
    const double cs = std::cos(turn), sn = std::sin(turn);
    const double rot[9] = {cs, 0, sn, 0, 1, 0, -sn, 0, cs};
    std::copy(rot, rot + 9, params.rotation);
    Job j;
    ASSERT_EQ(arcus_rainbow_cast(c.ctx, p.p, &params, &j.job), ARCUS_SUCCESS) << arcus_context_last_error(c.ctx);
    size_t count = 0;
    ASSERT_EQ(arcus_job_get_rainbow_glints(j.job, &count, nullptr, nullptr, nullptr, nullptr), ARCUS_SUCCESS);
    ASSERT_GT(count, 0u);
    std::vector<uint32_t> term(count);
    std::vector<double> dir(3 * count), area(count), cross(count);
    ASSERT_EQ(arcus_job_get_rainbow_glints(j.job, &count, term.data(), dir.data(), area.data(), cross.data()),
              ARCUS_SUCCESS);
    arcus_rainbow_stats s;
    arcus_job_get_rainbow_stats(j.job, &s);
    // Fresnel at the entry angle (unpolarised: the mean of s and p powers)
    const double ci = cs, ct = std::sqrt(1 - sn * sn / (n * n));
    const double rs = std::pow((ci - n * ct) / (ci + n * ct), 2), rp = std::pow((n * ci - ct) / (n * ci + ct), 2);
    for (uint32_t q = 0; q <= (turn == 0 ? 3u : 1u); ++q) {
      size_t main = count;
      double books = 0;
      for (size_t g = 0; g < count; ++g) {
        if (term[g] != q) continue;
        books += cross[g];
        if (main == count || area[g] > area[main]) main = g;
      }
      ASSERT_LT(main, count) << q;
      EXPECT_NEAR(books / s.intercepted, s.scattered[q], 1e-12 * s.scattered[q] + 1e-15) << q;
      // the term's Fresnel product for s and p light, averaged
      auto product = [&](double r) { return q == 0 ? r : (1 - r) * (1 - r) * std::pow(r, q - 1); };
      EXPECT_NEAR(cross[main] / area[main], (product(rs) + product(rp)) / 2, 1e-12) << "turn " << turn << " p " << q;
      const double theta = std::acos(std::clamp(dir[3 * main + 2], -1.0, 1.0)) * 180 / kPi;
      const double expect = q % 2 == 0 ? 180 - 2 * turn * 180 / kPi : 0;
      EXPECT_NEAR(theta, expect, 1e-9) << "turn " << turn << " p " << q;
    }
  }
  std::remove(path.c_str());
}

// Beams (arcus_rainbow_trace_beams) through the same glass cube, 2 mm across, face-on
// and turned 30° about y in one call: each face's glints carry exactly its shadow
// (4 mm² face-on; 4 cos 30° and 4 sin 30° mm² for the two lit faces turned) times the
// closed-form Fresnel product of its term, to rounding (1e-12), where the grid above
// is right to O(1/grid) in area; the books close (scattered + remaining = 1).
TEST(RainbowFlatMeshes, BeamsAreExact) {
  Ctx c;
  const std::string path = write_cube("arcus_beam_cube.obj");
  Particle p;
  ASSERT_EQ(arcus_particle_create_mesh(c.ctx, path.c_str(), 1e-3, 0, &p.p), ARCUS_SUCCESS)
      << arcus_context_last_error(c.ctx);
  const double n = 1.5, cs = std::cos(kPi / 6), sn = std::sin(kPi / 6);
  arcus_rainbow_params params;
  arcus_rainbow_params_init(&params);
  params.material = ARCUS_MATERIAL_FIXED;
  params.refractive_index = n;
  params.max_bounces = 3;
  const double rotations[18] = {1, 0, 0, 0, 1, 0, 0, 0, 1, cs, 0, sn, 0, 1, 0, -sn, 0, cs};
  Job j;
  ASSERT_EQ(arcus_rainbow_trace_beams(c.ctx, p.p, &params, 2, rotations, &j.job), ARCUS_SUCCESS)
      << arcus_context_last_error(c.ctx);
  size_t count = 0;
  ASSERT_EQ(arcus_job_get_rainbow_glints(j.job, &count, nullptr, nullptr, nullptr, nullptr), ARCUS_SUCCESS);
  std::vector<uint32_t> term(count);
  std::vector<double> dir(3 * count), area(count), cross(count);
  ASSERT_EQ(arcus_job_get_rainbow_glints(j.job, &count, term.data(), dir.data(), area.data(), cross.data()),
            ARCUS_SUCCESS);
  arcus_rainbow_stats s;
  ASSERT_EQ(arcus_job_get_rainbow_stats(j.job, &s), ARCUS_SUCCESS);
  const double face = 4e-6;  // m²
  EXPECT_NEAR(s.intercepted, (face + face * (cs + sn)) / 2, 1e-12 * face);
  double books = s.remaining;
  for (int q = 0; q <= 3; ++q) books += s.scattered[q];
  EXPECT_NEAR(books, 1, 1e-12);
  auto unpolarised = [&](double ci, int q) {
    const double ct = std::sqrt(1 - (1 - ci * ci) / (n * n));
    const double r[2] = {std::pow((ci - n * ct) / (ci + n * ct), 2), std::pow((n * ci - ct) / (n * ci + ct), 2)};
    double sum = 0;
    for (double x : r) sum += q == 0 ? x : (1 - x) * (1 - x) * std::pow(x, q - 1);
    return sum / 2;
  };
  // face-on: one glint per term, straight back (even p) or through (odd p)
  int turned_reflections = 0, straight_through = 0;
  for (size_t g = 0; g < count; ++g) {
    if (g < 4) {
      EXPECT_EQ(term[g], g) << g;  // the first orientation's four glints, in order
      EXPECT_NEAR(area[g], face, 1e-12 * face) << g;
      EXPECT_NEAR(cross[g] / area[g], unpolarised(1, static_cast<int>(g)), 1e-12) << g;
      EXPECT_NEAR(dir[3 * g + 2], g % 2 == 0 ? -1 : 1, 1e-12) << g;
      continue;
    }
    // turned: the two lit faces' light enters at cos 30° and cos 60°; p = 0 is one glint
    // per face, and p = 1 leaving through a face parallel to its entry goes straight
    // on with (1 − R)² of that entry (a beam may split, but every ray keeps its product)
    if (term[g] == 0) {
      const double ci = std::fabs(area[g] - face * cs) < 1e-12 * face ? cs : sn;
      EXPECT_NEAR(area[g], face * ci, 1e-12 * face) << g;
      EXPECT_NEAR(cross[g] / area[g], unpolarised(ci, 0), 1e-12) << g;
      EXPECT_NEAR(dir[3 * g + 2], 1 - 2 * ci * ci, 1e-12) << g;  // reflected: cos θ = −cos 2i
      ++turned_reflections;
    } else if (term[g] == 1 && dir[3 * g + 2] > 1 - 1e-12) {
      const double product = cross[g] / area[g];
      EXPECT_NEAR(std::min(std::fabs(product - unpolarised(cs, 1)), std::fabs(product - unpolarised(sn, 1))), 0,
                  1e-12) << g;
      ++straight_through;
    }
  }
  EXPECT_EQ(turned_reflections, 2);
  EXPECT_GE(straight_through, 2);
  std::remove(path.c_str());
}

// What beam tracing refuses, by name: a smooth mesh, a concave one, no orientations,
// a rotation that is not one.
TEST(RainbowFlatMeshes, BeamsRefuseWhatTheyCannotTrace) {
  Ctx c;
  const std::string cube = write_cube("arcus_beam_cube2.obj"), dented = write_cube("arcus_dented.obj", 0.2);
  arcus_rainbow_params params;
  arcus_rainbow_params_init(&params);
  const double identity[18] = {1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 0, 0, 0, 1, 0, 0, 0, -1};
  Job j;
  {
    Particle smooth;
    ASSERT_EQ(arcus_particle_create_mesh(c.ctx, cube.c_str(), 1e-3, 1, &smooth.p), ARCUS_SUCCESS);
    EXPECT_EQ(arcus_rainbow_trace_beams(c.ctx, smooth.p, &params, 1, identity, &j.job), ARCUS_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(arcus_context_last_error(c.ctx)).find("flat-faced"), std::string::npos);
  }
  {
    Particle concave;
    ASSERT_EQ(arcus_particle_create_mesh(c.ctx, dented.c_str(), 1e-3, 0, &concave.p), ARCUS_SUCCESS);
    EXPECT_EQ(arcus_rainbow_trace_beams(c.ctx, concave.p, &params, 1, identity, &j.job), ARCUS_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(arcus_context_last_error(c.ctx)).find("convex"), std::string::npos);
  }
  Particle p;
  ASSERT_EQ(arcus_particle_create_mesh(c.ctx, cube.c_str(), 1e-3, 0, &p.p), ARCUS_SUCCESS);
  EXPECT_EQ(arcus_rainbow_trace_beams(c.ctx, p.p, &params, 0, identity, &j.job), ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(std::string(arcus_context_last_error(c.ctx)).find("count"), std::string::npos);
  EXPECT_EQ(arcus_rainbow_trace_beams(c.ctx, p.p, &params, 2, identity, &j.job), ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(std::string(arcus_context_last_error(c.ctx)).find("rotations[1]"), std::string::npos);
  EXPECT_EQ(j.job, nullptr);
  std::remove(cube.c_str());
  std::remove(dented.c_str());
}

}  // namespace
