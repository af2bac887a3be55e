#pragma once
/// The bodies of the libFuzzer targets (fuzz/fuzz_*.cpp), shared with the GoogleTest
/// that replays fuzz/regressions/ (tests/fuzz/). Each takes any bytes; bad input must end
/// in an InputError or IoError. Anything else (another exception, a crash, a sanitizer
/// report, a broken invariant: abort()) is a finding. docs/robustness.md has the how-to.
#include <cstddef>
#include <cstdint>

namespace softsub::fuzz {

/// The bytes as .scene text, read from a base folder holding the meshes the examples and
/// tests name (cubeGeo/cube.obj, goo-torusGeo/torus.obj, meshes/*); a scene that reads is
/// written back and must read again to the same description, and is compiled (particle
/// cap 200,000).
int sceneReader(const std::uint8_t* data, std::size_t size);

/// The first byte picks the file's extension (0: .obj, 1: .ply, 2: .stl, modulo 3); the
/// rest is written to a temporary file and loaded by geometry::loadMesh, then filled at an
/// eighth of its extent (volume and surface, cap 100,000 voxels).
int meshLoader(const std::uint8_t* data, std::size_t size);

/// The bytes through each frame decoder: decodeSim, decodePdc and decodePly.
int frameReaders(const std::uint8_t* data, std::size_t size);

}  // namespace softsub::fuzz
