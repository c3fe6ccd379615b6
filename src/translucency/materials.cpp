#include "translucency/materials.h"

namespace arcus::translucency {

// Jensen, Marschner, Levoy & Hanrahan, "A Practical Model for Subsurface Light
// Transport", SIGGRAPH 2001, Figure 5, as pbrt-v4 transcribes it (src/pbrt/media.cpp,
// equal to pbrt-v3's src/core/medium.cpp); η = 1.3 except marble, 1.5 (Jensen 2001's
// text).  Chicken's red σ_a: 0.015 and 0.018 (pbrt) rather than 0.0015 and 0.0018
// (Mitsuba 0.6's materials.h); why, and what is not verified: data/translucency/README.md.
const Material kMaterials[] = {
    {"apple", {2.29, 2.39, 1.97}, {0.0030, 0.0034, 0.046}, 1.3},
    {"chicken1", {0.15, 0.21, 0.38}, {0.015, 0.077, 0.19}, 1.3},
    {"chicken2", {0.19, 0.25, 0.32}, {0.018, 0.088, 0.20}, 1.3},
    {"cream", {7.38, 5.47, 3.15}, {0.0002, 0.0028, 0.0163}, 1.3},
    {"ketchup", {0.18, 0.07, 0.03}, {0.061, 0.97, 1.45}, 1.3},
    {"marble", {2.19, 2.62, 3.00}, {0.0021, 0.0041, 0.0071}, 1.5},
    {"potato", {0.68, 0.70, 0.55}, {0.0024, 0.0090, 0.12}, 1.3},
    {"skimmilk", {0.70, 1.22, 1.90}, {0.0014, 0.0025, 0.0142}, 1.3},
    {"skin1", {0.74, 0.88, 1.01}, {0.032, 0.17, 0.48}, 1.3},
    {"skin2", {1.09, 1.59, 1.79}, {0.013, 0.070, 0.145}, 1.3},
    {"spectralon", {11.6, 20.4, 14.9}, {0.00, 0.00, 0.00}, 1.3},
    {"wholemilk", {2.55, 3.21, 3.77}, {0.0011, 0.0024, 0.014}, 1.3},
};
const size_t kMaterialCount = sizeof(kMaterials) / sizeof(kMaterials[0]);

}  // namespace arcus::translucency
