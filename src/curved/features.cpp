// The curved engine's kernel features and kernel source: the one place that says which
// -D flags each feature compiles with (README, "Kernels").
#include "curved/advance.h"

namespace arcus::curved {
namespace {

const FeatureTable kTable{"curved",
                          {{ARCUS_FEATURE_STRAIGHT, "STRAIGHT", "-D ARCUS_METHOD_STRAIGHT"},
                           {ARCUS_FEATURE_EULER, "EULER", "-D ARCUS_METHOD_EULER"},
                           {ARCUS_FEATURE_RK2, "RK2", "-D ARCUS_METHOD_RK2"},
                           {ARCUS_FEATURE_RK4, "RK4", "-D ARCUS_METHOD_RK4"},
                           {ARCUS_FEATURE_DP45, "DP45", "-D ARCUS_METHOD_DP45"},
                           {ARCUS_FEATURE_FIELD_LINEAR, "FIELD_LINEAR", "-D ARCUS_FIELD_LINEAR"},
                           {ARCUS_FEATURE_FIELD_LINEAR_N2, "FIELD_LINEAR_N2", "-D ARCUS_FIELD_LINEAR_N2"},
                           {ARCUS_FEATURE_FIELD_LUNEBURG, "FIELD_LUNEBURG", "-D ARCUS_FIELD_LUNEBURG"},
                           {ARCUS_FEATURE_FIELD_FISHEYE, "FIELD_FISHEYE", "-D ARCUS_FIELD_FISHEYE"},
                           {ARCUS_FEATURE_FIELD_ATMOSPHERE, "FIELD_ATMOSPHERE", "-D ARCUS_FIELD_ATMOSPHERE"},
                           {ARCUS_FEATURE_FIELD_GRID, "FIELD_GRID", "-D ARCUS_FIELD_GRID"},
                           {ARCUS_FEATURE_BOX, "BOX", "-D ARCUS_USE_BOX"},
                           {ARCUS_FEATURE_RECORD_PATH, "RECORD_PATH", "-D ARCUS_USE_RECORD_PATH"},
                           {ARCUS_FEATURE_DISPERSION, "DISPERSION", "-D ARCUS_USE_DISPERSION"}}};
const FeatureTableEntry kRegistered(&kTable);

const KernelSource kAdvance{"curved/advance",
                            {"common/real.h", "curved/field.h", "curved/advance_desc.h", "curved/state.h",
                             "curved/integrators.h", "curved/crossing.h", "curved/advance.cl"},
                            ""};

}  // namespace

const FeatureTable& feature_table() { return kTable; }
const KernelSource& advance_source() { return kAdvance; }

}  // namespace arcus::curved
