// The render suites' fixture (test_render.cpp, test_render_errors.cpp): scenes written
// to temporary files, rendered, and their hits and image read back.
#pragma once

#include <unistd.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "test_util.h"

namespace arcus_test {

struct Rendered {
  uint32_t width = 0, height = 0;
  std::vector<float> rgb;
  std::vector<double> points, distances;
  std::vector<int32_t> objects, primitives;
  std::vector<uint32_t> steps, tests;
  arcus_render_stats stats{};
};

class Render : public ArcusTest {
 protected:
  static std::string temp_file(const std::string& tag, const std::string& ext, const std::string& text) {
    const std::string path =
        ::testing::TempDir() + "arcus_render_" + tag + "_" + std::to_string(getpid()) + ext;
    std::ofstream(path) << text;
    return path;
  }
  static std::string mesh(const char* name) { return std::string(ARCUS_SOURCE_DIR) + "/data/meshes/" + name; }

  // A scene: the medium, camera and objects given as JSON fragments.
  static std::string scene_text(const std::string& medium, const std::string& camera, const std::string& objects,
                                const std::string& extra = "") {
    return R"({"name": "t", "medium": )" + medium +
           R"(, "integrator": {"method": "dp45", "rtol": 1e-12, "atol": 1e-6, "length": 1000},
              "camera": )" + camera +
           R"(, "materials": {"m": {"diffuse": [0.5, 0.5, 0.5]}}, "objects": )" + objects +
           R"(, "sky": {"type": "constant", "color": [0.2, 0.3, 0.4]})" + extra + "}";
  }

  arcus_scene_t* load(const std::string& text, const char* tag) {
    arcus_scene_t* s = nullptr;
    const arcus_status st = arcus_scene_load(ctx(), temp_file(tag, ".json", text).c_str(), &s);
    EXPECT_EQ(st, ARCUS_SUCCESS) << last_error();
    return s;
  }

  Rendered render(arcus_scene_t* scene, uint32_t techniques, int frames = 1) {
    Rendered out;
    arcus_renderer_t* r = nullptr;
    EXPECT_EQ(arcus_renderer_create(scene, &r), ARCUS_SUCCESS) << last_error();
    if (!r) return out;
    EXPECT_EQ(arcus_renderer_set_techniques(r, techniques), ARCUS_SUCCESS) << last_error();
    arcus_job_t* job = nullptr;
    for (int f = 0; f < frames; ++f) {
      if (job) arcus_job_release(job);
      job = nullptr;
      EXPECT_EQ(arcus_render_frame(r, nullptr, nullptr, &job), ARCUS_SUCCESS) << last_error();
      if (!job) break;
    }
    if (job) {
      arcus_job_get_render_image_size(job, &out.width, &out.height);
      const size_t n = size_t(out.width) * out.height;
      out.rgb.resize(3 * n);
      out.points.resize(3 * n);
      out.distances.resize(n);
      out.objects.resize(n);
      out.primitives.resize(n);
      out.steps.resize(n);
      out.tests.resize(n);
      EXPECT_EQ(arcus_job_get_render_image(job, out.rgb.data()), ARCUS_SUCCESS);
      EXPECT_EQ(arcus_job_get_render_hits(job, out.points.data(), out.objects.data(), out.primitives.data(),
                                          out.distances.data(), out.steps.data(), out.tests.data()),
                                          ARCUS_SUCCESS);
      EXPECT_EQ(arcus_job_get_render_stats(job, &out.stats), ARCUS_SUCCESS);
      arcus_job_release(job);
    }
    arcus_renderer_release(r);
    return out;
  }

  std::pair<arcus_status, std::string> load_error(const std::string& path) {
    arcus_scene_t* s = nullptr;
    const arcus_status st = arcus_scene_load(ctx(), path.c_str(), &s);
    if (s) arcus_scene_release(s);
    return {st, last_error()};
  }
};

// Möller–Trumbore on the host: the independent straight-ray reference.
inline bool ray_triangle(const double* o, const double* d, const double* a, const double* b, const double* c,
                         double* t) {
  const double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  const double p[3] = {d[1] * e2[2] - d[2] * e2[1], d[2] * e2[0] - d[0] * e2[2], d[0] * e2[1] - d[1] * e2[0]};
  const double det = e1[0] * p[0] + e1[1] * p[1] + e1[2] * p[2];
  if (std::fabs(det) < 1e-300) return false;
  const double s[3] = {o[0] - a[0], o[1] - a[1], o[2] - a[2]};
  const double u = (s[0] * p[0] + s[1] * p[1] + s[2] * p[2]) / det;
  if (u < 0 || u > 1) return false;
  const double q[3] = {s[1] * e1[2] - s[2] * e1[1], s[2] * e1[0] - s[0] * e1[2], s[0] * e1[1] - s[1] * e1[0]};
  const double v = (d[0] * q[0] + d[1] * q[1] + d[2] * q[2]) / det;
  if (v < 0 || u + v > 1) return false;
  *t = (e2[0] * q[0] + e2[1] * q[1] + e2[2] * q[2]) / det;
  return *t > 0;
}

// A medium of index 1, and a 48×32 camera at the origin looking down −z (30° high).
const std::string kConstantMedium = R"({"type": "constant", "n": 1.0})";
const std::string kPinholeCamera = R"({"position": [0, 0, 0], "look_at": [0, 0, -1], "up": [0, 1, 0],
                                       "vfov_deg": 30, "width": 48, "height": 32})";

// Curved optics must reduce to straight optics: in a constant medium every pixel of an
// image taken with kPinholeCamera hits exactly the triangle (of `tris`, 9 coordinates
// each, placed) that a straight pinhole ray through its centre hits, found here by brute
// force, at the same distance.
inline void expect_straight_pinhole_image(const Rendered& img, const std::vector<double>& tris) {
  const double tan_half = std::tan(15.0 * M_PI / 180.0), aspect = 48.0 / 32.0;
  ASSERT_EQ(img.width, 48u);
  ASSERT_EQ(img.height, 32u);
  int silhouette = 0;
  for (uint32_t j = 0; j < img.height; ++j)
    for (uint32_t i = 0; i < img.width; ++i) {
      const size_t p = size_t(j) * img.width + i;
      const double o[3] = {0, 0, 0};
      const double d[3] = {(2.0 * (i + 0.5) / img.width - 1) * tan_half * aspect,
                           (1 - 2.0 * (j + 0.5) / img.height) * tan_half, -1};
      double best = INFINITY, t;
      int tri = -1;
      for (size_t k = 0; 9 * k < tris.size(); ++k)
        if (ray_triangle(o, d, &tris[9 * k], &tris[9 * k + 3], &tris[9 * k + 6], &t) && t < best) {
          best = t;
          tri = static_cast<int>(k);
        }
      ASSERT_EQ(img.objects[p] >= 0, tri >= 0) << "pixel " << i << "," << j;
      if (tri < 0) continue;
      ++silhouette;
      EXPECT_EQ(img.primitives[p], tri) << "pixel " << i << "," << j;
      // The hit on the unit-speed straight path lies at arc length best·|d|; the kernel's
      // crossing ends within its tolerance (atol 1e-6 m + rtol·5 m).
      const double len = best * std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
      EXPECT_NEAR(img.distances[p], len, 1e-6) << "pixel " << i << "," << j;
    }
  EXPECT_GT(silhouette, 100);  // the object covers a good part of the image
}

// The icosphere's triangles, read from its OBJ by this test (not by the library).
inline std::vector<double> read_obj_triangles(const std::string& path, double scale, const double* at) {
  std::ifstream in(path);
  std::vector<double> v, tris;
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream ls(line);
    std::string tag;
    ls >> tag;
    if (tag == "v") {
      double x, y, z;
      ls >> x >> y >> z;
      v.insert(v.end(), {x * scale + at[0], y * scale + at[1], z * scale + at[2]});
    } else if (tag == "f") {
      std::string a;
      std::vector<int> idx;
      while (ls >> a) idx.push_back(std::stoi(a.substr(0, a.find('/'))) - 1);
      for (size_t k = 1; k + 1 < idx.size(); ++k)
        for (int c : {idx[0], idx[k], idx[k + 1]}) tris.insert(tris.end(), &v[3 * c], &v[3 * c] + 3);
    }
  }
  return tris;
}

}  // namespace arcus_test
