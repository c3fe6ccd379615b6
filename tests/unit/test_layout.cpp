// The kernel layout (lanes × groups): the device's choice, the engine's preference,
// and ARCUS_LANES / ARCUS_GROUPS parsed strictly.
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "core/error.h"
#include "core/layout.h"

namespace {

const uint32_t kLanes[] = {1, 2, 4, 8, 16};

arcus_status parse_status(const char* text) {
  try {
    arcus::parse_layout_value("ARCUS_LANES", text, kLanes, 5);
    return ARCUS_SUCCESS;
  } catch (const arcus::Error& e) {
    EXPECT_NE(std::string(e.what()).find("ARCUS_LANES"), std::string::npos) << e.what();
    return e.status();
  }
}

TEST(Layout, ValuesAreParsedStrictly) {
  for (const char* ok : {"1", "2", "4", "8", "16"})
    EXPECT_EQ(arcus::parse_layout_value("ARCUS_LANES", ok, kLanes, 5), static_cast<uint32_t>(std::atoi(ok)));
  // Each of these was read as 8 (or as something) by strtoul: trailing junk, a value
  // that wraps to 8 modulo 2^32, a sign, spaces, an empty number.
  for (const char* bad : {"8abc", "4294967304", "18446744073709551624", "-8", "+8", " 8", "8 ", "", "0x8", "3"})
    EXPECT_EQ(parse_status(bad), ARCUS_ERROR_INVALID_ARGUMENT) << "\"" << bad << "\"";
}

TEST(Layout, EnvironmentOverridesTheDeviceAndTheEngine) {
  arcus::DeviceEntry cpu{};
  cpu.info.lanes = 8;
  cpu.info.is_gpu = 0;
  arcus::DeviceEntry gpu = cpu;
  gpu.info.lanes = 1;
  gpu.info.is_gpu = 1;
  unsetenv("ARCUS_LANES");
  unsetenv("ARCUS_GROUPS");
  arcus::Layout l = arcus::choose_layout(cpu, 4);
  EXPECT_EQ(l.lanes, 8u);
  EXPECT_EQ(l.groups, 4u);
  EXPECT_EQ(l.per_item(), 32u);
  l = arcus::choose_layout(gpu, 4);  // one item per work-item on a GPU
  EXPECT_EQ(l.lanes, 1u);
  EXPECT_EQ(l.groups, 1u);
  setenv("ARCUS_LANES", "2", 1);
  setenv("ARCUS_GROUPS", "3", 1);
  l = arcus::choose_layout(cpu, 4);
  EXPECT_EQ(l.lanes, 2u);
  EXPECT_EQ(l.groups, 3u);
  setenv("ARCUS_GROUPS", "5", 1);
  EXPECT_THROW(arcus::choose_layout(cpu, 4), arcus::Error);
  unsetenv("ARCUS_LANES");
  unsetenv("ARCUS_GROUPS");
}

}  // namespace
