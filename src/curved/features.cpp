// The curved engine's kernel features and kernel source: the one place that says which
// -D flags each feature compiles with (README, "Kernels").
#include "curved/advance.h"

namespace arcus::curved {
namespace {

const FeatureTable kTable{"curved",
                          {{ARCUS_FEATURE_CURVED_STRAIGHT, "CURVED_STRAIGHT", "-D ARCUS_METHOD_STRAIGHT"},
                           {ARCUS_FEATURE_CURVED_EULER, "CURVED_EULER", "-D ARCUS_METHOD_EULER"},
                           {ARCUS_FEATURE_CURVED_RK2, "CURVED_RK2", "-D ARCUS_METHOD_RK2"},
                           {ARCUS_FEATURE_CURVED_RK4, "CURVED_RK4", "-D ARCUS_METHOD_RK4"},
                           {ARCUS_FEATURE_CURVED_DP45, "CURVED_DP45", "-D ARCUS_METHOD_DP45"},
                           {ARCUS_FEATURE_CURVED_FIELD_LINEAR, "CURVED_FIELD_LINEAR", "-D ARCUS_FIELD_LINEAR"},
                           {ARCUS_FEATURE_CURVED_FIELD_LINEAR_N2, "CURVED_FIELD_LINEAR_N2", "-D ARCUS_FIELD_LINEAR_N2"},
                           {ARCUS_FEATURE_CURVED_FIELD_LUNEBURG, "CURVED_FIELD_LUNEBURG", "-D ARCUS_FIELD_LUNEBURG"},
                           {ARCUS_FEATURE_CURVED_FIELD_FISHEYE, "CURVED_FIELD_FISHEYE", "-D ARCUS_FIELD_FISHEYE"},
                           {ARCUS_FEATURE_CURVED_FIELD_ATMOSPHERE, "CURVED_FIELD_ATMOSPHERE", "-D ARCUS_FIELD_ATMOSPHERE"},
                           {ARCUS_FEATURE_CURVED_FIELD_GRID, "CURVED_FIELD_GRID", "-D ARCUS_FIELD_GRID"},
                           {ARCUS_FEATURE_CURVED_BOX, "CURVED_BOX", "-D ARCUS_USE_BOX"},
                           {ARCUS_FEATURE_CURVED_RECORD_PATH, "CURVED_RECORD_PATH", "-D ARCUS_USE_RECORD_PATH"},
                           {ARCUS_FEATURE_CURVED_DISPERSION, "CURVED_DISPERSION", "-D ARCUS_USE_DISPERSION"}}};
const FeatureTableEntry kRegistered(&kTable);

const KernelSource kAdvance{"curved/advance",
                            {"common/real.h", "sky/air.h", "curved/field.h", "curved/advance_desc.h", "curved/state.h",
                             "curved/integrators.h", "curved/crossing.h", "curved/advance.cl"},
                            ""};

}  // namespace

const FeatureTable& feature_table() { return kTable; }
const KernelSource& advance_source() { return kAdvance; }

}  // namespace arcus::curved
