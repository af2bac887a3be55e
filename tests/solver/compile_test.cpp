// scene::compile: the interaction table and the initial state a scene describes.
#include <gtest/gtest.h>

#include "scene/compile.h"
#include "scene/reader.h"
#include "solver/simulation.h"

namespace softsub::scene {
namespace {

constexpr const char* kScene = R"(<Scene version="1">
  <Simulation><FramesPerSecond>25</FramesPerSecond><Substeps>4</Substeps><Frames>3</Frames>
    <Integrator>velocity-verlet</Integrator></Simulation>
  <Environment><Width>10</Width><Height>8</Height><Depth>6</Depth>
    <NormalAttenuation>0.3</NormalAttenuation><TangentAttenuation>0.2</TangentAttenuation>
    <Closed>true</Closed></Environment>
  <Fluid><Name>honey</Name><Viscosity>3</Viscosity><ParticleMass>2</ParticleMass>
    <InitialSpeed>1 0 0</InitialSpeed>
    <NumberOfParticles>2</NumberOfParticles><Particles>0 1 0  1 1 0</Particles>
    <Fill><Shape>box</Shape><Min>0 2 0</Min><Max>2 4 2</Max><Spacing>1</Spacing></Fill></Fluid>
  <Fluid><Name>oil</Name><InteractionDistance>1.2</InteractionDistance>
    <Fill><Shape>sphere</Shape><Center>0 5 0</Center><Radius>1</Radius><Spacing>1</Spacing></Fill></Fluid>
  <Fluid><Name>water</Name><NumberOfParticles>1</NumberOfParticles><Particles>3 1 0</Particles></Fluid>
  <Interactions>
    <FluidFluid><Linear><AtZero>4</AtZero><Cutoff>1.1</Cutoff><Min>0</Min><Max>4</Max></Linear>
      <Damping>0.5</Damping></FluidFluid>
    <Pair><A>oil</A><B>honey</B><Curve><Points>0 9 2.5 0</Points></Curve><RelativeVelocity>2</RelativeVelocity></Pair>
    <Pair><A>water</A><B>water</B><LennardJonesForce><Epsilon>1</Epsilon><Sigma>1</Sigma><Cutoff>2.5</Cutoff></LennardJonesForce></Pair>
  </Interactions>
</Scene>)";

TEST(Compile, ModelFollowsTheScene) {
  const Compiled c = compile(readSceneText(kScene, "compile.scene"));
  const solver::Model& m = c.model;
  EXPECT_EQ(m.framesPerSecond, 25);
  EXPECT_EQ(m.substeps, 4);
  EXPECT_EQ(m.frames, 3);
  EXPECT_EQ(m.integrator, solver::Integrator::VelocityVerlet);
  ASSERT_TRUE(m.container.has_value());
  EXPECT_EQ(m.container->lo, (std::array<double, 3>{-5, 0, -3}));
  EXPECT_EQ(m.container->hi, (std::array<double, 3>{5, 8, 3}));
  EXPECT_TRUE(m.container->closed);
  EXPECT_DOUBLE_EQ(m.container->restitution, 0.3);
  EXPECT_DOUBLE_EQ(m.container->friction, 0.2);

  ASSERT_EQ(m.fluids.size(), 3u);
  // honey: 2 explicit + 2x2x2 box; oil: the 7 lattice points within radius 1; water: 1.
  EXPECT_EQ(m.fluids[0].count, 10u);
  EXPECT_EQ(m.fluids[1].count, 7u);
  EXPECT_EQ(m.fluids[2].count, 1u);
  EXPECT_EQ(m.fluids[1].firstId, 10u);
  EXPECT_EQ(m.fluids[2].firstId, 17u);
  EXPECT_FLOAT_EQ(m.materials[0].inverseMass, 0.5f);

  // Own function + viscosity, the global function, pair overrides (both orders).
  const auto& t = m.table;
  EXPECT_TRUE(std::holds_alternative<forces::LennardJones>(t.interaction(0, 0).function));
  EXPECT_DOUBLE_EQ(t.interaction(0, 0).damping, 3);
  EXPECT_DOUBLE_EQ(forces::cutoff(t.interaction(1, 1).function), 1.2);
  EXPECT_EQ(t.interaction(0, 2), (forces::Interaction{forces::Linear{4, 1.1, 0, 4}, 0.5, 0}));
  EXPECT_EQ(t.interaction(2, 1), t.interaction(0, 2));
  EXPECT_TRUE(std::holds_alternative<forces::Curve>(t.interaction(1, 0).function));
  EXPECT_DOUBLE_EQ(t.interaction(0, 1).relativeVelocity, 2);
  EXPECT_TRUE(std::holds_alternative<forces::LennardJonesForce>(t.interaction(2, 2).function));
  EXPECT_DOUBLE_EQ(t.maxCutoff(), 2.5);

  // State: ids in scene order, explicit particles first, initial speed applied.
  const ParticleStore& p = c.state.particles;
  ASSERT_EQ(p.size(), 18u);
  EXPECT_EQ(p.px[1], 1.0f);
  EXPECT_EQ(p.vx[0], 1.0f);
  EXPECT_EQ(p.material[12], 1);
  EXPECT_EQ(p.owner[17], 2u);
  for (std::uint32_t k = 0; k < p.size(); ++k) EXPECT_EQ(p.id[k], k);
}

TEST(Compile, NoEnvironmentMeansNoWalls) {
  const Compiled c = compile(readSceneText(
      R"(<Scene><Fluid><Name>a</Name><NumberOfParticles>1</NumberOfParticles><Particles>0 0 0</Particles></Fluid></Scene>)",
      "free.scene"));
  EXPECT_FALSE(c.model.container.has_value());
  solver::Simulation sim(c.model, c.state);
  for (int f = 0; f < 24; ++f) sim.advanceFrame();
  EXPECT_LT(sim.state().particles.py[0], -4.0f) << "falls through where a floor would be";
}

}  // namespace
}  // namespace softsub::scene
