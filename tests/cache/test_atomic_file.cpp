// Atomic writes: complete or absent, no temporary files left behind, IoError on failure.
#include <sys/stat.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include "cache/atomic_file.h"
#include "cache/cache_test_support.h"
#include "core/error.h"

namespace softsub::cache {
namespace {

using test::listFiles;
using test::ScratchDir;

TEST(AtomicFile, WritesTheBytesAndLeavesNoTemporaryFile) {
  const ScratchDir dir;
  const auto path = dir.path() / "frame.0001.sim";
  const std::string bytes("binary\0data\nwith zero", 21);
  writeFileAtomic(path, bytes);
  EXPECT_EQ(readFileBytes(path), bytes);
  EXPECT_EQ(listFiles(dir.path()), std::vector<std::string>{"frame.0001.sim"});
}

TEST(AtomicFile, ReplacesAnExistingFile) {
  const ScratchDir dir;
  const auto path = dir.path() / "f.ply";
  writeFileAtomic(path, std::string(10000, 'a'));
  writeFileAtomic(path, "short");
  EXPECT_EQ(readFileBytes(path), "short");
  writeFileAtomic(path, "");
  EXPECT_EQ(readFileBytes(path), "");
  EXPECT_EQ(listFiles(dir.path()), std::vector<std::string>{"f.ply"});
}

TEST(AtomicFile, ManyWritesOfTheSameNameLeaveOneFile) {
  const ScratchDir dir;
  for (int i = 0; i < 50; ++i) writeFileAtomic(dir.path() / "x", std::to_string(i));
  EXPECT_EQ(readFileBytes(dir.path() / "x"), "49");
  EXPECT_EQ(listFiles(dir.path()).size(), 1U);
}

TEST(AtomicFile, DirectoryInTheWayThrowsAndLeavesNoFile) {
  const ScratchDir dir;
  const auto path = dir.path() / "blocked.sim";
  std::filesystem::create_directory(path);
  std::filesystem::create_directory(path / "inside");  // a non-empty folder cannot be replaced
  try {
    writeFileAtomic(path, "data");
    FAIL() << "no IoError";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("blocked.sim"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(std::filesystem::is_directory(path));
  EXPECT_TRUE(listFiles(dir.path()).empty());  // no temporary left either
}

TEST(AtomicFile, MissingFolderThrowsIoError) {
  const ScratchDir dir;
  const auto path = dir.path() / "missing" / "f.sim";
  try {
    writeFileAtomic(path, "data");
    FAIL() << "no IoError";
  } catch (const IoError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("missing"), std::string::npos) << what;
    EXPECT_NE(what.find("No such file"), std::string::npos) << what;
  }
  EXPECT_TRUE(listFiles(dir.path()).empty());
}

// Reading takes regular files only: a named pipe would block at the open (no writer),
// a link to /dev/zero would read until memory ran out, a folder is said to be one.
TEST(AtomicFile, ReadingRefusesPipesDevicesAndFolders) {
  const ScratchDir dir;
  const auto fifo = dir.path() / "x.pdc";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  const auto zero = dir.path() / "z.ply";
  std::filesystem::create_symlink("/dev/zero", zero);
  for (const auto& [path, says] :
       {std::pair{fifo, "not a regular file"}, std::pair{zero, "not a regular file"},
        std::pair{dir.path(), "it is a folder"}}) {
    try {
      (void)readFileBytes(path);
      FAIL() << "no IoError for " << path;
    } catch (const IoError& e) {
      EXPECT_NE(std::string(e.what()).find(says), std::string::npos) << e.what();
    }
  }
}

TEST(AtomicFile, ReadOnlyFolderThrowsAndKeepsTheOldFile) {
  if (::geteuid() == 0) GTEST_SKIP() << "root ignores folder permissions";
  const ScratchDir dir;
  const auto sub = dir.path() / "ro";
  std::filesystem::create_directory(sub);
  writeFileAtomic(sub / "f", "old");
  std::filesystem::permissions(
      sub, std::filesystem::perms::owner_read | std::filesystem::perms::owner_exec);
  EXPECT_THROW(writeFileAtomic(sub / "f", "new"), IoError);
  std::filesystem::permissions(sub, std::filesystem::perms::owner_all);
  EXPECT_EQ(readFileBytes(sub / "f"), "old");
  EXPECT_EQ(listFiles(sub), std::vector<std::string>{"f"});
}

TEST(AtomicFile, EnsureDirectoryCreatesParentsAndRefusesFiles) {
  const ScratchDir dir;
  ensureDirectory(dir.path() / "a" / "b" / "c");
  EXPECT_TRUE(std::filesystem::is_directory(dir.path() / "a" / "b" / "c"));
  ensureDirectory(dir.path() / "a");  // existing: fine
  writeFileAtomic(dir.path() / "file", "x");
  EXPECT_THROW(ensureDirectory(dir.path() / "file"), IoError);
  EXPECT_THROW(ensureDirectory(dir.path() / "file" / "sub"), IoError);
}

TEST(AtomicFile, ReadingAMissingFileOrAFolderThrowsIoError) {
  const ScratchDir dir;
  EXPECT_THROW(static_cast<void>(readFileBytes(dir.path() / "nope")), IoError);
  EXPECT_THROW(static_cast<void>(readFileBytes(dir.path())), IoError);
}

}  // namespace
}  // namespace softsub::cache
