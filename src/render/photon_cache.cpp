#include "render/photon_cache.h"

namespace arcus::render {

PhotonCache::PhotonCache() : data(std::make_unique<Data>()) {}
PhotonCache::~PhotonCache() = default;
size_t PhotonCache::bytes() const {
  if (!data) return 0;
  const Data& d = *data;
  const TraceOutput& t = d.results;
  return d.live.size() * sizeof(Live) + d.how.size() * 4 + d.previous_end.size() * 4 +
         (t.positions.size() + t.directions.size() + t.lengths.size()) * 8 + t.steps.size() * 8 +
         (t.status.size() + t.object.size() + t.primitive.size() + t.hit_kind.size() + t.hit_index.size() +
          t.hit_step.size() + t.tests.size()) * 4;
}

PhotonCache::Data::Key cache_key(const RenderScene* s, const arcus_advance_params& p, uint64_t count, uint64_t seed,
                                 const PhotonOptions& o) {
  PhotonCache::Data::Key k;
  k.scene = s;
  k.count = count;
  k.seed = seed;
  k.techniques = o.techniques & (ARCUS_TECHNIQUE_SYMMETRY | ARCUS_TECHNIQUE_UNDERSAMPLE);
  k.numbers = {double(p.method), double(p.precision), p.length, p.step, p.rtol, p.atol, p.min_step, p.max_step,
               double(p.max_rejections), double(p.max_steps), o.undersample_deg, double(o.undersample_n)};
  for (const LightDesc& l : s->desc.lights) {
    k.numbers.push_back(l.kind == LightKind::Sun ? 0 : 1);
    for (int a = 0; a < 3; ++a) k.numbers.insert(k.numbers.end(), {l.direction[a], l.position[a], l.power[a]});
  }
  return k;
}

}  // namespace arcus::render
