#include "solver/simulation.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "core/error.h"
#include "fluid/pair_forces.h"
#include "solver/stability.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

namespace softsub::solver {

namespace {

// Per-particle stages run over fixed blocks of slots in parallel: each slot is written by
// one task only and with the same arithmetic whatever the thread count.
constexpr std::size_t kBlock = 4096;

template <class Fn>
void forEachSlot(std::size_t n, Fn&& fn) {
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, kBlock), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) fn(i);
  });
}

// The same over ranges of slots: fn(begin, end).
template <class Fn>
void forEachRange(std::size_t n, Fn&& fn) {
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, kBlock),
                    [&](const tbb::blocked_range<std::size_t>& r) { fn(r.begin(), r.end()); });
}

// Short runs of slots that the per-particle stages test as one: a run where no particle
// needs a stage's scalar work skips it after one vectorised test.
constexpr std::size_t kRun = 32;

// The two largest squared displacements (a NaN counts as infinite): maxima are exact, so
// a parallel reduction gives the same pair whatever the split.
struct Top2 {
  float first = 0, second = 0;
  // The lowest slot whose displacement is the largest: the same for any split (each
  // task meets its slots in ascending order; ties keep the lower slot).
  std::uint32_t slot = UINT32_MAX;
  void add(float d2, std::size_t i) {
    if (!(d2 == d2)) d2 = INFINITY;
    if (d2 > first) {
      second = first;
      first = d2;
      slot = static_cast<std::uint32_t>(i);
    } else {
      if (d2 == first && i < slot) slot = static_cast<std::uint32_t>(i);
      if (d2 > second) second = d2;
    }
  }
  void join(const Top2& o) {
    add(o.first, o.slot);
    add(o.second, o.slot);  // never above o.first: cannot become the largest
  }
  // Adds the displacements of slots [b, e) from the reference positions (x of every
  // slot, then y, then z). Run by run: the squares into a buffer and their largest bit
  // pattern, one vectorised loop; only a run with one above the second largest so far
  // (as unsigned integers: any NaN, of either sign, counts as above) goes through add(),
  // for which the others change nothing. The same pair as adding every slot.
  [[gnu::always_inline]] void addDisplacements(const ParticleStore& s, const float* ref, std::size_t b,
                                               std::size_t e) {
    const std::size_t n = s.size();
    const float* __restrict px = s.px.data();
    const float* __restrict py = s.py.data();
    const float* __restrict pz = s.pz.data();
    const float* __restrict rx = ref;
    const float* __restrict ry = ref + n;
    const float* __restrict rz = ref + 2 * n;
    alignas(32) float d2[kRun];
    for (std::size_t r = b; r < e; r += kRun) {
      const std::size_t m = std::min(kRun, e - r);
      const std::uint32_t top = m == kRun ? squares(px + r, py + r, pz + r, rx + r, ry + r, rz + r, d2, kRun)
                                          : squares(px + r, py + r, pz + r, rx + r, ry + r, rz + r, d2, m);
      if (top <= std::bit_cast<std::uint32_t>(second)) continue;
      for (std::size_t k = 0; k < m; ++k) add(d2[k], r + k);
    }
  }
  // The squared displacements of m slots into d2, and their largest bit pattern. Inlined
  // with m = kRun for whole runs: a loop of known length vectorises without a remainder.
  [[gnu::always_inline]] static std::uint32_t squares(const float* __restrict px, const float* __restrict py,
                                                      const float* __restrict pz, const float* __restrict rx,
                                                      const float* __restrict ry, const float* __restrict rz,
                                                      float* __restrict d2, std::size_t m) {
    std::uint32_t top = 0;
    for (std::size_t k = 0; k < m; ++k) {
      const float dx = px[k] - rx[k], dy = py[k] - ry[k], dz = pz[k] - rz[k];
      d2[k] = dx * dx + dy * dy + dz * dz;
      top = std::max(top, std::bit_cast<std::uint32_t>(d2[k]));
    }
    return top;
  }
};

}  // namespace

std::size_t Model::particleCount() const {
  std::size_t n = 0;
  for (const FluidInfo& f : fluids) n += f.count;
  return n + bodies.particleCount();
}

Simulation::Simulation(const Model& model, State state) : model_(model), state_(std::move(state)) {
  double c = model_.table.maxCutoff();
  const std::size_t nm = model_.materials.size();
  for (const MaterialInfo& m : model_.materials) {
    materialInverseMass_.push_back(m.inverseMass);
    materialRadius_.push_back(m.radius);
  }
  if (!model_.bodies.empty()) {
    // Contacts need pairs out to the sum of the two radii: fluid/body to keep fluid out
    // of bodies, body/body for impulses, and those a little further where one particle
    // lies over the other's flat face (rigid::faceReach2). Lists reach that far at least.
    float bodyRadius = 0, anyRadius = 0;
    for (const MaterialInfo& m : model_.materials) {
      anyRadius = std::max(anyRadius, m.radius);
      if (m.body) bodyRadius = std::max(bodyRadius, m.radius);
    }
    rowRadius_.resize(nm);
    for (std::size_t a = 0; a < nm; ++a) {
      const MaterialInfo& m = model_.materials[a];
      const float contact =
          m.body ? std::max(m.radius + anyRadius, static_cast<float>(std::sqrt(rigid::faceReach2(m.radius, bodyRadius))))
                 : m.radius + bodyRadius;
      rowRadius_[a] = std::max(std::sqrt(model_.table.rowCutoff2(a)), contact);
      c = std::max(c, static_cast<double>(rowRadius_[a]));
    }
    listOptions_.rowRadius = rowRadius_;
    listOptions_.exclusiveOwnersFrom = model_.bodies.firstEntity;
    // Body particles start where their bodies put them.
    rigid_.findBodySlots(model_.bodies, state_.particles);
    rigid_.writeParticles(model_.bodies, state_.bodies, state_.particles);
  }
  cellSize_ = static_cast<float>(c > 0 ? c : 1.0);
  const bool windows = fluid::PairList::groups(model_.table, state_.particles.size(), listOptions_);
  skin_ = static_cast<float>(windows ? model_.windowListSkin : model_.pairListSkin) * cellSize_;
  // Speeds are measured in interaction distances: a material's own cutoff (or contact
  // reach for bodies), the longest one for a material that interacts with nothing.
  reach_.resize(nm);
  for (std::size_t a = 0; a < nm; ++a) {
    float r = rowRadius_.empty() ? std::sqrt(model_.table.rowCutoff2(a)) : rowRadius_[a];
    reach_[a] = r > 0 && std::isfinite(r) ? r : cellSize_;
  }
  invReach_.resize(nm);
  // At most FLT_MAX, so that a particle at rest scans as speed 0 even for an absurdly
  // small reach (0 * inf would be NaN).
  for (std::size_t a = 0; a < nm; ++a) invReach_[a] = std::min(1.0f / reach_[a], std::numeric_limits<float>::max());
  uniformReach_ = !invReach_.empty() && std::all_of(invReach_.begin(), invReach_.end(),
                                                    [&](float r) { return r == invReach_.front(); });
  substeps_ = std::max(1, model_.substeps);
  // Where each material's centres meet the container walls (one radius inside; a box
  // narrower than a particle holds it in the middle), once rather than per particle.
  if (model_.container) {
    const Container& box = *model_.container;
    for (const MaterialInfo& m : model_.materials) {
      std::array<float, 3> lo{}, hi{};
      if (m.body) {  // bodies meet the walls in the rigid solver, their particles never
        lo.fill(-INFINITY);
        hi.fill(INFINITY);
        wallLo_.push_back(lo);
        wallHi_.push_back(hi);
        continue;
      }
      for (int a = 0; a < 3; ++a) {
        lo[a] = static_cast<float>(box.lo[a]) + m.radius;
        hi[a] = static_cast<float>(box.hi[a]) - m.radius;
        if (lo[a] > hi[a]) lo[a] = hi[a] = 0.5f * static_cast<float>(box.lo[a] + box.hi[a]);
      }
      wallLo_.push_back(lo);
      wallHi_.push_back(hi);
      for (int a = 0; a < 3; ++a) {
        gateLo_[a] = std::max(gateLo_[a], lo[a]);
        gateHi_[a] = std::min(gateHi_[a], hi[a]);
      }
    }
    if (!box.closed) gateHi_[1] = INFINITY;  // no lid: nothing is stopped at the top
  }
  uniformMass_ = std::all_of(model_.materials.begin(), model_.materials.end(), [&](const MaterialInfo& m) {
    return m.inverseMass == model_.materials.front().inverseMass;
  });
  if (model_.adaptiveSubsteps) {
    const int stable = assessStability(model_, &state_).minimumSubsteps;
    stableSubsteps_ = stable > 0 ? stable : model_.maxSubsteps;
  }
}

double Simulation::time() const {
  return static_cast<double>(state_.frame) / model_.framesPerSecond;
}

// The list stays valid while no two particles can have closed more than the skin since
// it was built: a pair closes by at most the sum of its two displacements, so the sum
// of the two largest displacements is checked (less often stale than twice the
// largest when one particle flies off alone).
bool Simulation::listIsStale() {
  if (!listValid_) return true;
  const ParticleStore& s = state_.particles;
  const Top2 top = tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, s.size(), kBlock), Top2{},
      [&](const tbb::blocked_range<std::size_t>& r, Top2 t) {
        t.addDisplacements(s, ref_, r.begin(), r.end());
        return t;
      },
      [](Top2 a, const Top2& b) {
        a.join(b);
        return a;
      });
  fastestSlot_ = top.slot;
  return !(std::sqrt(top.first) + std::sqrt(top.second) < skin_);
}

void Simulation::computeForces() {
  ParticleStore& s = state_.particles;
  bool rebuild = knownStale_ >= 0 ? knownStale_ == 1 : listIsStale();
  knownStale_ = -1;
  // A list the displacements call stale may still hold every pair in reach when the
  // particles moved together (solver/list_guard.h). Asked only when lists die young:
  // each substep it keeps a list costs a pass over the particles, and a list that
  // lasts many substeps gains little from one more (docs/architecture.md).
  if (rebuild && listValid_ && model_.listGuard && listDiesYoung() &&
      guard_.proves(grid_, s, ref_, fastestSlot_))
    rebuild = false;
  if (rebuild) {
    // Only here is the store re-sorted: the list holds slots. The grid works in the
    // reference positions' memory (they are rewritten below).
    listValid_ = false;
    reserveListWork();
    grid_.rebuild(s, cellSize_ + skin_, listWork_.bytes());
  }
  if (rebuild && model_.bodies.empty()) {
    // Without bodies the rebuild adds the forces layer by layer as it lists them.
    forEachSlot(s.size(), [&](std::size_t i) { s.f[i] = Force{}; });
    list_.buildAndAccumulate(grid_, model_.table, s, skin_, listOptions_);
  } else {
    if (rebuild) {
      list_.build(grid_, model_.table, s, skin_, listOptions_);
      listRigidPairs();
    }
    fluid::setPairForces(list_, model_.table, s);
  }
  if (rebuild) {
    holdReference(s.px, s.py, s.pz);
    listValid_ = true;
    ++listBuilds_;
  }
  state_.forcesValid = true;
}

// Whether a list would last fewer than 8 substeps at the speed of the particle that
// moved most since the last build (fastestSlot_, found by the stale test): two such
// particles close by the skin in skin / (2 |v| dt) substeps. A function of the state,
// so a restored run decides as the uninterrupted one.
bool Simulation::listDiesYoung() const {
  const ParticleStore& s = state_.particles;
  if (fastestSlot_ >= s.size()) return true;
  const std::size_t i = fastestSlot_;
  const float v = std::sqrt(s.vx[i] * s.vx[i] + s.vy[i] * s.vy[i] + s.vz[i] * s.vz[i]);
  return !(16.0f * v * static_cast<float>(dt()) < skin_);
}

// The pairs of the list that involve a body particle (the store was just re-sorted).
void Simulation::listRigidPairs() {
  const ParticleStore& s = state_.particles;
  rigid_.findBodySlots(model_.bodies, s);
  rigidPairs_.clear();
  const std::uint32_t first = model_.bodies.firstEntity;
  const std::uint32_t* owner = s.owner.data();
  list_.forEachPair([&](std::uint32_t i, std::uint32_t j) {
    if (owner[i] >= first || owner[j] >= first) rigidPairs_.push_back({i, j});
  });
}

void Simulation::prepareBodies() {
  if (model_.bodies.empty()) return;
  rigid_.prepareDrag(model_.bodies, state_.bodies, state_.particles, rigidPairs_, materialInverseMass_,
                     model_.table, model_.gravity, this->dt());
}

void Simulation::stepBodies(double dt, rigid::FluidKick fluidKick) {
  if (model_.bodies.empty()) return;
  rigid_.step(
      model_.bodies, state_.bodies, state_.contacts, state_.particles, rigidPairs_, materialInverseMass_,
      &model_.table, model_.container ? &*model_.container : nullptr, model_.gravity, dt,
      model_.integrator == Integrator::ExplicitEuler ? 0.0 : dt,  // explicit Euler drifts before kicking
      fluidKick);
}

void Simulation::keepFluidOutOfBodies() {
  if (model_.bodies.empty()) return;
  rigid_.keepFluidOut(model_.bodies, state_.bodies, state_.particles, rigidPairs_, materialInverseMass_,
                      materialRadius_);
}

namespace {
// scanSpeeds' loop; inv(i) is slot i's 1 / reach.
template <class Inv>
[[gnu::always_inline]] inline void scanRange(const ParticleStore& s, std::size_t b, std::size_t e, Inv inv,
                                             std::uint32_t& okOut, std::uint32_t& topOut) {
  const float *px = s.px.data(), *py = s.py.data(), *pz = s.pz.data();
  const float *vx = s.vx.data(), *vy = s.vy.data(), *vz = s.vz.data();
  std::uint32_t ok = 1, top = topOut;
  for (std::size_t i = b; i != e; ++i) {
    // x - x is 0 for a finite x and NaN otherwise (no short circuit: no branch).
    const float p = (px[i] - px[i]) + (py[i] - py[i]) + (pz[i] - pz[i]);
    const float v = (vx[i] - vx[i]) + (vy[i] - vy[i]) + (vz[i] - vz[i]);
    ok &= static_cast<std::uint32_t>(p == 0.0f) & static_cast<std::uint32_t>(v == 0.0f);
    // May overflow to infinity for a finite but absurd speed: then it is beyond any limit.
    const float r = inv(i);
    const float v2 = (vx[i] * vx[i] + vy[i] * vy[i] + vz[i] * vz[i]) * r * r;
    const std::uint32_t bits = std::bit_cast<std::uint32_t>(v2);
    top = top > bits ? top : bits;
  }
  okOut = ok;
  topOut = top;
}

// Simulation::scanSpeeds for a reach all materials share (uniform: invReach[0]) or per
// material.
[[gnu::always_inline]] inline void scanSpeedsOf(const ParticleStore& s, std::size_t b, std::size_t e,
                                                bool uniform, const float* invReach, float& speed2,
                                                bool& finite) {
  std::uint32_t ok = 1, top = std::bit_cast<std::uint32_t>(speed2);
  if (uniform) {
    const float r = invReach[0];
    scanRange(s, b, e, [r](std::size_t) { return r; }, ok, top);
  } else {
    const std::uint16_t* material = s.material.data();
    scanRange(s, b, e, [=](std::size_t i) { return invReach[material[i]]; }, ok, top);
  }
  speed2 = std::bit_cast<float>(top);
  finite = finite && ok != 0;
}
}  // namespace

// checkFinite()'s scan of slots [b, e): `finite` false if a position or velocity there is
// not finite, `speed2` raised to the largest squared speed in reach units. Written so
// that it vectorises: the test is an integer "and", the maximum an integer one (squared
// speeds are >= 0, and the bit patterns of floats >= 0 order as the floats do; only a
// non-finite velocity gives a NaN, which may then come out as the speed, with `finite`
// false), and a reach that all materials share is read once instead of per particle.
void Simulation::scanSpeeds(const ParticleStore& s, std::size_t b, std::size_t e, float& speed2,
                            bool& finite) const {
  scanSpeedsOf(s, b, e, uniformReach_, invReach_.data(), speed2, finite);
}

// What the per-particle stages do to one particle, written once for the passes that run
// them one after another and for sweep(), which runs them in one.
struct Simulation::ParticleOps {
  ParticleStore& s;
  const MaterialInfo* mats;
  float gx, gy, gz;
  const Container* box;  // null: no walls
  float e, mu;           // the walls' restitution and friction
  const std::array<float, 3>* wallLo;
  const std::array<float, 3>* wallHi;
  bool uniformMass;                     // every material has mats[0]'s inverse mass
  std::array<float, 3> gateLo, gateHi;  // a centre inside these touches no wall, whatever its material
  float restDt;                         // the substep: what a resting contact's speed is measured in

  // v += (f / m + g) h for slots [from, to). Axis by axis through unaliased pointers, so that
  // each loop vectorises (one loop over six arrays did not: too many alias checks); the
  // inverse masses are gathered into a buffer first unless every material shares one.
  [[gnu::always_inline]] void kicks(std::size_t from, std::size_t to, float h) const {
    const float g[3] = {gx, gy, gz};
    float* const v[3] = {s.vx.data(), s.vy.data(), s.vz.data()};
    const Force* const f = s.f.data();
    alignas(32) float im[kRun];
    for (std::size_t r = from; r < to; r += kRun) {
      const std::size_t m = std::min(kRun, to - r);
      if (uniformMass) std::fill_n(im, m, mats[0].inverseMass);
      else
        for (std::size_t k = 0; k < m; ++k) im[k] = mats[s.material[r + k]].inverseMass;
      if (m == kRun) {  // a known length: no remainder loop
        kickAxis<&Force::x>(v[0] + r, f + r, im, g[0], h, kRun);
        kickAxis<&Force::y>(v[1] + r, f + r, im, g[1], h, kRun);
        kickAxis<&Force::z>(v[2] + r, f + r, im, g[2], h, kRun);
      } else {
        kickAxis<&Force::x>(v[0] + r, f + r, im, g[0], h, m);
        kickAxis<&Force::y>(v[1] + r, f + r, im, g[1], h, m);
        kickAxis<&Force::z>(v[2] + r, f + r, im, g[2], h, m);
      }
    }
  }
  template <float Force::*kAxis>
  [[gnu::always_inline]] static void kickAxis(float* __restrict v, const Force* __restrict f,
                                              const float* __restrict im, float g, float h, std::size_t m) {
    for (std::size_t k = 0; k < m; ++k) v[k] += (f[k].*kAxis * im[k] + g) * h;
  }
  // x += v dt for slots [from, to), axis by axis as the kick.
  [[gnu::always_inline]] void drifts(std::size_t from, std::size_t to, float dt) const {
    driftAxis(s.px.data() + from, s.vx.data() + from, dt, to - from);
    driftAxis(s.py.data() + from, s.vy.data() + from, dt, to - from);
    driftAxis(s.pz.data() + from, s.vz.data() + from, dt, to - from);
  }
  [[gnu::always_inline]] static void driftAxis(float* __restrict p, const float* __restrict v, float dt,
                                               std::size_t m) {
    for (std::size_t k = 0; k < m; ++k) p[k] += v[k] * dt;
  }
  // walls(i) for slots [from, to): run by run, a vectorised test against the bounds that
  // hold for every material skips the runs where no centre is near a wall.
  [[gnu::always_inline]] void wallsOf(std::size_t from, std::size_t to) const {
    const float* const p[3] = {s.px.data(), s.py.data(), s.pz.data()};
    for (std::size_t r = from; r < to; r += kRun) {
      const std::size_t m = std::min(kRun, to - r);
      std::uint32_t near = 0;
      for (int a = 0; a < 3; ++a)
        near |= m == kRun ? outside(p[a] + r, gateLo[a], gateHi[a], kRun)
                          : outside(p[a] + r, gateLo[a], gateHi[a], m);
      if (near == 0) continue;
      for (std::size_t i = r; i < r + m; ++i) walls(i);
    }
  }
  // Inlined with m = kRun for whole runs: a loop of known length vectorises without a
  // remainder.
  [[gnu::always_inline]] static std::uint32_t outside(const float* __restrict p, float lo, float hi,
                                                      std::size_t m) {
    std::uint32_t any = 0;
    for (std::size_t k = 0; k < m; ++k)
      any |= static_cast<std::uint32_t>(p[k] < lo) | static_cast<std::uint32_t>(p[k] > hi);
    return any;
  }
  // Container walls: a particle's centre stays one radius inside. On contact the
  // position is put back on the wall; if the particle moves into the wall, its normal
  // velocity v_n is reversed and scaled by the restitution e, and its tangential velocity
  // v_t is reduced by friction * min(|v_t|, Δv_n), Δv_n = (1 + e) |v_n| the normal
  // velocity change. At an impact this is the seed's rule (v_t becomes (1 - friction)
  // v_t); in resting or sliding contact the reduction is capped by the normal velocity
  // change, which makes it Coulomb friction (deceleration friction * g on a floor)
  // whatever the substep count. Resting contact: a particle that reaches the wall no
  // faster than its acceleration towards it gives in 2.5 substeps (gravity, or its
  // neighbours pressing it there) stops there, v_n = 0 and Δv_n = |v_n|, instead of
  // bouncing off at e |v_n|: a bounce each substep left particles that do not move with
  // an outward velocity in the caches (4.4 units/s in a pile pressed against the walls),
  // which motion blur would smear. Such a bounce would rise e² (2.5 a dt)² / 2a, a few
  // thousandths of a particle. Not for e = 1: an elastic wall reflects exactly (energy
  // is conserved; the LAMMPS comparison's reflective box). No walls at all without an
  // <Environment>.
  void walls(std::size_t i) const {
    float* pos[3] = {s.px.data(), s.py.data(), s.pz.data()};
    float* vel[3] = {s.vx.data(), s.vy.data(), s.vz.data()};
    const std::uint16_t m = s.material[i];
    for (int a = 0; a < 3; ++a) {
      const float lo = wallLo[m][a], hi = wallHi[m][a];
      const bool lid = a != 1 || box->closed;
      float& p = pos[a][i];
      float& v = vel[a][i];
      int side = 0;
      if (p < lo) { p = lo; side = -1; }
      else if (lid && p > hi) { p = hi; side = 1; }
      if (side == 0 || !(v * static_cast<float>(side) > 0)) continue;
      const float vn = std::abs(v);
      const float g = a == 0 ? gx : a == 1 ? gy : gz;
      const float f = a == 0 ? s.f[i].x : a == 1 ? s.f[i].y : s.f[i].z;
      const float towards = (f * mats[m].inverseMass + g) * static_cast<float>(side);  // > 0: into the wall
      const bool resting = e < 1.0f && vn <= 2.5f * towards * restDt;  // e = 1: exactly elastic
      v = resting ? 0.0f : -e * v;
      float& t1 = vel[(a + 1) % 3][i];
      float& t2 = vel[(a + 2) % 3][i];
      const float vt = std::sqrt(t1 * t1 + t2 * t2);
      if (vt > 0) {
        const float scale = 1.0f - mu * std::min(vt, (resting ? 1.0f : 1.0f + e) * vn) / vt;
        t1 *= scale;
        t2 *= scale;
      }
    }
  }
};

Simulation::ParticleOps Simulation::particleOps() {
  const Container* box = model_.container ? &*model_.container : nullptr;
  return {state_.particles,
          model_.materials.data(),
          static_cast<float>(model_.gravity.x()),
          static_cast<float>(model_.gravity.y()),
          static_cast<float>(model_.gravity.z()),
          box,
          box ? static_cast<float>(box->restitution) : 0.0f,
          box ? static_cast<float>(box->friction) : 0.0f,
          wallLo_.data(),
          wallHi_.data(),
          uniformMass_,
          gateLo_,
          gateHi_,
          static_cast<float>(dt())};
}

void Simulation::kick(float h) {
  const ParticleOps ops = particleOps();
  forEachRange(state_.particles.size(), [&](std::size_t b, std::size_t e) { ops.kicks(b, e, h); });
}

void Simulation::drift(float dt) {
  const ParticleOps ops = particleOps();
  forEachRange(state_.particles.size(), [&](std::size_t b, std::size_t e) { ops.drifts(b, e, dt); });
}

// No walls at all without an <Environment>.
void Simulation::applyWalls() {
  if (!model_.container) return;
  const ParticleOps ops = particleOps();
  forEachRange(state_.particles.size(), [&](std::size_t b, std::size_t e) { ops.wallsOf(b, e); });
}

namespace {
// What sweep() does to each block, and the findings it adds to.
struct SweepPlan {
  float h, dt;
  bool explicitEuler, walls, displacement, check;
  const float* ref;   // the list's reference positions (displacement)
  bool uniformReach;  // scanSpeedsOf
  const float* invReach;
};
struct SweepFound {
  Top2 top;
  float speed2 = 0;
  bool finite = true;
};
// One block: stage by stage (at most kBlock slots, in cache from the first stage on), so
// that the kick and the drift stay vectorised loops. Ops: Simulation::ParticleOps.
template <class Ops>
[[gnu::always_inline]] inline void sweepBlockBody(const Ops& ops, const SweepPlan& p, std::size_t b,
                                                  std::size_t e, SweepFound& f) {
  if (p.explicitEuler) {
    ops.drifts(b, e, p.dt);
    ops.kicks(b, e, p.h);
  } else {
    ops.kicks(b, e, p.h);
    ops.drifts(b, e, p.dt);
  }
  if (p.walls) ops.wallsOf(b, e);
  if (p.displacement) f.top.addDisplacements(ops.s, p.ref, b, e);
  if (p.check) scanSpeedsOf(ops.s, b, e, p.uniformReach, p.invReach, f.speed2, f.finite);
}
// The body is built twice where the pair kernels are (SOFTSUB_AVX2_COPY): for the
// baseline and for AVX2, the copy the kernels' choice selects (fluid::simdInUse). No FMA
// in the AVX2 copy (its target is AVX2 alone, and this file is built with
// -ffp-contract=off), so both do the same IEEE operations per particle: the same bits.
#if SOFTSUB_AVX2_COPY
template <class Ops>
__attribute__((target("avx2"))) void sweepBlockAvx2(const Ops& ops, const SweepPlan& p, std::size_t b,
                                                    std::size_t e, SweepFound& f) {
  sweepBlockBody(ops, p, b, e, f);
}
#endif
template <class Ops>
void sweepBlock(bool avx2, const Ops& ops, const SweepPlan& p, std::size_t b, std::size_t e, SweepFound& f) {
#if SOFTSUB_AVX2_COPY
  if (avx2) return sweepBlockAvx2(ops, p, b, e, f);
#else
  (void)avx2;
#endif
  sweepBlockBody(ops, p, b, e, f);
}
}  // namespace

void Simulation::sweep(float h, float dt, bool explicitEuler, bool check) {
  const ParticleOps ops = particleOps();
  const SweepPlan plan{h,
                       dt,
                       explicitEuler,
                       model_.container.has_value(),
                       listValid_,
                       check,
                       ref_,
                       uniformReach_,
                       invReach_.data()};
  const bool avx2 = fluid::simdInUse() == fluid::Simd::Avx2;
  const SweepFound found = tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, state_.particles.size(), kBlock), SweepFound{},
      [&](const tbb::blocked_range<std::size_t>& r, SweepFound f) {
        sweepBlock(avx2, ops, plan, r.begin(), r.end(), f);
        return f;
      },
      [](SweepFound a, const SweepFound& b) {
        a.top.join(b.top);
        a.speed2 = std::max(a.speed2, b.speed2);
        a.finite = a.finite && b.finite;
        return a;
      });
  knownStale_ =
      plan.displacement ? (std::sqrt(found.top.first) + std::sqrt(found.top.second) < skin_ ? 0 : 1) : 1;
  fastestSlot_ = found.top.slot;
  const Extremes extremes{std::sqrt(found.speed2), 0, found.finite};
  if (check) checkFinite(&extremes);
}

// The integrators, from kicks (velocity) and drifts (position):
//   explicit Euler (the seed's): forces at (x_n, v_n); x += v_n dt; v += a dt
//   symplectic Euler:            forces at (x_n, v_n); v += a dt; x += v_{n+1} dt
//   velocity Verlet:             v += a_n dt/2; x += v dt; forces at x_{n+1} (with the
//                                half-step velocity); v += a_{n+1} dt/2, the last kick
//                                merged with the next substep's first inside a frame
// Rigid bodies step once per substep whatever the integrator (semi-implicit Euler with
// impulses: Verlet has no explicit velocity for impulses to change, seed 2.3.4), after
// the fluid has moved, with the forces of the last evaluation (docs/architecture.md).
//
// Without bodies, the stages between two force evaluations run as one sweep() over the
// particles, with the blow-up check and the next stale-list test (7 passes over the
// store become 3 a substep); bodies move their particles after the walls, so with
// bodies the stages run one after another. Both are bitwise the same.
void Simulation::step() {
  const float dt = static_cast<float>(this->dt());
  const bool fused = model_.bodies.empty() && !staged_;
  switch (model_.integrator) {
    case Integrator::ExplicitEuler:
    case Integrator::SymplecticEuler: {
      const bool explicitEuler = model_.integrator == Integrator::ExplicitEuler;
      computeForces();
      state_.forcesValid = false;
      if (fused) {
        ++substepInFrame_;
        sweep(dt, dt, explicitEuler, true);
        return;
      }
      prepareBodies();  // where the forces were evaluated
      if (explicitEuler) {
        drift(dt);  // with v_n
        kick(dt);
      } else {
        kick(dt);
        drift(dt);  // with v_{n+1}
      }
      // The walls after the bodies' step, which corrects the fluid's explicit drag by a
      // change of velocity (RigidSolver::dragFluid): a wall's bounce in between turned
      // that change into a fling. Then the fluid is kept out of the bodies.
      stepBodies(this->dt());
      applyWalls();
      keepFluidOutOfBodies();
      break;
    }
    case Integrator::VelocityVerlet: {
      if (!state_.forcesValid) computeForces();
      // Leapfrog form: inside a frame, a substep's closing half kick and the next one's
      // opening half kick are one kick of dt (a pass over the particles fewer). The
      // frame's last substep closes with its half kick, so velocities are at whole steps
      // wherever a frame ends (caches, energies, checkpoints, --adaptive).
      const float opening = kickOwed_ ? dt : 0.5f * dt;
      // How the fluid came by this substep's kick of dt since its last drag correction:
      // one merged kick inside a frame; at a frame's start the closing half (taken with
      // the drag implicit, closingKick) and this opening half; on a run's first substep
      // the opening half alone.
      const rigid::FluidKick kicked = kickOwed_          ? rigid::FluidKick::Whole
                                      : state_.frame > 0 ? rigid::FluidKick::AfterHeldHalf
                                                         : rigid::FluidKick::OpeningHalf;
      const bool closes = substepInFrame_ + 1 >= substeps_;
      ++substepInFrame_;
      if (fused) {
        sweep(opening, dt, false, !closes);  // checked here unless the closing kick follows
      } else {
        prepareBodies();  // where the forces were evaluated
        kick(opening);
        drift(dt);
        stepBodies(this->dt(), kicked);
        applyWalls();  // as above
        keepFluidOutOfBodies();
      }
      computeForces();
      kickOwed_ = !closes;
      if (closes) closingKick();
      if (closes || !fused) checkFinite();
      return;
    }
  }
  ++substepInFrame_;
  checkFinite();
}

void Simulation::prepare() {
  if (model_.integrator == Integrator::VelocityVerlet && !state_.forcesValid) computeForces();
}

void Simulation::advanceFrame() {
  if (substepInFrame_ == 0 && model_.adaptiveSubsteps) {
    const double needed = neededSubsteps();
    substeps_ = capSubsteps(needed);
    capped_ = needed > substeps_ ? needed : 0;
  }
  while (substepInFrame_ < substeps_) step();
  finishFrame();
}

void Simulation::levelVelocities() {
  if (!kickOwed_) return;
  closingKick();  // with the forces of the last substep's positions
  kickOwed_ = false;
}

// Velocity Verlet's closing half kick, the bodies held: the fluid's drag near bodies
// implicitly (RigidSolver::dragFluidHeld), which the next frame's first substep takes
// back out of its own correction (FluidKick::AfterHeldHalf).
void Simulation::closingKick() {
  const float h = 0.5f * static_cast<float>(dt());
  kick(h);
  if (model_.bodies.empty()) return;
  rigid_.dragFluidHeld(model_.bodies, state_.bodies, state_.particles, rigidPairs_, materialInverseMass_,
                       model_.table, model_.gravity, 0.5 * this->dt());
}

void Simulation::finishFrame() {
  levelVelocities();
  ++state_.frame;
  substepInFrame_ = 0;
  checkFinite();
}

Simulation::Extremes Simulation::joinExtremes(Extremes a, const Extremes& b) {
  a.speed = std::max(a.speed, b.speed);
  a.acceleration = std::max(a.acceleration, b.acceleration);
  a.finite = a.finite && b.finite;
  return a;
}

Simulation::Extremes Simulation::scanParticles(bool withForces) const {
  const ParticleStore& s = state_.particles;
  const float gx = static_cast<float>(model_.gravity.x()), gy = static_cast<float>(model_.gravity.y()),
              gz = static_cast<float>(model_.gravity.z());
  const MaterialInfo* mats = model_.materials.data();
  const float* invReach = invReach_.data();
  return tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, s.size(), kBlock), Extremes{},
      [&](const tbb::blocked_range<std::size_t>& r, Extremes e) {
        float speed2 = 0, accel2 = 0;  // in reach units
        bool finite = true;
        scanSpeeds(s, r.begin(), r.end(), speed2, finite);
        if (withForces)
          for (std::size_t i = r.begin(); i != r.end(); ++i) {
            const float inv = invReach[s.material[i]];
            const float im = mats[s.material[i]].inverseMass;
            const float ax = s.f[i].x * im + gx, ay = s.f[i].y * im + gy, az = s.f[i].z * im + gz;
            const float a2 = (ax * ax + ay * ay + az * az) * inv * inv;
            if (a2 - a2 == 0.0f) accel2 = std::max(accel2, a2);  // unknown forces do not count
          }
        return joinExtremes(e, Extremes{std::sqrt(speed2), std::sqrt(accel2), finite});
      },
      joinExtremes);
}

double Simulation::neededSubsteps() const {
  const double fps = model_.framesPerSecond;
  double n = std::max({1, model_.substeps, stableSubsteps_});
  // The forces of the last evaluation (zero before the first, so gravity alone) are the
  // acceleration's estimate for every integrator.
  const Extremes e = scanParticles(true);
  if (e.finite) {
    // v T / n <= kAdaptiveTravel reach, and (a / 2) (T / n)^2 <= kAdaptiveTravel reach.
    n = std::max(n, std::ceil(e.speed / (fps * kAdaptiveTravel)));
    n = std::max(n, std::ceil(std::sqrt(0.5 * e.acceleration / kAdaptiveTravel) / fps));
  }
  return n;
}

int Simulation::capSubsteps(double needed) const {
  return static_cast<int>(std::clamp(needed, 1.0, static_cast<double>(std::max(1, model_.maxSubsteps))));
}

std::optional<Simulation::BodyTravel> Simulation::fastestBody() const {
  std::optional<BodyTravel> out;
  const rigid::BodySet& set = model_.bodies;
  for (std::size_t b = 0; b < set.bodies.size(); ++b) {
    const rigid::BodyInfo& info = set.bodies[b];
    if (!info.dynamic) continue;
    const rigid::BodyState& st = state_.bodies[b];
    const double travel =
        (st.velocity.norm() + rigid::angularVelocity(info, st).norm() * info.farthest) * dt();
    if (!out || travel / info.particleRadius > out->travel / out->particleRadius)
      out = BodyTravel{b, travel, info.particleRadius};
  }
  return out;
}

double Simulation::travelPerSubstep() const {
  const Extremes e = scanParticles(false);
  return e.finite ? e.speed * dt() : std::numeric_limits<double>::infinity();
}

Simulation::ListReference Simulation::listReference() const {
  if (!listValid_) return {};
  const std::size_t n = state_.particles.size();
  return {{ref_, n}, {ref_ + n, n}, {ref_ + 2 * n, n}};
}

void Simulation::reserveListWork() {
  const std::size_t n = state_.particles.size();
  listWork_.reserve(std::max(neighbors::CellGrid::workBytes(n), 3 * n * sizeof(float)));
}

void Simulation::holdReference(std::span<const float> x, std::span<const float> y, std::span<const float> z) {
  const std::size_t n = x.size();
  float* ref = reuseStorageAs<float>(listWork_.bytes().data(), 3 * n);
  ref_ = ref;
  forEachSlot(n, [&](std::size_t i) {
    ref[i] = x[i];
    ref[n + i] = y[i];
    ref[2 * n + i] = z[i];
  });
  guard_.hold(cellSize_, skin_);
}

void Simulation::restore(State state, std::vector<float> refX, std::vector<float> refY, std::vector<float> refZ) {
  const std::size_t n = state.particles.size();
  if (n != model_.particleCount() || n != state_.particles.size() ||
      state.bodies.size() != model_.bodies.bodies.size())
    throw std::invalid_argument("the checkpoint does not fit the scene: particle or object counts differ");
  if (!refX.empty() && (refX.size() != n || refY.size() != n || refZ.size() != n))
    throw std::invalid_argument("the checkpoint's list reference has the wrong size");
  // Each particle keeps its id's owner and material (what the model gave it), and every
  // value is finite: a checkpoint is trusted no further than a scene file.
  const ParticleStore& now = state_.particles;
  std::vector<std::uint32_t> slotOfId;
  now.slotsById(slotOfId);
  const ParticleStore& in = state.particles;
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint32_t id = in.id[i];
    if (id >= n) throw std::invalid_argument("the checkpoint has an out-of-range particle id");
    const std::uint32_t slot = slotOfId[id];
    if (in.owner[i] != now.owner[slot] || in.material[i] != now.material[slot])
      throw std::invalid_argument("the checkpoint's particles do not belong to this scene's fluids and objects");
  }
  const auto allFinite = [](const std::vector<float>& a) {
    return std::all_of(a.begin(), a.end(), [](float x) { return std::isfinite(x); });
  };
  for (const std::vector<float>* a : std::initializer_list<const std::vector<float>*>{
           &in.px, &in.py, &in.pz, &in.vx, &in.vy, &in.vz, &refX, &refY, &refZ})
    if (!allFinite(*a)) throw std::invalid_argument("the checkpoint holds a value that is not finite");
  if (!std::all_of(in.f.begin(), in.f.end(), [](const Force& f) {
        return std::isfinite(f.x) && std::isfinite(f.y) && std::isfinite(f.z) && std::isfinite(f.w);
      }))
    throw std::invalid_argument("the checkpoint holds a value that is not finite");
  for (const rigid::BodyState& b : state.bodies)
    if (!b.position.allFinite() || !b.velocity.allFinite() || !b.angularMomentum.allFinite() ||
        !b.orientation.coeffs().allFinite())
      throw std::invalid_argument("the checkpoint holds a body state that is not finite");
  const auto nb = static_cast<std::int32_t>(state.bodies.size());
  for (const rigid::ContactMemory& c : state.contacts)
    if (c.a < 0 || c.a >= nb || c.b < -1 || c.b >= nb || c.b == c.a ||
        (c.b == -1) != (c.wall >= 0 && c.wall < 6) || (c.b >= 0 && c.wall != -1) || !c.pointInA.allFinite() ||
        !c.force.allFinite())
      throw std::invalid_argument("the checkpoint holds a contact that does not fit the scene's objects");

  // Rebuild the grid and list from the positions they were built from: the store is
  // still in the order that build sorted it into, so the grid finds it sorted and the
  // list comes out exactly as before. On any failure the simulation is left as it was.
  State previous = std::move(state_);
  state_ = std::move(state);
  const auto giveBack = [&] {
    state_ = std::move(previous);
    listValid_ = false;
    knownStale_ = -1;
    if (!model_.bodies.empty()) rigid_.findBodySlots(model_.bodies, state_.particles);
  };
  substepInFrame_ = 0;
  kickOwed_ = false;
  substeps_ = std::max(1, model_.substeps);
  listValid_ = false;
  knownStale_ = -1;
  if (!model_.bodies.empty()) rigid_.findBodySlots(model_.bodies, state_.particles);
  if (refX.empty()) return;
  ParticleStore& s = state_.particles;
  s.px.swap(refX);
  s.py.swap(refY);
  s.pz.swap(refZ);
  try {
    reserveListWork();
    grid_.rebuild(s, cellSize_ + skin_, listWork_.bytes());
    // Cannot happen for a checkpoint this build wrote; refuse rather than diverge.
    if (grid_.reordered())
      throw std::invalid_argument("the checkpoint's particle order does not match its list reference");
    list_.build(grid_, model_.table, s, skin_, listOptions_);
    if (!model_.bodies.empty()) listRigidPairs();
  } catch (...) {
    s.px.swap(refX);
    s.py.swap(refY);
    s.pz.swap(refZ);
    giveBack();
    throw;
  }
  s.px.swap(refX);
  s.py.swap(refY);
  s.pz.swap(refZ);
  holdReference(refX, refY, refZ);
  listValid_ = true;
}

std::string Simulation::entityName(std::uint32_t owner) const {
  if (owner < model_.fluids.size()) return "fluid '" + model_.fluids[owner].name + "'";
  return "object '" + model_.bodies.bodies.at(owner - model_.bodies.firstEntity).name + "'";
}

void Simulation::checkFinite() const {
  checkFinite(nullptr);
}

// The check with the particles' scan done (sweep()) or, when `scanned` is null, to do.
void Simulation::checkFinite(const Extremes* scanned) const {
  bool ok = true;
  const double limit = model_.maxTravelPerSubstep * model_.framesPerSecond * substeps_;  // reach per second
  for (const rigid::BodyState& st : state_.bodies)
    ok = ok && st.position.allFinite() && st.velocity.allFinite() && st.angularMomentum.allFinite() &&
         st.orientation.coeffs().allFinite();
  if (ok) {
    const Extremes e = scanned != nullptr ? *scanned : scanParticles(false);
    ok = e.finite && !(limit > 0 && e.speed > limit);
  }
  if (!ok) reportBlowUp();
}

// Only on the way out: a serial scan that names the body, or the particle with the
// lowest id, that failed the check.
void Simulation::reportBlowUp() const {
  // What shortens the substep: with --adaptive on, its floor (Substeps) or its ceiling.
  // At the substeps' limit only a shorter frame shortens it.
  const std::string shorter =
      substeps_ >= kMaxStableSubsteps
          ? fmt::format("raise FramesPerSecond: the {} substeps a frame are the most there can be", substeps_)
      : model_.adaptiveSubsteps
          ? fmt::format("raise Substeps (the fewest --adaptive uses) or --max-substeps (now {})", model_.maxSubsteps)
          : std::string("raise Substeps or use --adaptive");
  const std::string when =
      substepInFrame_ > 0
          ? fmt::format("frame {}, substep {} of {}", state_.frame + 1, substepInFrame_, substeps_)
          : fmt::format("frame {}", state_.frame);
  for (std::size_t b = 0; b < state_.bodies.size(); ++b) {
    const rigid::BodyState& st = state_.bodies[b];
    const char* what = !st.position.allFinite()            ? "position"
                       : !st.velocity.allFinite()          ? "velocity"
                       : !st.angularMomentum.allFinite()   ? "angular momentum"
                       : !st.orientation.coeffs().allFinite() ? "rotation"
                                                              : nullptr;
    if (what == nullptr) continue;
    throw BlowUpError(fmt::format(
        "simulation blew up at {}: object '{}': its {} is not finite (forces too stiff for the time step: "
        "{}, lower the FluidObject function or check Mass)",
        when, model_.bodies.bodies[b].name, what, shorter));
  }
  const ParticleStore& s = state_.particles;
  const double limit = model_.maxTravelPerSubstep * model_.framesPerSecond * substeps_;
  static const char* names[6] = {"position x", "position y", "position z", "velocity x", "velocity y", "velocity z"};
  const std::vector<float>* arrays[6] = {&s.px, &s.py, &s.pz, &s.vx, &s.vy, &s.vz};
  std::size_t worst = s.size();
  std::string problem;
  bool tooFast = false;  // finite, beyond the speed limit
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (worst < s.size() && s.id[i] > s.id[worst]) continue;
    std::string p;
    for (int a = 0; a < 6 && p.empty(); ++a)
      if (!std::isfinite((*arrays[a])[i])) p = fmt::format("{} is {}", names[a], (*arrays[a])[i]);
    const bool finite = p.empty();
    if (p.empty() && limit > 0) {
      // The check's own arithmetic (scanParticles), so the particle it flagged is found.
      const float inv = invReach_[s.material[i]];
      const float v2 = (s.vx[i] * s.vx[i] + s.vy[i] * s.vy[i] + s.vz[i] * s.vz[i]) * inv * inv;
      if (std::sqrt(v2) > limit) {
        // The speed itself in double: v2 overflows float for speeds past about 1e19.
        const double vx = s.vx[i], vy = s.vy[i], vz = s.vz[i];
        p = fmt::format(
            "speed is {:.6g} units/s, beyond the limit of {:.6g} units/s ({} interaction distances of "
            "{:.6g} per substep)",
            std::sqrt(vx * vx + vy * vy + vz * vz), limit * reach_[s.material[i]], model_.maxTravelPerSubstep,
            reach_[s.material[i]]);
      }
    }
    if (p.empty()) continue;
    worst = i;
    problem = std::move(p);
    tooFast = finite;
  }
  if (worst == s.size()) throw BlowUpError(fmt::format("simulation blew up at {}", when));
  // A speed beyond the limit is not always the forces: a long fall with nothing below
  // gets there under gravity alone.
  const std::string advice =
      tooFast ? fmt::format("faster than the time step allows: {}; if the speed is real, as in a long fall with "
                            "no container below, raise run's --speed-limit or set it to 0; if the forces cause it, "
                            "lower MaximumForce or Viscosity",
                            shorter)
              : fmt::format("forces too stiff for the time step: {}, lower MaximumForce or Viscosity", shorter);
  throw BlowUpError(fmt::format("simulation blew up at {}: {}, particle id {}: {} ({})", when,
                                entityName(s.owner[worst]), s.id[worst], problem, advice));
}

// Each fluid's particles in id order: its ids are consecutive from firstId, so a pass over
// the slots puts every particle in its place (no id-to-slot table kept between frames: 4
// bytes a particle).
void Simulation::snapshot(FrameSnapshot& out) const {
  const ParticleStore& s = state_.particles;
  out.frame = state_.frame;
  out.time = time();
  out.framesPerSecond = model_.framesPerSecond;
  out.fluids.resize(model_.fluids.size());
  for (std::size_t f = 0; f < model_.fluids.size(); ++f) {
    const FluidInfo& info = model_.fluids[f];
    FluidSnapshot& fs = out.fluids[f];
    fs.name = info.name;
    fs.colour = info.colour;
    fs.particleSize = static_cast<float>(info.particleSize);
    fs.ids.resize(info.count);
    fs.positions.resize(3 * std::size_t{info.count});
    fs.velocities.resize(3 * std::size_t{info.count});
    for (std::uint32_t k = 0; k < info.count; ++k) fs.ids[k] = info.firstId + k;
  }
  for (std::size_t slot = 0; slot < s.size(); ++slot) {
    const std::uint32_t owner = s.owner[slot];
    if (owner >= model_.fluids.size()) continue;  // a body's particle
    FluidSnapshot& fs = out.fluids[owner];
    const std::size_t k = s.id[slot] - model_.fluids[owner].firstId;
    fs.positions[3 * k] = s.px[slot]; fs.positions[3 * k + 1] = s.py[slot]; fs.positions[3 * k + 2] = s.pz[slot];
    fs.velocities[3 * k] = s.vx[slot]; fs.velocities[3 * k + 1] = s.vy[slot]; fs.velocities[3 * k + 2] = s.vz[slot];
  }
  const std::vector<rigid::BodyInfo>& bodies = model_.bodies.bodies;
  out.objects.resize(bodies.size());
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    const rigid::BodyInfo& info = bodies[b];
    const rigid::BodyState& st = state_.bodies[b];
    ObjectSnapshot& o = out.objects[b];
    o.name = info.name;
    o.uniformScale = info.uniformScale;
    const Vec3 origin = st.position + st.orientation * info.originInBody;
    o.position = {origin.x(), origin.y(), origin.z()};
    o.rotation = {st.orientation.w(), st.orientation.x(), st.orientation.y(), st.orientation.z()};
    o.filename = info.geometryFile;
    o.velocity = {st.velocity.x(), st.velocity.y(), st.velocity.z()};
    const Vec3 w = info.dynamic ? rigid::angularVelocity(info, st) : Vec3::Zero();
    o.angularVelocity = {w.x(), w.y(), w.z()};
    o.centerOfMass = {st.position.x(), st.position.y(), st.position.z()};
  }
}

FrameSnapshot Simulation::snapshot() const {
  FrameSnapshot f;
  snapshot(f);
  return f;
}

std::size_t Simulation::memoryBytes() const {
  const ParticleStore& s = state_.particles;
  std::size_t b = 0;
  for (auto* a : {&s.px, &s.py, &s.pz, &s.vx, &s.vy, &s.vz}) b += a->capacity() * 4;
  b += s.f.capacity() * sizeof(Force);
  b += s.material.capacity() * 2 + s.owner.capacity() * 4 + s.id.capacity() * 4;
  b += list_.memoryBytes() + listWork_.size() + guard_.memoryBytes();
  b += rigidPairs_.capacity() * sizeof(rigid::SlotPair) + rigid_.bodySlots().size() * 4;
  b += model_.bodies.particleCount() * 12;  // body-space offsets
  return b + grid_.memoryBytes();
}

}  // namespace softsub::solver
