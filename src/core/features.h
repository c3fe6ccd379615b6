// Kernel features (Cycles' KERNEL_FEATURE_* mask, LuxCore's per-scene kernels): each
// engine keeps one table listing every feature's bit, name and build options.  The
// table is the single source of a job's -D flags, of its program-cache key and of the
// features the job reports.
#pragma once

#include <string>
#include <vector>

#include "arcus/arcus_core.h"

namespace arcus {

struct Feature {
  arcus_features bit;
  const char* name;     // as reported ("DP45")
  const char* options;  // OpenCL build options it adds ("-D ARCUS_METHOD_DP45")
};

struct FeatureTable {
  const char* owner;  // "core", "curved", ...
  std::vector<Feature> features;
};

// Registers an engine's table (at static initialisation, through FeatureTableEntry).
void register_feature_table(const FeatureTable* table);
struct FeatureTableEntry {
  explicit FeatureTableEntry(const FeatureTable* table) { register_feature_table(table); }
};

// Every registered table, the core's first.
const std::vector<const FeatureTable*>& feature_tables();

// "DP45 FIELD_LINEAR BOX" in bit order; throws ARCUS_ERROR_INVALID_ARGUMENT naming a
// bit no table defines.
std::string feature_names(arcus_features features);

// The build options of `features`, in bit order; throws as feature_names.
std::string feature_options(arcus_features features);

}  // namespace arcus
