// The handle registry: the core defines the kinds it owns (context, job) and every
// other module registers its own, so the core never names an engine's objects.  Each
// kind is registered once under a name of its own, which the messages for a handle of
// the wrong kind use ("field is a job, not a field").
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "core/handle.h"

namespace {

TEST(HandleKinds, EveryModulesKindIsRegisteredOnceUnderAUniqueName) {
  std::set<std::string> names;
  std::set<const arcus::HandleKind*> kinds;
  for (const arcus::HandleKind* kind : arcus::handle_kinds()) {
    EXPECT_TRUE(kinds.insert(kind).second) << kind->name() << " is registered twice";
    EXPECT_TRUE(names.insert(kind->name()).second) << "two kinds are named " << kind->name();
  }
  // The core's two, the scene and geometry modules', and those of the engines built into this library.
  for (const char* expected : {"context", "job", "scene", "mesh", "field", "renderer", "water", "particle"})
    EXPECT_EQ(names.count(expected), 1u) << expected << " is not registered";
}

}  // namespace
