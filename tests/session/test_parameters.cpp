// Editing a scene description by tag: every editable tag reaches its field; values are
// checked by the schema's ranges; unknown tags and fluids are refused listing what exists.
#include <gtest/gtest.h>

#include <functional>
#include <string>

#include "core/error.h"
#include "session/parameters.h"
#include "session_test_support.h"

namespace softsub::session {
namespace {

using test::smallScene;

/// The InputError `f` throws (a test failure when none).
InputError errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "no InputError";
  return InputError({}, "none");
}

TEST(Parameters, EveryFluidTagSetsItsField) {
  struct Row {
    const char* tag;
    const char* text;
    std::function<bool(const scene::FluidDesc&)> holds;
  };
  const Row rows[] = {
      {"InteractionDistance", "1.75", [](const scene::FluidDesc& f) { return f.params.interactionDistance == 1.75; }},
      {"Amplitude", "12.5", [](const scene::FluidDesc& f) { return f.params.amplitude == 12.5; }},
      {"FiniteDistance", "0.9", [](const scene::FluidDesc& f) { return f.params.finiteDistance == 0.9; }},
      {"MinimumForce", "-7", [](const scene::FluidDesc& f) { return f.params.minimumForce == -7; }},
      {"MaximumForce", "250", [](const scene::FluidDesc& f) { return f.params.maximumForce == 250; }},
      {"Viscosity", "4", [](const scene::FluidDesc& f) { return f.params.viscosity == 4; }},
      {"ParticleSize", "0.6", [](const scene::FluidDesc& f) { return f.params.particleSize == 0.6; }},
      {"ParticleMass", "2.5e0", [](const scene::FluidDesc& f) { return f.params.particleMass == 2.5; }},
      {"InitialSpeed", "0 -2 0.5", [](const scene::FluidDesc& f) { return f.initialSpeed == Vec3(0, -2, 0.5); }},
      {"Colour", " 0.1 0.2\t0.3 ", [](const scene::FluidDesc& f) { return f.colour == Vec3(0.1, 0.2, 0.3); }},
  };
  ASSERT_EQ(editableFluidTags().size(), std::size(rows));
  for (const Row& r : rows) {
    scene::SceneDesc d = smallScene();
    const scene::FluidDesc before = d.fluids[0];
    setFluidParameter(d, "syrup", r.tag, r.text);
    EXPECT_TRUE(r.holds(d.fluids[1])) << r.tag;
    EXPECT_EQ(d.fluids[0], before) << r.tag << ": only the named fluid changes";
    EXPECT_FALSE(r.holds(d.fluids[0])) << r.tag;
  }
}

TEST(Parameters, EverySimulationTagSetsItsField) {
  scene::SceneDesc d = smallScene();
  setSimulationParameter(d, "Substeps", "16");
  EXPECT_EQ(d.simulation.substeps, 16);
  setSimulationParameter(d, "FramesPerSecond", "30");
  EXPECT_EQ(d.simulation.framesPerSecond, 30);
  setSimulationParameter(d, "Gravity", "0 -3 0.25");
  EXPECT_EQ(d.simulation.gravity, Vec3(0, -3, 0.25));
  setSimulationParameter(d, "Frames", "48");
  EXPECT_EQ(d.simulation.frames, 48);
  setSimulationParameter(d, "Integrator", "velocity-verlet");
  EXPECT_EQ(d.simulation.integrator, scene::Integrator::VelocityVerlet);
  EXPECT_EQ(editableSimulationTags().size(), 5u);
}

TEST(Parameters, ValuesReadBackAsSceneText) {
  scene::SceneDesc d = smallScene();
  setFluidParameter(d, "goo", "Viscosity", "2.75");
  EXPECT_EQ(fluidParameterText(d, "goo", "Viscosity"), "2.75");
  EXPECT_EQ(fluidParameterText(d, "goo", "Colour"), "0.2 0.6 0.9");
  EXPECT_EQ(simulationParameterText(d, "Substeps"), "4");
  EXPECT_EQ(simulationParameterText(d, "Integrator"), "symplectic-euler");
}

TEST(Parameters, BadValuesAreRefusedWithTheAllowedRange) {
  scene::SceneDesc d = smallScene();
  const scene::SceneDesc before = d;
  InputError e = errorOf([&] { setFluidParameter(d, "goo", "ParticleSize", "-0.5"); });
  EXPECT_EQ(e.where().element, "Fluid/ParticleSize");
  EXPECT_EQ(e.allowed(), "> 0");
  e = errorOf([&] { setFluidParameter(d, "goo", "Viscosity", "-1"); });
  EXPECT_EQ(e.allowed(), ">= 0");
  e = errorOf([&] { setFluidParameter(d, "goo", "Viscosity", "1,5"); });  // no locale's comma
  EXPECT_NE(e.problem().find("'1,5' holds a comma"), std::string::npos) << e.what();
  e = errorOf([&] { setFluidParameter(d, "goo", "Amplitude", "nan"); });
  EXPECT_NE(std::string(e.what()).find("Fluid/Amplitude"), std::string::npos);
  e = errorOf([&] { setFluidParameter(d, "goo", "Colour", "1 2 3"); });
  EXPECT_NE(e.allowed().find("[0, 1]"), std::string::npos) << e.what();
  e = errorOf([&] { setFluidParameter(d, "goo", "Colour", "1 1"); });
  EXPECT_NE(e.problem().find("expected 3 numbers"), std::string::npos) << e.what();
  e = errorOf([&] { setSimulationParameter(d, "Substeps", "0"); });
  EXPECT_EQ(e.where().element, "Simulation/Substeps");
  EXPECT_EQ(e.allowed(), "integer [1, 10000]");
  e = errorOf([&] { setSimulationParameter(d, "Substeps", "2.5"); });
  EXPECT_NE(e.problem().find("not an integer"), std::string::npos);
  e = errorOf([&] { setSimulationParameter(d, "Integrator", "runge-kutta"); });
  EXPECT_NE(e.allowed().find("velocity-verlet"), std::string::npos);
  EXPECT_EQ(d, before);
}

TEST(Parameters, UnknownTagsAndFluidsListWhatExists) {
  scene::SceneDesc d = smallScene();
  const scene::SceneDesc before = d;
  InputError e = errorOf([&] { setFluidParameter(d, "goo", "Viscocity", "1"); });
  EXPECT_NE(e.problem().find("did you mean <Viscosity>"), std::string::npos) << e.what();
  EXPECT_NE(e.allowed().find("InteractionDistance, Amplitude"), std::string::npos) << e.what();
  EXPECT_NE(e.allowed().find("Colour"), std::string::npos);
  // Not editable one value at a time: the name and the particle list.
  e = errorOf([&] { setFluidParameter(d, "goo", "Name", "x"); });
  EXPECT_EQ(e.allowed().find("Name"), std::string::npos);
  errorOf([&] { setFluidParameter(d, "goo", "Particles", "0 0 0"); });
  e = errorOf([&] { setSimulationParameter(d, "Gravitation", "0 0 0"); });
  EXPECT_NE(e.allowed().find("Gravity"), std::string::npos);
  e = errorOf([&] { setFluidParameter(d, "honey", "Viscosity", "1"); });
  EXPECT_EQ(e.where().element, "Fluid");
  EXPECT_NE(e.problem().find("'honey'"), std::string::npos);
  EXPECT_EQ(e.allowed(), "goo, syrup");
  EXPECT_EQ(d, before);
}

TEST(Parameters, ErrorsNameTheirSource) {
  scene::SceneDesc d = smallScene();
  const InputError e = errorOf([&] { setFluidParameter(d, "goo", "Viscosity", "x", {"tweaks.txt", 7}); });
  EXPECT_EQ(std::string(e.what()).rfind("tweaks.txt:7: Fluid/Viscosity: ", 0), 0u) << e.what();
  EXPECT_NO_THROW(checkFluidParameter("Viscosity", "3"));
  EXPECT_THROW(checkFluidParameter("Viscosity", "-3"), InputError);
  EXPECT_THROW(checkSimulationParameter("Substeps", "100000"), InputError);
}

}  // namespace
}  // namespace softsub::session
