// Meshes for the translucency suites, built here (no files): a box and an icosphere,
// held by arcus_mesh_t handles.
#ifndef ARCUS_TESTS_TRANSLUCENCY_FIXTURE_H
#define ARCUS_TESTS_TRANSLUCENCY_FIXTURE_H

#include <arcus/arcus.h>
#include <gtest/gtest.h>

#include <cmath>
#include <algorithm>
#include <cstdint>
#include <map>
#include <utility>
#include <vector>

namespace {

// A triangle mesh held by an arcus_mesh_t.
struct MeshHandle {
  arcus_mesh_t* mesh = nullptr;
  MeshHandle(arcus_context_t* ctx, const std::vector<double>& v, const std::vector<uint32_t>& t) {
    EXPECT_EQ(arcus_mesh_create(ctx, v.size() / 3, v.data(), t.size() / 3, t.data(), &mesh), ARCUS_SUCCESS)
        << arcus_last_error();
  }
  MeshHandle(const MeshHandle&) = delete;
  MeshHandle& operator=(const MeshHandle&) = delete;
  ~MeshHandle() {
    if (mesh) arcus_mesh_release(mesh);
  }
};

// The box [lo, hi], its 12 triangles wound outwards.
inline void box(const double lo[3], const double hi[3], std::vector<double>* v, std::vector<uint32_t>* t) {
  const uint32_t base = static_cast<uint32_t>(v->size() / 3);
  for (int k = 0; k < 8; ++k)
    v->insert(v->end(), {k & 1 ? hi[0] : lo[0], k & 2 ? hi[1] : lo[1], k & 4 ? hi[2] : lo[2]});
  const uint32_t quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) t->insert(t->end(), {base + q[0], base + q[1], base + q[2], base + q[0], base + q[2], base + q[3]});
}

// A unit icosphere: the icosahedron's faces cut in four `levels` times, pushed out.
void icosphere(int levels, std::vector<double>* v, std::vector<uint32_t>* t) {
  const double p = (1 + std::sqrt(5.0)) / 2;
  *v = {-1, p, 0, 1, p, 0, -1, -p, 0, 1, -p, 0, 0, -1, p, 0, 1, p, 0, -1, -p, 0, 1, -p, p, 0, -1, p, 0, 1, -p, 0, -1, -p, 0, 1};
  *t = {0, 11, 5, 0, 5, 1, 0, 1, 7, 0, 7, 10, 0, 10, 11, 1, 5, 9, 5, 11, 4, 11, 10, 2, 10, 7, 6, 7, 1, 8,
        3, 9, 4, 3, 4, 2, 3, 2, 6, 3, 6, 8, 3, 8, 9, 4, 9, 5, 2, 4, 11, 6, 2, 10, 8, 6, 7, 9, 8, 1};
  for (int l = 0; l < levels; ++l) {
    std::vector<uint32_t> next;
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> made;  // an edge's midpoint, made once
    auto mid = [&](uint32_t a, uint32_t b) {
      const auto key = std::make_pair(std::min(a, b), std::max(a, b));
      const auto found = made.find(key);
      if (found != made.end()) return found->second;
      v->insert(v->end(), {0.5 * ((*v)[3 * a] + (*v)[3 * b]), 0.5 * ((*v)[3 * a + 1] + (*v)[3 * b + 1]),
                           0.5 * ((*v)[3 * a + 2] + (*v)[3 * b + 2])});
      return made[key] = static_cast<uint32_t>(v->size() / 3 - 1);
    };
    for (size_t f = 0; f < t->size(); f += 3) {
      const uint32_t a = (*t)[f], b = (*t)[f + 1], c = (*t)[f + 2];
      const uint32_t ab = mid(a, b), bc = mid(b, c), ca = mid(c, a);
      next.insert(next.end(), {a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca});
    }
    *t = next;
  }
  for (size_t i = 0; i < v->size(); i += 3) {
    const double r = std::sqrt((*v)[i] * (*v)[i] + (*v)[i + 1] * (*v)[i + 1] + (*v)[i + 2] * (*v)[i + 2]);
    for (int a = 0; a < 3; ++a) (*v)[i + a] /= r;
  }
}

}  // namespace

#endif  // ARCUS_TESTS_TRANSLUCENCY_FIXTURE_H
