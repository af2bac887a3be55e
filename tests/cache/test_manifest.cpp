// Per-frame manifests and the cleanup of a killed run's temporaries (issue #7).
#include <sys/wait.h>
#include <unistd.h>

#include <fstream>

#include <fmt/format.h>

#include <gtest/gtest.h>

#include "cache/atomic_file.h"
#include "cache/cache_test_support.h"
#include "cache/manifest.h"
#include "core/error.h"

namespace softsub::cache {
namespace {

namespace fs = std::filesystem;

Manifest sample() {
  Manifest m;
  m.frame = 12;
  m.substeps = 9;
  m.fingerprint = 0x00ab'cdef'0123'4567ULL;
  m.files = {{"pdc/goo Shape.3000.pdc", 1234}, {"scene.0012.sim", 99}};
  m.checkpoint = ManifestEntry{"checkpoint/scene.0012.state", 4096};
  return m;
}

TEST(Manifest, RoundTripsEveryField) {
  const Manifest m = sample();
  const std::string text = encodeManifest(m);
  const Manifest back = decodeManifest(text, "m");
  EXPECT_EQ(back.frame, 12);
  EXPECT_EQ(back.substeps, 9);
  EXPECT_EQ(back.fingerprint, m.fingerprint);
  ASSERT_EQ(back.files.size(), 2u);
  EXPECT_EQ(back.files[0].path, "pdc/goo Shape.3000.pdc");  // a space in a name survives
  EXPECT_EQ(back.files[0].bytes, 1234u);
  ASSERT_TRUE(back.checkpoint);
  EXPECT_EQ(back.checkpoint->path, "checkpoint/scene.0012.state");
  EXPECT_EQ(encodeManifest(back), text);
  Manifest bare = m;
  bare.checkpoint.reset();
  EXPECT_FALSE(decodeManifest(encodeManifest(bare), "m").checkpoint);
}

TEST(Manifest, RefusesCutDamagedAndEscapingManifests) {
  const std::string text = encodeManifest(sample());
  const auto refused = [](const std::string& t) {
    try {
      (void)decodeManifest(t, "run/m.manifest");
    } catch (const InputError& e) {
      EXPECT_EQ(e.where().file, "run/m.manifest");
      return true;
    }
    return false;
  };
  // Every cut short of the whole file is refused (the 'end' line comes last).
  for (std::size_t keep = 0; keep < text.size(); ++keep) EXPECT_TRUE(refused(text.substr(0, keep))) << keep;
  EXPECT_TRUE(refused(text + "file 1 extra\n"));
  for (const auto& [from, to] : std::vector<std::pair<std::string, std::string>>{
           {"frame 12", "frame -1"},
           {"frame 12", "frame 1x"},
           {"substeps 9", "substeps 0"},
           {"fingerprint 00abcdef01234567", "fingerprint 123"},
           {"file 99 scene.0012.sim", "file 99 /etc/passwd"},
           {"file 99 scene.0012.sim", "file 99 ../other/scene.0012.sim"},
           {"file 99 scene.0012.sim", "file x scene.0012.sim"},
           {"file 99 scene.0012.sim", "files 99 scene.0012.sim"},
           {"softsub manifest 1", "softsub manifest 2"}}) {
    std::string bad = text;
    const auto at = bad.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    bad.replace(at, from.size(), to);
    EXPECT_TRUE(refused(bad)) << to;
  }
}

TEST(Manifest, AFrameIsCompleteOnlyWithEveryListedFileAtItsSize) {
  test::ScratchDir tmp;
  const fs::path dir = tmp.path();
  writeFileAtomic(dir / "a.sim", "12345");
  ensureDirectory(dir / "pdc");
  writeFileAtomic(dir / "pdc" / "b.pdc", "xy");
  Manifest m;
  m.files = {entryOf(dir, dir / "a.sim"), entryOf(dir, dir / "pdc" / "b.pdc")};
  EXPECT_EQ(m.files[1].path, "pdc/b.pdc");
  EXPECT_EQ(m.files[1].bytes, 2u);
  EXPECT_EQ(incompleteReason(dir, m, false), "");
  EXPECT_NE(incompleteReason(dir, m, true), "") << "no checkpoint";
  writeFileAtomic(dir / "pdc" / "b.pdc", "xyz");
  EXPECT_NE(incompleteReason(dir, m, false).find("has 3 bytes, not 2"), std::string::npos);
  fs::remove(dir / "a.sim");
  EXPECT_NE(incompleteReason(dir, m, false).find("'a.sim' is missing"), std::string::npos);
  EXPECT_THROW((void)entryOf(dir, dir / "nothing"), IoError);
}

TEST(Manifest, FramesAreFoundByNameForTheirSceneOnly) {
  test::ScratchDir tmp;
  const fs::path dir = tmp.path();
  EXPECT_TRUE(manifestFrames(dir, "s").empty()) << "no manifest folder";
  ensureDirectory(dir / "manifest");
  for (const std::int64_t f : {3, 0, 12345, 10}) writeFileAtomic(manifestPath(dir, "s.v2", f), "");
  EXPECT_EQ(manifestPath(dir, "s.v2", 3), dir / "manifest" / "s.v2.0003.manifest");
  // Other scenes, other suffixes and names that are not a frame tag are not frames.
  for (const char* other : {"s.0001.manifest", "s.v2.0004.manifes", "s.v2.04.manifest", "s.v2.00x1.manifest",
                            "s.v2.00001.manifest", "t.v2.0005.manifest"})
    writeFileAtomic(dir / "manifest" / other, "");
  EXPECT_EQ(manifestFrames(dir, "s.v2"), (std::vector<std::int64_t>{0, 3, 10, 12345}));
  EXPECT_EQ(manifestFrames(dir, "s"), (std::vector<std::int64_t>{1}));
  ensureDirectory(dir / "checkpoint");
  writeFileAtomic(checkpointPath(dir, "s.v2", 7), "");
  EXPECT_EQ(checkpointPath(dir, "s.v2", 7), dir / "checkpoint" / "s.v2.0007.state");
  EXPECT_EQ(checkpointFrames(dir, "s.v2"), (std::vector<std::int64_t>{7}));
}

/// The pid of a process that has exited (reaped), for a "dead writer".
long deadPid() {
  const pid_t pid = ::fork();
  if (pid == 0) ::_exit(0);
  int status = 0;
  ::waitpid(pid, &status, 0);
  return pid;
}

TEST(StaleTemporaries, ThoseOfDeadWritersOnThisHostGoAndEverythingElseStays) {
  test::ScratchDir tmp;
  const fs::path dir = tmp.path();
  ensureDirectory(dir / "pdc");
  ensureDirectory(dir / "deep" / "er");
  const std::string host = hostTag();
  EXPECT_EQ(host.find('.'), std::string::npos);
  // writeFileAtomic's temporaries carry this host and process.
  const std::string own = temporaryPathFor(dir / "s.sim").filename().string();
  EXPECT_EQ(own.rfind(fmt::format(".s.sim.tmp.{}.{}.", host, ::getpid()), 0), 0u) << own;
  const long dead = deadPid();
  const long alive = static_cast<long>(::getppid());  // the test runner's parent lives on
  const std::vector<fs::path> stale = {
      dir / fmt::format(".s.0001.sim.tmp.{}.{}.0", host, dead),
      dir / "pdc" / fmt::format(".gooShape.250.pdc.tmp.{}.{}.17", host, dead),
      // This process's own id on a leftover: an earlier process had it (a container's pid 1).
      dir / fmt::format(".s.0003.sim.tmp.{}.{}.5", host, ::getpid())};
  const std::vector<fs::path> kept = {
      dir / fmt::format(".s.0002.sim.tmp.{}.{}.3", host, alive),          // a live writer's
      dir / fmt::format(".s.0004.sim.tmp.otherhost.{}.3", dead),         // another host's
      dir / "s.0001.sim",                                                  // frames
      dir / fmt::format("s.tmp.{}.{}.0", host, dead),                      // not hidden
      dir / fmt::format(".s.sim.tmp.{}.{}.x", host, dead),                 // counter not a number
      dir / ".notes.tmp",                                                  // no pid
      dir / "deep" / "er" / fmt::format(".x.tmp.{}.{}.0", host, dead)};   // two levels down
  for (const fs::path& p : stale) std::ofstream(p) << "half";
  for (const fs::path& p : kept) std::ofstream(p) << "x";
  EXPECT_EQ(removeStaleTemporaries(dir), stale.size());
  for (const fs::path& p : stale) EXPECT_FALSE(fs::exists(p)) << p;
  for (const fs::path& p : kept) EXPECT_TRUE(fs::exists(p)) << p;
  EXPECT_EQ(removeStaleTemporaries(dir / "missing"), 0u);
}

TEST(StaleTemporaries, ALeftoverWithTheNextTemporaryNameDoesNotStopAWrite) {
  test::ScratchDir tmp;
  const fs::path file = tmp.path() / "s.0001.sim";
  // Occupy the names the next writes would take (a killed run with the same process id).
  const std::string next = temporaryPathFor(file).filename().string();
  const auto dot = next.rfind('.');
  const std::uint64_t n = std::stoull(next.substr(dot + 1));
  for (std::uint64_t k = n + 1; k < n + 4; ++k)
    std::ofstream(tmp.path() / (next.substr(0, dot + 1) + std::to_string(k))) << "left";
  writeFileAtomic(file, "frame");
  EXPECT_EQ(readFileBytes(file), "frame");
}

}  // namespace
}  // namespace softsub::cache
