#pragma once
/// Small scenes for the session tests (a few hundred particles: fast).
#include <gtest/gtest.h>

#include <cstddef>
#include <vector>

#include "cache/cache_test_support.h"
#include "scene/scene_desc.h"

namespace softsub::session::test {

using cache::test::ScratchDir;

/// Two fluids in a container (a 4x4x4 block of "goo" above a 3x2x3 block of "syrup"),
/// 4 substeps at 24 fps; with `objects`, two small dynamic boxes beside them.
inline scene::SceneDesc smallScene(bool objects = false) {
  scene::SceneDesc d;
  d.simulation.substeps = 4;
  d.simulation.frames = 24;
  d.environment = scene::EnvironmentDesc{};
  scene::FluidDesc goo;
  goo.name = "goo";
  goo.colour = {0.2, 0.6, 0.9};
  goo.params.viscosity = 1;
  scene::FillDesc box;
  box.min = {-2.2, 4, -2.2};
  box.max = {2.3, 8.5, 2.3};
  box.spacing = 1.1;
  goo.fills.push_back(box);
  d.fluids.push_back(goo);
  scene::FluidDesc syrup;
  syrup.name = "syrup";
  syrup.colour = {0.9, 0.5, 0.1};
  syrup.params.particleSize = 0.8;
  box.min = {-2.2, 0.5, -2.2};
  box.max = {1.2, 2.7, 1.2};
  syrup.fills.push_back(box);
  d.fluids.push_back(syrup);
  if (objects) {
    for (int i = 0; i < 2; ++i) {
      scene::ObjectDesc o;
      o.name = i == 0 ? "crate" : "brick";
      o.shape = scene::ObjectShape::Box;
      o.size = {1, 1, 1};
      o.particleSize = 0.5;
      o.initialPosition = {i == 0 ? 5.0 : -5.0, 2, 0};
      d.objects.push_back(o);
    }
  }
  return d;
}

/// Positions of every fluid of a snapshot, one after the other.
inline std::vector<float> positionsOf(const FrameSnapshot& f) {
  std::vector<float> out;
  for (const FluidSnapshot& s : f.fluids) out.insert(out.end(), s.positions.begin(), s.positions.end());
  return out;
}

}  // namespace softsub::session::test
