// Programs are cached per device and feature set in memory, and across processes on
// disk (ARCUS_CACHE_DIR): a later runtime loads what an earlier one built; a corrupt or
// truncated file is rebuilt, never trusted; "off" writes nothing.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/runtime.h"
#include "unit_util.h"

namespace {

namespace fs = std::filesystem;
using arcus_unit::Context;
using arcus_unit::ScopedEnv;
using arcus_unit::TempDir;

struct JobRun {
  arcus_status status = ARCUS_ERROR_INVALID_ARGUMENT;
  arcus_job_stats stats{};
  std::vector<double> positions;
  std::string message;
};

// One RK4 job on a fresh context (so, once the last context is gone, a fresh runtime
// whose in-memory cache is empty) or on `ctx` if given.
JobRun run_job(arcus_context_t* given = nullptr, int32_t method = ARCUS_METHOD_RK4) {
  Context own;
  arcus_context_t* ctx = given ? given : own.ctx;
  JobRun r;
  const double g[3] = {0, 0.1, 0}, o[3] = {0, 0, 0}, d[3] = {1, 0.2, 0};
  arcus_field_t* field = nullptr;
  EXPECT_EQ(arcus_field_create_linear(ctx, 1.0, g, &field), ARCUS_SUCCESS);
  arcus_advance_params p;
  arcus_advance_params_init(&p);
  p.method = method;
  p.step = 0.1;
  p.length = 2.0;
  arcus_job_t* job = nullptr;
  r.status = arcus_advance(ctx, field, &p, 1, o, d, nullptr, &job);
  r.message = arcus_context_last_error(ctx);
  if (job) {
    arcus_job_get_stats(job, &r.stats);
    r.positions.resize(3);
    arcus_job_get_end_states(job, r.positions.data(), nullptr, nullptr, nullptr, nullptr);
    arcus_job_release(job);
  }
  arcus_field_release(field);
  return r;
}

std::vector<fs::path> cache_files(const std::string& dir) {
  std::vector<fs::path> files;
  if (fs::exists(dir))
    for (const auto& e : fs::directory_iterator(dir)) files.push_back(e.path());
  return files;
}

TEST(ProgramCache, ALaterRuntimeLoadsTheProgramFromDisk) {
  TempDir dir;
  ScopedEnv env("ARCUS_CACHE_DIR", dir.path());
  const JobRun cold = run_job();
  ASSERT_EQ(cold.status, ARCUS_SUCCESS) << cold.message;
  EXPECT_EQ(cold.stats.program_origin, ARCUS_PROGRAM_BUILT);
  ASSERT_EQ(cache_files(dir.path()).size(), 1u);
  const JobRun warm = run_job();
  ASSERT_EQ(warm.status, ARCUS_SUCCESS) << warm.message;
  EXPECT_EQ(warm.stats.program_origin, ARCUS_PROGRAM_DISK_CACHE);
  std::printf("build from source %.3f s, load from disk %.3f s\n", cold.stats.build_seconds, warm.stats.build_seconds);
  // Determinism: the cached binary computes the same numbers.
  EXPECT_EQ(warm.positions, cold.positions);
  // Within one runtime the second job takes the program from memory.
  Context ctx;
  run_job(ctx);
  EXPECT_EQ(run_job(ctx).stats.program_origin, ARCUS_PROGRAM_MEMORY_CACHE);
  // Another feature set is another program, in a file of its own.
  EXPECT_EQ(run_job(nullptr, ARCUS_METHOD_EULER).stats.program_origin, ARCUS_PROGRAM_BUILT);
  EXPECT_EQ(cache_files(dir.path()).size(), 2u);
}

TEST(ProgramCache, ACorruptOrTruncatedFileIsRebuiltNotTrusted) {
  TempDir dir;
  ScopedEnv env("ARCUS_CACHE_DIR", dir.path());
  const JobRun reference = run_job();
  ASSERT_EQ(reference.status, ARCUS_SUCCESS);
  const std::vector<fs::path> files = cache_files(dir.path());
  ASSERT_EQ(files.size(), 1u);
  std::string intact;
  {
    std::ifstream in(files[0], std::ios::binary);
    intact.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  ASSERT_GT(intact.size(), 100u);
  std::string flipped = intact;
  flipped[flipped.size() / 2] ^= 0x5a;  // a bit error inside the binary: the checksum catches it
  std::string wrong_key = intact;
  wrong_key[40] ^= 0x01;  // the stored key no longer matches the job's
  const std::vector<std::pair<const char*, std::string>> damaged{{"truncated", intact.substr(0, intact.size() / 2)},
                                                                  {"empty", ""},
                                                                  {"bit flip", flipped},
                                                                  {"other key", wrong_key},
                                                                  {"garbage", std::string(4096, '\x7f')}};
  for (const auto& d : damaged) {
    std::ofstream(files[0], std::ios::binary | std::ios::trunc) << d.second;
    const JobRun rebuilt = run_job();
    ASSERT_EQ(rebuilt.status, ARCUS_SUCCESS) << d.first << ": " << rebuilt.message;
    EXPECT_EQ(rebuilt.stats.program_origin, ARCUS_PROGRAM_BUILT) << d.first;
    EXPECT_EQ(rebuilt.positions, reference.positions) << d.first;
    // ... and the file is whole again: the next runtime loads it.
    EXPECT_EQ(run_job().stats.program_origin, ARCUS_PROGRAM_DISK_CACHE) << d.first;
  }
}

TEST(ProgramCache, OffKeepsNothingOnDisk) {
  TempDir dir;
  ScopedEnv home("XDG_CACHE_HOME", dir.path());  // where the default would be
  ScopedEnv env("ARCUS_CACHE_DIR", "off");
  EXPECT_EQ(arcus::program_cache_dir(), "");
  EXPECT_EQ(run_job().stats.program_origin, ARCUS_PROGRAM_BUILT);
  EXPECT_EQ(run_job().stats.program_origin, ARCUS_PROGRAM_BUILT);
  EXPECT_FALSE(fs::exists(fs::path(dir.path()) / "arcus"));
}

TEST(ProgramCache, DefaultDirectoryIsPerUser) {
  unsetenv("ARCUS_CACHE_DIR");
  {
    ScopedEnv xdg("XDG_CACHE_HOME", "/some/cache");
    EXPECT_EQ(arcus::program_cache_dir(), "/some/cache/arcus");
  }
  unsetenv("XDG_CACHE_HOME");
  ScopedEnv home("HOME", "/home/someone");
  EXPECT_EQ(arcus::program_cache_dir(), "/home/someone/.cache/arcus");
}

// An internal hook injects a bad build option: the build fails, and the call says so
// with the compiler's log.
TEST(KernelBuild, AFailedBuildIsAKernelBuildErrorWithTheLog) {
  ScopedEnv env("ARCUS_CACHE_DIR", "off");
  arcus::testing::set_extra_build_options("-D __kernel=@");
  const JobRun r = run_job();
  arcus::testing::set_extra_build_options("");
  EXPECT_EQ(r.status, ARCUS_ERROR_KERNEL_BUILD);
  EXPECT_NE(r.message.find("-D __kernel=@"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("error"), std::string::npos) << "the compiler's log: " << r.message;
  // The failure is not cached: the same job builds once the option is gone.
  EXPECT_EQ(run_job().status, ARCUS_SUCCESS);
}

}  // namespace
