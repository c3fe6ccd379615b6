// Sets an environment variable for one scope and restores the previous value (the
// library reads ARCUS_DEVICE, ARCUS_LANES, ARCUS_CACHE_DIR ... at every call).
#ifndef ARCUS_TESTS_SCOPED_ENV_H
#define ARCUS_TESTS_SCOPED_ENV_H

#include <stdlib.h>

#include <cstdlib>
#include <string>

class ScopedEnv {
 public:
  ScopedEnv(const char* name, const std::string& value) : name_(name) {
    if (const char* old = std::getenv(name)) {
      had_ = true;
      old_ = old;
    }
    setenv(name, value.c_str(), 1);
  }
  ~ScopedEnv() {
    if (had_)
      setenv(name_.c_str(), old_.c_str(), 1);
    else
      unsetenv(name_.c_str());
  }
  ScopedEnv(const ScopedEnv&) = delete;
  ScopedEnv& operator=(const ScopedEnv&) = delete;

 private:
  std::string name_, old_;
  bool had_ = false;
};

#endif  // ARCUS_TESTS_SCOPED_ENV_H
