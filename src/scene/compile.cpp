#include "scene/compile.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "core/error.h"
#include "geometry/fill.h"
#include "geometry/mesh_loader.h"
#include "scene/bodies.h"
#include "scene/fill.h"
#include "scene/reader.h"

namespace softsub::scene {

// The reader's cap keeps every fluid index a valid 16-bit material index.
static_assert(kMaxFluids - 1 <= std::numeric_limits<std::uint16_t>::max());

solver::Integrator toSolver(Integrator i) {
  switch (i) {
    case Integrator::ExplicitEuler: return solver::Integrator::ExplicitEuler;
    case Integrator::SymplecticEuler: return solver::Integrator::SymplecticEuler;
    case Integrator::VelocityVerlet: return solver::Integrator::VelocityVerlet;
  }
  return solver::Integrator::SymplecticEuler;
}

namespace {

forces::Interaction toInteraction(const InteractionDesc& d) {
  return {d.function, d.damping, d.relativeVelocity};
}

}  // namespace

namespace {

// See Compiled::warnings. The fluids' particles, one fluid at a time (they come first,
// in scene order), then the objects', from their bodies' initial poses (the simulation
// places them; the store does not hold them yet).
std::vector<std::string> initialStateWarnings(const solver::Model& m, const ParticleStore& s,
                                              const solver::State& state) {
  std::vector<std::string> out;
  std::vector<std::pair<std::size_t, std::string>> groups;  // first slot past each fluid
  std::size_t n = 0;
  for (const solver::FluidInfo& f : m.fluids) {
    n += f.count;
    groups.emplace_back(n, fmt::format("Fluid '{}'", f.name));
  }
  if (m.container) {
    const solver::Container& c = *m.container;
    const auto outside = [&](std::size_t i) {
      return s.px[i] < c.lo[0] || s.px[i] > c.hi[0] || s.py[i] < c.lo[1] || (c.closed && s.py[i] > c.hi[1]) ||
             s.pz[i] < c.lo[2] || s.pz[i] > c.hi[2];
    };
    const std::string box = fmt::format("x [{:g}, {:g}], y [{:g}, {}], z [{:g}, {:g}]", c.lo[0], c.hi[0], c.lo[1],
                                        c.closed ? fmt::format("{:g}", c.hi[1]) : "open top", c.lo[2], c.hi[2]);
    std::size_t from = 0;
    for (std::size_t f = 0; f < groups.size(); ++f) {
      const auto& [to, what] = groups[f];
      std::size_t count = 0;
      for (std::size_t i = from; i < to; ++i) count += outside(i) ? 1 : 0;
      // Inside the box, but nearer a wall than the half ParticleSize at which the walls
      // keep centres, by more than a tenth of the size: the first substep moves them
      // into their neighbours at once. A fill flush with the walls at a spacing below
      // its ParticleSize went from a total energy of 976 to 31,392 in a frame (a review).
      // (A container narrower than the ParticleSize has a warning of its own.)
      const double r = 0.5 * m.fluids[f].particleSize, tolerance = 0.2 * r;
      const bool roomy = c.hi[0] - c.lo[0] >= 2 * r && c.hi[2] - c.lo[2] >= 2 * r &&
                         (!c.closed || c.hi[1] - c.lo[1] >= 2 * r);
      std::size_t near = 0;
      double deepest = 0;
      for (std::size_t i = from; i < to && count == 0 && roomy; ++i) {
        const double p[3] = {s.px[i], s.py[i], s.pz[i]};
        double depth = 0;
        for (int a = 0; a < 3; ++a) {
          const double lo = c.lo[a] + r, hi = c.hi[a] - r;
          depth = std::max(depth, lo - p[a]);
          if (a != 1 || c.closed) depth = std::max(depth, p[a] - hi);
        }
        if (depth > tolerance) {
          ++near;
          deepest = std::max(deepest, depth);
        }
      }
      if (count > 0)
        out.push_back(fmt::format("{}: {} of {} particles start outside the container ({}); its walls put them "
                                  "back inside on the first substep, with a jolt",
                                  what, count, to - from, box));
      else if (near > 0)
        out.push_back(fmt::format(
            "{}: {} of {} particles start nearer the container's walls than half their ParticleSize "
            "{:g}, where the walls keep their centres (by up to {:.3g}): the first substep moves them "
            "into their neighbours, with a jolt; start the fill half a ParticleSize inside the walls, "
            "or set ParticleSize to the particles' spacing",
            what, near, to - from, m.fluids[f].particleSize, deepest));
      from = to;
    }
    // The objects: the same test on each particle's initial world position.
    const rigid::BodySet& set = m.bodies;
    for (std::size_t b = 0; b < set.bodies.size() && b < state.bodies.size(); ++b) {
      const rigid::BodyInfo& info = set.bodies[b];
      const rigid::BodyState& pose = state.bodies[b];
      const Mat3 r = pose.orientation.toRotationMatrix();
      std::size_t count = 0;
      Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY);
      for (std::uint32_t k = info.firstId - set.firstId; k < info.firstId - set.firstId + info.count; ++k) {
        const Vec3 p = pose.position + r * Vec3(set.ox[k], set.oy[k], set.oz[k]);
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
        count += p.x() < c.lo[0] || p.x() > c.hi[0] || p.y() < c.lo[1] || (c.closed && p.y() > c.hi[1]) ||
                         p.z() < c.lo[2] || p.z() > c.hi[2]
                     ? 1
                     : 0;
      }
      // A body wider than the container on some axis cannot be put inside by the walls
      // (a mesh in millimetres in a scene in centimetres was flung 120 units in a frame).
      int wider = -1;
      for (int a = 0; a < 3 && wider < 0; ++a)
        if ((a != 1 || c.closed) && hi[a] - lo[a] + 2 * info.particleRadius > c.hi[a] - c.lo[a]) wider = a;
      if (wider >= 0)
        out.push_back(
            fmt::format("Object '{}': its particles span {:g} in {}, more than the container's {:g}; {} (a "
                        "mesh in other units? UniformScale scales it)",
                        info.name, hi[wider] - lo[wider] + 2 * info.particleRadius, "xyz"[wider],
                        c.hi[wider] - c.lo[wider],
                        info.dynamic ? "the walls push it in with a jolt, turning a long body or flinging it"
                                     : "the fluids cannot reach the part outside"));
      else if (count > 0)
        out.push_back(fmt::format(
            "Object '{}': {} of {} particles start outside the container ({}); {}", info.name, count, info.count, box,
            info.dynamic ? "the walls push the body back inside over the first substeps, with a jolt"
                         : "a static body never moves, and the fluids inside cannot reach the part outside"));
    }
  }
  // A ParticleSize far from the particles' own spacing: it sets how far the walls keep
  // their centres, the surfaces' radius and the drawing, and its default, 1, is absolute;
  // a centimetre-scale scene that left it out collapsed onto a line between walls that
  // left it no room. The spacing: the median distance to the nearest neighbour of up to
  // 64 particles spread over the fluid.
  std::size_t begin = 0;
  for (std::size_t f = 0; f < m.fluids.size(); begin += m.fluids[f].count, ++f) {
    const solver::FluidInfo& fluid = m.fluids[f];
    if (fluid.count < 2) continue;
    const std::size_t samples = std::min<std::size_t>(fluid.count, 64);
    std::vector<double> nearest;
    for (std::size_t k = 0; k < samples; ++k) {
      const std::size_t i = begin + k * fluid.count / samples;
      double best = INFINITY;
      for (std::size_t j = begin; j < begin + fluid.count; ++j) {
        const double dx = double(s.px[j]) - s.px[i], dy = double(s.py[j]) - s.py[i], dz = double(s.pz[j]) - s.pz[i];
        const double d2 = dx * dx + dy * dy + dz * dz;
        if (j != i && d2 > 0) best = std::min(best, d2);
      }
      if (std::isfinite(best)) nearest.push_back(std::sqrt(best));
    }
    if (nearest.empty()) continue;
    std::nth_element(nearest.begin(), nearest.begin() + static_cast<std::ptrdiff_t>(nearest.size() / 2), nearest.end());
    const double spacing = nearest[nearest.size() / 2];
    const double ratio = fluid.particleSize / spacing;
    if (ratio > 3 || ratio < 1.0 / 3)
      out.push_back(fmt::format(
          "Fluid '{}': ParticleSize {:g} is {:.3g} times the spacing of its particles ({:.3g}); the walls keep "
          "particle centres half a ParticleSize from them, and surfaces and pictures use it: set ParticleSize "
          "near the spacing (a scene in other units must set it: the default, 1, is absolute)",
          fluid.name, fluid.particleSize, ratio, spacing));
    if (m.container) {
      const solver::Container& c = *m.container;
      const double room = std::min({c.hi[0] - c.lo[0], c.hi[2] - c.lo[2], c.closed ? c.hi[1] - c.lo[1] : INFINITY});
      if (room < fluid.particleSize)
        out.push_back(fmt::format("Fluid '{}': the container is {:g} across, narrower than its ParticleSize {:g}: the "
                                  "walls, which keep centres half a ParticleSize in, leave no room and squeeze the "
                                  "fluid onto a line",
                                  fluid.name, room, fluid.particleSize));
    }
  }
  // Exact duplicates: sorted positions, equal neighbours.
  std::vector<std::array<float, 3>> p(n);
  for (std::size_t i = 0; i < n; ++i) p[i] = {s.px[i], s.py[i], s.pz[i]};
  std::sort(p.begin(), p.end());
  std::size_t same = 0;
  for (std::size_t i = 1; i < n; ++i) same += p[i] == p[i - 1] ? 1 : 0;
  if (same > 0)
    out.push_back(fmt::format("Particles: {} {} exactly where another one does (a repeated <Fill> or point?); a "
                              "pair at distance 0 has no direction, so they never push apart",
                              same, same == 1 ? "particle sits" : "particles sit"));
  return out;
}

// Functions whose cutoff is so many times their own length scale (FiniteDistance, sigma)
// that the table, at its cap of pieces, no longer follows their shape: an
// InteractionDistance of 1e6 made a fluid repel where it attracts (a black-box review).
// Each distinct function once; named by the first pair of rows that uses it.
std::vector<std::string> samplingWarnings(const SceneDesc& d, const solver::Model& m,
                                          const ParticleStore& store) {
  std::vector<std::string> out;
  const std::size_t rows = m.table.materials(), nf = d.fluids.size();
  // A body row is named by its objects (objects with the same interactions share one).
  const auto rowName = [&](std::size_t r) {
    if (r < nf) return fmt::format("fluid '{}'", d.fluids[r].name);
    std::vector<std::string> names;
    for (const rigid::BodyInfo& b : m.bodies.bodies)
      if (b.count > 0 && b.firstId < store.size() && store.material[b.firstId] == r)
        names.push_back(fmt::format("'{}'", b.name));
    return fmt::format("object{} {}", names.size() == 1 ? "" : "s", fmt::join(names, ", "));
  };
  std::vector<forces::PairFunction> seen;
  for (std::size_t a = 0; a < rows; ++a)
    for (std::size_t b = a; b < rows; ++b) {
      if (a >= nf && b >= nf) continue;  // bodies meet by impulses
      const forces::PairFunction& f = m.table.interaction(a, b).function;
      const int n = forces::intervalsFor(f);
      if (n < forces::kMaxIntervals || std::find(seen.begin(), seen.end(), f) != seen.end()) continue;
      seen.push_back(f);
      const double error = forces::samplingError(f, n);
      if (!(error > 0.02)) continue;
      const double rc = forces::cutoff(f), length = forces::lengthScale(f);
      const std::string who =
          a == b ? fmt::format("Fluid '{}': its own function", d.fluids[a].name)
                 : fmt::format("Interactions: the function between {} and {}", rowName(a), rowName(b));
      out.push_back(fmt::format(
          "{} reaches {:g}, {:.3g} times its length scale {:g} (FiniteDistance, sigma or the closest Curve "
          "points): the force table's {} pieces are {:.3g} long, and the force it applies strays by up to "
          "{:.0f}% of its largest value at that scale; keep the cutoff (InteractionDistance, Cutoff) under "
          "about 1,000 times the length scale",
          who, rc, rc / length, length, n, rc / n, 100 * error));
    }
  return out;
}

// Fluid/object drag so strong that one pair's rate, (Damping + RelativeVelocity) dt / m
// with m the lighter of the fluid particle and a dynamic object, passes 1e4: the drag is
// implicit, but the forces it is corrected from are single precision, and their rounding
// then outweighs the balance (Damping 1e8 on a particle of mass 1 made a plate and the
// particle on it gain momentum: 40 -> 1,056; a review). Any rate past 1 already stops the
// fluid against the object within a substep.
std::vector<std::string> dragWarnings(const SceneDesc& d, const solver::Model& m) {
  std::vector<std::string> out;
  const double dt = m.dt();
  for (const FluidDesc& fluid : d.fluids)
    for (const ObjectDesc& o : d.objects) {
      const PairDesc* pair = findPair(d.interactions, fluid.name, o.name);
      const InteractionDesc& in = pair ? pair->interaction : d.interactions.fluidObject;
      // The lighter side decides: a light body under a heavy particle loses the balance
      // as soon (a plate of mass 0.01 under a particle of mass 1, Damping 1e5: +54%).
      const double mass =
          o.isDynamic ? std::min(fluid.params.particleMass, o.mass) : fluid.params.particleMass;
      const double rate = (in.damping + in.relativeVelocity) * dt / mass;
      if (!(rate > 1e4)) continue;
      out.push_back(fmt::format(
          "Interactions: the fluid/object drag between fluid '{}' and object '{}' (Damping {:g}, "
          "RelativeVelocity {:g}; the lighter mass {:g}) is {:.3g} times what one substep of {:.3g} s can "
          "follow, for each pair of particles: past about 10,000 the single-precision forces lose the drag's "
          "balance and create momentum; any value above {:.3g} (that mass / dt) already stops the two "
          "together within a substep",
          fluid.name, o.name, in.damping, in.relativeVelocity, mass, rate, dt, mass / dt));
      break;  // one warning a fluid
    }
  return out;
}

// A static object never moves: initial velocities given to one would be dropped without
// a word.
std::vector<std::string> staticObjectWarnings(const SceneDesc& d) {
  std::vector<std::string> out;
  for (const ObjectDesc& o : d.objects) {
    const bool linear = !o.initialLinearVelocity.isZero(), angular = !o.initialAngularVelocity.isZero();
    if (o.isDynamic || (!linear && !angular)) continue;
    out.push_back(fmt::format(
        "Object '{}' (line {}) is static (IsDynamic false): its {} not used, as a static object never moves; "
        "set IsDynamic true for a body that moves",
        o.name, o.line,
        linear && angular ? "InitialLinearVelocity and InitialAngularVelocity are"
                          : (linear ? "InitialLinearVelocity is" : "InitialAngularVelocity is")));
  }
  return out;
}

// A fluid whose own function is zero (FiniteDistance) at or past its cutoff
// (InteractionDistance) only pushes, at up to MaximumForce, and ends in a jump at the
// cutoff: raising FiniteDistance to make particles larger and leaving InteractionDistance
// at its absolute default, 1.5, made a ball of fluid fly apart without a word (a review).
// Not for a fluid whose own function a <Pair> replaces.
std::vector<std::string> ownFunctionWarnings(const SceneDesc& d) {
  std::vector<std::string> out;
  for (const FluidDesc& f : d.fluids) {
    const fluid::FluidParams& p = f.params;
    if (p.finiteDistance < p.interactionDistance) continue;
    if (std::any_of(d.interactions.pairs.begin(), d.interactions.pairs.end(),
                    [&](const PairDesc& q) { return q.a == f.name && q.b == f.name; }))
      continue;
    out.push_back(fmt::format(
        "Fluid '{}' (line {}): FiniteDistance {:g} is not below InteractionDistance {:g}: its own "
        "force only pushes its particles apart (up to MaximumForce {:g}) and never holds them "
        "together, and stops with a jump at the cutoff; InteractionDistance is usually about 1.5 "
        "times FiniteDistance ({:g})",
        f.name, f.line, p.finiteDistance, p.interactionDistance, p.maximumForce, 1.5 * p.finiteDistance));
  }
  return out;
}

}  // namespace

double cubicVirial(const forces::PairFunction& f, double a) {
  const double cut = forces::cutoff(f);
  if (!(a > 0) || !(cut > 0)) return 0;
  // How many n in Z^3 have |n|^2 = k, for k up to 64^2 (neighbours out to 64 spacings:
  // a lattice finer than a 64th of the cutoff is counted to there only).
  constexpr int kMost = 64;
  static const std::vector<int> shells = [] {
    std::vector<int> count(kMost * kMost + 1, 0);
    for (int x = -kMost; x <= kMost; ++x)
      for (int y = -kMost; y <= kMost; ++y)
        for (int z = -kMost; z <= kMost; ++z) {
          const int k = x * x + y * y + z * z;
          if (k <= kMost * kMost) ++count[static_cast<std::size_t>(k)];
        }
    return count;
  }();
  const double most = std::min(cut / a, static_cast<double>(kMost));
  const auto last = static_cast<std::size_t>(std::floor(most * most));
  double w = 0;
  for (std::size_t k = 1; k <= last; ++k) {
    const double r = a * std::sqrt(static_cast<double>(k));
    if (r >= cut) break;
    if (shells[k] > 0) w += shells[k] * r * forces::evaluate(f, r);
  }
  return w;
}

std::vector<double> cubicRests(const forces::PairFunction& f, double from) {
  std::vector<double> rests;
  const double cut = forces::cutoff(f);
  if (!(cut > 0) || !(from > 0) || from >= cut) return rests;
  constexpr int kSteps = 200;  // rests closer than half a percent of the range are not told apart
  const double step = (cut - from) / kSteps;
  double previous = cubicVirial(f, from);
  for (int k = 1; k <= kSteps; ++k) {
    const double a = from + k * step, w = cubicVirial(f, a);
    // Pushes apart below, no longer above (pulls, or no force: a fluid without
    // attraction swells until its particles stop pushing): a rest.
    if (previous > 0 && w <= 0) {
      double below = a - step, above = a;
      for (int i = 0; i < 40; ++i) {
        const double mid = 0.5 * (below + above);
        (cubicVirial(f, mid) > 0 ? below : above) = mid;
      }
      rests.push_back(above);
    }
    previous = w;
  }
  return rests;
}

std::optional<double> cubicRestFrom(const std::vector<double>& rests, const forces::PairFunction& f,
                                    double near) {
  const double w = cubicVirial(f, near);
  if (w > 0)  // pushed apart: to the first rest above
    for (const double r : rests)
      if (r > near) return r;
  if (w < 0)  // pulled together: to the last rest below
    for (auto r = rests.rbegin(); r != rests.rend(); ++r)
      if (*r < near) return *r;
  return std::nullopt;
}

std::optional<double> cubicRestSpacing(const forces::PairFunction& f, double near) {
  const double cut = forces::cutoff(f);
  if (!(cut > 0) || !(near > 0) || near >= cut) return std::nullopt;  // no neighbour in reach
  return cubicRestFrom(cubicRests(f, std::max(std::min(cut / 4, near / 4), cut / 64)), f, near);
}

namespace {

// A fill far from the spacing its fluid rests at changes its volume in the first
// frames: the jelly example's cube (Spacing 1.12, rest about 0.945) lost 41% of its
// volume in mid-air in 4 frames, and a mud layer at 0.8 (rest about 0.97) swelled by 63%
// (a black-box review). Warned per fill, from the fluid's own function (or the Pair
// that replaces it), when the volume would change by more than 35%: the examples' fills
// at 1.1 of fluids that rest at 0.96-0.98 (about 30%, much of it hidden by their splash
// or slowed by their viscosity) stay quiet. The rests are found once a fluid.
std::vector<std::string> fillSpacingWarnings(const SceneDesc& d) {
  std::vector<std::string> out;
  for (const FluidDesc& f : d.fluids) {
    if (f.fills.empty()) continue;
    forces::PairFunction own = fluid::ownFunction(f.params);
    const PairDesc* self = findPair(d.interactions, f.name, f.name);
    if (self != nullptr) own = self->interaction.function;
    // From a quarter of the cutoff or of the finest fill's spacing, whichever is less (a
    // fill well above its rest finds it below: a review's InteractionDistance 4.5 filled
    // at 2.5 rests at 0.92), but not below a 64th of the cutoff (the shells counted).
    const double cut = forces::cutoff(own);
    double from = cut / 4;
    for (const FillDesc& fill : f.fills) from = std::min(from, fill.spacing / 4);
    from = std::max(from, cut / 64);
    const std::vector<double> rests = cubicRests(own, from);
    const std::string force = self != nullptr ? fmt::format("its own <Pair> (line {})", self->line)
                                              : std::string("this fluid's own force");
    const std::string distances = self != nullptr ? std::string("that <Pair>'s distances")
                                                  : std::string("FiniteDistance and InteractionDistance");
    for (const FillDesc& fill : f.fills) {
      // A shell; particles out of each other's reach; a fill that pulls itself together
      // finer than the search reaches below it (a cutoff hundreds of times its
      // spacing): nothing to say.
      if (fill.surface || !(fill.spacing < cut)) continue;
      if (fill.spacing < 4 * from * (1 - 1e-9) && cubicVirial(own, fill.spacing) < 0) continue;
      const std::optional<double> rest = cubicRestFrom(rests, own, fill.spacing);
      if (!rest) {
        // Only a function that pushes at no spacing searched collapses the fill.
        if (rests.empty() && cubicVirial(own, fill.spacing) < 0 && !(cubicVirial(own, from) > 0))
          out.push_back(
              fmt::format("Fluid '{}': the fill at line {} has Spacing {:g}, and {} only pulls such a "
                          "lattice together: it "
                          "collapses until its particles overlap; give the function a push at short range",
                          f.name, fill.line, fill.spacing, force));
        continue;
      }
      const double ratio = *rest / fill.spacing, volume = ratio * ratio * ratio;
      if (volume > 0.65 && volume < 1.35) continue;
      const std::string change =
          volume < 1e-3  ? std::string("shrinks to under a thousandth of its volume")
          : volume > 1e3 ? std::string("swells to over a thousand times its volume (it bursts apart)")
          : volume < 0.5 ? fmt::format("shrinks to about {:.2g} of its volume", volume)
          : volume < 1   ? fmt::format("shrinks by about {:.0f}% in volume", (1 - volume) * 100)
          : volume <= 2  ? fmt::format("swells by about {:.0f}% in volume", (volume - 1) * 100)
                         : fmt::format("swells to about {:.3g} times its volume (it bursts apart)", volume);
      out.push_back(
          fmt::format("Fluid '{}': the fill at line {} has Spacing {:g}, but {} holds such a lattice at rest "
                      "about {:.3g} apart, "
                      "so it {} in its first frames; fill at Spacing {:.3g}, or scale {} by {:.3g} (the rest "
                      "spacing follows "
                      "them)",
                      f.name, fill.line, fill.spacing, force, *rest, change, *rest, distances, 1 / ratio));
    }
  }
  return out;
}

// The seed's two global functions are absolute: cutoffs 1 (fluid/fluid) and 1.5
// (fluid/object) and forces of 5, made for particles about a unit apart. A scene in
// other units that leaves them out gets them at the wrong scale (a black-box review:
// centimetre fluids 11 cm apart pushed each other to +-15 units, and a pair list whose
// radius was the unit cutoff made the run 54 times slower; at a scale of 100 they pass
// through each other). Warned once for each function, for the first pair of a fluid's
// reach (its own function's cutoff) and the default's cutoff more than 5 times off the
// seed's proportion (1.5 to 1 and 1.5 to 1.5).
std::vector<std::string> defaultInteractionWarnings(const SceneDesc& d, const solver::Model& m) {
  std::vector<std::string> out;
  const InteractionsDesc seed;
  const auto paired = [&](const std::string& a, const std::string& b) {
    return std::any_of(d.interactions.pairs.begin(), d.interactions.pairs.end(),
                       [&](const PairDesc& p) { return (p.a == a && p.b == b) || (p.a == b && p.b == a); });
  };
  // A fluid's reach: its own function's cutoff (a Pair naming it twice replaces it).
  const auto reach = [&](std::size_t f) {
    const FluidDesc& fluid = d.fluids[f];
    for (const PairDesc& p : d.interactions.pairs)
      if (p.a == fluid.name && p.b == fluid.name) return forces::cutoff(p.interaction.function);
    return fluid.params.interactionDistance;
  };
  const auto offScale = [](double fluidReach, double defaultCutoff, double seedRatio) {
    const double r = fluidReach / defaultCutoff / seedRatio;
    return r < 0.2 || r > 5;
  };
  const auto has = [&](std::size_t f) { return f < m.fluids.size() && m.fluids[f].count > 0; };
  if (d.interactions.fluidFluid == seed.fluidFluid) {
    const double cut = forces::cutoff(seed.fluidFluid.function);
    bool warned = false;
    for (std::size_t a = 0; a < d.fluids.size() && !warned; ++a)
      for (std::size_t b = a + 1; b < d.fluids.size() && !warned; ++b) {
        if (!has(a) || !has(b) || paired(d.fluids[a].name, d.fluids[b].name)) continue;
        const double r = std::max(reach(a), reach(b));
        if (!offScale(r, cut, 1.5)) continue;
        warned = true;
        out.push_back(fmt::format(
            "Interactions: fluids '{}' and '{}' (reach {:g}) meet through the default fluid/fluid function, "
            "the "
            "seed's Linear from 5 at contact to 0 at distance {:g} in absolute units: at this scale it {}; "
            "give "
            "<FluidFluid> (or a <Pair> for them) in the scene's units",
            d.fluids[a].name, d.fluids[b].name, r, cut,
            r < cut ? "pushes them apart from much further than they reach, and its long list slows the run"
                    : "hardly acts, and they pass through each other"));
      }
  }
  if (d.interactions.fluidObject == seed.fluidObject && !d.objects.empty()) {
    const double cut = forces::cutoff(seed.fluidObject.function);
    bool warned = false;
    for (std::size_t f = 0; f < d.fluids.size() && !warned; ++f)
      for (const ObjectDesc& o : d.objects) {
        if (!has(f) || paired(d.fluids[f].name, o.name)) continue;
        const double r = reach(f);
        if (!offScale(r, cut, 1.0)) continue;
        warned = true;
        out.push_back(
            fmt::format("Interactions: fluid '{}' (reach {:g}) meets object '{}' through the default "
                        "fluid/object function, "
                        "the seed's Linear from 5 at contact to 0 at distance {:g} in absolute units: at "
                        "this scale it {}; "
                        "give <FluidObject> (or a <Pair> for them) in the scene's units",
                        d.fluids[f].name, r, o.name, cut,
                        r < cut ? "pushes the fluid from much further than it reaches"
                                : "hardly acts, and the fluid passes through the object"));
        break;
      }
  }
  return out;
}

// Appends the points of fluid fd's fill k to `points`.
void fillPoints(const SceneDesc& desc, const FluidDesc& fd, std::size_t k, std::vector<Vec3>& points) {
  const FillDesc& fill = fd.fills[k];
  if (fill.shape != FillShape::Mesh) {
    generateFill(fill, points);
    return;
  }
  // The reader checked the path, the mesh and its bound against the particle cap; the
  // loader's and the fill's warnings (repairs, open meshes) are not shown here.
  const geometry::TriangleMesh mesh = geometry::loadMesh(
      std::filesystem::path(desc.baseDir) / fill.geometry, nullptr,
      desc.baseDir.empty() ? std::filesystem::path(".") : std::filesystem::path(desc.baseDir));
  const geometry::MeshFillResult r =
      geometry::fillMesh(mesh, {.spacing = fill.spacing,
                                .surfaceOnly = fill.surface,
                                .maxParticles = geometry::meshFillBound(mesh, fill.spacing)});
  // As a box or sphere fill that makes nothing is refused when the scene is read (a mesh
  // fill's count is known only now, from the fill itself).
  if (r.points.empty())
    throw InputError(
        {desc.file, fill.line, fmt::format("Fluid '{}'/Fill[{}]", fd.name, k + 1)},
        fmt::format("the mesh fill of '{}' makes no particles at Spacing {:g}", fill.geometry, fill.spacing),
        "a Spacing smaller than the mesh's thickness, or <Surface>true</Surface> for a thin or "
        "open mesh");
  points.insert(points.end(), r.points.begin(), r.points.end());
}

}  // namespace

Compiled compile(const SceneDesc& desc) {
  Compiled out;
  solver::Model& m = out.model;
  m.framesPerSecond = desc.simulation.framesPerSecond;
  m.substeps = desc.simulation.substeps;
  m.frames = desc.simulation.frames;
  m.gravity = desc.simulation.gravity;
  m.integrator = toSolver(desc.simulation.integrator);
  if (desc.environment) {
    const EnvironmentDesc& e = *desc.environment;
    solver::Container c;
    c.lo = {-e.width / 2, 0, -e.depth / 2};
    c.hi = {e.width / 2, e.height, e.depth / 2};
    c.closed = e.closed;
    c.restitution = e.normalAttenuation;
    c.friction = e.tangentAttenuation;
    m.container = c;
  }

  const std::size_t nf = desc.fluids.size();
  m.table = forces::InteractionTable(nf);
  for (std::size_t a = 0; a < nf; ++a) {
    const FluidDesc& fa = desc.fluids[a];
    for (std::size_t b = a; b < nf; ++b) {
      const FluidDesc& fb = desc.fluids[b];
      const PairDesc* p = findPair(desc.interactions, fa.name, fb.name);
      try {
        if (p) m.table.set(a, b, toInteraction(p->interaction));
        else if (a == b) m.table.set(a, a, {fluid::ownFunction(fa.params), fa.params.viscosity, 0});
        else m.table.set(a, b, toInteraction(desc.interactions.fluidFluid));
      } catch (const std::length_error& e) {  // the table's size cap (forces::kMaxTableFloats)
        throw InputError({desc.file, p ? p->line : fa.line, p ? "Interactions/Pair" : "Fluid"}, e.what(),
                         "fewer distinct pair functions (pairs with the same function share one table), "
                         "or shorter cutoffs relative to FiniteDistance");
      }
    }
  }

  // The objects' geometry first: fills with OutsideObjects leave out what lies inside them.
  ObjectShapes shapes(desc);
  std::vector<std::string> carved;  // warnings about fills left empty by OutsideObjects
  out.leftOutInsideObjects.assign(nf, 0);
  ParticleStore& store = out.state.particles;
  std::vector<Vec3> points;
  std::uint32_t nextId = 0;
  for (std::size_t f = 0; f < nf; ++f) {
    const FluidDesc& fd = desc.fluids[f];
    points.assign(fd.particles.begin(), fd.particles.end());
    for (std::size_t k = 0; k < fd.fills.size(); ++k) {
      const FillDesc& fill = fd.fills[k];
      const std::size_t from = points.size();
      fillPoints(desc, fd, k, points);
      if (!fill.outsideObjects) continue;
      const double radius = 0.5 * fd.params.particleSize;
      const auto kept = std::remove_if(points.begin() + static_cast<std::ptrdiff_t>(from), points.end(),
                                       [&](const Vec3& p) { return shapes.inside(p, radius); });
      const auto left = static_cast<std::size_t>(kept - points.begin()) - from;
      if (left == 0)
        carved.push_back(
            fmt::format("Fluid '{}'/Fill[{}] (line {}): all {} of its points lie inside objects "
                        "(OutsideObjects true), so it adds no particles",
                        fd.name, k + 1, fill.line, points.size() - from));
      out.leftOutInsideObjects[f] += static_cast<std::size_t>(points.end() - kept);
      points.erase(kept, points.end());
    }
    if (points.empty())
      throw InputError({desc.file, fd.line, fmt::format("Fluid '{}'", fd.name)},
                       "every point of the fluid's fills lies inside an object (OutsideObjects true), so it "
                       "has no particles",
                       "fills that reach outside the objects, or OutsideObjects false");
    solver::FluidInfo info;
    info.name = fd.name;
    info.colour = {static_cast<float>(fd.colour.x()), static_cast<float>(fd.colour.y()),
                   static_cast<float>(fd.colour.z())};
    info.particleSize = fd.params.particleSize;
    info.particleMass = fd.params.particleMass;
    info.firstId = nextId;
    info.count = static_cast<std::uint32_t>(points.size());
    m.fluids.push_back(info);
    m.materials.push_back({static_cast<float>(1.0 / fd.params.particleMass),
                           static_cast<float>(fd.params.particleSize / 2)});
    store.reserve(store.size() + points.size());
    const auto v = fd.initialSpeed.cast<float>();
    for (const Vec3& p : points)
      store.add(static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z()), v.x(),
                v.y(), v.z(), static_cast<std::uint16_t>(f), static_cast<std::uint32_t>(f));
    nextId += info.count;
  }
  std::vector<std::string> inside;
  addBodies(desc, std::move(shapes), m, out.state, out.objectMeshes, &inside);
  out.warnings = initialStateWarnings(m, store, out.state);
  for (std::string& w : inside) out.warnings.push_back(std::move(w));
  for (std::string& w : carved) out.warnings.push_back(std::move(w));
  for (std::string& w : ownFunctionWarnings(desc)) out.warnings.push_back(std::move(w));
  for (std::string& w : fillSpacingWarnings(desc)) out.warnings.push_back(std::move(w));
  for (std::string& w : defaultInteractionWarnings(desc, m)) out.warnings.push_back(std::move(w));
  for (std::string& w : staticObjectWarnings(desc)) out.warnings.push_back(std::move(w));
  for (std::string& w : samplingWarnings(desc, m, store)) out.warnings.push_back(std::move(w));
  for (std::string& w : dragWarnings(desc, m)) out.warnings.push_back(std::move(w));
  return out;
}

}  // namespace softsub::scene
