// Programs are cached per device and feature set in memory, and across processes on
// disk (ARCUS_CACHE_DIR): a later runtime loads what an earlier one built; a corrupt or
// truncated file is rebuilt, never trusted; "off" writes nothing.  The disk cache is
// this user's alone (docs/security.md): a directory or entry that another user owns or
// could write is not used, so a planted program never runs, and no planted link is
// ever written through.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/kernel_source.h"
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
  r.status = arcus_curved_advance(ctx, field, &p, 1, o, d, nullptr, &job);
  r.message = arcus_context_last_error(ctx);
  if (job) {
    arcus_job_get_stats(job, &r.stats);
    r.positions.resize(3);
    arcus_job_get_curved_end_states(job, r.positions.data(), nullptr, nullptr, nullptr, nullptr);
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

// ---- the cache is this user's alone ----------------------------------------------------

std::string read_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

void write_file(const fs::path& p, const std::string& data) { std::ofstream(p, std::ios::binary | std::ios::trunc) << data; }

mode_t mode_of(const fs::path& p) {
  struct stat st {};
  EXPECT_EQ(::lstat(p.c_str(), &st), 0) << p;
  return st.st_mode & 07777;
}

// Another user for chown: "nobody".  Only root can give files away; the tests that need
// it are skipped otherwise (CI runs as root).
constexpr uid_t kOtherUser = 65534;
bool can_chown() { return ::geteuid() == 0; }

// A cache entry (runtime.cpp's format) holding `binary` under `key`.
std::string entry(const std::string& key, const std::string& binary) {
  auto u64 = [](uint64_t v) { return std::string(reinterpret_cast<const char*>(&v), sizeof v); };
  return std::string("arcus program cache 1\n") + u64(key.size()) + key + u64(binary.size()) + binary +
         u64(arcus::fnv1a64(binary.data(), binary.size()));
}

// The parts of an entry written by the library: key and binary.
std::pair<std::string, std::string> parts(const std::string& data) {
  size_t pos = std::strlen("arcus program cache 1\n");
  uint64_t n = 0;
  std::memcpy(&n, data.data() + pos, 8);
  const std::string key = data.substr(pos + 8, n);
  pos += 8 + n;
  std::memcpy(&n, data.data() + pos, 8);
  return {key, data.substr(pos + 8, n)};
}

// A working program planted under the RK4 job's name: the Euler job's binary, re-keyed
// and re-checksummed as the RK4 program.  Loaded, it would give Euler's (different)
// numbers, so the tests can tell whether it ran.
struct Planted {
  fs::path file;     // the RK4 job's entry
  std::string data;  // the planted entry
  JobRun reference;  // RK4 built from source
};
Planted plant(const std::string& dir) {
  Planted p;
  p.reference = run_job();
  EXPECT_EQ(p.reference.status, ARCUS_SUCCESS);
  const auto before = cache_files(dir);
  EXPECT_EQ(before.size(), 1u);
  p.file = before.at(0);
  EXPECT_EQ(run_job(nullptr, ARCUS_METHOD_EULER).status, ARCUS_SUCCESS);
  fs::path euler;
  for (const auto& f : cache_files(dir))
    if (f != p.file) euler = f;
  const std::string rk4_key = parts(read_file(p.file)).first;
  p.data = entry(rk4_key, parts(read_file(euler)).second);
  return p;
}

TEST(ProgramCacheSecurity, APlantedProgramRunsOnlyWhenTheEntryIsTheUsersOwn) {
  TempDir dir;
  ScopedEnv env("ARCUS_CACHE_DIR", dir.path());
  const Planted p = plant(dir.path());
  // Control: the planted entry, owned by this user, is loaded and runs (so the test can
  // tell a planted program from the real one).
  write_file(p.file, p.data);
  const JobRun trusted = run_job();
  ASSERT_EQ(trusted.status, ARCUS_SUCCESS);
  EXPECT_EQ(trusted.stats.program_origin, ARCUS_PROGRAM_DISK_CACHE);
  EXPECT_NE(trusted.positions, p.reference.positions) << "the planted (Euler) program ran";
  // Writable by others: whoever could write it may have planted it.  Rebuilt, replaced.
  write_file(p.file, p.data);
  ASSERT_EQ(::chmod(p.file.c_str(), 0666), 0);
  const JobRun shared = run_job();
  EXPECT_EQ(shared.stats.program_origin, ARCUS_PROGRAM_BUILT);
  EXPECT_EQ(shared.positions, p.reference.positions);
  EXPECT_EQ(mode_of(p.file) & 077, 0u) << "replaced by a private entry";
  if (!can_chown()) GTEST_SKIP() << "giving a file to another user needs root";
  // Owned by another user (who can write into the directory through some other hole).
  write_file(p.file, p.data);
  ASSERT_EQ(::chown(p.file.c_str(), kOtherUser, kOtherUser), 0);
  const JobRun foreign = run_job();
  EXPECT_EQ(foreign.stats.program_origin, ARCUS_PROGRAM_BUILT);
  EXPECT_EQ(foreign.positions, p.reference.positions) << "the planted program must not run";
}

TEST(ProgramCacheSecurity, ADirectoryOthersCanWriteIsNotUsedAndSaysSo) {
  TempDir parent;
  const fs::path dir = fs::path(parent.path()) / "shared";
  ASSERT_TRUE(fs::create_directory(dir));
  ASSERT_EQ(::chmod(dir.c_str(), 01777), 0);  // as /tmp: anyone may create files in it
  ScopedEnv env("ARCUS_CACHE_DIR", dir.string());
  ::testing::internal::CaptureStderr();
  const JobRun first = run_job();
  const JobRun second = run_job();
  const std::string warning = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(first.stats.program_origin, ARCUS_PROGRAM_BUILT);
  EXPECT_EQ(second.stats.program_origin, ARCUS_PROGRAM_BUILT) << "no cache at all";
  EXPECT_TRUE(cache_files(dir.string()).empty()) << "nothing written there";
  EXPECT_NE(warning.find(dir.string()), std::string::npos) << warning;
  EXPECT_NE(warning.find("writable by group or others"), std::string::npos) << warning;
  EXPECT_EQ(warning.find("warning", warning.find("warning") + 1), std::string::npos) << "warned once: " << warning;
  if (!can_chown()) GTEST_SKIP() << "giving a directory to another user needs root";
  ASSERT_EQ(::chmod(dir.c_str(), 0755), 0);
  ASSERT_EQ(::chown(dir.c_str(), kOtherUser, kOtherUser), 0);
  ::testing::internal::CaptureStderr();
  EXPECT_EQ(run_job().stats.program_origin, ARCUS_PROGRAM_BUILT);
  EXPECT_EQ(run_job().stats.program_origin, ARCUS_PROGRAM_BUILT);
  EXPECT_TRUE(cache_files(dir.string()).empty());
  ::testing::internal::GetCapturedStderr();  // warned already for this path (above)
}

TEST(ProgramCacheSecurity, DirectoriesAreCreatedPrivateAndEntriesTooWhateverTheUmask) {
  TempDir parent;
  const fs::path dir = fs::path(parent.path()) / "a" / "b";
  ScopedEnv env("ARCUS_CACHE_DIR", dir.string());
  const mode_t old = ::umask(0);
  const JobRun r = run_job();
  ::umask(old);
  ASSERT_EQ(r.status, ARCUS_SUCCESS);
  EXPECT_EQ(mode_of(fs::path(parent.path()) / "a"), 0700u);
  EXPECT_EQ(mode_of(dir), 0700u);
  const auto files = cache_files(dir.string());
  ASSERT_EQ(files.size(), 1u);
  EXPECT_EQ(mode_of(files[0]), 0600u);
  EXPECT_EQ(run_job().stats.program_origin, ARCUS_PROGRAM_DISK_CACHE);
}

TEST(ProgramCacheSecurity, APlantedSymlinkIsNeitherReadNorWrittenThrough) {
  TempDir dir, elsewhere;
  ScopedEnv env("ARCUS_CACHE_DIR", dir.path());
  const JobRun reference = run_job();
  ASSERT_EQ(reference.status, ARCUS_SUCCESS);
  const fs::path file = cache_files(dir.path()).at(0);
  // A file the victim owns and nobody should overwrite, and links to it at the entry's
  // name and at every temporary name the old writer would have used.
  const fs::path victim = fs::path(elsewhere.path()) / "precious";
  write_file(victim, "do not overwrite");
  ASSERT_EQ(::chmod(victim.c_str(), 0600), 0);
  fs::remove(file);
  fs::create_symlink(victim, file);
  for (int n = 0; n < 64; ++n)
    fs::create_symlink(victim, file.string() + ".tmp" + std::to_string(::getpid()) + "." + std::to_string(n));
  const JobRun r = run_job();
  ASSERT_EQ(r.status, ARCUS_SUCCESS) << r.message;
  EXPECT_EQ(r.stats.program_origin, ARCUS_PROGRAM_BUILT) << "a link is not an entry";
  EXPECT_EQ(read_file(victim), "do not overwrite");
  EXPECT_FALSE(fs::is_symlink(file)) << "the link was replaced by the entry";
  EXPECT_EQ(run_job().stats.program_origin, ARCUS_PROGRAM_DISK_CACHE);
}

TEST(ProgramCacheSecurity, AnEntryTooLargeToBeArcusIsNotReadIntoMemory) {
  TempDir dir;
  ScopedEnv env("ARCUS_CACHE_DIR", dir.path());
  ASSERT_EQ(run_job().status, ARCUS_SUCCESS);
  const fs::path file = cache_files(dir.path()).at(0);
  fs::resize_file(file, uint64_t(1) << 40);  // 1 TiB, sparse: only its size is real
  const JobRun r = run_job();
  EXPECT_EQ(r.stats.program_origin, ARCUS_PROGRAM_BUILT);
  EXPECT_LT(fs::file_size(file), uint64_t(1) << 20) << "replaced by the real entry";
}

}  // namespace
