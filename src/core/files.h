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

// A regular file open for reading: opened without blocking (a FIFO swapped in after a
// check would otherwise wait for a writer) and checked again on the descriptor; closed
// with the object.  Errors name the file as require_regular's do.
class RegularFile {
 public:
  explicit RegularFile(const std::string& path);
  ~RegularFile();
  RegularFile(const RegularFile&) = delete;
  RegularFile& operator=(const RegularFile&) = delete;

  uint64_t size() const { return size_; }
  // Reads up to `bytes` into `dst` (blocking, as for any regular file); 0 at the end.
  size_t read_some(char* dst, size_t bytes);
  // Reads exactly `bytes`: "<path>: the file ended early" if it shrank meanwhile.
  void read_exact(char* dst, size_t bytes);

 private:
  std::string path_;
  int fd_ = -1;
  uint64_t size_ = 0;
};

// The whole regular file at `path`, refused before reading when it is larger than
// max_bytes ("<path>: 1.5 GiB is more than the 64 MiB allowed (<bound_name> raises
// it)").  Opened without blocking and checked again on the open descriptor, since the
// path may have been swapped for a FIFO since.
std::string read_all(const std::string& path, uint64_t max_bytes, const char* bound_name);

}  // namespace arcus::files
