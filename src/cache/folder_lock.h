#pragma once
/// One writer per output folder: `run` and `mesh` hold `<folder>/.softsub.lock` while
/// they change the folder, so that a second run started into it (a farm task re-queued
/// while its first attempt still runs) is refused instead of deleting the first run's
/// files under it.
#include <filesystem>
#include <optional>
#include <string>

namespace softsub::cache {

/// Holds an exclusive lock (flock) on `<folder>/.softsub.lock` from construction to
/// destruction. The kernel releases it when the process ends however it ends (a
/// SIGKILL, a crash), so a lock file left behind never blocks the next run. The file
/// holds the holder's process id, host and start time, for the refusal's message; it is
/// removed while still locked when the holder ends normally.
class FolderLock {
 public:
  /// Creates `folder` if needed, then takes the lock. InputError (exit code 2, nothing
  /// written) naming the holder when another process holds it. On a file system without
  /// locks (some network mounts) there is nothing to take: no lock, no error.
  explicit FolderLock(const std::filesystem::path& folder);
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;
  ~FolderLock();
  /// Whether the lock is held (false where the file system has no locks).
  [[nodiscard]] bool held() const { return fd_ >= 0; }
  /// The lock file's name in a folder.
  static constexpr const char* kFileName = ".softsub.lock";

 private:
  std::filesystem::path path_;
  int fd_ = -1;
};

}  // namespace softsub::cache
