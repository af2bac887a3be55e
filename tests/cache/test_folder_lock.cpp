// One writer per output folder (cache::FolderLock): a second holder is refused with the
// first one's name, the lock file goes with its holder, and a lock file left by a
// process that is gone (a SIGKILL) blocks nothing.
// These tests hold two locks in one process: flock treats two open file descriptions
// of one file apart, as two processes, on local file systems (a temporary folder on a
// mount where flock is emulated by POSIX locks, as NFS does, would let the second in).
#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <fmt/format.h>

#include "cache/atomic_file.h"
#include "cache/cache_test_support.h"
#include "cache/folder_lock.h"
#include "core/error.h"

namespace softsub::cache {
namespace {

using test::ScratchDir;

FolderLock lockFor(const std::filesystem::path& folder, const std::string& command = "run") {
  return FolderLock(folder, command, {"command line", 0, "--out"}, "wait for it to end");
}

TEST(FolderLock, ASecondHolderIsRefusedWithTheFirstsNameUntilItEnds) {
  ScratchDir dir;
  const std::filesystem::path folder = dir.path() / "shot" / "out";
  {
    const FolderLock first(folder, "mesh", {"command line", 0, "SIMDIR"}, "");  // creates the folder
    ASSERT_TRUE(first.held());
    ASSERT_TRUE(std::filesystem::exists(folder / FolderLock::kFileName));
    const std::optional<std::string> who = FolderLock::holder(folder);
    ASSERT_TRUE(who.has_value());
    EXPECT_EQ(
        who->rfind("softsub mesh, pid " + std::to_string(::getpid()) + " on host " + hostTag() + ", since ",
                   0),
        0u)
        << *who;
    try {
      const FolderLock second(folder, "run", {"command line", 0, "--out"}, "wait for it to end");
      FAIL() << "a second lock was taken";
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("--out: '" + folder.string() +
                          "' is being written by another softsub process (softsub "
                          "mesh, pid " +
                          std::to_string(::getpid()) + " on host "),
                std::string::npos)
          << what;
      EXPECT_NE(what.find("(allowed: wait for it to end)"), std::string::npos) << what;
    }
  }
  EXPECT_FALSE(std::filesystem::exists(folder / FolderLock::kFileName)) << "the holder removes it";
  EXPECT_FALSE(FolderLock::holder(folder).has_value());
  const FolderLock again = lockFor(folder);
  EXPECT_TRUE(again.held());
}

// A lock file whose holder is gone (left on disk, no process holds its lock) is taken
// over, and `holder` does not name a process of this host that is gone; one that
// another open file description holds (as another process would) is not taken.
TEST(FolderLock, ALeftoverFileIsTakenOverAndAHeldOneIsNot) {
  ScratchDir dir;
  const std::filesystem::path file = dir.path() / FolderLock::kFileName;
  {
    const std::string gone = fmt::format("softsub run, pid 999999999 on host {}, since then\n", hostTag());
    const int fd = ::open(file.c_str(), O_RDWR | O_CREAT, 0666);
    ASSERT_GE(fd, 0);
    ASSERT_EQ(::write(fd, gone.data(), gone.size()), static_cast<ssize_t>(gone.size()));
    ::close(fd);
  }
  EXPECT_FALSE(FolderLock::holder(dir.path()).has_value());
  {
    const FolderLock lock = lockFor(dir.path());
    EXPECT_TRUE(lock.held());
  }
  const int other = ::open(file.c_str(), O_RDWR | O_CREAT, 0666);
  ASSERT_GE(other, 0);
  const std::string farm = "softsub run, pid 42 on host farm7, since 10:00\n";
  ASSERT_EQ(::write(other, farm.data(), farm.size()), static_cast<ssize_t>(farm.size()));
  ASSERT_EQ(::flock(other, LOCK_EX | LOCK_NB), 0);
  // Another host's process may live: named.
  EXPECT_EQ(FolderLock::holder(dir.path()).value_or(""), "softsub run, pid 42 on host farm7, since 10:00");
  EXPECT_THROW(
      {
        try {
          const FolderLock lock = lockFor(dir.path());
        } catch (const InputError& e) {
          EXPECT_NE(std::string(e.what()).find("(softsub run, pid 42 on host farm7, since 10:00)"),
                    std::string::npos)
              << e.what();
          throw;
        }
      },
      InputError);
  ::close(other);
}

// A folder this process cannot write: no lock and no error here (the writes that
// follow fail with their own message), and no file left.
TEST(FolderLock, AFolderThatCannotBeWrittenHasNoLockAndNoError) {
  if (::geteuid() == 0) GTEST_SKIP() << "root writes anywhere";
  ScratchDir dir;
  const std::filesystem::path folder = dir.path() / "ro";
  std::filesystem::create_directories(folder);
  std::filesystem::permissions(folder,
                               std::filesystem::perms::owner_read | std::filesystem::perms::owner_exec);
  {
    const FolderLock lock = lockFor(folder);
    EXPECT_FALSE(lock.held());
  }
  EXPECT_FALSE(std::filesystem::exists(folder / FolderLock::kFileName));
  std::filesystem::permissions(folder, std::filesystem::perms::owner_all);
}

}  // namespace
}  // namespace softsub::cache
