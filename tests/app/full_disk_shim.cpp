// A disk that fills up, for the tests: preloaded (LD_PRELOAD) into softsub, it lets
// writes to files (descriptors above 2) through until SOFTSUB_TEST_DISK_BYTES bytes have
// been written in all, then fails every further one with ENOSPC, as a full disk does.
#include <dlfcn.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdlib>

namespace {

using WriteFn = ssize_t (*)(int, const void*, size_t);
std::atomic<long long> written{0};

}  // namespace

extern "C" ssize_t write(int fd, const void* buf, size_t n) {
  static const WriteFn real = reinterpret_cast<WriteFn>(dlsym(RTLD_NEXT, "write"));
  if (fd > 2) {
    const char* limit = std::getenv("SOFTSUB_TEST_DISK_BYTES");
    const long long budget = limit != nullptr ? std::atoll(limit) : -1;
    const auto size = static_cast<long long>(n);
    if (budget >= 0 && written.fetch_add(size) + size > budget) {
      written.fetch_sub(size);
      errno = ENOSPC;
      return -1;
    }
  }
  return real(fd, buf, n);
}
