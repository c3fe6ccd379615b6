#include "bvh/embree_scene.h"

#include <algorithm>
#include <limits>
#include <thread>

#include "core/error.h"

namespace arcus::bvh {
namespace {

thread_local std::string g_error;

}  // namespace

RTCDevice shared_embree_device() {
  static const RTCDevice device = [] {
    RTCDevice d = rtcNewDevice(nullptr);
    if (!d) fail(ARCUS_ERROR_UNSUPPORTED, "Embree: could not create a device");
    rtcSetDeviceErrorFunction(
        d, [](void*, RTCError, const char* message) { g_error = message ? message : "unknown Embree error"; }, nullptr);
    return d;
  }();
  return device;
}

std::string last_embree_error() {
  std::string m;
  m.swap(g_error);
  return m;
}

EmbreeScene::EmbreeScene(const std::vector<const geometry::Mesh*>& meshes) {
  RTCDevice device = shared_embree_device();
  last_embree_error();
  scene_ = rtcNewScene(device);
  rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);
  uint32_t first = 0;
  for (size_t g = 0; g < meshes.size(); ++g) {
    require_pointer(meshes[g], "EmbreeScene: a mesh");
    const geometry::Mesh& m = *meshes[g];
    mesh_first_.push_back(first);
    first += static_cast<uint32_t>(m.triangle_count());
    if (m.triangle_count() == 0) continue;  // Embree refuses empty buffers
    RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* v = static_cast<float*>(
        rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), m.vertex_count()));
    auto* t = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                             3 * sizeof(unsigned), m.triangle_count()));
    if (!v || !t) {
      rtcReleaseGeometry(geom);
      rtcReleaseScene(scene_);
      fail(ARCUS_ERROR_OUT_OF_MEMORY, "EmbreeScene: " + last_embree_error());
    }
    std::copy(m.positions.begin(), m.positions.end(), v);
    std::copy(m.triangles.begin(), m.triangles.end(), t);
    rtcCommitGeometry(geom);
    rtcAttachGeometryByID(scene_, geom, static_cast<unsigned>(g));
    rtcReleaseGeometry(geom);
  }
  rtcCommitScene(scene_);
  const std::string error = last_embree_error();
  if (!error.empty()) {
    rtcReleaseScene(scene_);
    fail(ARCUS_ERROR_INVALID_ARGUMENT, "EmbreeScene: " + error);
  }
}

EmbreeScene::EmbreeScene(const geometry::Mesh& mesh) : EmbreeScene(std::vector<const geometry::Mesh*>{&mesh}) {}

EmbreeScene::~EmbreeScene() { rtcReleaseScene(scene_); }

std::vector<Hit> EmbreeScene::closest_hits(const std::vector<Segment>& segments, unsigned threads) const {
  std::vector<Hit> hits(segments.size());
  auto part = [&](size_t begin, size_t end) {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    for (size_t i = begin; i < end; ++i) {
      const Segment& s = segments[i];
      RTCRayHit rh;
      rh.ray.org_x = static_cast<float>(s.origin[0]);
      rh.ray.org_y = static_cast<float>(s.origin[1]);
      rh.ray.org_z = static_cast<float>(s.origin[2]);
      rh.ray.dir_x = static_cast<float>(s.direction[0]);
      rh.ray.dir_y = static_cast<float>(s.direction[1]);
      rh.ray.dir_z = static_cast<float>(s.direction[2]);
      rh.ray.tnear = 0.0f;
      rh.ray.tfar = static_cast<float>(s.t_max);
      rh.ray.time = 0.0f;
      rh.ray.mask = std::numeric_limits<unsigned>::max();
      rh.ray.id = 0;
      rh.ray.flags = 0;
      rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
      rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
      rtcIntersect1(scene_, &context, &rh);
      if (rh.hit.geomID != RTC_INVALID_GEOMETRY_ID) {
        hits[i].primitive = static_cast<int32_t>(mesh_first_[rh.hit.geomID] + rh.hit.primID);
        hits[i].t = rh.ray.tfar;
        hits[i].u = rh.hit.u;
        hits[i].v = rh.hit.v;
      }
    }
  };
  threads = std::max(1u, threads);
  const size_t chunk = (segments.size() + threads - 1) / threads;
  std::vector<std::thread> pool;
  for (unsigned k = 1; k < threads; ++k)
    pool.emplace_back(part, std::min(segments.size(), k * chunk), std::min(segments.size(), (k + 1) * chunk));
  part(0, std::min(segments.size(), chunk));
  for (std::thread& t : pool) t.join();
  return hits;
}

}  // namespace arcus::bvh
