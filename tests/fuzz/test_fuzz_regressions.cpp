// Every input in fuzz/regressions/<target>/ (what the fuzzers found, docs/robustness.md),
// the fuzz seeds and the scenes of the repository, through the fuzz targets' bodies: each
// must return (bad input refused with an InputError or IoError); a crash, another
// exception or a broken invariant (the targets abort) fails.
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "targets.h"

namespace softsub::fuzz {
namespace {

namespace fs = std::filesystem;

const fs::path kSource(SOFTSUB_SOURCE_DIR);

std::string bytesOf(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::vector<fs::path> filesIn(const fs::path& dir, const std::string& ext = {}) {
  std::vector<fs::path> out;
  if (!fs::is_directory(dir)) return out;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.is_regular_file() && (ext.empty() || e.path().extension() == ext)) out.push_back(e.path());
  std::sort(out.begin(), out.end());
  return out;
}

int run(int (*target)(const std::uint8_t*, std::size_t), const std::string& bytes) {
  return target(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
}

TEST(FuzzRegressions, SceneReader) {
  std::vector<fs::path> inputs = filesIn(kSource / "fuzz/regressions/scene_reader");
  for (const char* dir : {"examples", "tests/data/scenes/good", "tests/data/scenes/bad", "tests/data/bad"})
    for (const fs::path& p : filesIn(kSource / dir, ".scene")) inputs.push_back(p);
  ASSERT_GE(inputs.size(), 80U);
  for (const fs::path& p : inputs) {
    SCOPED_TRACE(p.string());
    EXPECT_EQ(run(sceneReader, bytesOf(p)), 0);
  }
}

TEST(FuzzRegressions, MeshLoader) {
  int count = 0;
  for (const fs::path& p : filesIn(kSource / "fuzz/regressions/mesh_loader")) {
    SCOPED_TRACE(p.string());
    EXPECT_EQ(run(meshLoader, bytesOf(p)), 0);
    ++count;
  }
  // Seeds and the bad meshes, with the first byte naming their extension.
  for (const char* dir : {"fuzz/seeds/meshes", "tests/data/bad/meshes", "tests/data/scenes/good/cubeGeo",
                          "examples/goo-torusGeo"})
    for (const fs::path& p : filesIn(kSource / dir)) {
      const std::string ext = p.extension().string();
      const char prefix = ext == ".obj" ? 0 : ext == ".ply" ? 1 : ext == ".stl" ? 2 : -1;
      if (prefix < 0) continue;
      SCOPED_TRACE(p.string());
      std::string bytes(1, prefix);
      bytes.append(bytesOf(p));  // (not operator+: GCC 12 warns -Wrestrict inside it)
      EXPECT_EQ(run(meshLoader, bytes), 0);
      ++count;
    }
  EXPECT_GE(count, 15);
}

TEST(FuzzRegressions, FrameReaders) {
  std::vector<fs::path> inputs = filesIn(kSource / "fuzz/regressions/frame_readers");
  for (const fs::path& p : filesIn(kSource / "fuzz/seeds/frames")) inputs.push_back(p);
  ASSERT_GE(inputs.size(), 3U);
  for (const fs::path& p : inputs) {
    SCOPED_TRACE(p.string());
    EXPECT_EQ(run(frameReaders, bytesOf(p)), 0);
  }
}

}  // namespace
}  // namespace softsub::fuzz
