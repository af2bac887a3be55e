#pragma once
/// One writer per output folder: `run`, `mesh` and the viewer's S hold
/// `<folder>/.softsub.lock` while they change the folder, so that a second writer
/// started into it (a farm task re-queued while its first attempt still runs) is
/// refused instead of deleting the first one's files under it.
#include <filesystem>
#include <optional>
#include <string>

#include "core/error.h"

namespace softsub::cache {

/// Holds an exclusive lock (flock) on `<folder>/.softsub.lock` from construction to
/// destruction. The kernel releases it when the process ends however it ends (a
/// SIGKILL, a crash), so a lock file left behind never blocks the next writer. The file
/// names the holder (`softsub run, pid 4121 on host farm07, since ...`) for a refusal's
/// message; the holder removes it, still locked, when it ends normally.
class FolderLock {
 public:
  /// Creates `folder` if needed, then takes the lock for `command` (`run`, `mesh`,
  /// `view`). When another process holds it: InputError at `where` (exit code 2,
  /// nothing written) naming the holder, with `remedy` as what is allowed. Where
  /// nothing can be locked (a file system without locks, a folder this process cannot
  /// write: the writes themselves will fail with their own error) there is no lock
  /// and no error. Locks are only as good as the mount's: a network mount whose locks
  /// are local to each host (NFS's local_lock) does not keep two hosts apart.
  FolderLock(const std::filesystem::path& folder, const std::string& command, InputLocation where,
             std::string remedy);
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;
  ~FolderLock();
  /// Whether the lock is held.
  [[nodiscard]] bool held() const { return fd_ >= 0; }
  /// Who holds the lock of `folder` now (the holder's line), if anyone: for `info`.
  [[nodiscard]] static std::optional<std::string> holder(const std::filesystem::path& folder);
  /// The lock file's name in a folder.
  static constexpr const char* kFileName = ".softsub.lock";

 private:
  std::filesystem::path path_;
  int fd_ = -1;
};

}  // namespace softsub::cache
