// LiveSession: edits continue from the same state and change what follows; invalid edits
// leave the old settings running; restart, saving and the in-memory recording.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <vector>

#include "cache/sim_format.h"
#include "core/error.h"
#include "scene/compile.h"
#include "scene/reader.h"
#include "session/live_session.h"
#include "session/parameters.h"
#include "session_test_support.h"
#include "solver/simulation.h"

namespace softsub::session {
namespace {

using test::positionsOf;
using test::ScratchDir;
using test::smallScene;

/// Every per-particle array of a state, slot by slot.
void expectSameParticles(const ParticleStore& a, const ParticleStore& b) {
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(a.id, b.id);
  EXPECT_EQ(a.px, b.px);
  EXPECT_EQ(a.py, b.py);
  EXPECT_EQ(a.pz, b.pz);
  EXPECT_EQ(a.vx, b.vx);
  EXPECT_EQ(a.vy, b.vy);
  EXPECT_EQ(a.vz, b.vz);
  EXPECT_EQ(a.owner, b.owner);
}

/// The largest distance between the same particle in two snapshots.
double largestMove(const FrameSnapshot& a, const FrameSnapshot& b) {
  const std::vector<float> pa = positionsOf(a), pb = positionsOf(b);
  EXPECT_EQ(pa.size(), pb.size());
  double d = 0;
  for (std::size_t i = 0; i + 2 < pa.size() && i + 2 < pb.size(); i += 3)
    d = std::max(d, std::hypot(double(pa[i]) - pb[i], double(pa[i + 1]) - pb[i + 1], double(pa[i + 2]) - pb[i + 2]));
  return d;
}

/// RMS deviation of a fluid's velocities from their mean: what viscosity damps.
double velocitySpread(const FluidSnapshot& f) {
  double mean[3] = {0, 0, 0};
  const std::size_t n = f.count();
  for (std::size_t k = 0; k < n; ++k)
    for (int a = 0; a < 3; ++a) mean[a] += f.velocities[3 * k + a] / double(n);
  double sum = 0;
  for (std::size_t k = 0; k < n; ++k)
    for (int a = 0; a < 3; ++a) sum += std::pow(f.velocities[3 * k + a] - mean[a], 2);
  return std::sqrt(sum / double(n));
}

void advance(LiveSession& s, int frames) {
  for (int f = 0; f < frames; ++f) s.advanceFrame();
}

TEST(LiveSession, StartsAtFrameZeroOfAFreshCompile) {
  ScratchDir dir;
  const LiveSession s(smallScene(true), "small", dir.path());
  scene::Compiled c = scene::compile(smallScene(true));
  const solver::Simulation fresh(c.model, std::move(c.state));
  EXPECT_EQ(s.frame(), 0);
  EXPECT_EQ(positionsOf(s.snapshot()), positionsOf(fresh.snapshot()));
  ASSERT_EQ(s.snapshot().fluids.size(), 2u);
  EXPECT_EQ(s.snapshot().fluids[0].colour, (std::array<float, 3>{0.2f, 0.6f, 0.9f}));
  EXPECT_EQ(s.recordedFrames(), 1u);
  ASSERT_EQ(s.objectMeshes().size(), 2u);
  EXPECT_EQ(s.objectMeshes()[1].vertices, c.objectMeshes[1].vertices);
  EXPECT_EQ(s.objectMeshes()[1].triangles, c.objectMeshes[1].triangles);
  EXPECT_EQ(s.snapshot().objects[0].filename, "smallGeo/crate.obj");
}

TEST(LiveSession, AnInvalidStartingSceneIsRefused) {
  ScratchDir dir;
  scene::SceneDesc d = smallScene();
  d.fluids[1].name = "goo";  // two fluids of one name
  EXPECT_THROW(LiveSession(d, "small", dir.path()), InputError);
}

TEST(LiveSession, AViscosityEditContinuesFromTheSameStateAndChangesWhatFollows) {
  ScratchDir dir;
  LiveSession edited(smallScene(), "small", dir.path());
  LiveSession twin(smallScene(), "small", dir.path());
  advance(edited, 6);
  advance(twin, 6);
  ASSERT_EQ(positionsOf(edited.snapshot()), positionsOf(twin.snapshot()));  // deterministic
  const FrameSnapshot before = edited.snapshot();
  const solver::State stateBefore = edited.simulation().state();

  setFluidParameter(edited.editableDesc(), "goo", "Viscosity", "4");
  EXPECT_TRUE(edited.hasPendingEdits());
  EXPECT_EQ(edited.applyEdits(), EditResult::Continued);
  EXPECT_FALSE(edited.hasPendingEdits());
  EXPECT_EQ(edited.desc().fluids[0].params.viscosity, 4);
  EXPECT_EQ(edited.model().table.interaction(0, 0).damping, 4);
  // Right after the edit: the same frame, particles, velocities.
  EXPECT_EQ(edited.frame(), 6);
  EXPECT_EQ(positionsOf(edited.snapshot()), positionsOf(before));
  expectSameParticles(edited.simulation().state().particles, stateBefore.particles);
  EXPECT_FALSE(edited.simulation().state().forcesValid);
  EXPECT_EQ(edited.recordedFrames(), 7u);  // the recording goes on

  advance(edited, 6);
  advance(twin, 6);
  EXPECT_EQ(edited.frame(), 12);
  // Four times the viscosity: the goo moves differently from its twin, and as viscosity
  // does: its particles' velocities are pulled together (measured 0.62 against 1.43).
  EXPECT_GT(largestMove(edited.snapshot(), twin.snapshot()), 0.01);
  EXPECT_LT(velocitySpread(edited.snapshot().fluids[0]), 0.7 * velocitySpread(twin.snapshot().fluids[0]));
  EXPECT_EQ(edited.recordedFrames(), 13u);
}

TEST(LiveSession, AnInvalidEditThrowsAndTheOldSettingsKeepRunning) {
  ScratchDir dir;
  LiveSession s(smallScene(), "small", dir.path());
  advance(s, 2);
  s.editableDesc().fluids[0].params.particleSize = -1;  // not through setFluidParameter
  try {
    s.applyEdits();
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("ParticleSize"), std::string::npos) << e.what();
    EXPECT_EQ(e.allowed(), "> 0");
    EXPECT_EQ(e.where().file, "small.scene (edited)");
  }
  EXPECT_EQ(s.desc().fluids[0].params.particleSize, 1);
  EXPECT_EQ(s.editableDesc().fluids[0].params.particleSize, 1);  // the edit is dropped
  EXPECT_EQ(s.model().fluids[0].particleSize, 1);
  EXPECT_EQ(s.frame(), 2);

  // A rule between two fields: each value alone is in range.
  setFluidParameter(s.editableDesc(), "goo", "MinimumForce", "500");
  EXPECT_THROW(s.applyEdits(), InputError);
  EXPECT_EQ(s.desc().fluids[0].params.minimumForce, -20);
  EXPECT_EQ(s.model().table.interaction(0, 0), (forces::Interaction{fluid::ownFunction(fluid::FluidParams{}), 1, 0}));
  s.advanceFrame();
  EXPECT_EQ(s.frame(), 3);
}

TEST(LiveSession, EditsThatChangeTheParticlesRestart) {
  ScratchDir dir;
  LiveSession s(smallScene(), "small", dir.path());
  const std::size_t before = s.model().particleCount();
  advance(s, 3);
  s.editableDesc().fluids[1].fills[0].spacing = 0.8;  // more syrup
  EXPECT_EQ(s.applyEdits(), EditResult::Restarted);
  EXPECT_EQ(s.frame(), 0);
  EXPECT_GT(s.model().particleCount(), before);
  EXPECT_EQ(s.recordedFrames(), 1u);
  scene::Compiled c = scene::compile(s.desc());
  const solver::Simulation fresh(c.model, std::move(c.state));
  EXPECT_EQ(positionsOf(s.snapshot()), positionsOf(fresh.snapshot()));

  advance(s, 2);
  setFluidParameter(s.editableDesc(), "goo", "InitialSpeed", "0 -5 0");  // an initial state
  EXPECT_EQ(s.applyEdits(), EditResult::Restarted);
  EXPECT_EQ(s.snapshot().fluids[0].velocities[1], -5);
}

// Two boxes share one material row until one gets a Pair of its own: the particles of
// that box must move to the new row, or the kernel would read the wrong interaction.
TEST(LiveSession, AnInteractionEditMovesObjectParticlesToTheirNewRow) {
  ScratchDir dir;
  LiveSession s(smallScene(true), "small", dir.path());
  advance(s, 2);
  ASSERT_EQ(s.model().materials.size(), 3u);  // goo, syrup, one row for both boxes
  scene::PairDesc p;
  p.a = "goo";
  p.b = "brick";
  p.interaction.function = forces::Linear{9, 1.2, 0, 9};
  s.editableDesc().interactions.pairs.push_back(p);
  EXPECT_EQ(s.applyEdits(), EditResult::Continued);
  ASSERT_EQ(s.model().materials.size(), 4u);
  const ParticleStore& store = s.simulation().state().particles;
  const std::uint32_t brick = s.model().bodies.firstEntity + 1;
  std::size_t brickParticles = 0;
  for (std::size_t i = 0; i < store.size(); ++i) {
    if (store.owner[i] < s.model().bodies.firstEntity) continue;
    const std::size_t row = store.material[i];
    const forces::Interaction& withGoo = s.model().table.interaction(row, 0);
    if (store.owner[i] == brick) {
      ++brickParticles;
      EXPECT_EQ(withGoo.function, forces::PairFunction(forces::Linear{9, 1.2, 0, 9}));
    } else {
      EXPECT_EQ(withGoo.function, s.desc().interactions.fluidObject.function);
    }
  }
  EXPECT_GT(brickParticles, 0u);
  advance(s, 2);
  EXPECT_EQ(s.frame(), 4);
}

TEST(LiveSession, RestartReturnsToFrameZero) {
  ScratchDir dir;
  LiveSession s(smallScene(true), "small", dir.path());
  const FrameSnapshot first = s.snapshot();
  advance(s, 4);
  EXPECT_GT(largestMove(s.snapshot(), first), 0.01);
  s.restart();
  EXPECT_EQ(s.frame(), 0);
  scene::Compiled c = scene::compile(smallScene(true));
  const solver::Simulation fresh(c.model, std::move(c.state));
  EXPECT_EQ(positionsOf(s.snapshot()), positionsOf(fresh.snapshot()));
  EXPECT_EQ(s.snapshot().objects[1].position, fresh.snapshot().objects[1].position);
  EXPECT_EQ(s.recordedFrames(), 1u);
  EXPECT_EQ(s.recorded()[0].frame, 0);
}

TEST(LiveSession, SavedSceneReadsBackEqualWithTheEdit) {
  ScratchDir dir;
  LiveSession s(smallScene(true), "small", dir.path());
  setFluidParameter(s.editableDesc(), "syrup", "Viscosity", "7.5");
  setSimulationParameter(s.editableDesc(), "Substeps", "12");
  ASSERT_EQ(s.applyEdits(), EditResult::Continued);
  const std::filesystem::path file = dir.path() / "tweaked.scene";
  s.saveScene(file);
  const scene::SceneDesc back = scene::readSceneFile(file.string());
  EXPECT_EQ(back, s.desc());
  EXPECT_EQ(back.fluids[1].params.viscosity, 7.5);
  EXPECT_EQ(back.simulation.substeps, 12);
}

TEST(LiveSession, WrittenRecordingReadsBackAsTheRecordedFrames) {
  ScratchDir dir;
  const std::filesystem::path out = dir.path() / "smallSim";
  LiveSession s(smallScene(true), "small", out);
  const int n = 5;
  advance(s, n);
  ASSERT_EQ(s.recordedFrames(), std::size_t{n + 1});
  const RecordedWrite w = s.writeRecorded();
  EXPECT_EQ(w.frames, std::size_t{n + 1});
  EXPECT_EQ(w.firstFrame, 0);
  EXPECT_EQ(w.lastFrame, n);
  EXPECT_EQ(w.folder, out);
  std::size_t simFiles = 0;
  for (const auto& e : std::filesystem::directory_iterator(out)) simFiles += e.path().extension() == ".sim";
  EXPECT_EQ(simFiles, std::size_t{n + 1});
  for (int f = 0; f <= n; ++f) {
    const FrameSnapshot& kept = s.recorded()[static_cast<std::size_t>(f)];
    const FrameSnapshot back = cache::readSimFile(out / ("small.000" + std::to_string(f) + ".sim")).frame;
    EXPECT_EQ(back.frame, f);
    EXPECT_EQ(positionsOf(back), positionsOf(kept)) << "frame " << f;
    ASSERT_EQ(back.objects.size(), 2u);
    EXPECT_EQ(back.objects[0].position, kept.objects[0].position);
  }
  EXPECT_NE(positionsOf(s.recorded()[0]), positionsOf(s.recorded()[n]));
  EXPECT_TRUE(std::filesystem::is_regular_file(out / "smallGeo" / "crate.obj"));
  EXPECT_TRUE(std::filesystem::is_regular_file(out / "pdc" / "gooShape.1250.pdc"));
}

TEST(LiveSession, RecordingStopsAtTheMemoryCapAndAtStopRecordingAt) {
  ScratchDir dir;
  LiveSession capped(smallScene(), "small", dir.path());
  const std::size_t perFrame = capped.recordedBytes();
  capped.setRecordingCap(perFrame * 5 / 2);  // room for two frames and a half
  advance(capped, 4);
  EXPECT_EQ(capped.recordedFrames(), 2u);
  EXPECT_FALSE(capped.recording());
  EXPECT_NE(capped.recordingNote().find("memory cap"), std::string::npos) << capped.recordingNote();
  EXPECT_NE(capped.recordingNote().find("frame 2"), std::string::npos) << capped.recordingNote();
  capped.restart();  // clears the recording and records again
  EXPECT_TRUE(capped.recording());
  EXPECT_EQ(capped.recordedFrames(), 1u);
  EXPECT_EQ(capped.recordingNote(), "");

  LiveSession stopping(smallScene(), "small", dir.path());
  stopping.setStopRecordingAt(2);
  advance(stopping, 5);
  ASSERT_EQ(stopping.recordedFrames(), 3u);
  EXPECT_EQ(stopping.recorded().back().frame, 2);
  EXPECT_FALSE(stopping.recording());
  EXPECT_NE(stopping.recordingNote().find("after frame 2"), std::string::npos);

  LiveSession off(smallScene(), "small", dir.path());
  off.setRecording(false);
  advance(off, 2);
  EXPECT_EQ(off.recordedFrames(), 1u);  // frame 0, kept before it was switched off
  LiveSession none(smallScene(), "small", dir.path(), cache::Formats{false, false, false});
  EXPECT_FALSE(none.recording());
  EXPECT_EQ(none.recordedFrames(), 0u);
}

TEST(LiveSession, ABlowUpKeepsTheLastGoodFrameUntilRestart) {
  ScratchDir dir;
  scene::SceneDesc d;
  scene::FluidDesc f;
  f.name = "dust";
  f.params.particleMass = 1e-30;  // the capped force of two nearly coincident particles overflows
  f.particles = {{0, 0, 0}, {0.02, 0, 0}};
  d.fluids.push_back(f);
  scene::PairDesc p;
  p.a = p.b = "dust";
  p.interaction.function = forces::LennardJonesForce{1, 1, 2.5};
  d.interactions.pairs.push_back(p);
  LiveSession s(d, "dust", dir.path());
  EXPECT_THROW(s.advanceFrame(), BlowUpError);
  EXPECT_TRUE(s.blownUp());
  EXPECT_EQ(s.frame(), 0);
  EXPECT_EQ(s.snapshot().fluids[0].positions[3], 0.02f);
  EXPECT_THROW(s.advanceFrame(), BlowUpError);
  EXPECT_EQ(s.applyEdits(), EditResult::Restarted);  // nothing to continue from
  EXPECT_FALSE(s.blownUp());
  EXPECT_EQ(s.frame(), 0);
}

TEST(LiveSession, TimesItsSubsteps) {
  ScratchDir dir;
  LiveSession s(smallScene(), "small", dir.path());
  EXPECT_EQ(s.lastStepMilliseconds(), 0);
  s.advanceFrame();
  EXPECT_GT(s.lastStepMilliseconds(), 0);
  EXPECT_LT(s.lastStepMilliseconds(), 1000);
}

}  // namespace
}  // namespace softsub::session

namespace softsub::session {
namespace {

// The seed's -drawPerFrame 0: stepping substep by substep gives bitwise the frames of
// stepping frame by frame, records only whole frames, and a frame call finishes a
// frame begun by substeps.
TEST(LiveSessionSubsteps, SubstepBySubstepEqualsFrameByFrame) {
  test::ScratchDir dirA, dirB;
  LiveSession byFrame(test::smallScene(true), "small", dirA.path());
  LiveSession bySubstep(test::smallScene(true), "small", dirB.path());
  const int substeps = byFrame.model().substeps;
  ASSERT_GT(substeps, 1);
  for (int f = 0; f < 3; ++f) {
    byFrame.advanceFrame();
    for (int k = 1; k < substeps; ++k) {
      EXPECT_FALSE(bySubstep.advanceSubstep());
      EXPECT_EQ(bySubstep.substepInFrame(), k);
      EXPECT_EQ(bySubstep.frame(), f);  // a frame in progress keeps its number
    }
    EXPECT_TRUE(bySubstep.advanceSubstep());
    EXPECT_EQ(bySubstep.substepInFrame(), 0);
    EXPECT_EQ(bySubstep.frame(), f + 1);
    EXPECT_EQ(test::positionsOf(bySubstep.snapshot()), test::positionsOf(byFrame.snapshot()));
  }
  EXPECT_EQ(bySubstep.recordedFrames(), byFrame.recordedFrames());
  // Half a frame by substeps, then a frame call: it finishes that frame.
  for (int k = 0; k < substeps / 2; ++k) bySubstep.advanceSubstep();
  bySubstep.advanceFrame();
  byFrame.advanceFrame();
  EXPECT_EQ(bySubstep.frame(), byFrame.frame());
  EXPECT_EQ(test::positionsOf(bySubstep.snapshot()), test::positionsOf(byFrame.snapshot()));
  // A restart forgets the frame in progress.
  bySubstep.advanceSubstep();
  bySubstep.restart();
  EXPECT_EQ(bySubstep.substepInFrame(), 0);
  EXPECT_EQ(bySubstep.frame(), 0);
}

}  // namespace
}  // namespace softsub::session
