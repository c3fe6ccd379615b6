// The ocean engine's kernel features and its kernel source (README, "Kernels"): water
// without inelastic constituents compiles no inelastic code, an unbounded medium no
// boundary tests, a trace without depths no irradiance tallies.
#include "arcus/arcus_ocean.h"
#include "core/features.h"
#include "core/kernel_source.h"

namespace arcus::ocean {
namespace {

const FeatureTable kTable{"ocean",
                          {{ARCUS_FEATURE_OCEAN_INELASTIC, "OCEAN_INELASTIC", "-D ARCUS_USE_OCEAN_INELASTIC"},
                           {ARCUS_FEATURE_OCEAN_BOUNDARIES, "OCEAN_BOUNDARIES", "-D ARCUS_USE_OCEAN_BOUNDARIES"},
                           {ARCUS_FEATURE_OCEAN_DEPTHS, "OCEAN_DEPTHS", "-D ARCUS_USE_OCEAN_DEPTHS"},
                           {ARCUS_FEATURE_OCEAN_PHOTON_MAP, "OCEAN_PHOTON_MAP", "-D ARCUS_USE_OCEAN_PHOTON_MAP"},
                           {ARCUS_FEATURE_OCEAN_BEAM, "OCEAN_BEAM", "-D ARCUS_USE_OCEAN_BEAM"}}};
const FeatureTableEntry kRegistered(&kTable);

const KernelSource kTrace{"ocean/trace", {"common/real.h", "common/philox.h", "ocean/ocean_desc.h", "ocean/trace.cl"}, ""};

}  // namespace

const KernelSource& trace_source() { return kTrace; }

}  // namespace arcus::ocean
