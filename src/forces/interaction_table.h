#pragma once
/// Sampled pair functions and the material x material table of interactions (the
/// seed's "dictionary of interactions"), owned by a Model: never a singleton.
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "forces/function.h"

namespace softsub::forces {

/// Default number of linear pieces a function is sampled into (seed 3.4.2). Measured
/// error bounds are in tests/forces; 2048 keeps the true LJ force within 1e-3 relative.
inline constexpr int kDefaultIntervals = 2048;

/// A function sampled on [0, cutoff] at `intervals` equal pieces and interpolated
/// linearly. Stored as (value, slope-per-piece) pairs so one lookup reads one pair.
struct SampledFunction {
  double cutoff = 0;              ///< zero from here on
  double invDr = 0;               ///< intervals / cutoff
  std::vector<float> pieces;      ///< 2 * intervals: value at piece start, increment

  /// The interpolated value at r (0 for r >= cutoff or r < 0 handled as r = 0).
  [[nodiscard]] double at(double r) const;
  /// Number of linear pieces.
  [[nodiscard]] std::size_t intervals() const { return pieces.size() / 2; }
};

/// Samples f into `intervals` linear pieces. The sample at the cutoff takes the limit
/// from below, so a function with a jump at its cutoff keeps its value up to it.
SampledFunction sample(const PairFunction& f, int intervals = kDefaultIntervals);

/// The most pieces one function is sampled into (2 MiB of table).
inline constexpr int kMaxIntervals = 1 << 18;
/// The most floats a whole table holds (256 MiB): a scene of many fluids, each pair with
/// its own <Pair> function, is refused rather than left to run out of memory.
inline constexpr std::size_t kMaxTableFloats = std::size_t{1} << 26;

/// The pieces the table samples f into: `intervals`, or more when f's own length scale
/// (FiniteDistance, sigma, the closest two points of a Curve) is under half its cutoff,
/// so that it gets at least intervals / 2 pieces per length scale, up to kMaxIntervals.
/// Why: a long-range cohesion (InteractionDistance 200 x FiniteDistance) had its 12-6
/// core in 10 pieces and felt a force of 11 where the formula gives 0. Scenes whose
/// cutoffs are at most twice their length scales (every example) are sampled as before.
[[nodiscard]] int intervalsFor(const PairFunction& f, int intervals = kDefaultIntervals);

/// f's own length scale: FiniteDistance, sigma, the closest two points of a Curve; 0 for
/// a function without one (a straight line).
[[nodiscard]] double lengthScale(const PairFunction& f);

/// How far f sampled into `intervals` pieces strays from f where its shape is, over
/// [0.9, 4] length scales (within the cutoff): the largest difference there over the
/// largest |f| there; 0 for a function without a length scale. A cutoff so long that the table's
/// pieces (kMaxIntervals at most) are as long as the length scale makes it large.
[[nodiscard]] double samplingError(const PairFunction& f, int intervals);

/// One table entry: what the pair kernel needs for a (material a, material b) pair.
/// Hot, small and plain; precomputed constants only.
struct PairEntry {
  float cutoff2 = 0;           ///< squared cutoff; pairs at or beyond it do nothing
  float invDr = 0;             ///< pieces per unit distance
  float damping = 0;           ///< viscosity: force += damping * (v_j - v_i)
  float relativeVelocity = 0;  ///< force += k * ((v_j - v_i) . n) n
  std::uint32_t offset = 0;    ///< start of this function's pieces in samples()
  std::uint32_t lastPiece = 0; ///< intervals - 1 (clamps float rounding at the cutoff)
};

/// The true Lennard-Jones force (LennardJonesForce) in closed form, for the grouped pair
/// kernel (fluid::PairList, docs/architecture.md "Two kernels"): with
/// u = sigma2 / max(r^2, minR2), F(r) / r = (a u^3 - b) u^4, and zero from cutoff2 on.
/// minR2 is where |F| reaches the formula's clamp (forces::evaluate, 1e12 force units;
/// 0.16 sigma for epsilon 1): closer than that, r^2 is taken as minR2, so F / r is held
/// and the force falls in proportion to r, where the formula's clamp holds F itself. A
/// liquid never comes that close (U is about 1e11 epsilon there): only a run that has
/// blown up does, and the solver's blow-up check stops it.
struct ClosedFormLj {
  float a = 0;        ///< 48 epsilon / sigma^2
  float b = 0;        ///< 24 epsilon / sigma^2
  float sigma2 = 0;   ///< sigma^2
  float cutoff2 = 0;  ///< squared cutoff
  float minR2 = 0;    ///< squared distance below which r^2 is taken as this
};

/// What a pair of materials does to each other, before sampling.
struct Interaction {
  PairFunction function = Linear{0, 1, 0, 0};
  double damping = 0;
  double relativeVelocity = 0;
  bool operator==(const Interaction&) const = default;
};

/// The material x material interaction table. Symmetric: set(a, b) also sets (b, a).
/// Identical functions share one sampled buffer.
class InteractionTable {
 public:
  /// An empty table (no materials).
  InteractionTable() = default;
  /// A table for `materials` materials, every pair doing nothing.
  explicit InteractionTable(std::size_t materials, int intervals = kDefaultIntervals);

  /// Sets the interaction of materials a and b (and b and a).
  void set(std::size_t a, std::size_t b, const Interaction& interaction);

  /// Number of materials (rows).
  [[nodiscard]] std::size_t materials() const { return materials_; }
  /// The entry for (a, b).
  [[nodiscard]] const PairEntry& entry(std::size_t a, std::size_t b) const {
    return entries_[a * materials_ + b];
  }
  /// The un-sampled description for (a, b).
  [[nodiscard]] const Interaction& interaction(std::size_t a, std::size_t b) const {
    return described_[a * materials_ + b];
  }
  /// All entries, row-major (a * materials() + b).
  [[nodiscard]] std::span<const PairEntry> entries() const { return entries_; }
  /// All sampled pieces; entries point into this. Starts with one zero piece (offset 0)
  /// that pairs doing nothing point at: every entry's table is readable.
  [[nodiscard]] std::span<const float> samples() const { return samples_; }
  /// Squared longest cutoff of material a with any material (kernel pre-filter).
  [[nodiscard]] float rowCutoff2(std::size_t a) const { return rowCutoff2_[a]; }
  /// Whether some pair has a damping or relative-velocity term (the kernel loads
  /// velocities only then).
  [[nodiscard]] bool hasVelocityTerms() const { return velocityEntries_ > 0; }
  /// Whether some pair has a relative-velocity term (without one, the kernel skips it).
  [[nodiscard]] bool hasRelativeVelocity() const { return relativeEntries_ > 0; }
  /// The longest cutoff of any pair (the grid's cell size is this plus the list skin).
  [[nodiscard]] double maxCutoff() const;
  /// The closed form of the table's one interaction when the kernel can evaluate it in
  /// registers instead of reading the table: one material, whose own function is the
  /// true Lennard-Jones force (epsilon, sigma and cutoff > 0) with no velocity terms (a
  /// physically based liquid such as LAMMPS's LJ benchmark). Otherwise nothing.
  [[nodiscard]] const std::optional<ClosedFormLj>& closedFormLj() const { return closedForm_; }
  /// The sampled function of (a, b) evaluated at r, as the kernel does.
  [[nodiscard]] double sampledAt(std::size_t a, std::size_t b, double r) const;

 private:
  std::uint32_t addSamples(const PairFunction& f, double* cutoffOut, int* intervalsOut);

  std::size_t materials_ = 0;
  int intervals_ = kDefaultIntervals;
  std::vector<PairEntry> entries_;
  std::vector<Interaction> described_;
  std::vector<float> samples_;
  std::size_t velocityEntries_ = 0;  // entries with a damping or relative-velocity term
  std::size_t relativeEntries_ = 0;  // entries with a relative-velocity term
  std::vector<float> rowCutoff2_;
  std::optional<ClosedFormLj> closedForm_;  // see closedFormLj()
  struct Sampled {
    PairFunction function;
    std::uint32_t offset;
    int intervals;
  };
  std::vector<Sampled> sampledFunctions_;  // dedupe
  std::size_t lastFound_ = 0;              // index of the function addSamples last found
};

}  // namespace softsub::forces
