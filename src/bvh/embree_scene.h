// Embree on the host: the process' Embree device (shared by the BVH builder and every
// scene), and an RTCScene of the same triangles as a TriangleBvh, whose rtcIntersect1
// is the oracle of the OpenCL traversal in tests and a candidate intersector on CPUs.
#pragma once

#include <embree3/rtcore.h>

#include <string>
#include <vector>

#include "bvh/bvh.h"
#include "geometry/mesh.h"

namespace arcus::bvh {

// Created on first use, kept for the process; its errors go to last_embree_error().
RTCDevice shared_embree_device();

// This thread's last Embree error message ("" if none); reading it clears it.
std::string last_embree_error();

class EmbreeScene {
 public:
  // One geometry per mesh (float vertices: Embree's precision), robust traversal, so
  // triangle indices match build_triangles of the same meshes.
  explicit EmbreeScene(const std::vector<const geometry::Mesh*>& meshes);
  explicit EmbreeScene(const geometry::Mesh& mesh);
  ~EmbreeScene();
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;

  // The closest hit of each segment (rtcIntersect1, tnear 0, tfar t_max), split over
  // `threads` std::threads.  Hit.primitive is the triangle index over all meshes,
  // Hit.slot and Hit.tests stay -1 and 0.
  std::vector<Hit> closest_hits(const std::vector<Segment>& segments, unsigned threads = 1) const;

 private:
  RTCScene scene_ = nullptr;
  std::vector<uint32_t> mesh_first_;
};

}  // namespace arcus::bvh
