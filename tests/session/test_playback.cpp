// Playback of recorded folders: frames in order with the recorded positions, colours and
// sizes from the scene file beside the folder, meshes read once, clear errors.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "cache/atomic_file.h"
#include "cache/manifest.h"
#include "core/error.h"
#include "scene/compile.h"
#include "session/live_session.h"
#include "session/playback.h"
#include "session_test_support.h"

namespace softsub::session {
namespace {

namespace fs = std::filesystem;
using test::positionsOf;
using test::ScratchDir;
using test::smallScene;

/// Records `frames` frames of the small scene (objects included) at `fps` into
/// `<dir>/smallSim`, and with `sceneFile` saves the scene as `<dir>/small.scene`.
LiveSession recordSmall(const fs::path& dir, int frames, bool sceneFile, double fps = 24) {
  scene::SceneDesc d = smallScene(true);
  d.simulation.framesPerSecond = fps;
  LiveSession s(d, "small", dir / "smallSim", cache::Formats{true, false, false});
  for (int f = 0; f < frames; ++f) s.advanceFrame();
  s.writeRecorded();
  if (sceneFile) s.saveScene(dir / "small.scene");
  return s;
}

TEST(Playback, PlaysTheRecordedFramesWithTheSceneBesideIt) {
  ScratchDir dir;
  const LiveSession s = recordSmall(dir.path(), 6, true);
  const Playback p(dir.path() / "smallSim");
  EXPECT_EQ(p.sceneName(), "small");
  ASSERT_EQ(p.frameCount(), 7u);
  EXPECT_EQ(p.frameNumbers(), (std::vector<std::int64_t>{0, 1, 2, 3, 4, 5, 6}));
  ASSERT_TRUE(p.scene().has_value());
  EXPECT_EQ(*p.scene(), s.desc());
  EXPECT_EQ(p.sceneNote(), "");
  EXPECT_EQ(p.framesPerSecond(), 24);
  for (std::size_t i = 0; i < p.frameCount(); ++i) {
    const FrameSnapshot f = p.load(i);
    EXPECT_EQ(f.frame, static_cast<std::int64_t>(i));
    EXPECT_EQ(positionsOf(f), positionsOf(s.recorded()[i])) << i;
    ASSERT_EQ(f.objects.size(), 2u);
    EXPECT_EQ(f.objects[1].rotation, s.recorded()[i].objects[1].rotation);
  }
  const FrameSnapshot last = p.load(6);
  ASSERT_EQ(last.fluids.size(), 2u);
  EXPECT_EQ(last.fluids[1].name, "syrup");
  EXPECT_EQ(last.fluids[1].colour, (std::array<float, 3>{0.9f, 0.5f, 0.1f}));
  EXPECT_EQ(last.fluids[1].particleSize, 0.8f);
  EXPECT_EQ(last.fluids[0].colour, (std::array<float, 3>{0.2f, 0.6f, 0.9f}));
  EXPECT_EQ(last.framesPerSecond, 24);
  // The meshes, once, as the session had them.
  ASSERT_EQ(p.objectMeshes().size(), 2u);
  EXPECT_EQ(p.objectMeshes()[0].name, "crate");
  ASSERT_EQ(p.objectMeshes()[0].vertices.size(), s.objectMeshes()[0].vertices.size());
  for (std::size_t v = 0; v < s.objectMeshes()[0].vertices.size(); ++v) {
    const Vec3& a = s.objectMeshes()[0].vertices[v];
    EXPECT_EQ(p.objectMeshes()[0].vertices[v], (std::array<double, 3>{a.x(), a.y(), a.z()}));
  }
  EXPECT_EQ(p.objectMeshes()[0].triangles, s.objectMeshes()[0].triangles);
  EXPECT_THROW((void)p.load(7), std::out_of_range);
}

TEST(Playback, WithoutASceneFileDefaultsAndTheFramesOwnRate) {
  ScratchDir dir;
  const LiveSession s = recordSmall(dir.path(), 3, false, 30);
  const Playback p(dir.path() / "smallSim");
  EXPECT_FALSE(p.scene().has_value());
  EXPECT_NEAR(p.framesPerSecond(), 30, 1e-9);
  const FrameSnapshot f = p.load(2);
  EXPECT_EQ(f.fluids[1].colour, (std::array<float, 3>{1, 1, 1}));
  EXPECT_EQ(f.fluids[1].particleSize, 1);
  EXPECT_EQ(positionsOf(f), positionsOf(s.recorded()[2]));
}

TEST(Playback, AnInvalidSceneBesideIsNotedAndIgnored) {
  ScratchDir dir;
  recordSmall(dir.path(), 1, false);
  cache::writeFileAtomic(dir.path() / "small.scene", "<Scene version=\"1\"><Nonsense/></Scene>");
  const Playback p(dir.path() / "smallSim");
  EXPECT_FALSE(p.scene().has_value());
  EXPECT_NE(p.sceneNote().find("Nonsense"), std::string::npos) << p.sceneNote();
  EXPECT_EQ(p.frameCount(), 2u);
}

TEST(Playback, OpensAFrameFileAndPicksTheFoldersScene) {
  ScratchDir dir;
  recordSmall(dir.path(), 2, true);
  // A stray scene's frames in the same folder, more of them: the folder's name decides.
  const fs::path folder = dir.path() / "smallSim";
  for (int f = 0; f < 5; ++f)
    fs::copy_file(folder / "small.0000.sim", folder / ("other.000" + std::to_string(f) + ".sim"));
  EXPECT_EQ(Playback(folder).sceneName(), "small");
  EXPECT_EQ(Playback(folder.string() + "/").frameCount(), 3u);
  // mesh and render took one silently: the choice is noted, with how to take the other.
  ASSERT_EQ(Playback(folder).notes().size(), 1u);
  EXPECT_EQ(
      Playback(folder).notes()[0],
      "the folder holds frames of 2 scenes: 'small' taken, not 'other' (give one of a scene's .sim files to "
      "take that scene)");
  const Playback other(folder / "other.0003.sim");
  EXPECT_EQ(other.sceneName(), "other");
  EXPECT_TRUE(other.notes().empty());  // chosen by its frame file: nothing to note
  EXPECT_EQ(other.frameCount(), 5u);
  EXPECT_EQ(other.frameNumber(4), 4);
  // Any folder of frames: the scene with the most.
  const fs::path loose = dir.path() / "loose";
  fs::create_directories(loose / "smallGeo");
  fs::copy(folder / "smallGeo", loose / "smallGeo");
  fs::copy_file(folder / "small.0001.sim", loose / "small.0001.sim");
  fs::copy_file(folder / "small.0002.sim", loose / "small.0002.sim");
  fs::copy_file(folder / "other.0001.sim", loose / "other.0001.sim");
  const Playback any(loose);
  EXPECT_EQ(any.sceneName(), "small");
  EXPECT_EQ(any.frameNumbers(), (std::vector<std::int64_t>{1, 2}));
  EXPECT_TRUE(any.scene().has_value());  // small.scene lies beside "loose" too
  fs::remove(dir.path() / "small.scene");
  const Playback bare(loose);
  EXPECT_FALSE(bare.scene().has_value());
  EXPECT_NEAR(bare.framesPerSecond(), 24, 1e-9);  // frame 1 at 1/24 s
}

// A fresh run into a folder keeps an earlier, longer run's later frames (it never
// deletes cache files) and removes that run's manifests; render and mesh once played
// and meshed those frames as the last run's. With manifests, frames past the last one
// are left out and said to be; a folder without any manifest plays every frame.
TEST(Playback, FramesPastTheLastManifestAreAnEarlierRunsAndLeftOut) {
  ScratchDir dir;
  const LiveSession s = recordSmall(dir.path(), 6, true);
  const fs::path folder = dir.path() / "smallSim";
  const Playback all(folder);
  EXPECT_EQ(all.frameCount(), 7u);
  EXPECT_TRUE(all.notes().empty());
  fs::create_directories(folder / "manifest");
  for (const std::int64_t f : {0, 1, 2}) std::ofstream(cache::manifestPath(folder, "small", f)) << "x\n";
  const Playback kept(folder);
  ASSERT_EQ(kept.frameCount(), 3u);
  EXPECT_EQ(kept.frameNumbers().back(), 2);
  ASSERT_EQ(kept.notes().size(), 1u);
  EXPECT_NE(kept.notes()[0].find("frames 3 to 6 of 'small' left out"), std::string::npos) << kept.notes()[0];
  EXPECT_EQ(positionsOf(kept.load(2)), positionsOf(all.load(2)));
}

TEST(Playback, AFolderWithoutFramesSaysWhatItExpects) {
  ScratchDir dir;
  cache::writeFileAtomic(dir.path() / "notes.txt", "hello");
  cache::writeFileAtomic(dir.path() / "broken.sim", "no frame number");
  try {
    (void)Playback(dir.path());
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("<scene>.NNNN.sim"), std::string::npos) << e.what();
    EXPECT_NE(e.allowed().find("softsub run"), std::string::npos);
  }
  EXPECT_THROW((void)Playback(dir.path() / "missing"), IoError);
  EXPECT_THROW((void)Playback(dir.path() / "notes.txt"), InputError);
}

TEST(Playback, AMissingOrEscapingMeshIsAnError) {
  ScratchDir dir;
  recordSmall(dir.path(), 1, false);
  const fs::path folder = dir.path() / "smallSim";
  fs::remove(folder / "smallGeo" / "brick.obj");
  EXPECT_THROW((void)Playback(folder), IoError);
  std::string text = cache::readFileBytes(folder / "small.0000.sim");
  const std::string from = "smallGeo/crate.obj";
  text.replace(text.find(from), from.size(), "../../crate.obj");
  cache::writeFileAtomic(folder / "small.0000.sim", text);
  try {
    (void)Playback(folder);
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("not inside the recorded folder"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace softsub::session
