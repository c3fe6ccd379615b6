// Helpers of the unit suites (which link the library's objects, internals included).
#pragma once

#include <gtest/gtest.h>
#include <stdlib.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "arcus/arcus.h"
#include "core/error.h"
#include "scoped_env.h"

namespace arcus_unit {

using ::ScopedEnv;

// The error a call throws (status and message), or success.
struct Failure {
  arcus_status status = ARCUS_SUCCESS;
  std::string message;
};
inline Failure failure_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const arcus::Error& e) {
    return {e.status(), e.what()};
  }
  return {};
}

// A fresh directory, removed with its contents at the end of the scope.
class TempDir {
 public:
  TempDir() {
    std::string pattern = (std::filesystem::temp_directory_path() / "arcus_unit_XXXXXX").string();
    path_ = mkdtemp(&pattern[0]) ? pattern : "";
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

// A CSV of data/<folder>/ without its header line, which must be `header`; its fields
// as written (the embedded tables' tests compare them with the library's numbers).
using Rows = std::vector<std::vector<std::string>>;
inline Rows read_data_csv(const std::string& folder, const std::string& name, const std::string& header) {
  std::ifstream in(std::string(ARCUS_SOURCE_DIR) + "/data/" + folder + "/" + name);
  EXPECT_TRUE(in) << name;
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, header) << name;
  Rows rows;
  while (std::getline(in, line)) {
    std::istringstream s(line);
    std::vector<std::string> fields;
    for (std::string f; std::getline(s, f, ',');) fields.push_back(f);
    rows.push_back(fields);
  }
  return rows;
}

struct Context {
  arcus_context_t* ctx = nullptr;
  Context() { EXPECT_EQ(arcus_context_create(ARCUS_DEVICE_DEFAULT, &ctx), ARCUS_SUCCESS) << arcus_last_error(); }
  ~Context() {
    if (ctx) arcus_context_release(ctx);
  }
  operator arcus_context_t*() const { return ctx; }
};

}  // namespace arcus_unit
