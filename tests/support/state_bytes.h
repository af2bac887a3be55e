#pragma once
// A simulation's state as raw bytes, for bitwise comparisons (threads, checkpoints) and
// pinned hashes: every particle's position and velocity (and with `withForces` its
// force) in slot order, the ids, then every body's position, velocity, angular momentum
// and orientation (w, x, y, z), then the bodies' contact memory (State::contacts).
#include <cstdint>
#include <vector>

#include "solver/simulation.h"

namespace softsub::scenarios {

inline std::vector<std::uint8_t> stateBytes(const solver::Simulation& sim, bool withForces = false) {
  std::vector<std::uint8_t> out;
  const auto append = [&out](const void* data, std::size_t bytes) {
    const auto* b = static_cast<const std::uint8_t*>(data);
    out.insert(out.end(), b, b + bytes);
  };
  const ParticleStore& p = sim.state().particles;
  for (const std::vector<float>* a : {&p.px, &p.py, &p.pz, &p.vx, &p.vy, &p.vz}) append(a->data(), a->size() * 4);
  if (withForces)
    for (float Force::*c : {&Force::x, &Force::y, &Force::z})  // every x, then y, then z
      for (const Force& f : p.f) append(&(f.*c), 4);
  append(p.id.data(), p.id.size() * sizeof(std::uint32_t));
  for (const rigid::BodyState& b : sim.state().bodies) {
    const double v[13] = {b.position.x(),        b.position.y(),        b.position.z(),
                          b.velocity.x(),        b.velocity.y(),        b.velocity.z(),
                          b.angularMomentum.x(), b.angularMomentum.y(), b.angularMomentum.z(),
                          b.orientation.w(),     b.orientation.x(),     b.orientation.y(),
                          b.orientation.z()};
    append(v, sizeof v);
  }
  for (const rigid::ContactMemory& c : sim.state().contacts) {
    const std::int32_t k[3] = {c.a, c.b, c.wall};
    const double v[6] = {c.pointInA.x(), c.pointInA.y(), c.pointInA.z(),
                         c.force.x(),    c.force.y(),    c.force.z()};
    append(k, sizeof k);
    append(v, sizeof v);
  }
  return out;
}

}  // namespace softsub::scenarios
