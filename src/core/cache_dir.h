// A cache directory that only this user can write, as ccache, pip and PoCL keep theirs:
// what is read back from it is run (compiled programs), so an entry someone else could
// have written is never trusted.  docs/security.md states the model.
//   - The directory is created 0700 (whatever the umask) and used only when it is owned
//     by this user and not writable by group or others; otherwise a warning is printed
//     once per directory and the cache is off.
//   - An entry is read only when it is a regular file (no symlink is followed) owned by
//     this user, not writable by others, and no larger than the caller's bound.
//   - An entry is written to a fresh temporary file (O_CREAT | O_EXCL | O_NOFOLLOW, mode
//     0600) and renamed into place, so no planted link is ever written through and a
//     reader never sees half an entry.
// Every operation is relative to the directory opened once, so renaming the path
// afterwards changes nothing.  A failure costs only the cache: nothing here throws.
#pragma once

#include <cstddef>
#include <optional>
#include <string>

namespace arcus {

class CacheDir {
 public:
  // Opens (creating what is missing) the directory at `path`; `what` names the cache in
  // the warning ("program cache").  Check usable() before anything else.
  CacheDir(const std::string& path, const char* what);
  ~CacheDir();
  CacheDir(const CacheDir&) = delete;
  CacheDir& operator=(const CacheDir&) = delete;

  bool usable() const { return fd_ >= 0; }
  const std::string& path() const { return path_; }

  // The entry `name` (a plain file name), or nothing when it is missing or not to be
  // trusted (see above) or larger than max_bytes.
  std::optional<std::string> read(const std::string& name, size_t max_bytes) const;

  // Stores `data` as `name`; false when it could not be written (nothing is left behind).
  bool write(const std::string& name, const std::string& data) const;

 private:
  std::string path_;
  int fd_ = -1;
};

}  // namespace arcus
