// The translucency engine's kernel features (bits 48–55; arcus_translucency.h): the one
// table that gives their -D flags, their program-cache key and the names jobs report.
#include "arcus/arcus_translucency.h"
#include "core/features.h"

namespace arcus::translucency {
namespace {

const FeatureTable kTable{
    "translucency",
    {{ARCUS_FEATURE_TRANSLUCENCY_DIPOLE, "TRANSLUCENCY_DIPOLE", "-D ARCUS_USE_DIPOLE"},
     {ARCUS_FEATURE_TRANSLUCENCY_HIERARCHICAL, "TRANSLUCENCY_HIERARCHICAL", "-D ARCUS_USE_HIERARCHICAL"},
     {ARCUS_FEATURE_TRANSLUCENCY_HISTOGRAM, "TRANSLUCENCY_HISTOGRAM", "-D ARCUS_USE_HISTOGRAM"},
     {ARCUS_FEATURE_TRANSLUCENCY_TABLE, "TRANSLUCENCY_TABLE", "-D ARCUS_USE_PROFILE_TABLE"}}};
const FeatureTableEntry kRegistered(&kTable);

}  // namespace
}  // namespace arcus::translucency
