// One writer per output folder (cache::FolderLock): a second holder is refused with the
// first one's name, the lock file goes with its holder, and a lock file left by a
// process that is gone (a SIGKILL) blocks nothing.
#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <fmt/format.h>

#include "cache/cache_test_support.h"
#include "cache/folder_lock.h"
#include "core/error.h"

namespace softsub::cache {
namespace {

using test::ScratchDir;

TEST(FolderLock, ASecondHolderIsRefusedWithTheFirstsNameUntilItEnds) {
  ScratchDir dir;
  const std::filesystem::path folder = dir.path() / "shot" / "out";
  {
    const FolderLock first(folder);  // creates the folder
    ASSERT_TRUE(first.held());
    ASSERT_TRUE(std::filesystem::exists(folder / FolderLock::kFileName));
    try {
      const FolderLock second(folder);
      FAIL() << "a second lock was taken";
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("is being written by another softsub run (pid " + std::to_string(::getpid()) +
                          " on host "),
                std::string::npos)
          << what;
      EXPECT_NE(what.find("--out"), std::string::npos) << what;
    }
  }
  EXPECT_FALSE(std::filesystem::exists(folder / FolderLock::kFileName)) << "the holder removes it";
  const FolderLock again(folder);
  EXPECT_TRUE(again.held());
}

// A lock file whose holder is gone (left on disk, no process holds its lock) is taken
// over; one another open file description holds (as another process would) is not.
TEST(FolderLock, ALeftoverFileIsTakenOverAndAHeldOneIsNot) {
  ScratchDir dir;
  const std::filesystem::path file = dir.path() / FolderLock::kFileName;
  {
    const int fd = ::open(file.c_str(), O_RDWR | O_CREAT, 0666);
    ASSERT_GE(fd, 0);
    ASSERT_EQ(::write(fd, "pid 1 on host gone, since then\n", 31), 31);
    ::close(fd);
  }
  {
    const FolderLock lock(dir.path());
    EXPECT_TRUE(lock.held());
  }
  const int other = ::open(file.c_str(), O_RDWR | O_CREAT, 0666);
  ASSERT_GE(other, 0);
  ASSERT_EQ(::write(other, "pid 42 on host farm7, since 10:00\n", 34), 34);
  ASSERT_EQ(::flock(other, LOCK_EX | LOCK_NB), 0);
  EXPECT_THROW(
      {
        try {
          const FolderLock lock(dir.path());
        } catch (const InputError& e) {
          EXPECT_NE(std::string(e.what()).find("(pid 42 on host farm7, since 10:00)"), std::string::npos)
              << e.what();
          throw;
        }
      },
      InputError);
  ::close(other);
}

}  // namespace
}  // namespace softsub::cache
