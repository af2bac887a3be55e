// FrameWriter: the --formats parser, exactly the expected files per format subset,
// byte-identical reruns, and failures that leave complete-or-absent frames.
#include <gtest/gtest.h>

#include "cache/atomic_file.h"
#include "cache/cache_test_support.h"
#include "cache/frame_writer.h"
#include "cache/pdc_format.h"
#include "cache/ply_format.h"
#include "cache/sim_format.h"
#include "core/error.h"

namespace softsub::cache {
namespace {

using test::listFiles;
using test::makeFrame;
using test::ScratchDir;

bool same(const Formats& a, const Formats& b) {
  return a.sim == b.sim && a.pdc == b.pdc && a.ply == b.ply && a.mesh == b.mesh && a.vdb == b.vdb;
}

TEST(Formats, ParsesListsAllAndNone) {
  EXPECT_TRUE(same(parseFormats("sim,pdc,ply"), Formats{true, true, true}));
  EXPECT_TRUE(same(parseFormats("all"), Formats{true, true, true}));
  EXPECT_TRUE(same(parseFormats("none"), Formats{false, false, false}));
  EXPECT_TRUE(same(parseFormats("ply"), Formats{false, false, true}));
  EXPECT_TRUE(same(parseFormats(" sim , ply "), Formats{true, false, true}));
  EXPECT_TRUE(same(parseFormats("pdc,pdc"), Formats{false, true, false}));
  EXPECT_TRUE(same(parseFormats("pdc,all"), Formats{true, true, true}));
}

// The surfaces are opt-in (slow): `all` keeps meaning sim,pdc,ply.
TEST(Formats, SurfacesAreOptInAndRoundTrip) {
  EXPECT_TRUE(same(parseFormats("sim,mesh,vdb"), Formats{true, false, false, true, true}));
  EXPECT_TRUE(same(parseFormats("all,mesh"), Formats{true, true, true, true, false}));
  EXPECT_TRUE(same(parseFormats("vdb"), Formats{false, false, false, false, true}));
  EXPECT_FALSE(parseFormats("all").mesh);
  EXPECT_FALSE(parseFormats("all").vdb);
  EXPECT_FALSE(Formats{}.mesh);
  for (const char* list : {"sim,mesh", "mesh,vdb", "sim,pdc,ply,mesh,vdb", "none", "vdb"})
    EXPECT_EQ(formatsToString(parseFormats(list)), list);
}

TEST(Formats, RefusesUnknownNamesListingTheAllowedOnes) {
  for (const char* bad : {"", "obj", "sim,,ply", "sim,", "none,sim", "SIM", "sim ply"}) {
    try {
      static_cast<void>(parseFormats(bad));
      ADD_FAILURE() << "accepted '" << bad << "'";
    } catch (const InputError& e) {
      EXPECT_EQ(e.where().element, "--formats");
      for (const char* name : {"sim", "pdc", "ply", "all", "none"}) {
        EXPECT_NE(e.allowed().find(name), std::string::npos) << e.allowed();
      }
    }
  }
  try {
    static_cast<void>(parseFormats("sim,obj"));
  } catch (const InputError& e) {
    EXPECT_NE(e.problem().find("'obj'"), std::string::npos) << e.problem();
  }
}

TEST(Formats, ToStringRoundTripsEveryCombination) {
  for (int bits = 0; bits < 8; ++bits) {
    const Formats f{(bits & 1) != 0, (bits & 2) != 0, (bits & 4) != 0};
    EXPECT_TRUE(same(parseFormats(formatsToString(f)), f)) << formatsToString(f);
  }
  EXPECT_EQ(formatsToString(Formats{}), "sim,pdc,ply");
  EXPECT_EQ(formatsToString(Formats{false, false, false}), "none");
}

TEST(FrameWriter, EachFormatSubsetWritesExactlyItsFiles) {
  const FrameSnapshot frame = makeFrame();  // frame 10 at 24 fps, fluids honey and oil
  const std::string sim = "demo.0010.sim";
  const std::string ply = "ply/demo.0010.ply";
  const std::string pdcHoney = "pdc/honeyShape.2500.pdc";
  const std::string pdcOil = "pdc/oilShape.2500.pdc";
  for (int bits = 1; bits < 8; ++bits) {
    const Formats f{(bits & 1) != 0, (bits & 2) != 0, (bits & 4) != 0};
    const ScratchDir scratch;
    const auto dir = scratch.path() / "demoSim";
    FrameWriter writer(dir, "demo", f);
    writer.onFrame(frame);
    std::vector<std::string> expected;
    if (f.pdc) expected.insert(expected.end(), {pdcHoney, pdcOil});
    if (f.ply) expected.push_back(ply);
    if (f.sim) expected.push_back(sim);
    std::vector<std::string> written;
    for (const auto& p : writer.lastWritten())
      written.push_back(p.lexically_relative(dir).string());
    EXPECT_EQ(written, expected) << formatsToString(f);  // .sim last
    std::sort(expected.begin(), expected.end());
    EXPECT_EQ(listFiles(dir), expected) << formatsToString(f);
    EXPECT_EQ(std::filesystem::exists(dir / "pdc"), f.pdc);
    EXPECT_EQ(std::filesystem::exists(dir / "ply"), f.ply);
  }
}

TEST(FrameWriter, NoneWritesNothing) {
  const ScratchDir scratch;
  FrameWriter writer(scratch.path() / "out", "demo", parseFormats("none"));
  writer.onFrame(makeFrame());
  EXPECT_FALSE(std::filesystem::exists(scratch.path() / "out"));
  EXPECT_TRUE(writer.lastWritten().empty());
}

TEST(FrameWriter, FilesHoldTheEncodedFrames) {
  const ScratchDir scratch;
  FrameWriter writer(scratch.path(), "demo");
  FrameSnapshot frame = makeFrame();
  for (std::int64_t f = 0; f < 3; ++f) {
    frame.frame = f;
    frame.time = static_cast<double>(f) / 24.0;
    writer.onFrame(frame);
  }
  EXPECT_EQ(listFiles(scratch.path()).size(), 3U * 4U);
  EXPECT_EQ(readFileBytes(scratch.path() / "demo.0002.sim"), encodeSim(frame));
  EXPECT_EQ(readFileBytes(scratch.path() / "ply" / "demo.0002.ply"), encodePly(frame));
  EXPECT_EQ(readFileBytes(scratch.path() / "pdc" / "oilShape.500.pdc"), encodePdc(frame.fluids[1]));
  EXPECT_EQ(readPdcFile(scratch.path() / "pdc" / "honeyShape.0.pdc").count, 3);
  EXPECT_EQ(readSimFile(scratch.path() / "demo.0001.sim").frame.frame, 1);
  EXPECT_EQ(readPlyFile(scratch.path() / "ply" / "demo.0000.ply").vertexCount, 8U);
}

TEST(FrameWriter, SameSnapshotGivesIdenticalBytes) {
  const ScratchDir a, b;
  FrameWriter first(a.path(), "demo");
  FrameWriter second(b.path(), "demo");
  const FrameSnapshot frame = makeFrame();
  first.onFrame(frame);
  second.onFrame(makeFrame());
  const std::vector<std::string> files = listFiles(a.path());
  ASSERT_EQ(files, listFiles(b.path()));
  std::vector<std::string> before;
  for (const std::string& f : files) {
    EXPECT_EQ(readFileBytes(a.path() / f), readFileBytes(b.path() / f)) << f;
    before.push_back(readFileBytes(a.path() / f));
  }
  first.onFrame(frame);  // rewriting a frame replaces its files with the same bytes
  for (std::size_t i = 0; i < files.size(); ++i)
    EXPECT_EQ(readFileBytes(a.path() / files[i]), before[i]);
  EXPECT_EQ(listFiles(a.path()), files);
}

TEST(FrameWriter, FailureLeavesNoPartialFileAndNoSim) {
  const ScratchDir scratch;
  FrameWriter writer(scratch.path(), "demo");
  std::filesystem::create_directories(scratch.path() / "ply" / "demo.0010.ply" / "x");
  EXPECT_THROW(writer.onFrame(makeFrame()), IoError);
  // PDC files came first and are complete; the PLY is blocked; the .sim (written last) is absent.
  EXPECT_EQ(listFiles(scratch.path()),
            (std::vector<std::string>{"pdc/honeyShape.2500.pdc", "pdc/oilShape.2500.pdc"}));
  EXPECT_EQ(readPdcFile(scratch.path() / "pdc" / "oilShape.2500.pdc").count, 5);
}

TEST(FrameWriter, OutputFolderThatIsAFileThrowsIoError) {
  const ScratchDir scratch;
  writeFileAtomic(scratch.path() / "out", "x");
  FrameWriter writer(scratch.path() / "out", "demo");
  EXPECT_THROW(writer.onFrame(makeFrame()), IoError);
}

TEST(FrameWriter, BadNamesAreRefusedBeforeWriting) {
  const ScratchDir scratch;
  EXPECT_THROW(FrameWriter(scratch.path(), "a/b"), InputError);
  FrameWriter writer(scratch.path() / "out", "demo");
  FrameSnapshot frame = makeFrame();
  frame.fluids[1].name = "../escape";
  EXPECT_THROW(writer.onFrame(frame), InputError);
  EXPECT_FALSE(std::filesystem::exists(scratch.path() / "out"));
}

}  // namespace
}  // namespace softsub::cache
