#include "core/features.h"

#include <algorithm>

#include "core/error.h"

namespace arcus {
namespace {

// Features every engine shares.
const FeatureTable kCore{"core",
                         {{ARCUS_FEATURE_FLOAT, "FLOAT", "-D ARCUS_USE_FLOAT -cl-single-precision-constant"}}};

std::vector<const FeatureTable*>& tables() {
  static std::vector<const FeatureTable*> all{&kCore};
  return all;
}

const Feature* find(arcus_features bit) {
  for (const FeatureTable* t : feature_tables())
    for (const Feature& f : t->features)
      if (f.bit == bit) return &f;
  return nullptr;
}

// Applies `part` to each set bit's feature, lowest bit first, joined by spaces.
template <class Part>
std::string join(arcus_features features, Part part) {
  std::string s;
  for (int b = 0; b < 64; ++b) {
    const arcus_features bit = arcus_features(1) << b;
    if (!(features & bit)) continue;
    const Feature* f = find(bit);
    if (!f) fail(ARCUS_ERROR_INVALID_ARGUMENT, "features: bit " + std::to_string(b) + " is not a feature of arcus");
    s += (s.empty() ? "" : " ") + std::string(part(*f));
  }
  return s;
}

}  // namespace

void register_feature_table(const FeatureTable* table) { tables().push_back(table); }

const std::vector<const FeatureTable*>& feature_tables() { return tables(); }

std::string feature_names(arcus_features features) {
  return join(features, [](const Feature& f) { return f.name; });
}

std::string feature_options(arcus_features features) {
  return join(features, [](const Feature& f) { return f.options; });
}

}  // namespace arcus
