// Jensen et al. 2001's measured translucent materials (data/translucency/README.md).
#pragma once

#include <cstddef>

namespace arcus::translucency {

struct Material {
  const char* name;
  double sigma_s_prime[3], sigma_a[3];  // mm⁻¹, R G B
  double eta;
};

extern const Material kMaterials[];
extern const size_t kMaterialCount;

}  // namespace arcus::translucency
