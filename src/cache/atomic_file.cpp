#include "cache/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cctype>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <system_error>

#include <fmt/format.h>

#include "core/error.h"

namespace softsub::cache {
namespace {

std::string reason(int err) { return std::generic_category().message(err); }

[[noreturn]] void fail(std::string_view action, const std::filesystem::path& path, int err) {
  throw IoError(fmt::format("cannot {} '{}': {}", action, path.string(), reason(err)));
}

/// A name no other writer uses at the same time: `.<name>.tmp.<host>.<pid>.<counter>`,
/// hidden so that tools listing frames skip it. The host tells a later run on shared
/// storage which leftovers it may judge by process id (removeStaleTemporaries).
std::filesystem::path temporaryName(const std::filesystem::path& path) {
  static std::atomic<std::uint64_t> counter{0};
  const std::uint64_t n = counter.fetch_add(1, std::memory_order_relaxed);
  std::filesystem::path tmp = path;
  tmp.replace_filename(fmt::format(".{}.tmp.{}.{}.{}", path.filename().string(), hostTag(),
                                   static_cast<long>(::getpid()), n));
  return tmp;
}

/// Writes every byte, retrying short writes and interrupted calls; returns 0 or errno.
int writeAll(int fd, std::string_view bytes) {
  const char* p = bytes.data();
  std::size_t left = bytes.size();
  while (left > 0) {
    const ssize_t n = ::write(fd, p, left);
    if (n < 0) {
      if (errno == EINTR) continue;
      return errno;
    }
    if (n == 0) return EIO;
    p += n;
    left -= static_cast<std::size_t>(n);
  }
  return 0;
}

}  // namespace

std::string hostTag() {
  static const std::string tag = [] {
    char name[256] = {};
    if (::gethostname(name, sizeof name - 1) != 0 || name[0] == '\0') return std::string("host");
    std::string t;
    for (const char* c = name; *c != '\0'; ++c) {
      const auto u = static_cast<unsigned char>(*c);
      t += (std::isalnum(u) != 0 || *c == '-') ? *c : '_';  // no '.': the name is parsed by its dots
    }
    return t;
  }();
  return tag;
}

std::filesystem::path temporaryPathFor(const std::filesystem::path& path) { return temporaryName(path); }

void writeFileAtomic(const std::filesystem::path& path, std::string_view bytes) {
  if (path.filename().empty()) fail("write", path, EISDIR);
  // O_EXCL: never write through a stale temporary or a link someone placed there. A
  // leftover of a killed run with the same name (same host, a reused process id) makes
  // the next name be tried instead.
  std::filesystem::path tmp = temporaryName(path);
  int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
  for (int tries = 0; fd < 0 && errno == EEXIST && tries < 100; ++tries) {
    tmp = temporaryName(path);
    fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
  }
  if (fd < 0) fail("write", path, errno);

  int err = writeAll(fd, bytes);
  // close() can report a deferred write error (NFS, quota): it must be checked too.
  if (::close(fd) != 0 && err == 0) err = errno;
  if (err == 0 && std::rename(tmp.c_str(), path.c_str()) != 0) err = errno;
  if (err != 0) {
    ::unlink(tmp.c_str());
    fail("write", path, err);
  }
  // No fsync: rename makes the frame complete-or-absent for a killed process, which is
  // what a resumed run relies on; surviving a power cut would cost an fsync per file.
}

void ensureDirectory(const std::filesystem::path& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) {
    throw IoError(fmt::format("cannot create folder '{}': {}", dir.string(), ec.message()));
  }
  if (!std::filesystem::is_directory(dir, ec)) {
    throw IoError(fmt::format("cannot create folder '{}': {}", dir.string(),
                              ec ? ec.message() : reason(ENOTDIR)));
  }
}

std::string readFileBytes(const std::filesystem::path& path) {
  // Only a regular file (after links): a named pipe would block the open until some
  // writer came, and a device such as /dev/zero would be read until memory ran out.
  std::error_code statError;
  const std::filesystem::file_status st = std::filesystem::status(path, statError);
  if (!statError && std::filesystem::exists(st) && !std::filesystem::is_regular_file(st))
    throw IoError(fmt::format("cannot read '{}': {}", path.string(),
                              std::filesystem::is_directory(st)
                                  ? "it is a folder"
                                  : "not a regular file (a pipe, socket or device)"));
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (f == nullptr) fail("read", path, errno);
  std::string bytes;
  std::error_code sizeError;
  const auto expected = std::filesystem::file_size(path, sizeError);
  if (!sizeError) bytes.reserve(static_cast<std::size_t>(expected));
  char chunk[1 << 16];
  for (;;) {
    const std::size_t n = std::fread(chunk, 1, sizeof chunk, f);
    bytes.append(chunk, n);
    if (n < sizeof chunk) break;
  }
  const bool failed = std::ferror(f) != 0;
  const int err = errno;
  std::fclose(f);
  if (failed) fail("read", path, err != 0 ? err : EIO);
  return bytes;
}

}  // namespace softsub::cache
