// Errors inside the library are exceptions carrying an arcus_status; the C entry
// points (api.cpp) turn them into return codes and last-error messages.
#pragma once

#include <stdexcept>
#include <string>

#include "arcus/arcus.h"

namespace arcus {

class Error : public std::runtime_error {
 public:
  Error(arcus_status status, const std::string& message) : std::runtime_error(message), status_(status) {}
  arcus_status status() const { return status_; }

 private:
  arcus_status status_;
};

[[noreturn]] inline void fail(arcus_status status, const std::string& message) { throw Error(status, message); }

// Throws ARCUS_ERROR_INVALID_ARGUMENT with `message` unless `ok`.
inline void require(bool ok, const std::string& message) {
  if (!ok) fail(ARCUS_ERROR_INVALID_ARGUMENT, message);
}

// Throws ARCUS_ERROR_INVALID_ARGUMENT naming `name` when `p` is null.
template <class T>
inline void require_pointer(const T* p, const char* name) {
  if (!p) fail(ARCUS_ERROR_INVALID_ARGUMENT, std::string(name) + " is NULL");
}

}  // namespace arcus
