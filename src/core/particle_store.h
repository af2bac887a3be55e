#pragma once
/// The one particle store: every particle of every entity, structure of arrays.
#include <cstdint>
#include <span>
#include <vector>

namespace softsub {

/// One particle's force: x, y, z and a fourth component that stays 0. Why a record and
/// not three arrays like the rest of the store: the pair kernel adds each pair's force
/// to a partner j it reaches through the list, and one 16-byte read-modify-write of a
/// record costs a third of the instructions of three scalar ones in three arrays
/// (docs/architecture.md, "The pair kernel").
struct alignas(16) Force {
  float x = 0, y = 0, z = 0, w = 0;
  bool operator==(const Force&) const = default;
};

/// Structure-of-arrays particle storage. Slots are reordered (permute) when the
/// neighbour grid sorts particles by cell; each particle keeps its stable id, which
/// outputs use for ordering. Arrays are public on purpose: the kernels read them
/// directly, and every array is reordered in exactly one place (permute()).
class ParticleStore {
 public:
  // Hot data: what the force and integration kernels sweep.
  std::vector<float> px, py, pz;  ///< position, scene units
  std::vector<float> vx, vy, vz;  ///< velocity, units/s
  std::vector<Force> f;           ///< force accumulated this evaluation, mass*units/s^2
  std::vector<std::uint16_t> material;  ///< row/column in the InteractionTable
  // Cold data.
  std::vector<std::uint32_t> owner;  ///< entity index (fluid index in the model)
  std::vector<std::uint32_t> id;     ///< stable id, 0..size()-1, unique

  /// Number of particles.
  [[nodiscard]] std::size_t size() const { return px.size(); }

  /// Reserves room for n particles in every array.
  void reserve(std::size_t n);

  /// Appends a particle and returns its slot; its id is the current size().
  std::size_t add(float x, float y, float z, float vxi, float vyi, float vzi,
                  std::uint16_t materialIndex, std::uint32_t ownerIndex);

  /// Reorders the store so that new slot k holds old slot order[k]. `order` must be a
  /// permutation of 0..size()-1, and `scratch` hold at least size() values.
  ///
  /// Forces are not carried: they come back zero. Why: the store is reordered only when
  /// the neighbour grid is rebuilt, right before the forces are computed again, so the
  /// force records' memory serves as the scratch of the six float arrays and the store
  /// needs no permutation buffer of its own (10 bytes a particle saved). The integer
  /// arrays go through `scratch` (the grid lends its dead sort keys).
  void permute(std::span<const std::uint32_t> order, std::span<std::uint32_t> scratch);

  /// slotOfId[id] = current slot of that id; filled into `out` (resized to size()).
  void slotsById(std::vector<std::uint32_t>& out) const;
};

}  // namespace softsub
