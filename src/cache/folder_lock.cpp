#include "cache/folder_lock.h"

#include <cerrno>
#include <cstring>
#include <ctime>
#include <string>

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fmt/format.h>

#include "cache/atomic_file.h"
#include "core/error.h"

namespace softsub::cache {

namespace {

// What the holder wrote into the lock file: "pid <n> on host <h>, since <time>".
std::string holderOf(int fd) {
  char text[256] = {};
  const ssize_t n = ::pread(fd, text, sizeof text - 1, 0);
  std::string holder = n > 0 ? std::string(text, static_cast<std::size_t>(n)) : std::string();
  while (!holder.empty() && (holder.back() == '\n' || holder.back() == '\0')) holder.pop_back();
  return holder.empty() ? std::string("a process that has not written its name yet") : holder;
}

}  // namespace

FolderLock::FolderLock(const std::filesystem::path& folder) : path_(folder / kFileName) {
  ensureDirectory(folder);
  // Open, lock, and check that the file locked is still the one at the path: a holder
  // that ends removes the file while it holds the lock, so a file opened just before
  // that is not the lock any more.
  for (int attempt = 0; attempt < 100; ++attempt) {
    const int fd = ::open(path_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0666);
    if (fd < 0) throw IoError(fmt::format("cannot create {}: {}", path_.string(), std::strerror(errno)));
    if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
      const int err = errno;
      if (err == EWOULDBLOCK) {
        const std::string holder = holderOf(fd);
        ::close(fd);
        throw InputError(
            {"command line", 0, "--out"},
            fmt::format("'{}' is being written by another softsub run ({})", folder.string(), holder),
            "wait for that run to end, or write into another folder (--out)");
      }
      ::close(fd);
      if (err == ENOLCK || err == EOPNOTSUPP || err == ENOSYS) return;  // no locks here: carry on without
      throw IoError(fmt::format("cannot lock {}: {}", path_.string(), std::strerror(err)));
    }
    struct stat opened {
    }, named{};
    if (::fstat(fd, &opened) == 0 && ::stat(path_.c_str(), &named) == 0 && opened.st_dev == named.st_dev &&
        opened.st_ino == named.st_ino) {
      fd_ = fd;
      break;
    }
    ::close(fd);  // removed or replaced since it was opened: try the file at the path now
  }
  if (fd_ < 0) throw IoError(fmt::format("cannot lock {}: it keeps being replaced", path_.string()));
  const std::time_t now = std::time(nullptr);
  char when[32] = {};
  std::tm local{};
  if (::localtime_r(&now, &local) != nullptr) std::strftime(when, sizeof when, "%Y-%m-%d %H:%M:%S", &local);
  const std::string holder = fmt::format("pid {} on host {}, since {}\n", ::getpid(), hostTag(), when);
  if (::ftruncate(fd_, 0) == 0) {
    const ssize_t written = ::pwrite(fd_, holder.data(), holder.size(), 0);
    (void)written;  // the name is for messages only
  }
}

FolderLock::~FolderLock() {
  if (fd_ < 0) return;
  ::unlink(path_.c_str());  // still locked: a run waiting on this file finds it gone and retries
  ::close(fd_);
}

}  // namespace softsub::cache
