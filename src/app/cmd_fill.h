#pragma once
/// `softsub fill MESH --spacing S`: the seed's "convert to particles" shelf tool. Fills a
/// mesh with a lattice of particles and writes them as a PLY point cloud or as a
/// `<Fluid>` block to paste into a scene.
#include <cstdint>
#include <string>

namespace CLI {
class App;
}

namespace softsub::app {

/// The options of `fill`.
struct FillOptions {
  std::string mesh;                  ///< OBJ, PLY, STL, glTF, FBX (anything assimp reads)
  double spacing = 0;                ///< lattice step = particle diameter, > 0
  std::string out;                   ///< .ply to write; empty: print a <Fluid> snippet
  bool sceneSnippet = false;         ///< print the <Fluid> block on stdout (the default without --out)
  bool surface = false;              ///< sample the surface only (thin shells, open meshes)
  std::string name = "filled";       ///< the fluid's name in the snippet / PLY
  std::uint64_t maxParticles = 20'000'000;  ///< refuse larger fills before allocating
  bool quiet = false;                ///< no summary on stderr
};

/// Adds the `fill` subcommand bound to `options` and returns it.
CLI::App* addFillCommand(CLI::App& root, FillOptions& options);

/// Runs it; returns the exit code (errors are thrown: InputError, IoError).
int fillCommand(const FillOptions& options);

}  // namespace softsub::app
