// `softsub render` and `softsub run --preview` end to end: the pictures written, their
// size, what they show (each fluid's colour where its particles project, the floor at the
// bottom, object meshes), recorded folders drawn like the scene, the movie, and refusals.
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "app_test_util.h"
#include "cache/sim_format.h"
#include "picture_checks.h"

namespace softsub::apptest {
namespace {

constexpr int kWidth = 320;
constexpr int kHeight = 200;

std::vector<std::string> pictureNames(const std::string& stem, int first, int last) {
  std::vector<std::string> out;
  for (int f = first; f <= last; ++f) out.push_back(fmt::format("{}.{:04}.png", stem, f));
  return out;
}

/// `softsub render <input> --out <out> --width 320 --height 200 <extra> -q`.
RunResult render(const fs::path& input, const fs::path& out, const std::string& extra, const fs::path& cwd) {
  return runSoftsub(fmt::format("render {} --out {} --width {} --height {} {} -q", quote(input), quote(out),
                                kWidth, kHeight, extra),
                    cwd);
}

/// Each fluid of `frame` shows in its colour where its particles' centroid projects, and
/// not where no particle projects; the picture is not blank.
void expectFluidsWhereTheyProject(const render::Image& im, const render::Camera& cam,
                                  const FrameSnapshot& frame) {
  ASSERT_FALSE(frame.fluids.empty());
  EXPECT_GT(distinctColours(im), 500u) << "blank or nearly blank picture";
  EXPECT_GT(brightnessSpread(im), 10.0);
  // A window about one particle across (the centroid of a filled block is seen through
  // its front face, made of particles of the same fluid).
  const int half = std::max(2, static_cast<int>(largestPixelRadius(cam, frame, im.height)));
  for (const FluidSnapshot& f : frame.fluids) {
    SCOPED_TRACE(f.name);
    const auto px = render::projectToPixel(cam, centroid(f), im.width, im.height);
    ASSERT_TRUE(px);
    ASSERT_GE((*px)[0], 0);
    ASSERT_LT((*px)[0], im.width);
    ASSERT_GE((*px)[1], 0);
    ASSERT_LT((*px)[1], im.height);
    EXPECT_GE(shareShowing(im, (*px)[0], (*px)[1], half, f.colour), 0.5)
        << "fluid colour missing around its centroid's pixel " << (*px)[0] << ", " << (*px)[1];
    // Another fluid of a clearly different hue is not what is seen there.
    for (const FluidSnapshot& g : frame.fluids) {
      if (&g == &f || !distinguishable(f.colour, g.colour)) continue;
      EXPECT_LT(shareShowing(im, (*px)[0], (*px)[1], half, g.colour), 0.2) << g.name << " seen at " << f.name;
    }
    // At least a few hundred pixels of it over the whole picture.
    EXPECT_GT(shareShowing(im, f.colour) * im.width * im.height, 200.0);
  }
  // Where no particle projects (far from all of them) no fluid colour shows.
  const auto [empty, distance] = emptiestPixel(cam, frame, im.width, im.height);
  ASSERT_GT(distance, 3 * half) << "no empty region in this picture";
  for (const FluidSnapshot& f : frame.fluids)
    EXPECT_EQ(shareShowing(im, empty[0], empty[1], half, f.colour), 0.0)
        << f.name << " seen in the empty region at " << empty[0] << ", " << empty[1];
}

class RenderScene : public ::testing::TestWithParam<std::string> {};

TEST_P(RenderScene, FramesArePicturesOfEachFluidWhereItsParticlesProject) {
  TempDir tmp;
  const fs::path scene = copyInto(examplesDir() / GetParam(), tmp.path());
  const std::string stem = scene.stem().string();
  const fs::path out = tmp / "pictures";
  const RunResult r = render(scene, out, "--frames 0:2", tmp.path());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.err, "") << "-q prints nothing but errors";
  EXPECT_EQ(listFrameFiles(out), pictureNames(stem, 0, 2));
  for (const std::string& name : pictureNames(stem, 0, 2)) {
    const render::Image im = readPng(out / name);
    EXPECT_EQ(im.width, kWidth) << name;
    EXPECT_EQ(im.height, kHeight) << name;
    EXPECT_GT(distinctColours(im), 500u) << name;
  }
  const scene::SceneDesc desc = scene::readSceneFile(scene.string());
  const render::Camera cam = cameraOf(desc);
  const FrameSnapshot frame = initialFrame(desc);
  ASSERT_EQ(frame.fluids.size(), desc.fluids.size());
  for (std::size_t k = 0; k < desc.fluids.size(); ++k)  // the colours come from the scene
    EXPECT_EQ(frame.fluids[k].colour, (std::array<float, 3>{static_cast<float>(desc.fluids[k].colour.x()),
                                                            static_cast<float>(desc.fluids[k].colour.y()),
                                                            static_cast<float>(desc.fluids[k].colour.z())}));
  expectFluidsWhereTheyProject(readPng(out / pictureNames(stem, 0, 0)[0]), cam, frame);
}

INSTANTIATE_TEST_SUITE_P(Examples, RenderScene, ::testing::Values("two-fluids.scene", "honey-drop.scene"),
                         [](const auto& p) {
                           std::string n = fs::path(p.param).stem().string();
                           std::replace(n.begin(), n.end(), '-', '_');
                           return n;
                         });

TEST(RenderCli, TheFloorIsGreyAtTheBottomOfThePicture) {
  // honey-drop: a ball above the middle of the floor, which stays in sight.
  TempDir tmp;
  const fs::path scene = copyInto(examplesDir() / "honey-drop.scene", tmp.path());
  const fs::path out = tmp / "pictures";
  const RunResult r = render(scene, out, "--frames 0", tmp.path());
  ASSERT_EQ(r.code, 0) << r.err;
  ASSERT_EQ(listFrameFiles(out), pictureNames("honey-drop", 0, 0));
  const render::Image im = readPng(out / "honey-drop.0000.png");
  const scene::SceneDesc desc = scene::readSceneFile(scene.string());
  ASSERT_TRUE(desc.environment);
  const render::Camera cam = cameraOf(desc);
  const FrameSnapshot frame = initialFrame(desc);
  const Vec3 middle(0, 0, 0);  // the container's floor is y = 0, centred on x = z = 0
  ASSERT_FALSE(hiddenByParticles(cam, middle, frame)) << "the scene hides the floor's middle";
  const auto px = render::projectToPixel(cam, middle, im.width, im.height);
  ASSERT_TRUE(px);
  EXPECT_GT((*px)[1], im.height / 2.0) << "the floor's middle is not in the lower half";
  EXPECT_LT((*px)[1], im.height);
  // Grey (the floor's checker is neutral) and lighter than the dark background, in a
  // window a few pixels across (the checker's cells differ a little).
  const Hsv floor = meanHsv(im, (*px)[0], (*px)[1], 3);
  EXPECT_LT(floor.saturation, 0.12);
  EXPECT_GT(floor.value, 0.35);
  for (const FluidSnapshot& f : frame.fluids)
    EXPECT_EQ(shareShowing(im, (*px)[0], (*px)[1], 3, f.colour), 0.0);
  // The top left corner looks above the horizon (the top of the view is tilted up) and
  // is far from every particle: background there, darker than the floor.
  ASSERT_GT(cam.pitch + 0.5 * cam.fovY, 0);
  const double corner[2] = {2, 2};
  const double clearance = 3 * largestPixelRadius(cam, frame, im.height);
  for (const FluidSnapshot& f : frame.fluids) {
    for (std::size_t k = 0; k < f.count(); ++k) {
      const auto q = render::projectToPixel(
          cam, Vec3(f.positions[3 * k], f.positions[3 * k + 1], f.positions[3 * k + 2]), im.width, im.height);
      if (!q) continue;
      ASSERT_GT(std::hypot((*q)[0] - corner[0], (*q)[1] - corner[1]), clearance);
    }
  }
  EXPECT_LT(meanHsv(im, corner[0], corner[1], 2).value, floor.value);
}

/// Records `two-fluids` (frames 0..3, .sim only) into `<dir>/two-fluidsSim`, beside a copy of the scene.
fs::path recordTwoFluids(const fs::path& dir) {
  const fs::path scene = copyInto(examplesDir() / "two-fluids.scene", dir);
  const fs::path recorded = dir / "two-fluidsSim";
  const RunResult run =
      runSoftsub("run " + quote(scene) + " --frames 3 --formats sim -q --out " + quote(recorded), dir);
  EXPECT_EQ(run.code, 0) << run.err;
  return recorded;
}

TEST(RenderCli, ARecordedFolderIsDrawnLikeTheScene) {
  TempDir tmp;
  const fs::path recorded = recordTwoFluids(tmp.path());
  const fs::path scene = tmp / "two-fluids.scene";
  const fs::path fromScene = tmp / "fromScene", fromFolder = tmp / "fromFolder";
  const RunResult a = render(scene, fromScene, "--frames 1:3", tmp.path());
  ASSERT_EQ(a.code, 0) << a.err;
  const RunResult b = render(recorded, fromFolder, "--frames 1:3", tmp.path());
  ASSERT_EQ(b.code, 0) << b.err;
  // Named after the scene in both cases.
  EXPECT_EQ(listFrameFiles(fromScene), pictureNames("two-fluids", 1, 3));
  ASSERT_EQ(listFrameFiles(fromFolder), pictureNames("two-fluids", 1, 3));
  // The `.sim` text holds every float exactly (shortest round-trip digits), and the colours,
  // sizes, container and camera come from the scene beside the folder: the same frames
  // give the same pictures, pixel for pixel.
  for (const std::string& name : pictureNames("two-fluids", 1, 3)) {
    const render::Image x = readPng(fromScene / name), y = readPng(fromFolder / name);
    ASSERT_EQ(x.width, kWidth);
    ASSERT_EQ(x.height, kHeight);
    EXPECT_EQ(differingPixels(x, y), 0u) << name;
  }
}

// Shells complete folder names with a trailing slash: the scene beside the folder must
// still be found (colours, container, camera).
TEST(RenderCli, AFolderNamedWithATrailingSlashOrByOneOfItsFramesIsDrawnTheSame) {
  TempDir tmp;
  const fs::path recorded = recordTwoFluids(tmp.path());
  const RunResult a = render(recorded, tmp / "plain", "--frames 1", tmp.path());
  ASSERT_EQ(a.code, 0) << a.err;
  const RunResult b = render(recorded.string() + "/", tmp / "slash", "--frames 1", tmp.path());
  ASSERT_EQ(b.code, 0) << b.err;
  ASSERT_EQ(listFrameFiles(tmp / "slash"), pictureNames("two-fluids", 1, 1));
  EXPECT_EQ(differingPixels(readPng(tmp / "plain" / "two-fluids.0001.png"),
                            readPng(tmp / "slash" / "two-fluids.0001.png")),
            0u);
  // One .sim file of the recording plays its folder.
  const RunResult c = render(recorded / "two-fluids.0000.sim", tmp / "file", "--frames 1", tmp.path());
  ASSERT_EQ(c.code, 0) << c.err;
  ASSERT_EQ(listFrameFiles(tmp / "file"), pictureNames("two-fluids", 1, 1));
  EXPECT_EQ(differingPixels(readPng(tmp / "plain" / "two-fluids.0001.png"),
                            readPng(tmp / "file" / "two-fluids.0001.png")),
            0u);
}

// "Every option is checked before anything is created" (docs/cli.md) holds for a recorded
// folder too, whose frames are only known once it is opened.
TEST(RenderCli, ARangeOutsideARecordingIsRefusedBeforeAnythingIsCreated) {
  TempDir tmp;
  const fs::path recorded = recordTwoFluids(tmp.path());
  const fs::path out = tmp / "pictures";
  const RunResult r = render(recorded, out, "--frames 10:20", tmp.path());
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("--frames"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));
}

// A recording is drawn as it was simulated: --substeps and --max-particles, which change how
// a scene is simulated, were silently ignored with one; they are refused, naming the option,
// before anything is created.
TEST(RenderCli, SimulationOptionsWithARecordingAreRefused) {
  TempDir tmp;
  const fs::path recorded = recordTwoFluids(tmp.path());
  const fs::path out = tmp / "pictures";
  for (const auto& [option, value] : {std::pair<std::string, std::string>{"--substeps", " 4"},
                                      std::pair<std::string, std::string>{"--max-particles", " 100000"}}) {
    const RunResult r = render(recorded, out, option + value, tmp.path());
    EXPECT_EQ(r.code, 2) << r.err;
    EXPECT_EQ(r.err.rfind("error: command line: " + option + ": is for a scene: ", 0), 0u) << r.err;
    EXPECT_NE(r.err.find("is a recording"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out)) << option;
    // The same option with the scene is taken.
    const RunResult scene = render(tmp / "two-fluids.scene", out, option + value + " --frames 0", tmp.path());
    EXPECT_EQ(scene.code, 0) << scene.err;
    fs::remove_all(out);
  }
}

// The scene's name names the pictures: a scene file named with a tab wrote PNG names with
// a tab. As for run, the name is checked before anything is made and the error names the
// scene file; a recorded folder whose frames carry such a name is refused naming the folder.
TEST(RenderCli, ASceneNameThatCannotBeAFileNameIsRefusedBeforeAnythingIsMade) {
  TempDir tmp;
  const std::string name = "a\tb.scene";
  fs::copy_file(examplesDir() / "two-fluids.scene", tmp / name);
  const RunResult r = render(tmp / name, tmp / "o", "--frames 0", tmp.path());
  EXPECT_EQ(r.code, 2) << r.err;
  const std::string expected =
      "error: " + (tmp / "a\\tb.scene").string() + ": scene name: name 'a?b' cannot be used";
  EXPECT_EQ(r.err.rfind(expected, 0), 0u) << r.err;
  EXPECT_FALSE(fs::exists(tmp / "o"));

  const fs::path recorded = recordTwoFluids(tmp.path());
  fs::create_directory(tmp / "tabbed");
  fs::copy_file(recorded / "two-fluids.0000.sim", tmp / "tabbed" / "a\tb.0000.sim");
  const RunResult rec = render(tmp / "tabbed", tmp / "p", "", tmp.path());
  EXPECT_EQ(rec.code, 2) << rec.err;
  EXPECT_EQ(
      rec.err.rfind("error: " + (tmp / "tabbed").string() + ": scene name: name 'a?b' cannot be used", 0), 0u)
      << rec.err;
  EXPECT_FALSE(fs::exists(tmp / "p"));
}

TEST(RenderCli, AnObjectIsDrawnAsItsMeshAtItsPose) {
  TempDir tmp;
  const fs::path scene = copyInto(examplesDir() / "box-on-jelly.scene", tmp.path());
  // The same scene without its object.
  std::string text = readFile(scene);
  const auto from = text.find("<Object>"), to = text.find("</Object>");
  ASSERT_NE(from, std::string::npos);
  ASSERT_NE(to, std::string::npos);
  text.erase(from, to + std::string("</Object>").size() - from);
  const fs::path bare = tmp / "jelly-only.scene";
  {
    std::FILE* f = std::fopen(bare.c_str(), "wb");
    ASSERT_NE(f, nullptr);
    std::fwrite(text.data(), 1, text.size(), f);
    std::fclose(f);
  }
  const RunResult a = render(scene, tmp / "with", "--frames 0", tmp.path());
  ASSERT_EQ(a.code, 0) << a.err;
  const RunResult b = render(bare, tmp / "without", "--frames 0", tmp.path());
  ASSERT_EQ(b.code, 0) << b.err;
  const render::Image with = readPng(tmp / "with" / "box-on-jelly.0000.png");
  const render::Image without = readPng(tmp / "without" / "jelly-only.0000.png");
  ASSERT_EQ(with.rgb.size(), without.rgb.size());

  // Where the mesh lands: its vertices at the object's frame-0 pose, projected.
  const scene::SceneDesc desc = scene::readSceneFile(scene.string());
  const render::Camera cam = cameraOf(desc);
  scene::Compiled compiled = scene::compile(desc);
  ASSERT_EQ(compiled.objectMeshes.size(), 1u);
  const geometry::TriangleMesh mesh = compiled.objectMeshes[0];
  const solver::Simulation sim(compiled.model, std::move(compiled.state));
  const FrameSnapshot frame = sim.snapshot();
  ASSERT_EQ(frame.objects.size(), 1u);
  double lo[2] = {1e300, 1e300}, hi[2] = {-1e300, -1e300};
  Vec3 middle(0, 0, 0);
  for (const Vec3& v : mesh.vertices) {
    const Vec3 w = placed(frame.objects[0], v);
    middle += w / static_cast<double>(mesh.vertices.size());
    const auto px = render::projectToPixel(cam, w, with.width, with.height);
    ASSERT_TRUE(px);
    for (int k = 0; k < 2; ++k) {
      lo[k] = std::min(lo[k], (*px)[k]);
      hi[k] = std::max(hi[k], (*px)[k]);
    }
  }
  const auto centre = render::projectToPixel(cam, middle, with.width, with.height);
  ASSERT_TRUE(centre);
  ASSERT_GT(hi[0] - lo[0], 10) << "the object is too small in the picture to test";

  // At the mesh's centre: the mesh's neutral grey, lit, brighter than what is behind it
  // in the picture without the object; the jelly's colour is not what is seen.
  const Hsv on = meanHsv(with, (*centre)[0], (*centre)[1], 2);
  const Hsv off = meanHsv(without, (*centre)[0], (*centre)[1], 2);
  EXPECT_LT(on.saturation, 0.2);
  EXPECT_GT(on.value, off.value + 0.15);
  EXPECT_EQ(shareShowing(with, (*centre)[0], (*centre)[1], 2, frame.fluids[0].colour), 0.0);
  // The pictures differ, and (almost) only where the mesh projects: its projected
  // bounding box, a pixel of margin for rasterisation.
  std::size_t differing = 0, inside = 0;
  for (int y = 0; y < with.height; ++y)
    for (int x = 0; x < with.width; ++x) {
      const std::uint8_t *p = with.at(x, y), *q = without.at(x, y);
      if (p[0] == q[0] && p[1] == q[1] && p[2] == q[2]) continue;
      ++differing;
      inside += x >= lo[0] - 1 && x <= hi[0] + 1 && y >= lo[1] - 1 && y <= hi[1] + 1;
    }
  EXPECT_GT(differing, static_cast<std::size_t>(0.3 * (hi[0] - lo[0]) * (hi[1] - lo[1])));
  EXPECT_GE(static_cast<double>(inside), 0.95 * static_cast<double>(differing));
  // The jelly is drawn in both.
  const auto jelly = render::projectToPixel(cam, centroid(frame.fluids[0]), with.width, with.height);
  ASSERT_TRUE(jelly);
  EXPECT_GE(shareShowing(with, (*jelly)[0], (*jelly)[1], 2, frame.fluids[0].colour), 0.5);
  EXPECT_GE(shareShowing(without, (*jelly)[0], (*jelly)[1], 2, frame.fluids[0].colour), 0.5);
}

TEST(RenderCli, SurfaceDrawsEachFluidAsItsMeshWhereItsParticlesAre) {
  // --surface draws each fluid as its blobby surface: its colour where the particles
  // project and nowhere empty (as for particles), in a picture that is not the particles'.
  TempDir tmp;
  const fs::path scene = copyInto(examplesDir() / "two-fluids.scene", tmp.path());
  const RunResult r = render(scene, tmp / "s", "--frames 0 --surface", tmp.path());
  ASSERT_EQ(r.code, 0) << r.err;
  ASSERT_EQ(render(scene, tmp / "p", "--frames 0", tmp.path()).code, 0);
  const scene::SceneDesc desc = scene::readSceneFile(scene.string());
  const render::Image surface = readPng(tmp / "s" / pictureNames("two-fluids", 0, 0)[0]);
  const render::Image particles = readPng(tmp / "p" / pictureNames("two-fluids", 0, 0)[0]);
  expectFluidsWhereTheyProject(surface, cameraOf(desc), initialFrame(desc));
  EXPECT_GT(differingPixels(surface, particles), static_cast<std::size_t>(kWidth * kHeight / 100))
      << "the surface picture is the particle picture";
}

struct Refusal {
  std::string name;    ///< test name
  std::string args;    ///< after the input, before --out
  std::string naming;  ///< what the message must name
};

class RenderRefuses : public ::testing::TestWithParam<Refusal> {};

TEST_P(RenderRefuses, WithExitTwoNamingTheOptionAndCreatesNothing) {
  TempDir tmp;
  const fs::path scene = copyInto(examplesDir() / "two-fluids.scene", tmp.path());
  const fs::path out = tmp / "pictures";
  const RunResult r =
      runSoftsub(fmt::format("render {} {} --out {}", quote(scene), GetParam().args, quote(out)), tmp.path());
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find(GetParam().naming), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out)) << "--out created for a refused command";
  EXPECT_EQ(listEntries(tmp.path()), std::vector<std::string>{"two-fluids.scene"});
}

INSTANTIATE_TEST_SUITE_P(
    BadOptions, RenderRefuses,
    ::testing::Values(Refusal{"WidthTooSmall", "--width 5", "--width"},
                      Refusal{"HeightTooLarge", "--height 16385", "--height"},
                      Refusal{"RangeBackwards", "--frames 5:2", "--frames"},
                      Refusal{"RangeNotANumber", "--frames x", "--frames"},
                      Refusal{"RangeNegative", "--frames -3:2", "--frames"},
                      Refusal{"RangePastTheEnd", "--frames 100:120", "--frames"},
                      Refusal{"MovieOddWidth", "--width 321 --height 200 --movie m.mp4", "--movie"},
                      Refusal{"MovieOddHeight", "--width 320 --height 201 --movie m.mp4", "--movie"},
                      // It replaced the scene with an MP4, exit 0.
                      Refusal{"MovieOverTheScene", "--movie two-fluids.scene", "--movie"},
                      Refusal{"MovieNotMp4", "--movie clip.mov", "--movie"},
                      Refusal{"VoxelWithoutSurface", "--voxel-size 0.1", "--voxel-size"},
                      Refusal{"VoxelTooSmall", "--surface --voxel-size 1e-6", "--voxel-size"},
                      // 100000 was accepted while run, view and the schema stop at 10000.
                      Refusal{"SubstepsAboveTheSchemasCap", "--substeps 10001", "--substeps"}),
    [](const auto& p) { return p.param.name; });

TEST(RenderCli, AFolderWithoutFramesIsRefused) {
  TempDir tmp;
  const fs::path folder = tmp / "emptySim";
  fs::create_directories(folder);
  {
    std::FILE* f = std::fopen((folder / "notes.txt").c_str(), "wb");
    ASSERT_NE(f, nullptr);
    std::fclose(f);
  }
  const fs::path out = tmp / "pictures";
  const RunResult r = runSoftsub("render " + quote(folder) + " --out " + quote(out), tmp.path());
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find(folder.string()), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(".sim"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));
}

TEST(RenderCli, AMovieIsAnMp4OfThePictures) {
  if (findProgram("ffmpeg").empty()) GTEST_SKIP() << "ffmpeg is not installed";
  TempDir tmp;
  const fs::path scene = copyInto(examplesDir() / "two-fluids.scene", tmp.path());
  const fs::path out = tmp / "pictures", movie = tmp / "two-fluids.mp4";
  const RunResult r = render(scene, out, "--frames 0:5 --movie " + quote(movie), tmp.path());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(listFrameFiles(out), pictureNames("two-fluids", 0, 5));
  ASSERT_TRUE(fs::is_regular_file(movie));
  const std::string bytes = readFile(movie);
  EXPECT_GT(bytes.size(), 2000u);  // six 320x200 pictures, not an empty container
  ASSERT_GE(bytes.size(), 8u);
  EXPECT_EQ(bytes.substr(4, 4), "ftyp") << "not an MP4 (ISO base media) file";
  // Nothing but the scene, the pictures and the movie: no partial file left behind.
  EXPECT_EQ(listEntries(tmp.path()),
            (std::vector<std::string>{"pictures", "two-fluids.mp4", "two-fluids.scene"}));
}

/// The number of samples (video frames) of an MP4 with one track: its `stsz` box's
/// sample count (ISO/IEC 14496-12: size, "stsz", version and flags, sample size, count).
std::uint32_t mp4SampleCount(const std::string& bytes) {
  const std::size_t at = bytes.find("stsz");
  if (at == std::string::npos || at + 16 > bytes.size()) return 0;
  std::uint32_t n = 0;
  for (std::size_t k = at + 12; k < at + 16; ++k) n = n << 8 | static_cast<unsigned char>(bytes[k]);
  return n;
}

// The movie holds this render's pictures and no other. It was encoded from the folder's
// numbered sequence from the first frame on, so a second take rendered into the same
// folder for fewer frames got the first take's later pictures appended, without a word.
TEST(RenderCli, AMovieHoldsThePicturesOfThisRenderOnly) {
  if (findProgram("ffmpeg").empty()) GTEST_SKIP() << "ffmpeg is not installed";
  TempDir tmp;
  const fs::path scene = copyInto(examplesDir() / "two-fluids.scene", tmp.path());
  const fs::path out = tmp / "pictures";
  ASSERT_EQ(render(scene, out, "--frames 0:6", tmp.path()).code, 0);
  for (const auto& [frames, count] :
       {std::pair<std::string, std::uint32_t>{"0:2", 3}, {"3:4", 2}, {"5", 1}}) {
    const fs::path movie = tmp / ("take-" + std::to_string(count) + ".mp4");
    const RunResult r = render(scene, out, "--frames " + frames + " --movie " + quote(movie), tmp.path());
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(mp4SampleCount(readFile(movie)), count) << frames;
  }
  // The all-frames movie counts them all (the count above is the movie's, not a constant).
  ASSERT_EQ(render(scene, out, "--movie all.mp4", tmp.path()).code, 0);
  EXPECT_EQ(mp4SampleCount(readFile(tmp / "all.mp4")), listFrameFiles(out).size());
  // No folder of links or partial movie left behind.
  EXPECT_EQ(listEntries(tmp.path()),
            (std::vector<std::string>{"all.mp4", "pictures", "take-1.mp4", "take-2.mp4", "take-3.mp4",
                                      "two-fluids.scene"}));
}

// A recording played without its scene file is drawn grey at size 1 with no container:
// that is said on stderr whether or not it is a terminal (a farm's log), and --scene
// gives the scene, as for mesh; with a scene as the input --scene is refused.
TEST(RenderCli, ARecordingAwayFromItsSceneIsWarnedAboutAndTakesOneWithScene) {
  TempDir tmp;
  const fs::path recorded = recordTwoFluids(tmp.path());
  const fs::path moved = tmp / "elsewhere" / "two-fluidsSim";
  fs::create_directories(moved.parent_path());
  fs::rename(recorded, moved);
  const std::string size = fmt::format(" --width {} --height {} --frames 2", kWidth, kHeight);
  const RunResult bare = runSoftsub("render " + quote(moved) + " --out bare" + size, tmp.path());
  ASSERT_EQ(bare.code, 0) << bare.err;
  EXPECT_NE(
      bare.err.find("warning: no usable scene file at " + (tmp / "elsewhere/two-fluids.scene").string() +
                    ": every fluid is drawn grey at ParticleSize 1"),
      std::string::npos)
      << bare.err;
  const RunResult given =
      runSoftsub("render " + quote(moved) + " --scene two-fluids.scene --out given" + size, tmp.path());
  ASSERT_EQ(given.code, 0) << given.err;
  EXPECT_EQ(given.err, "");
  ASSERT_EQ(render(tmp / "two-fluids.scene", tmp / "scene", "--frames 2", tmp.path()).code, 0);
  EXPECT_EQ(
      differingPixels(readPng(tmp / "scene/two-fluids.0002.png"), readPng(tmp / "given/two-fluids.0002.png")),
      0u);
  EXPECT_GT(
      differingPixels(readPng(tmp / "scene/two-fluids.0002.png"), readPng(tmp / "bare/two-fluids.0002.png")),
      0u);
  const RunResult refused =
      render(tmp / "two-fluids.scene", tmp / "no", "--scene two-fluids.scene", tmp.path());
  EXPECT_EQ(refused.code, 2);
  EXPECT_EQ(refused.err.rfind("error: command line: --scene: is for a recorded folder", 0), 0u)
      << refused.err;
  EXPECT_FALSE(fs::exists(tmp / "no"));
}

// Frames left out of a folder (no manifest: a killed run's; a .sim changed since the run)
// are missing pictures and surfaces: render and mesh say so on stderr terminal or not
// (they were notes for a terminal only), and --quiet silences them.
TEST(RenderCli, FramesLeftOutOfARecordingAreWarnedAboutWithoutATerminal) {
  TempDir tmp;
  const fs::path recorded = recordTwoFluids(tmp.path());
  fs::remove(recorded / "manifest" / "two-fluids.0003.manifest");
  const std::string size = fmt::format(" --width {} --height {}", kWidth, kHeight);
  const RunResult r = runSoftsub("render " + quote(recorded) + " --out p" + size, tmp.path());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("warning: frames 3 to 3 of 'two-fluids' left out: they have no manifest"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(listFrameFiles(tmp / "p"), pictureNames("two-fluids", 0, 2));
  const RunResult m = runSoftsub("mesh " + quote(recorded), tmp.path());
  ASSERT_EQ(m.code, 0) << m.err;
  EXPECT_NE(m.err.find("warning: frames 3 to 3 of 'two-fluids' left out"), std::string::npos) << m.err;
  const RunResult quiet = runSoftsub("render " + quote(recorded) + " --out q -q" + size, tmp.path());
  ASSERT_EQ(quiet.code, 0) << quiet.err;
  EXPECT_EQ(quiet.err, "");
  // A middle frame's .sim gone: the frames after it were drawn across the gap, silently
  // (a review); now they are left out and said to be, as for a changed file.
  fs::remove(recorded / "two-fluids.0001.sim");
  const RunResult gap = runSoftsub("render " + quote(recorded) + " --out g" + size, tmp.path());
  ASSERT_EQ(gap.code, 0) << gap.err;
  EXPECT_NE(gap.err.find("warning: frames 1 to 2 of 'two-fluids' left out: frame 1's .sim file is missing"),
            std::string::npos)
      << gap.err;
  EXPECT_EQ(listFrameFiles(tmp / "g"), pictureNames("two-fluids", 0, 0));
}

TEST(RunPreview, WritesAPictureOfTheLastFrame) {
  TempDir tmp;
  const fs::path scene = copyInto(examplesDir() / "honey-drop.scene", tmp.path());
  const fs::path out = tmp / "out";
  const RunResult r = runSoftsub(
      "run " + quote(scene) + " --frames 3 --formats sim --preview -q --out " + quote(out), tmp.path());
  ASSERT_EQ(r.code, 0) << r.err;
  ASSERT_TRUE(fs::is_regular_file(out / "honey-drop.preview.png")) << r.err;
  const render::Image im = readPng(out / "honey-drop.preview.png");
  EXPECT_EQ(im.width, 960);
  EXPECT_EQ(im.height, 540);
  // The last frame, as recorded, with the scene's colours, where it projects.
  const scene::SceneDesc desc = scene::readSceneFile(scene.string());
  FrameSnapshot last = cache::readSimFile(out / "honey-drop.0003.sim").frame;
  ASSERT_EQ(last.fluids.size(), desc.fluids.size());
  for (std::size_t k = 0; k < last.fluids.size(); ++k) {
    const Vec3& c = desc.fluids[k].colour;
    last.fluids[k].colour = {static_cast<float>(c.x()), static_cast<float>(c.y()), static_cast<float>(c.z())};
    last.fluids[k].particleSize = static_cast<float>(desc.fluids[k].params.particleSize);
  }
  expectFluidsWhereTheyProject(im, cameraOf(desc), last);
}

// A fresh run removes the earlier run's frames; its preview picture went on showing the
// earlier run's last frame under the scene's name. It goes with them now.
TEST(RunPreview, AFreshRunWithoutPreviewRemovesTheEarlierRunsPicture) {
  TempDir tmp;
  const fs::path scene = copyInto(examplesDir() / "two-fluids.scene", tmp.path());
  const std::string run = "run " + quote(scene) + " --frames 1 --formats sim -q --out o";
  ASSERT_EQ(runSoftsub(run + " --preview", tmp.path()).code, 0);
  ASSERT_TRUE(fs::is_regular_file(tmp / "o/two-fluids.preview.png"));
  // Resumed (nothing left to do): the run's own picture stays.
  ASSERT_EQ(runSoftsub(run + " --resume", tmp.path()).code, 0);
  EXPECT_TRUE(fs::is_regular_file(tmp / "o/two-fluids.preview.png"));
  // Resumed to a later frame without --preview: the picture of the old last frame goes.
  ASSERT_EQ(
      runSoftsub("run " + quote(scene) + " --frames 2 --formats sim -q --out o --resume", tmp.path()).code,
      0);
  EXPECT_FALSE(fs::exists(tmp / "o/two-fluids.preview.png"));
  ASSERT_EQ(runSoftsub(run + " --preview", tmp.path()).code, 0);
  ASSERT_EQ(runSoftsub(run, tmp.path()).code, 0);
  EXPECT_FALSE(fs::exists(tmp / "o/two-fluids.preview.png"));
  EXPECT_TRUE(fs::is_regular_file(tmp / "o/two-fluids.0001.sim"));
}

// --formats none writes no caches, and --preview still draws the picture it asks for:
// the folder is made for the picture alone, and only once it can be drawn. A system that
// cannot draw (here: no EGL vendor library) gets a warning and no empty folder, which it
// used to get.
TEST(RunPreview, WithFormatsNoneTheFolderHoldsThePictureAlone) {
  TempDir tmp;
  const fs::path scene = copyInto(examplesDir() / "two-fluids.scene", tmp.path());
  const std::string args = " run " + quote(scene) + " --frames 1 --formats none --preview -q --out ";
  const RunResult r = runSoftsub(args + "o", tmp.path());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(listFiles(tmp / "o"), std::vector<std::string>{"two-fluids.preview.png"});
  const RunResult cannot = runCommand(
      "__EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent " + quote(softsubBinary()) + args + "p", tmp.path());
  EXPECT_EQ(cannot.code, 0) << cannot.err;
  if (cannot.err.find("warning: no preview picture: cannot draw off-screen") == std::string::npos)
    GTEST_SKIP() << "this system draws without an EGL vendor library: " << cannot.err;
  EXPECT_FALSE(fs::exists(tmp / "p"));
}

}  // namespace
}  // namespace softsub::apptest
