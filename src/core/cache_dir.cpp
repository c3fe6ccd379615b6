#include "core/cache_dir.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <mutex>
#include <random>
#include <set>

namespace arcus {
namespace {

// Why a directory or entry is not to be trusted, or "" when it is.
std::string distrust(const struct stat& st) {
  if (st.st_uid != ::geteuid())
    return "it is owned by uid " + std::to_string(st.st_uid) + ", not by this user (uid " +
           std::to_string(::geteuid()) + ")";
  if (st.st_mode & (S_IWGRP | S_IWOTH)) return "it is writable by group or others";
  return "";
}

void warn_once(const std::string& path, const char* what, const std::string& why) {
  static std::mutex mutex;
  static std::set<std::string> warned;
  std::lock_guard<std::mutex> lock(mutex);
  if (!warned.insert(path).second) return;
  std::fprintf(stderr,
               "arcus: warning: the %s %s is not used: %s; someone else could plant entries there that arcus "
               "would run as you.  Make it yours (chown, chmod go-w) or point ARCUS_CACHE_DIR at a private "
               "directory; until then nothing is cached.\n",
               what, path.c_str(), why.c_str());
}

// Creates each missing component of `path` with mode 0700 (mkdir's mode is masked by
// the umask, which can only narrow it).
void make_directories(const std::string& path) {
  for (size_t at = path.find('/', 1);; at = path.find('/', at + 1)) {
    const std::string prefix = at == std::string::npos ? path : path.substr(0, at);
    if (!prefix.empty() && ::mkdir(prefix.c_str(), 0700) != 0 && errno != EEXIST) return;
    if (at == std::string::npos) return;
  }
}

bool write_all(int fd, const std::string& data) {
  const char* p = data.data();
  size_t left = data.size();
  while (left) {
    const ssize_t n = ::write(fd, p, left);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    p += n;
    left -= static_cast<size_t>(n);
  }
  return true;
}

}  // namespace

CacheDir::CacheDir(const std::string& path, const char* what) : path_(path) {
  if (path.empty()) return;
  make_directories(path);
  const int fd = ::open(path.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) {
    warn_once(path, what, std::string("it cannot be opened: ") + std::strerror(errno));
    return;
  }
  struct stat st {};
  std::string why = ::fstat(fd, &st) != 0 ? std::string("fstat failed: ") + std::strerror(errno) : distrust(st);
  if (!why.empty()) {
    warn_once(path, what, why);
    ::close(fd);
    return;
  }
  fd_ = fd;
}

CacheDir::~CacheDir() {
  if (fd_ >= 0) ::close(fd_);
}

std::optional<std::string> CacheDir::read(const std::string& name, size_t max_bytes) const {
  if (fd_ < 0) return std::nullopt;
  // O_NOFOLLOW: a symlink is refused (ELOOP), not followed; O_NONBLOCK: a FIFO never blocks.
  const int fd = ::openat(fd_, name.c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) return std::nullopt;
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{fd};
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode) || !distrust(st).empty() ||
      static_cast<unsigned long long>(st.st_size) > max_bytes)
    return std::nullopt;
  std::string data(static_cast<size_t>(st.st_size), '\0');
  size_t got = 0;
  while (got < data.size()) {
    const ssize_t n = ::read(fd, &data[got], data.size() - got);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return std::nullopt;  // shrank meanwhile: not the entry it was
    got += static_cast<size_t>(n);
  }
  return data;
}

bool CacheDir::write(const std::string& name, const std::string& data) const {
  if (fd_ < 0) return false;
  thread_local std::mt19937_64 random{std::random_device{}()};
  for (int attempt = 0; attempt < 8; ++attempt) {
    char suffix[32];
    std::snprintf(suffix, sizeof suffix, ".tmp%016llx", static_cast<unsigned long long>(random()));
    const std::string tmp = name + suffix;
    const int fd = ::openat(fd_, tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0600);
    if (fd < 0) {
      if (errno == EEXIST) continue;  // a name taken (or planted): draw another
      return false;
    }
    const bool written = write_all(fd, data);
    const bool closed = ::close(fd) == 0;
    // rename replaces whatever `name` is (a planted symlink included) without following it.
    if (written && closed && ::renameat(fd_, tmp.c_str(), fd_, name.c_str()) == 0) return true;
    ::unlinkat(fd_, tmp.c_str(), 0);
    return false;
  }
  return false;
}

}  // namespace arcus
