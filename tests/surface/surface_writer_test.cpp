// SurfaceWriter: file names, an empty fluid's files, determinism.
#include <filesystem>
#include <random>

#include <gtest/gtest.h>

#include "cache/atomic_file.h"
#include "cache/obj_format.h"
#include "surface/surface_writer.h"

namespace softsub::surface {
namespace {

namespace fs = std::filesystem;

struct Scratch {
  fs::path path = fs::temp_directory_path() /
                  ("softsub-surface-writer-" + std::to_string(std::random_device{}()));
  ~Scratch() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
};

FrameSnapshot frameWith(std::int64_t number) {
  FrameSnapshot frame;
  frame.frame = number;
  FluidSnapshot ball;
  ball.name = "ball";
  ball.particleSize = 1;
  for (int x = 0; x < 4; ++x)
    for (int y = 0; y < 4; ++y)
      for (int z = 0; z < 4; ++z) {
        ball.ids.push_back(static_cast<std::uint32_t>(ball.ids.size()));
        for (const int c : {x, y, z}) ball.positions.push_back(static_cast<float>(c));
        for (int k = 0; k < 3; ++k) ball.velocities.push_back(0);
      }
  FluidSnapshot none;
  none.name = "none";
  frame.fluids = {ball, none};
  return frame;
}

// An empty fluid still gets its files: a valid OBJ with no face and an empty level set,
// so a sequence importer finds every frame.
TEST(SurfaceWriter, WritesEveryFluidEmptyOnesIncluded) {
  Scratch dir;
  SurfaceWriter writer(dir.path, true, true);
  writer.onFrame(frameWith(7));
  EXPECT_EQ(writer.lastWritten(),
            (std::vector<fs::path>{meshPath(dir.path, "ball", 7), vdbPath(dir.path, "ball", 7),
                                   meshPath(dir.path, "none", 7), vdbPath(dir.path, "none", 7)}));
  EXPECT_EQ(meshPath(dir.path, "ball", 7), dir.path / "mesh/ball.0007.obj");
  const cache::ObjectMesh ball = cache::decodeObj(cache::readFileBytes(meshPath(dir.path, "ball", 7)), "b");
  EXPECT_FALSE(ball.triangles.empty());
  EXPECT_EQ(ball.normals.size(), ball.vertices.size());
  const cache::ObjectMesh none = cache::decodeObj(cache::readFileBytes(meshPath(dir.path, "none", 7)), "n");
  EXPECT_EQ(none.name, "none");
  EXPECT_TRUE(none.vertices.empty());
  EXPECT_TRUE(LevelSet::readVdb(vdbPath(dir.path, "none", 7)).empty());
  EXPECT_FALSE(LevelSet::readVdb(vdbPath(dir.path, "ball", 7)).empty());
  for (const auto& entry : fs::directory_iterator(dir.path / "vdb"))
    EXPECT_EQ(entry.path().extension(), ".vdb") << entry.path();  // no temporary left

  const std::string first = cache::readFileBytes(meshPath(dir.path, "ball", 7));
  writer.onFrame(frameWith(7));
  EXPECT_EQ(cache::readFileBytes(meshPath(dir.path, "ball", 7)), first);
}

TEST(SurfaceWriter, NothingSelectedWritesNothing) {
  Scratch dir;
  SurfaceWriter writer(dir.path, false, false);
  writer.onFrame(frameWith(0));
  EXPECT_TRUE(writer.lastWritten().empty());
  EXPECT_FALSE(fs::exists(dir.path));
}

}  // namespace
}  // namespace softsub::surface
