// The feature tables: one source for the -D flags, the program-cache key and the names
// a job reports.  Every public ARCUS_FEATURE_* bit must be in exactly one table, with a
// unique name and build options of its own.
#include <gtest/gtest.h>

#include <cctype>
#include <set>
#include <string>

#include "arcus/arcus.h"
#include "core/error.h"
#include "core/features.h"

namespace {

// Every bit the public headers define (arcus_core.h and each engine's header:
// arcus_curved.h, arcus_render.h, arcus_ocean.h, arcus_rainbow.h, arcus_translucency.h).
const arcus_features kPublic[] = {
    ARCUS_FEATURE_FLOAT,
    ARCUS_FEATURE_CURVED_STRAIGHT,         ARCUS_FEATURE_CURVED_EULER,           ARCUS_FEATURE_CURVED_RK2,
    ARCUS_FEATURE_CURVED_RK4,              ARCUS_FEATURE_CURVED_DP45,            ARCUS_FEATURE_CURVED_FIELD_LINEAR,
    ARCUS_FEATURE_CURVED_FIELD_LINEAR_N2,  ARCUS_FEATURE_CURVED_FIELD_LUNEBURG,  ARCUS_FEATURE_CURVED_FIELD_FISHEYE,
    ARCUS_FEATURE_CURVED_FIELD_ATMOSPHERE, ARCUS_FEATURE_CURVED_FIELD_GRID,      ARCUS_FEATURE_CURVED_BOX,
    ARCUS_FEATURE_CURVED_RECORD_PATH,      ARCUS_FEATURE_CURVED_DISPERSION,
    ARCUS_FEATURE_RENDER_GEOMETRY,         ARCUS_FEATURE_RENDER_RECORD_STATE,
    ARCUS_FEATURE_OCEAN_INELASTIC,         ARCUS_FEATURE_OCEAN_BOUNDARIES,       ARCUS_FEATURE_OCEAN_DEPTHS,
    ARCUS_FEATURE_OCEAN_PHOTON_MAP,        ARCUS_FEATURE_OCEAN_BEAM,
    ARCUS_FEATURE_RAINBOW_IMPLICIT,        ARCUS_FEATURE_RAINBOW_MESH,           ARCUS_FEATURE_RAINBOW_AZIMUTH,
    ARCUS_FEATURE_TRANSLUCENCY_DIPOLE,     ARCUS_FEATURE_TRANSLUCENCY_HIERARCHICAL,
    ARCUS_FEATURE_TRANSLUCENCY_HISTOGRAM,  ARCUS_FEATURE_TRANSLUCENCY_TABLE};

TEST(FeatureTables, EveryPublicBitIsInExactlyOneTableWithItsOwnNameAndOptions) {
  std::set<arcus_features> bits;
  std::set<std::string> names, options;
  size_t entries = 0;
  for (const arcus::FeatureTable* t : arcus::feature_tables()) {
    // The test-only null engine's bit is not public (arcus_null.h is not installed);
    // tests/test_null_engine.cpp checks it.
    if (std::string(t->owner) == "null") continue;
    for (const arcus::Feature& f : t->features) {
      ++entries;
      EXPECT_EQ(f.bit & (f.bit - 1), 0u) << f.name << ": one bit per feature";
      EXPECT_TRUE(bits.insert(f.bit).second) << f.name << ": bit defined twice";
      EXPECT_TRUE(names.insert(f.name).second) << f.name << ": name defined twice";
      EXPECT_TRUE(options.insert(f.options).second) << f.name << ": options shared with another feature";
      EXPECT_EQ(std::string(f.options).rfind("-D ARCUS_", 0), 0u) << f.name << ": " << f.options;
    }
  }
  EXPECT_EQ(entries, sizeof kPublic / sizeof *kPublic) << "a table holds a bit the headers do not define";
  for (arcus_features bit : kPublic) EXPECT_EQ(bits.count(bit), 1u) << "bit " << bit << " is in no table";
  // The core's table comes first and holds the precision bit every engine shares.
  ASSERT_FALSE(arcus::feature_tables().empty());
  EXPECT_STREQ(arcus::feature_tables().front()->owner, "core");
}

TEST(FeatureTables, AnEngineFeatureIsNamedAfterItsEngine) {
  // The API's grammar (arcus_core.h, "Names"): "<ENGINE>_<NAME>", the core's bare.
  for (const arcus::FeatureTable* t : arcus::feature_tables()) {
    std::string prefix = std::string(t->owner) == "core" ? "" : std::string(t->owner) + "_";
    for (char& c : prefix) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    for (const arcus::Feature& f : t->features)
      EXPECT_EQ(std::string(f.name).rfind(prefix, 0), 0u) << f.name << " of the " << t->owner << " table";
  }
}

TEST(FeatureTables, NamesAndOptionsFollowBitOrder) {
  const arcus_features f = ARCUS_FEATURE_CURVED_BOX | ARCUS_FEATURE_CURVED_DP45 | ARCUS_FEATURE_FLOAT;
  EXPECT_EQ(arcus::feature_names(f), "FLOAT CURVED_DP45 CURVED_BOX");
  EXPECT_EQ(arcus::feature_options(f),
            "-D ARCUS_USE_FLOAT -cl-single-precision-constant -D ARCUS_METHOD_DP45 -D ARCUS_USE_BOX");
  EXPECT_EQ(arcus::feature_names(0), "");
}

TEST(FeatureTables, AnUnknownBitIsAnError) {
  try {
    arcus::feature_names(ARCUS_FEATURE_CURVED_RK4 | (arcus_features(1) << 63));
    FAIL() << "bit 63 is no feature";
  } catch (const arcus::Error& e) {
    EXPECT_EQ(e.status(), ARCUS_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(e.what()).find("bit 63"), std::string::npos) << e.what();
  }
  char buffer[64];
  EXPECT_EQ(arcus_features_to_string(arcus_features(1) << 54, buffer, sizeof buffer), ARCUS_ERROR_INVALID_ARGUMENT);
}

}  // namespace
