// The path cache of curved photon mapping's first generation (photons.h, PATH_CACHE and
// smart step selection's temporal prediction): what a frame leaves to the next, and the
// key of what it depends on.
#pragma once

#include <cstdint>
#include <vector>

#include "render/photon_emission.h"
#include "render/photons.h"

namespace arcus::render {

struct PhotonCache::Data {
  // What the first generation depends on.
  struct Key {
    const RenderScene* scene = nullptr;
    uint64_t count = 0, seed = 0;
    uint32_t techniques = 0;  // SYMMETRY | UNDERSAMPLE
    std::vector<double> numbers;  // the integrator, the lights, t and n
    bool operator==(const Key& o) const {
      return scene == o.scene && count == o.count && seed == o.seed && techniques == o.techniques &&
             numbers == o.numbers;
    }
  };
  Key key;
  bool has_paths = false;   // PATH_CACHE: the first generation below
  std::vector<Live> live;
  TraceOutput results;
  std::vector<int32_t> how;
  std::vector<int32_t> previous_end;  // SMART_STEP: per photon of the last frame's first generation
};

// The key of a first generation: the scene, the count, the seed, the result-changing
// techniques, the integrator, the lights, undersampling's t and n.
PhotonCache::Data::Key cache_key(const RenderScene* s, const arcus_advance_params& p, uint64_t count, uint64_t seed,
                                 const PhotonOptions& o);

}  // namespace arcus::render
