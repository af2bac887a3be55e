#pragma once
/// Checkpoints: a simulation's whole state as bytes, so that a run restored from one
/// continues bit for bit as if it had never stopped (`softsub run --resume`). The solver
/// encodes and decodes; writing the bytes to a file is the caller's (the solver never
/// writes files). docs/cache-formats.md, "Checkpoints", has the layout.
#include <cstdint>
#include <string>
#include <string_view>

#include "core/hash.h"
#include "solver/simulation.h"

namespace softsub::solver {

/// What a checkpoint says about itself without being restored.
struct CheckpointInfo {
  std::int64_t frame = 0;
  std::uint64_t fingerprint = 0;  ///< the run's settings, as given to encodeCheckpoint
  std::uint64_t particles = 0;
  std::uint64_t bodies = 0;
};

/// Appends nothing, replaces `out` with the checkpoint of `sim`'s current state: the
/// particle store in slot order (positions, velocities, forces, materials, owners, ids),
/// whether the forces are current, the positions the pair list was built from, every
/// body's state, the frame, `fingerprint` (the caller's hash of everything that decides
/// the run: scene, overrides, output settings) and a checksum of it all.
void encodeCheckpoint(const Simulation& sim, std::uint64_t fingerprint, std::string& out);

/// Reads the header of a checkpoint; InputError (element "checkpoint") when the bytes are
/// not a whole, intact checkpoint of this version (wrong magic, truncated, checksum).
[[nodiscard]] CheckpointInfo checkpointInfo(std::string_view bytes, const std::string& file);

/// Restores `sim` (built from the same Model) from `bytes`. InputError when the bytes are
/// damaged, their fingerprint is not `fingerprint`, or they do not fit the model.
void restoreCheckpoint(Simulation& sim, std::string_view bytes, std::uint64_t fingerprint, const std::string& file);

}  // namespace softsub::solver
