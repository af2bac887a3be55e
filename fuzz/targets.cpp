#include "targets.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

#include "cache/pdc_format.h"
#include "cache/ply_format.h"
#include "cache/sim_format.h"
#include "core/error.h"
#include "geometry/fill.h"
#include "geometry/mesh_loader.h"
#include "scene/compile.h"
#include "scene/reader.h"
#include "scene/writer.h"

namespace softsub::fuzz {

namespace {

namespace fs = std::filesystem;

/// A broken invariant: print it and abort, which libFuzzer records as a crash.
[[noreturn]] void finding(const char* what, const std::string& detail) {
  std::fprintf(stderr, "fuzz finding: %s: %s\n", what, detail.c_str());
  std::abort();
}

/// A folder of this process under the temporary folder, removed at exit.
class ScratchFolder {
 public:
  ScratchFolder() {
    std::string pattern = (fs::temp_directory_path() / "softsub-fuzz-XXXXXX").string();
    if (mkdtemp(pattern.data()) == nullptr) finding("setup", "mkdtemp failed");
    path_ = pattern;
  }
  ~ScratchFolder() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  ScratchFolder(const ScratchFolder&) = delete;
  ScratchFolder& operator=(const ScratchFolder&) = delete;
  [[nodiscard]] const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

/// The scene target's base folder: the meshes the seed scenes name, copied from the
/// source tree once.
const fs::path& sceneBase() {
  static const ScratchFolder folder;
  static const bool filled = [] {
    const fs::path src(SOFTSUB_SOURCE_DIR);
    std::error_code ec;
    fs::create_directories(folder.path() / "cubeGeo", ec);
    fs::create_directories(folder.path() / "goo-torusGeo", ec);
    fs::copy_file(src / "tests/data/scenes/good/cubeGeo/cube.obj", folder.path() / "cubeGeo/cube.obj", ec);
    fs::copy_file(src / "examples/goo-torusGeo/torus.obj", folder.path() / "goo-torusGeo/torus.obj", ec);
    fs::copy(src / "tests/data/bad/meshes", folder.path() / "meshes", fs::copy_options::recursive, ec);
    return true;
  }();
  (void)filled;
  return folder.path();
}

void writeBytes(const fs::path& file, const std::uint8_t* data, std::size_t size) {
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  if (!out) finding("setup", "cannot write " + file.string());
}

}  // namespace

int sceneReader(const std::uint8_t* data, std::size_t size) {
  const std::string file = (sceneBase() / "fuzz.scene").string();
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  scene::ReadOptions options;
  options.maxParticles = 200'000;
  scene::SceneDesc desc;
  try {
    desc = scene::readSceneText(text, file, options);
  } catch (const InputError&) {
    return 0;
  } catch (const IoError&) {
    return 0;
  }
  // What the reader accepts, the writer writes and the reader reads back unchanged.
  const std::string written = scene::writeSceneText(desc);
  try {
    scene::SceneDesc again = scene::readSceneText(written, file, options);
    again.baseDir = desc.baseDir;
    if (!(scene::writeSceneText(again) == written)) finding("round trip", "the rewritten scene differs");
  } catch (const InputError& e) {
    finding("round trip", std::string("the written scene is refused: ") + e.what());
  }
  // A valid description compiles, or is refused with an InputError where only compiling
  // can tell (a mesh fill that makes no particles, a fluid whose fills OutsideObjects
  // leaves empty: scene-format.md); any other exception escapes and is a finding.
  try {
    (void)scene::compile(desc);
  } catch (const InputError&) {
    return 0;
  }
  return 0;
}

int meshLoader(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  static const ScratchFolder folder;
  static const char* const kExtensions[] = {".obj", ".ply", ".stl"};
  const fs::path file = folder.path() / std::string("mesh").append(kExtensions[data[0] % 3]);
  writeBytes(file, data + 1, size - 1);
  geometry::TriangleMesh mesh;
  geometry::MeshLoadReport report;
  try {
    mesh = geometry::loadMesh(file, &report);
  } catch (const InputError&) {
    return 0;
  } catch (const IoError&) {
    return 0;
  }
  // A loaded mesh is what the header promises: finite vertices, indices in range, at
  // least one triangle.
  if (mesh.triangles.empty()) finding("loadMesh", "no triangles");
  for (const Vec3& v : mesh.vertices)
    if (!v.allFinite()) finding("loadMesh", "a non-finite vertex");
  for (const auto& t : mesh.triangles)
    for (const std::uint32_t i : t)
      if (i >= mesh.vertices.size()) finding("loadMesh", "an index out of range");
  (void)geometry::countEdges(mesh);
  const Aabb box = mesh.bounds();
  const double extent =
      std::max({box.hi[0] - box.lo[0], box.hi[1] - box.lo[1], box.hi[2] - box.lo[2]});
  for (const bool surface : {false, true}) {
    try {
      (void)geometry::fillMesh(mesh, {.spacing = extent > 0 ? extent / 8 : 1,
                                      .surfaceOnly = surface,
                                      .maxParticles = 100'000});
    } catch (const InputError&) {
    }
  }
  return 0;
}

int frameReaders(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  try {
    (void)cache::decodeSim(bytes, "f.sim");
  } catch (const InputError&) {
  }
  try {
    (void)cache::decodePdc(bytes, "f.pdc");
  } catch (const InputError&) {
  }
  try {
    (void)cache::decodePly(bytes, "f.ply");
  } catch (const InputError&) {
  }
  return 0;
}

}  // namespace softsub::fuzz
