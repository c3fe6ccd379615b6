#include "render/scene.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "curved/advance.h"
#include "geometry/mesh.h"
#include "render/sky_light.h"
#include "sky/scattering.h"

namespace arcus::render {
namespace {

// Scale, then rotate about x, y and z (degrees), then translate: a 3×4 row-major matrix.
void object_matrix(const ObjectDesc& o, double m[12]) {
  const double kDeg = M_PI / 180.0;
  const double cx = std::cos(o.rotate_deg[0] * kDeg), sx = std::sin(o.rotate_deg[0] * kDeg);
  const double cy = std::cos(o.rotate_deg[1] * kDeg), sy = std::sin(o.rotate_deg[1] * kDeg);
  const double cz = std::cos(o.rotate_deg[2] * kDeg), sz = std::sin(o.rotate_deg[2] * kDeg);
  const double rx[9] = {1, 0, 0, 0, cx, -sx, 0, sx, cx};
  const double ry[9] = {cy, 0, sy, 0, 1, 0, -sy, 0, cy};
  const double rz[9] = {cz, -sz, 0, sz, cz, 0, 0, 0, 1};
  auto mul = [](const double* a, const double* b, double* out) {
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) out[3 * i + j] = a[3 * i] * b[j] + a[3 * i + 1] * b[3 + j] + a[3 * i + 2] * b[6 + j];
  };
  double zy[9], r[9];
  mul(rz, ry, zy);
  mul(zy, rx, r);
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) m[4 * i + j] = r[3 * i + j] * o.scale[j];
    m[4 * i + 3] = o.translate[i];
  }
}

void grow(std::array<double, 3>* lo, std::array<double, 3>* hi, const double* p) {
  for (int a = 0; a < 3; ++a) {
    (*lo)[a] = std::min((*lo)[a], p[a]);
    (*hi)[a] = std::max((*hi)[a], p[a]);
  }
}

std::string key(size_t object, const char* member) {
  return "$.objects[" + std::to_string(object) + "]." + member;
}

using Bounds = std::array<double, 3>;

// Object i, a mesh (from its file, or given in memory): placed, its texture coordinates
// per corner, grown into lo/hi.
geometry::Mesh add_mesh(RenderScene* scene, const ObjectDesc& o, size_t i, const std::string& path,
                        const scene::GivenMeshes& given, Bounds* lo, Bounds* hi) {
  double m[12];
  object_matrix(o, m);
  geometry::Mesh mesh;
  if (!o.mesh_name.empty()) {
    mesh = geometry::transformed(given.get(o.mesh_name, path + ": " + key(i, "mesh")), m);
  } else {
    try {
      mesh = geometry::transformed(geometry::load_mesh(o.file), m);
    } catch (const Error& e) {
      fail(e.status(), path + ": " + key(i, "file") + ": " + e.what());
    }
  }
  for (size_t v = 0; v < mesh.vertex_count(); ++v) grow(lo, hi, &mesh.positions[3 * v]);
  std::vector<double> uvs;
  if (!mesh.uvs.empty())
    for (size_t t = 0; t < mesh.triangle_count(); ++t)
      for (int c = 0; c < 3; ++c) {
        const uint32_t v = mesh.triangles[3 * t + c];
        uvs.push_back(mesh.uvs[2 * v]);
        uvs.push_back(mesh.uvs[2 * v + 1]);
      }
  scene->mesh_uvs.push_back(std::move(uvs));
  scene->mesh_object.push_back(static_cast<int32_t>(i));
  return mesh;
}

// Object i, a sphere or a disc, grown into lo/hi.
void add_shape(RenderScene* scene, const ObjectDesc& o, size_t i, const std::string& path, Bounds* lo, Bounds* hi) {
  require(scene->shapes.size() < ARCUS_MAX_SHAPES,
          path + ": $.objects: more than " + std::to_string(ARCUS_MAX_SHAPES) + " spheres and discs");
  arcus_shape_d s{};
  for (int a = 0; a < 3; ++a) {
    s.center[a] = o.center[a];
    s.normal[a] = o.normal[a];
  }
  s.radius = o.radius;
  s.kind = o.kind == ObjectKind::Sphere ? ARCUS_SHAPE_SPHERE : ARCUS_SHAPE_DISC;
  for (int a = 0; a < 3; ++a) {
    // A disc's extent along an axis is r·sqrt(1 − n_a²).
    const double half = o.kind == ObjectKind::Sphere ? o.radius
                                                      : o.radius * std::sqrt(std::max(0.0, 1 - o.normal[a] * o.normal[a]));
    (*lo)[a] = std::min((*lo)[a], o.center[a] - half);
    (*hi)[a] = std::max((*hi)[a], o.center[a] + half);
  }
  scene->shapes.push_back(s);
  scene->shape_object.push_back(static_cast<int32_t>(i));
}

// The bounds: the scene's own, else everything grown by 1 % (and 1 m), so that no
// primitive lies on the box where rays stop.  The camera must lie inside.
void set_bounds(RenderScene* scene, const Bounds& lo, const Bounds& hi, const std::string& path) {
  const RenderDesc& d = scene->desc;
  for (int a = 0; a < 3; ++a) {
    const double margin = 0.01 * (hi[a] - lo[a]) + 1.0;
    scene->lo[a] = d.has_bounds ? d.params.box_min[a] : lo[a] - margin;
    scene->hi[a] = d.has_bounds ? d.params.box_max[a] : hi[a] + margin;
  }
  for (int a = 0; a < 3; ++a)
    require(d.camera.position[a] > scene->lo[a] && d.camera.position[a] < scene->hi[a],
            path + ": $.camera.position: the camera must lie inside $.bounds");
}

// The materials' textures and the sky's image, each error naming its key.
void read_images(RenderScene* scene, const std::string& path) {
  const RenderDesc& d = scene->desc;
  scene->textures.resize(d.materials.size());
  for (size_t m = 0; m < d.materials.size(); ++m)
    if (!d.materials[m].texture.empty()) {
      try {
        scene->textures[m] = image::MipPyramid(image::read_image(d.materials[m].texture));
      } catch (const Error& e) {
        fail(e.status(), path + ": $.materials." + d.materials[m].name + ".texture: " + e.what());
      }
    }
  if (d.sky.kind == SkyKind::Image) {
    try {
      scene->sky_image = image::read_image(d.sky.file);
    } catch (const Error& e) {
      fail(e.status(), path + ": $.sky.file: " + e.what());
    }
  }
  if (d.sky.kind == SkyKind::Daylight) {
    // The renderer's panoramas put azimuth a at column −a/360° (image_io.h's equirect_uv),
    // sky_panorama at +a/360°: the sky is symmetric about the sun's vertical, so the sun
    // at −a gives the renderer's sky.
    const LightDesc& sun = *std::find_if(d.lights.begin(), d.lights.end(), [](const LightDesc& l) { return l.daylight; });
    image::Image& sky = scene->sky_image;
    sky.width = 1024;
    sky.height = 512;
    sky.channels = {"R", "G", "B"};
    sky.pixels = sky::sky_panorama(d.atmosphere, (90 - sun.elevation_deg) * M_PI / 180, -sun.azimuth_deg * M_PI / 180,
                                   sky.width, sky.height);
    for (float& v : sky.pixels) v = static_cast<float>(v * d.sky.intensity);
    scene->sky_irradiance = sky_irradiance_map(sky, sun.power, sun.elevation_deg, d.atmosphere.ground_albedo);
  }
}

// Everything is read and built before the context's lock is taken; only the library
// objects are created under it.
arcus_scene_s* load(arcus_context_t* ctx, const std::string& path, const scene::GivenMeshes& given,
                    const scene::Locked& locked) {
  auto scene = std::make_unique<RenderScene>(ctx);
  RenderDesc& d = scene->desc;
  d = parse_render_file(path);
  curved::FieldBuild field = curved::build_scene_medium(d.medium, d.params, path);

  Bounds lo, hi;
  lo.fill(INFINITY);
  hi.fill(-INFINITY);
  grow(&lo, &hi, d.camera.position.array().data());
  std::vector<geometry::Mesh> meshes;
  for (size_t i = 0; i < d.objects.size(); ++i) {
    if (d.objects[i].kind == ObjectKind::Mesh)
      meshes.push_back(add_mesh(scene.get(), d.objects[i], i, path, given, &lo, &hi));
    else
      add_shape(scene.get(), d.objects[i], i, path, &lo, &hi);
  }
  std::vector<const geometry::Mesh*> pointers;
  for (const auto& m : meshes) pointers.push_back(&m);
  if (!pointers.empty()) {
    scene->triangles = bvh::build_triangles(pointers);
    const auto& order = scene->triangles.tree.order;
    scene->slot_of.resize(order.size());
    for (size_t slot = 0; slot < order.size(); ++slot) scene->slot_of[order[slot]] = static_cast<uint32_t>(slot);
  }
  set_bounds(scene.get(), lo, hi, path);
  read_images(scene.get(), path);

  scene->name = d.name;
  scene->description = d.description;
  scene->document = d.document;
  scene->attach_field(std::move(field), locked);
  return scene.release();
}

const scene::LoaderEntry kLoader("render", load, "camera");

}  // namespace

void RenderScene::upload(arcus_context_t* ctx, bool single) {
  const int i = single ? 1 : 0;
  if (!device_bvh[i] && triangles.triangle_count() > 0)
    device_bvh[i] = std::make_shared<bvh::DeviceBvh>(ctx, triangles, single);
  if (!device_shapes[i] && !shapes.empty()) {
    if (single) {
      std::vector<arcus_shape_f> f(shapes.size());
      for (size_t s = 0; s < shapes.size(); ++s) {
        for (int a = 0; a < 3; ++a) {
          f[s].center[a] = static_cast<float>(shapes[s].center[a]);
          f[s].normal[a] = static_cast<float>(shapes[s].normal[a]);
        }
        f[s].radius = static_cast<float>(shapes[s].radius);
        f[s].kind = shapes[s].kind;
      }
      device_shapes[i] = std::make_shared<DeviceBuffer>(ctx, f.size() * sizeof(f[0]), "the scene's shapes", f.data());
    } else {
      device_shapes[i] =
          std::make_shared<DeviceBuffer>(ctx, shapes.size() * sizeof(shapes[0]), "the scene's shapes", shapes.data());
    }
  }
}

RenderScene* render_scene(arcus_scene_s* scene) {
  auto* r = dynamic_cast<RenderScene*>(scene);
  if (!r) fail(ARCUS_ERROR_INVALID_ARGUMENT, std::string("scene is a ") + scene->engine + " scene, not a render one");
  return r;
}

}  // namespace arcus::render
