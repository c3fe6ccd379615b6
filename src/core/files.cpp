#include "core/files.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <system_error>

#include "core/error.h"
#include "core/limits.h"

namespace arcus::files {
namespace {

[[noreturn]] void fail_io(const std::string& path, const std::string& what) { fail(ARCUS_ERROR_IO, path + ": " + what); }

std::string errno_text(int err) { return std::error_code(err, std::generic_category()).message(); }

// Written escaped: a message is a C string, which a NUL would cut short.
std::string printable_path(const std::string& path) {
  std::string out;
  for (char c : path) out += c == '\0' ? std::string("\\x00") : std::string(1, c);
  return out;
}

void require_regular_mode(const std::string& path, mode_t mode) {
  if (S_ISREG(mode)) return;
  const char* kind = S_ISDIR(mode)    ? "a directory"
                     : S_ISFIFO(mode) ? "a FIFO"
                     : S_ISCHR(mode)  ? "a character device"
                     : S_ISBLK(mode)  ? "a block device"
                     : S_ISSOCK(mode) ? "a socket"
                                      : "not a regular file";
  fail_io(path, std::string("is ") + kind + ", not a regular file");
}

}  // namespace

uint64_t require_regular(const std::string& path) {
  if (path.find('\0') != std::string::npos) fail_io(printable_path(path), "the file name contains a NUL character");
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0)
    fail_io(path, "cannot read: " + errno_text(errno));
  require_regular_mode(path, st.st_mode);
  return static_cast<uint64_t>(st.st_size);
}

RegularFile::RegularFile(const std::string& path) : path_(path) {
  require_regular(path);
  fd_ = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd_ < 0) fail_io(path, "cannot open: " + errno_text(errno));
  struct stat st {};
  if (::fstat(fd_, &st) != 0) {
    const int err = errno;
    ::close(fd_);
    fail_io(path, "cannot read: " + errno_text(err));
  }
  if (!S_ISREG(st.st_mode)) {
    ::close(fd_);
    require_regular_mode(path, st.st_mode);
  }
  ::fcntl(fd_, F_SETFL, ::fcntl(fd_, F_GETFL) & ~O_NONBLOCK);
  size_ = static_cast<uint64_t>(st.st_size);
}

RegularFile::~RegularFile() { ::close(fd_); }

size_t RegularFile::read_some(char* dst, size_t bytes) {
  for (;;) {
    const ssize_t n = ::read(fd_, dst, bytes);
    if (n >= 0) return static_cast<size_t>(n);
    if (errno != EINTR) fail_io(path_, "cannot read: " + errno_text(errno));
  }
}

void RegularFile::read_exact(char* dst, size_t bytes) {
  while (bytes) {
    const size_t n = read_some(dst, bytes);
    if (n == 0) fail_io(path_, "the file ended early (it shrank while being read)");
    dst += n;
    bytes -= n;
  }
}

std::string read_all(const std::string& path, uint64_t max_bytes, const char* bound_name) {
  RegularFile file(path);
  if (file.size() > max_bytes)
    fail_io(path, limits::bytes_text(double(file.size())) + " is more than the " +
                      limits::bytes_text(double(max_bytes)) + " allowed (" + bound_name + " raises the bound)");
  std::string text;
  text.reserve(static_cast<size_t>(file.size()));
  char buf[65536];
  while (const size_t n = file.read_some(buf, sizeof buf)) {
    if (text.size() + n > max_bytes)  // it grew while being read
      fail_io(path, "grew past the " + limits::bytes_text(double(max_bytes)) + " allowed (" + bound_name +
                        " raises the bound)");
    text.append(buf, n);
  }
  return text;
}

}  // namespace arcus::files
