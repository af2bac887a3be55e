#pragma once
/// The pair list's second validity test: a list that the two largest displacements can
/// no longer vouch for may still be complete when the particles moved *together* (a
/// falling or flowing body of goo, a sloshing pool, a turning object).
///
/// Why: a pair can only come within its cutoff if the two particles closed by more than
/// the skin since the list was built, i.e. |d_i - d_j| >= skin for their displacements
/// d. The simple test bounds that by |d_i| + |d_j|, so a blob falling at 10 units/s is
/// rebuilt every few substeps though no two of its particles moved relative to each
/// other. Here the list's grid cells are grouped into blocks of 2 x 2 x 2 (wider where
/// the scene is spread thin), and each block gets a centre c (the middle of its
/// particles' displacements) and a radius r (the largest |d - c| in it). For i in block
/// A and j in block B, |d_i - d_j| <= r_A + |c_A - c_B| + r_B, so the list is complete
/// when that is below the skin for every pair of blocks that touch (and each block with
/// itself). Blocks that do not touch were at least two cells apart when the list was
/// built, more than the longest reach plus two skins, so their pairs need only the whole
/// scene's displacement spread to stay below the reach plus a skin.
///
/// Cost: one pass over the particles, slab by slab (the blocks of one coordinate on the
/// grid's major axis are a run of contiguous slots, so each slab's particles are read
/// twice while in cache), and it stops as soon as one block pair fails: a list that
/// must be rebuilt costs little more than its first failing slabs.
///
/// Exact (maxima, minima and one comparison per block pair): the same answer for any
/// thread count, and a function of the positions and the reference only, so a
/// checkpoint continues bit for bit. docs/architecture.md, "The pair list".
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

#include "core/particle_store.h"
#include "neighbors/cell_grid.h"

namespace softsub::solver {

class ListGuard {
 public:
  ListGuard();
  ~ListGuard();
  ListGuard(ListGuard&&) noexcept;
  ListGuard& operator=(ListGuard&&) noexcept;

  /// For a list just built on a grid of cells reach + skin wide, rebuilt at the
  /// reference positions. `reach`: the longest distance at which a pair interacts;
  /// `skin`: the list's margin. The blocks are laid out at the first proves().
  void hold(float reach, float skin);
  /// Whether every pair that can be within its reach at the store's current positions
  /// was within reach + skin at `ref` (x of every slot, then y, then z: the positions
  /// the grid was built at), so is listed. False when any displacement is not finite or
  /// the grid's coordinates wrap. `hint`: a slot whose block is looked at first (the
  /// largest displacement, where a failure is likeliest); it changes the cost only.
  [[nodiscard]] bool proves(const neighbors::CellGrid& grid, const ParticleStore& s, const float* ref,
                            std::size_t hint = SIZE_MAX);
  /// Number of blocks laid out for the current list (0: none yet, or no test; tests).
  [[nodiscard]] std::size_t blocks() const { return blocks_; }
  /// Bytes held.
  [[nodiscard]] std::size_t memoryBytes() const;

 private:
  struct Scratch;
  std::unique_ptr<Scratch> scratch_;
  void layOut(const neighbors::CellGrid& grid);

  bool laidOut_ = false;
  int widthShift_ = 1;               // a block is 2^widthShift_ cells a side
  std::size_t dims_[3] = {0, 0, 0};  // blocks along the key's minor, middle, major axes
  std::size_t blocks_ = 0;
  float reach_ = 0, skin_ = 0;
};

}  // namespace softsub::solver
