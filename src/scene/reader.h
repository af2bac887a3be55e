#pragma once
/// Reading and validating .scene files (docs/scene-format.md). Every problem is an
/// InputError naming the file, line, element, the problem and what is allowed; a
/// SceneDesc that comes back is valid, so later stages can trust it.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.h"
#include "scene/scene_desc.h"

namespace softsub::scene {

/// Most fluids a scene may have: a particle's fluid is a 16-bit material index, and the
/// interaction table holds fluids x fluids entries (1024 fluids: about a million).
inline constexpr std::size_t kMaxFluids = 1024;

/// Limits the reader enforces on top of the format's own rules.
struct ReadOptions {
  /// Most particles a scene may make (explicit positions, fills and objects, counted without
  /// generating anything); a bigger scene is refused before anything is allocated.
  std::uint64_t maxParticles = 20'000'000;
  /// Largest scene file (or text) read, in bytes; a bigger one is refused before it is
  /// read. 1 GiB holds the explicit positions of some 40 million particles.
  std::uint64_t maxFileBytes = std::uint64_t{1} << 30;
  /// When set, receives one line per warning (a mesh repaired on loading, a mesh fill of
  /// a mesh that is not closed, non-manifold edges): `<file>:<line>: <element>: <text>`.
  std::vector<std::string>* warnings = nullptr;
};

/// Reads and validates the scene file at path. Throws IoError if it cannot be read,
/// InputError if it is not a valid scene.
SceneDesc readSceneFile(const std::string& path, const ReadOptions& options = {});

/// Reads and validates scene text; fileName is only used in messages.
/// Throws InputError if it is not a valid scene.
SceneDesc readSceneText(std::string_view text, const std::string& fileName,
                        const ReadOptions& options = {});

/// Throws InputError at `where` unless `name` is a valid fluid name, with the problem and
/// rule the reader gives for a <Fluid><Name>: letters, digits, _ and -, not empty, at most
/// kMaxNameLength (core/names.h) characters. For names from elsewhere (`fill --name`).
void checkFluidName(std::string_view name, const InputLocation& where);

}  // namespace softsub::scene
