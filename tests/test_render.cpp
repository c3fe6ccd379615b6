// Rendering through curved light (arcus_render.h): straight optics as the limit of
// curved optics, smart step selection's exactness and the hard cases.  Bad input:
// test_render_errors.cpp.
#include <algorithm>

#include "render_fixture.h"

using namespace arcus_test;

namespace {

// Curved optics must reduce to straight optics (render_fixture.h:
// expect_straight_pinhole_image).
TEST_F(Render, AConstantMediumRendersTheStraightPinholeImage) {
  const double at[3] = {0, 0, -5};
  const std::string objects = R"([{"type": "mesh", "file": ")" + mesh("icosphere.obj") +
                              R"(", "material": "m", "translate": [0, 0, -5], "scale": 1.5}])";
  arcus_scene_t* scene = load(scene_text(kConstantMedium, kPinholeCamera, objects), "straight");
  ASSERT_NE(scene, nullptr);
  const Rendered img = render(scene, 0);
  arcus_scene_release(scene);
  expect_straight_pinhole_image(img, read_obj_triangles(mesh("icosphere.obj"), 1.5, at));
}

// The inferior mirage at 120×60: the scene the technique tests render.
std::string small_mirage() {
  std::ifstream in(std::string(ARCUS_SOURCE_DIR) + "/scenes/inferior_mirage.json");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  text.replace(text.find("\"height\": 400"), 13, "\"height\": 60");
  text.replace(text.find("\"width\": 800"), 12, "\"width\": 120");
  const std::string data_ref = "../data/", data = std::string(ARCUS_SOURCE_DIR) + "/data/";
  for (size_t at = text.find(data_ref); at != std::string::npos; at = text.find(data_ref, at + data.size()))
    text.replace(at, data_ref.size(), data);  // the mesh and the ground's texture
  return text;
}

// Smart step selection skips tests but proves the skipped steps empty, so its hits are
// exactly those of the exhaustive scan: same object, same primitive, same point.
TEST_F(Render, SmartStepSelectionFindsExactlyTheExhaustiveScansHits) {
  arcus_scene_t* scene = load(small_mirage(), "smart");
  ASSERT_NE(scene, nullptr);
  const Rendered full = render(scene, 0);
  const Rendered smart = render(scene, ARCUS_TECHNIQUE_SMART_STEP, 2);  // the second frame predicts from the first
  const Rendered spatial = render(scene, ARCUS_TECHNIQUE_SMART_STEP, 1);
  arcus_scene_release(scene);
  for (const Rendered* r : {&smart, &spatial}) {
    ASSERT_EQ(r->objects.size(), full.objects.size());
    int hits = 0;
    for (size_t p = 0; p < full.objects.size(); ++p) {
      ASSERT_EQ(r->objects[p], full.objects[p]) << "pixel " << p;
      ASSERT_EQ(r->primitives[p], full.primitives[p]) << "pixel " << p;
      if (full.objects[p] < 0) continue;
      ++hits;
      for (int a = 0; a < 3; ++a) EXPECT_EQ(r->points[3 * p + a], full.points[3 * p + a]) << "pixel " << p;
    }
    EXPECT_GT(hits, 1000);
  }
  EXPECT_LT(smart.stats.tests, full.stats.tests);
}

// Hit points of two renders: how many pixels see another primitive, and the largest
// and mean distance between the hits of the others.
struct Difference {
  size_t other_primitive = 0, hits = 0;
  double max = 0, mean = 0;
};
Difference compare(const Rendered& a, const Rendered& b) {
  Difference d;
  for (size_t p = 0; p < a.objects.size(); ++p) {
    if (a.objects[p] != b.objects[p] || a.primitives[p] != b.primitives[p]) {
      ++d.other_primitive;
      continue;
    }
    if (a.objects[p] < 0) continue;
    double e = 0;
    for (int c = 0; c < 3; ++c) e += std::pow(a.points[3 * p + c] - b.points[3 * p + c], 2);
    d.max = std::max(d.max, std::sqrt(e));
    d.mean += std::sqrt(e);
    ++d.hits;
  }
  if (d.hits) d.mean /= d.hits;
  return d;
}

// Path caching keeps each pixel's recorded path, so a second frame only intersects:
// its hits equal a frame traced from scratch bit for bit (the walk moves a hit onto the
// path with the same integrator step from the same state as the trace does).
TEST_F(Render, APathCachedSecondFrameEqualsARecomputedOne) {
  arcus_scene_t* scene = load(small_mirage(), "cache");
  ASSERT_NE(scene, nullptr);
  const Rendered full = render(scene, 0);
  const Rendered cached = render(scene, ARCUS_TECHNIQUE_PATH_CACHE, 2);
  arcus_scene_release(scene);
  EXPECT_EQ(cached.stats.rays_cached, cached.objects.size());
  // Every cached path leads to its own hit again, but for the few the first frame
  // recorded only in part (room for 99.9 % of them), which are traced again.
  EXPECT_EQ(cached.stats.rays_traced, cached.stats.rays_unresolved);
  EXPECT_LT(cached.stats.rays_unresolved, cached.objects.size() / 100);
  EXPECT_GT(cached.stats.cache_bytes, 0u);
  const Difference d = compare(full, cached);
  EXPECT_EQ(d.other_primitive, 0u);
  EXPECT_GT(d.hits, 1000u);
  EXPECT_EQ(d.max, 0.0);
}

// With smart step selection a cached path's walk proves its chunks of 16 chords before
// the predicted hit with the capsules made once, and each sun's shadow rays are walked
// along the paths the first frame recorded for them (static lights): the second frame
// is the recomputed one, hits and image, exactly; mirrored (symmetry) to rounding.
TEST_F(Render, CachedPathsAndShadowRaysWalkedWithProofsGiveTheRecomputedFrame) {
  arcus_scene_t* scene = load(small_mirage(), "cache_proofs");
  ASSERT_NE(scene, nullptr);
  const Rendered full = render(scene, 0);
  const Rendered cached = render(scene, ARCUS_TECHNIQUE_SMART_STEP | ARCUS_TECHNIQUE_PATH_CACHE, 2);
  const Rendered mirrored =
      render(scene, ARCUS_TECHNIQUE_SMART_STEP | ARCUS_TECHNIQUE_SYMMETRY | ARCUS_TECHNIQUE_PATH_CACHE, 2);
  arcus_scene_release(scene);
  EXPECT_EQ(cached.stats.rays_cached, cached.objects.size());
  EXPECT_GT(cached.stats.shadow_rays, 1000u);
  EXPECT_LT(cached.stats.tests, full.stats.tests);
  const Difference d = compare(full, cached);
  EXPECT_EQ(d.other_primitive, 0u);
  EXPECT_GT(d.hits, 1000u);
  EXPECT_EQ(d.max, 0.0);
  size_t other_colour = 0;
  for (size_t k = 0; k < full.rgb.size(); ++k) other_colour += cached.rgb[k] != full.rgb[k];
  EXPECT_EQ(other_colour, 0u);  // the shadow rays' walks block exactly the traced ones' pixels
  const Difference m = compare(full, mirrored);
  EXPECT_EQ(m.other_primitive, 0u);
  EXPECT_LT(m.max, 1e-9);  // as SymmetryGivesTheFullComputationsHitsToRounding
}

// Symmetry mirrors the left half's paths: the full computation's hits to rounding.  The
// mirrored rays start in directions that differ from the pixels' own by rounding
// (~1e-16), which DP45 carries along a 2 km path to ~1e-12 m.
TEST_F(Render, SymmetryGivesTheFullComputationsHitsToRounding) {
  arcus_scene_t* scene = load(small_mirage(), "symmetry");
  ASSERT_NE(scene, nullptr);
  const Rendered full = render(scene, 0);
  const Rendered half = render(scene, ARCUS_TECHNIQUE_SYMMETRY);
  arcus_scene_release(scene);
  // Paths end at their hits; a mirrored ray that passes where its original hit (the
  // shuttle is not symmetric) walks off the end and is traced instead.
  EXPECT_EQ(half.stats.rays_traced, half.objects.size() / 2 + half.stats.rays_unresolved);
  EXPECT_EQ(half.stats.rays_mirrored, half.objects.size() / 2);
  EXPECT_LT(half.stats.rays_unresolved, half.objects.size() / 50);
  const Difference d = compare(full, half);
  EXPECT_EQ(d.other_primitive, 0u);
  EXPECT_LT(d.max, 1e-9);
}

// Undersampling interpolates half the paths (α = ½) between traced neighbours.  Its
// error bound is the thesis' own figure for this scene (Table 5.2: 0.005 km mean error
// of undersampling on the inferior mirage) divided by 50: 0.1 m mean; and at most 1 %
// of pixels (silhouette pixels, where neighbours hit different primitives) may see
// another primitive.
TEST_F(Render, UndersamplingKeepsTheHitPointErrorWithinItsBound) {
  arcus_scene_t* scene = load(small_mirage(), "undersample");
  ASSERT_NE(scene, nullptr);
  const Rendered full = render(scene, 0);
  const Rendered under = render(scene, ARCUS_TECHNIQUE_UNDERSAMPLE);
  arcus_scene_release(scene);
  EXPECT_NEAR(double(under.stats.rays_interpolated) / under.objects.size(), 0.5, 0.02);
  const Difference d = compare(full, under);
  EXPECT_LE(d.other_primitive, under.objects.size() / 100);
  EXPECT_GT(d.hits, 1000u);
  EXPECT_LT(d.mean, 0.1);
  std::printf("undersampling: mean hit-point error %.3e m, largest %.3e m, %zu of %zu pixels on another primitive\n",
              d.mean, d.max, d.other_primitive, under.objects.size());
}

// All four together: smart step selection on cached, mirrored and interpolated paths
// finds the hits the techniques without it find.
TEST_F(Render, SmartStepSelectionOnWalkedPathsFindsTheSameHits) {
  arcus_scene_t* scene = load(small_mirage(), "all");
  ASSERT_NE(scene, nullptr);
  const uint32_t paths = ARCUS_TECHNIQUE_SYMMETRY | ARCUS_TECHNIQUE_UNDERSAMPLE | ARCUS_TECHNIQUE_PATH_CACHE;
  const Rendered plain = render(scene, paths, 2);
  const Rendered smart = render(scene, paths | ARCUS_TECHNIQUE_SMART_STEP, 2);
  arcus_scene_release(scene);
  const Difference d = compare(plain, smart);
  EXPECT_EQ(d.other_primitive, 0u);
  EXPECT_EQ(d.max, 0.0);
  EXPECT_LT(smart.stats.tests, plain.stats.tests);
}

// Hard cases stay finite and sensible: an empty scene, a camera inside a closed mesh,
// and a sun 1.5e11 m away, in double and in float.
TEST_F(Render, AnEmptySceneShowsTheSkyEverywhere) {
  arcus_scene_t* scene = load(scene_text(R"({"type": "constant", "n": 1.0})",
                                         R"({"position": [0, 0, 0], "look_at": [1, 0, 0], "vfov_deg": 40,
                                             "width": 16, "height": 8})",
                                         "[]", R"(, "bounds": {"min": [-10, -10, -10], "max": [10, 10, 10]})"),
                              "empty");
  ASSERT_NE(scene, nullptr);
  const Rendered img = render(scene, 0);
  arcus_scene_release(scene);
  for (size_t p = 0; p < img.objects.size(); ++p) {
    EXPECT_EQ(img.objects[p], -1);
    EXPECT_FLOAT_EQ(img.rgb[3 * p + 2], 0.4f);
  }
}

TEST_F(Render, ACameraInsideAClosedMeshSeesItsInsideEverywhere) {
  const std::string objects =
      R"([{"type": "mesh", "file": ")" + mesh("icosphere.obj") + R"(", "material": "m", "scale": 3}])";
  arcus_scene_t* scene = load(scene_text(R"({"type": "linear", "n0": 1.0, "gradient": [0, 0.01, 0]})",
                                         R"({"position": [0.1, 0.2, 0.3], "look_at": [1, 0, 0], "vfov_deg": 120,
                                             "width": 24, "height": 16})",
                                         objects),
                              "inside");
  ASSERT_NE(scene, nullptr);
  const Rendered img = render(scene, ARCUS_TECHNIQUE_SMART_STEP);
  arcus_scene_release(scene);
  for (size_t p = 0; p < img.objects.size(); ++p) {
    EXPECT_EQ(img.objects[p], 0) << "pixel " << p;
    // Every hit lies on the sphere of radius 3 to within the icosphere's flattening.
    const double r = std::sqrt(img.points[3 * p] * img.points[3 * p] + img.points[3 * p + 1] * img.points[3 * p + 1] +
                               img.points[3 * p + 2] * img.points[3 * p + 2]);
    EXPECT_GT(r, 3 * 0.98);
    EXPECT_LT(r, 3 * 1.0 + 1e-9);
  }
}

// The sun as a sphere 1.5e11 m away whose radius subtends 0.53°: a camera looking at it
// sees it in the middle of the image and the sky at the corners, in double and float.
TEST_F(Render, TheSunAtOnePointFiveTimesTenToTheElevenMetresIsHitInDoubleAndFloat) {
  for (const char* precision : {"double", "float"}) {
    const double d = 1.5e11, radius = d * std::tan(0.265 * M_PI / 180);
    std::ostringstream text;
    text.precision(17);
    text << R"({"name": "sun", "medium": {"type": "constant", "n": 1.0},
               "integrator": {"method": "dp45", "length": 3e11, "precision": ")"
         << precision << R"("},
               "camera": {"position": [0, 0, 0], "look_at": [1, 0, 0], "vfov_deg": 1.0, "width": 21, "height": 21},
               "materials": {"sun": {"emission": [1, 1, 1]}},
               "objects": [{"type": "sphere", "center": [)"
         << d << R"(, 0, 0], "radius": )" << radius << R"(, "material": "sun"}],
               "sky": {"type": "constant", "color": [0, 0, 0]}})";
    arcus_scene_t* scene = load(text.str(), precision);
    ASSERT_NE(scene, nullptr);
    const Rendered img = render(scene, 0);
    arcus_scene_release(scene);
    ASSERT_EQ(img.objects.size(), 21u * 21u);
    EXPECT_EQ(img.objects[10 * 21 + 10], 0) << precision;  // the centre
    EXPECT_EQ(img.objects[0], -1) << precision;            // a corner: 0.7° off axis
    // The disc's radius is 0.265° = 5.3 pixels of 1/21°: pixels within 5 of the centre hit.
    for (int j = 0; j < 21; ++j)
      for (int i = 0; i < 21; ++i) {
        const double r = std::hypot(i - 10, j - 10);
        if (r < 4.5) {
          EXPECT_EQ(img.objects[j * 21 + i], 0) << precision << " " << i << "," << j;
        }
        if (r > 6.5) {
          EXPECT_EQ(img.objects[j * 21 + i], -1) << precision << " " << i << "," << j;
        }
        if (img.objects[j * 21 + i] == 0) {
          // The straight ray through the pixel's centre meets the sphere at the closed
          // form t = (D² − r²) / (b + sqrt(b² − D² + r²)), b = D·dx/|d| (stable form):
          // in double to 1e-4 of the radius.  In float the end of a 1.5e11 m step rounds
          // to 1 part in 1.7e7, so float is held to 1e-6 of the distance.
          const double t = std::tan(0.5 * M_PI / 180);
          const double px = (2.0 * (i + 0.5) / 21 - 1) * t, py = (1 - 2.0 * (j + 0.5) / 21) * t;
          const double b = d / std::sqrt(1 + px * px + py * py);
          const double expected = (d * d - radius * radius) / (b + std::sqrt(b * b - d * d + radius * radius));
          const bool single = std::string(precision) == "float";
          EXPECT_NEAR(img.distances[j * 21 + i], expected, single ? 1e-6 * d : 1e-4 * radius) << precision;
          EXPECT_FLOAT_EQ(img.rgb[3 * (j * 21 + i)], 1.0f);
        }
      }
  }
}

// Spectral rendering through a dispersive atmosphere: the sunset scene, its telephoto
// frame narrowed to 0.2° tall at 120×100 (0.002° a pixel) around the sun's upper limb.
// Air lifts short wavelengths more than long ones (by ~0.006° between 420 and 680 nm
// here), so just below the limb the pixels see the sun at short wavelengths only —
// green, as Rayleigh extinction at this air mass has taken the blue — while deep inside
// the disc every wavelength reaches it: within the limb's top four rows one is greener
// (G/R higher by a fifth) than the disc, in every column.  A spectral scene compiles
// per-ray dispersion; an RGB scene does not.
TEST_F(Render, ASpectralSunsetHasAGreenUpperRimAndCompilesDispersionOnlyWhenSpectral) {
  std::ifstream in(std::string(ARCUS_SOURCE_DIR) + "/scenes/sunset_spectral.json");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  for (const auto& [from, to] : {std::pair<std::string, std::string>{"\"width\": 960", "\"width\": 120"},
                                  {"\"height\": 540", "\"height\": 100"},
                                  {"\"vfov_deg\": 0.28125", "\"vfov_deg\": 0.2"}}) {
    const size_t at = text.find(from);
    ASSERT_NE(at, std::string::npos) << from << " is not in sunset_spectral.json";
    text.replace(at, from.size(), to);
  }
  arcus_scene_t* scene = load(text, "sunset");
  ASSERT_NE(scene, nullptr);
  arcus_renderer_t* r = nullptr;
  ASSERT_EQ(arcus_renderer_create(scene, &r), ARCUS_SUCCESS);
  arcus_job_t* job = nullptr;
  ASSERT_EQ(arcus_render_frame(r, nullptr, nullptr, &job), ARCUS_SUCCESS) << last_error();
  arcus_features features = 0;
  ASSERT_EQ(arcus_job_get_features(job, &features), ARCUS_SUCCESS);
  EXPECT_TRUE(features & ARCUS_FEATURE_CURVED_DISPERSION);
  const int w = 120, h = 100;
  std::vector<float> rgb(w * h * 3);
  ASSERT_EQ(arcus_job_get_render_image(job, rgb.data()), ARCUS_SUCCESS);
  std::vector<int32_t> objects(w * h);  // as the first (shortest) wavelength sees them
  ASSERT_EQ(arcus_job_get_render_hits(job, nullptr, objects.data(), nullptr, nullptr, nullptr, nullptr), ARCUS_SUCCESS);
  arcus_job_release(job);
  arcus_renderer_release(r);
  arcus_scene_release(scene);
  int columns = 0;
  for (int i = 0; i < w; ++i) {
    int top = -1;
    for (int j = 0; j < h && top < 0; ++j)
      if (objects[j * w + i] == 0) top = j;
    if (top < 0 || top + 12 >= h) continue;
    // The topmost row may see only the violet end (R and G below 0: out of sRGB's
    // gamut), so the rim is the greenest of the top four rows.
    const float* inside = &rgb[3 * ((top + 12) * w + i)];
    bool greener = false;
    for (int j = top; j <= top + 3; ++j) {
      const float* p = &rgb[3 * (j * w + i)];
      greener |= p[1] > 0 && p[1] > 1.2f * inside[1] / inside[0] * std::max(p[0], 0.0f);
    }
    EXPECT_TRUE(greener) << "column " << i;
    ++columns;
  }
  EXPECT_GT(columns, 60);
  // The inferior mirage is an RGB scene: no dispersion compiled.
  arcus_scene_t* rgb_scene = load(small_mirage(), "rgb");
  ASSERT_NE(rgb_scene, nullptr);
  ASSERT_EQ(arcus_renderer_create(rgb_scene, &r), ARCUS_SUCCESS);
  ASSERT_EQ(arcus_render_frame(r, nullptr, nullptr, &job), ARCUS_SUCCESS) << last_error();
  ASSERT_EQ(arcus_job_get_features(job, &features), ARCUS_SUCCESS);
  EXPECT_FALSE(features & ARCUS_FEATURE_CURVED_DISPERSION);
  EXPECT_TRUE(features & ARCUS_FEATURE_RENDER_GEOMETRY);
  arcus_job_release(job);
  arcus_renderer_release(r);
  arcus_scene_release(rgb_scene);
}

}  // namespace
