#include "cache/folder_lock.h"

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <string>

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fmt/format.h>

#include "cache/atomic_file.h"

namespace softsub::cache {

namespace {

// What the holder wrote into the lock file, on one line.
std::string holderOf(int fd) {
  char text[256] = {};
  const ssize_t n = ::pread(fd, text, sizeof text - 1, 0);
  std::string holder = n > 0 ? std::string(text, static_cast<std::size_t>(n)) : std::string();
  while (!holder.empty() && (holder.back() == '\n' || holder.back() == '\0')) holder.pop_back();
  return holder.empty() ? std::string("a process that has not written its name yet") : holder;
}

// Whether `fd` is the file at `path` (not one removed or replaced since it was opened).
bool isFileAt(int fd, const std::filesystem::path& path) {
  struct stat opened {
  }, named{};
  return ::fstat(fd, &opened) == 0 && ::stat(path.c_str(), &named) == 0 && opened.st_dev == named.st_dev &&
         opened.st_ino == named.st_ino;
}

}  // namespace

FolderLock::FolderLock(const std::filesystem::path& folder, const std::string& command, InputLocation where,
                       std::string remedy)
    : path_(folder / kFileName) {
  ensureDirectory(folder);
  // Open, lock, and check that the file locked is still the one at the path: a holder
  // that ends removes the file while it holds the lock, so a file opened just before
  // that is not the lock any more.
  for (int attempt = 0; attempt < 100; ++attempt) {
    bool created = true;
    int fd = ::open(path_.c_str(), O_RDWR | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd < 0 && errno == EEXIST) {
      created = false;
      fd = ::open(path_.c_str(), O_RDWR | O_CLOEXEC);
      if (fd < 0 && errno == ENOENT) continue;  // removed by its holder meanwhile
    }
    if (fd < 0) {
      const int err = errno;
      if (err == EACCES || err == EROFS || err == EPERM) return;  // nothing to write here either
      throw IoError(fmt::format("cannot create '{}': {}", path_.string(), std::strerror(err)));
    }
    if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
      const int err = errno;
      if (err == EWOULDBLOCK) {
        const std::string holder = holderOf(fd);
        ::close(fd);
        throw InputError(
            std::move(where),
            fmt::format("'{}' is being written by another softsub process ({})", folder.string(), holder),
            std::move(remedy));
      }
      if (created) ::unlink(path_.c_str());
      ::close(fd);
      if (err == ENOLCK || err == EOPNOTSUPP || err == ENOSYS) return;  // no locks here: carry on without
      throw IoError(fmt::format("cannot lock '{}': {}", path_.string(), std::strerror(err)));
    }
    if (isFileAt(fd, path_)) {
      fd_ = fd;
      break;
    }
    ::close(fd);  // removed or replaced since it was opened: try the file at the path now
  }
  if (fd_ < 0) throw IoError(fmt::format("cannot lock '{}': it keeps being replaced", path_.string()));
  const std::time_t now = std::time(nullptr);
  char when[32] = {};
  std::tm local{};
  if (::localtime_r(&now, &local) != nullptr) std::strftime(when, sizeof when, "%Y-%m-%d %H:%M:%S", &local);
  const std::string holder =
      fmt::format("softsub {}, pid {} on host {}, since {}\n", command, ::getpid(), hostTag(), when);
  if (::ftruncate(fd_, 0) == 0) {
    const ssize_t written = ::pwrite(fd_, holder.data(), holder.size(), 0);
    (void)written;  // the name is for messages only
  }
}

FolderLock::~FolderLock() {
  if (fd_ < 0) return;
  // Still locked: a writer waiting on this file finds it gone and retries. Only if it
  // is still this lock's file (the folder may have been removed and made again).
  if (isFileAt(fd_, path_)) ::unlink(path_.c_str());
  ::close(fd_);
}

std::optional<std::string> FolderLock::holder(const std::filesystem::path& folder) {
  // Read, not locked: even a shared lock for a moment would refuse a writer starting
  // then. The holder's line, when its process lives (this host) or may (another host).
  const std::filesystem::path path = folder / kFileName;
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return std::nullopt;
  const std::string line = holderOf(fd);
  ::close(fd);
  int pid = 0;
  char host[128] = {};
  const std::size_t at = line.find(", pid ");
  if (at == std::string::npos || std::sscanf(line.c_str() + at, ", pid %d on host %127[^,]", &pid, host) != 2)
    return std::nullopt;
  if (host == hostTag() && (pid <= 0 || (::kill(pid, 0) != 0 && errno == ESRCH))) return std::nullopt;
  return line;
}

}  // namespace softsub::cache
