// The render engine's kernel features and its kernel source: the curved engine's
// advance with the per-step hook against the scene (README, "Kernels").
#include "core/features.h"
#include "render/trace.h"

namespace arcus::render {
namespace {

const FeatureTable kTable{"render",
                          {{ARCUS_FEATURE_RENDER_GEOMETRY, "RENDER_GEOMETRY", "-D ARCUS_USE_GEOMETRY"},
                           {ARCUS_FEATURE_RENDER_RECORD_STATE, "RENDER_RECORD_STATE", "-D ARCUS_USE_RECORD_STATE"}}};
const FeatureTableEntry kRegistered(&kTable);

const KernelSource kTrace{"render/trace",
                          {"common/real.h", "sky/air.h", "curved/field.h", "curved/advance_desc.h", "curved/state.h",
                           "curved/integrators.h", "curved/crossing.h", "bvh/bvh_desc.h", "bvh/traverse.h",
                           "render/render_desc.h", "render/hits.h", "curved/advance.cl", "render/walk.cl"},
                          ""};

}  // namespace

const KernelSource& trace_source() { return kTrace; }

}  // namespace arcus::render
