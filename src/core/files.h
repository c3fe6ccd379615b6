// Input files as every reader opens them: regular files only (a FIFO would block the
// caller for ever, a device such as /dev/zero never ends, a directory is no data), and
// never more bytes than the reader's bound.  Errors are ARCUS_ERROR_IO starting with the
// file's name.
#pragma once

#include <cstdint>
#include <string>

namespace arcus::files {

// The size of the regular file at `path` (symlinks followed): else "<path>: cannot
// read: No such file or directory", "<path>: is a FIFO, not a regular file", ...
uint64_t require_regular(const std::string& path);

// The whole regular file at `path`, refused before reading when it is larger than
// max_bytes ("<path>: 1.5 GiB is more than the 64 MiB allowed (<bound_name> raises
// it)").  Opened without blocking and checked again on the open descriptor, since the
// path may have been swapped for a FIFO since.
std::string read_all(const std::string& path, uint64_t max_bytes, const char* bound_name);

}  // namespace arcus::files
