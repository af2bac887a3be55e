// Checkpoints (issue #7): a simulation restored from a checkpoint continues bit for bit
// as the one that wrote it, for every integrator, with bodies and with adaptive
// substeps; damaged or foreign checkpoints are refused.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "core/error.h"
#include "scene/compile.h"
#include "scene/reader.h"
#include "solver/checkpoint.h"
#include "solver/simulation.h"
#include "support/state_bytes.h"

namespace softsub::solver {
namespace {

std::string example(const std::string& name) { return std::string(SOFTSUB_SOURCE_DIR) + "/examples/" + name; }

// The whole store in slot order (forces too) and every body's state, as raw bytes.
std::vector<std::uint8_t> stateBytes(const Simulation& sim) { return scenarios::stateBytes(sim, true); }

struct Case {
  std::string scene;
  scene::Integrator integrator;
  bool adaptive;
};

std::string caseName(const ::testing::TestParamInfo<Case>& info) {
  std::string s = info.param.scene.substr(0, info.param.scene.find('.'));
  for (char& c : s)
    if (c == '-') c = '_';
  return s + "_" + std::to_string(static_cast<int>(info.param.integrator)) + (info.param.adaptive ? "_adaptive" : "");
}

scene::Compiled compileCase(const Case& c) {
  scene::SceneDesc d = scene::readSceneFile(example(c.scene));
  d.simulation.integrator = c.integrator;
  scene::Compiled compiled = scene::compile(d);
  compiled.model.adaptiveSubsteps = c.adaptive;
  return compiled;
}

class Restore : public ::testing::TestWithParam<Case> {};

TEST_P(Restore, ContinuesBitForBitAsTheRunThatWroteIt) {
  constexpr std::uint64_t kRun = 0x1234;
  scene::Compiled a = compileCase(GetParam());
  Simulation original(a.model, std::move(a.state));
  for (int f = 0; f < 5; ++f) original.advanceFrame();
  std::string bytes;
  encodeCheckpoint(original, kRun, bytes);
  EXPECT_EQ(checkpointInfo(bytes, "x").frame, 5);
  EXPECT_EQ(checkpointInfo(bytes, "x").particles, original.state().particles.size());

  scene::Compiled b = compileCase(GetParam());
  Simulation restored(b.model, std::move(b.state));
  restoreCheckpoint(restored, bytes, kRun, "x");
  EXPECT_EQ(restored.state().frame, 5);
  EXPECT_EQ(stateBytes(restored), stateBytes(original));
  // Several frames, so several pair-list rebuilds and re-sorts after the restored list.
  const std::int64_t builds = original.listBuilds();
  for (int f = 0; f < 10; ++f) {
    original.advanceFrame();
    restored.advanceFrame();
    ASSERT_EQ(stateBytes(restored), stateBytes(original)) << "frame " << original.state().frame;
    ASSERT_EQ(restored.substeps(), original.substeps());
  }
  EXPECT_GT(original.listBuilds(), builds) << "the continuation rebuilt the list at least once";
  // A second checkpoint of the restored run is the original's, byte for byte.
  std::string again, fromOriginal;
  encodeCheckpoint(restored, kRun, again);
  encodeCheckpoint(original, kRun, fromOriginal);
  EXPECT_EQ(again, fromOriginal);
}

INSTANTIATE_TEST_SUITE_P(
    Examples, Restore,
    ::testing::Values(Case{"two-fluids.scene", scene::Integrator::SymplecticEuler, false},
                      Case{"two-fluids.scene", scene::Integrator::VelocityVerlet, false},
                      Case{"softsub-demo.scene", scene::Integrator::ExplicitEuler, true},
                      Case{"box-on-jelly.scene", scene::Integrator::SymplecticEuler, false},
                      Case{"box-on-jelly.scene", scene::Integrator::VelocityVerlet, true},
                      Case{"wall-impact.scene", scene::Integrator::SymplecticEuler, false},
                      // Bodies resting on bodies from the first substep: the contact memory.
                      Case{"crate-stack.scene", scene::Integrator::SymplecticEuler, false}),
    caseName);

class Refuse : public ::testing::Test {
 protected:
  void SetUp() override {
    scene::Compiled c = scene::compile(scene::readSceneFile(example("two-fluids.scene")));
    model_ = std::move(c.model);
    Simulation sim(model_, std::move(c.state));
    sim.advanceFrame();
    encodeCheckpoint(sim, 7, bytes_);
  }
  [[nodiscard]] std::string problemOf(const std::string& bytes, std::uint64_t fingerprint = 7) {
    scene::Compiled c = scene::compile(scene::readSceneFile(example("two-fluids.scene")));
    Simulation sim(model_, std::move(c.state));
    const auto before = stateBytes(sim);
    try {
      restoreCheckpoint(sim, bytes, fingerprint, "run/x.state");
    } catch (const InputError& e) {
      EXPECT_EQ(stateBytes(sim), before) << "a refused checkpoint changes nothing";
      EXPECT_EQ(e.where().file, "run/x.state");
      return e.problem();
    }
    return "accepted";
  }
  Model model_;
  std::string bytes_;
};

TEST_F(Refuse, DamagedCutForeignAndOtherRunsCheckpoints) {
  EXPECT_EQ(problemOf(bytes_), "accepted");
  for (std::size_t at : {std::size_t{3}, std::size_t{40}, bytes_.size() / 2, bytes_.size() - 3}) {
    std::string flipped = bytes_;
    flipped[at] = static_cast<char>(flipped[at] ^ 0x10);
    EXPECT_NE(problemOf(flipped), "accepted") << "byte " << at;
  }
  for (std::size_t keep : {std::size_t{0}, std::size_t{10}, std::size_t{60}, bytes_.size() - 1})
    EXPECT_NE(problemOf(bytes_.substr(0, keep)), "accepted") << keep << " bytes";
  EXPECT_NE(problemOf(bytes_ + "x"), "accepted");
  EXPECT_NE(problemOf(bytes_, 8).find("other settings"), std::string::npos);
  EXPECT_NE(problemOf("not a checkpoint at all, but long enough to have a header and a sum"), "accepted");
  // A checkpoint of another scene (other counts) does not fit this model.
  scene::Compiled other = scene::compile(scene::readSceneFile(example("honey-drop.scene")));
  Simulation sim(other.model, std::move(other.state));
  std::string foreign;
  encodeCheckpoint(sim, 7, foreign);
  EXPECT_NE(problemOf(foreign).find("does not fit"), std::string::npos);
}

/// `bytes` with its checksum made right again: what a crafted (not a damaged) file is.
std::string resealed(std::string bytes) {
  const std::uint64_t sum = hashBytes(std::string_view(bytes).substr(0, bytes.size() - 8));
  std::memcpy(bytes.data() + bytes.size() - 8, &sum, 8);
  return bytes;
}

TEST_F(Refuse, CraftedCheckpointsWithAValidChecksumAreStillRefusedAndChangeNothing) {
  constexpr std::size_t kHeader = 48;
  const std::size_t n = checkpointInfo(bytes_, "x").particles;
  ASSERT_GT(n, 2u);
  const std::size_t materialAt = kHeader + 9 * 4 * n, ownerAt = materialAt + 2 * n, idAt = ownerAt + 4 * n;
  EXPECT_EQ(problemOf(resealed(bytes_)), "accepted");
  // A particle moved to the other fluid (owner and material of another id).
  std::string owner = bytes_;
  std::uint32_t o;
  std::memcpy(&o, owner.data() + ownerAt, 4);
  o ^= 1u;
  std::memcpy(owner.data() + ownerAt, &o, 4);
  EXPECT_NE(problemOf(resealed(owner)).find("do not belong"), std::string::npos);
  // A position that is not finite.
  std::string nan = bytes_;
  const float inf = std::numeric_limits<float>::infinity();
  std::memcpy(nan.data() + kHeader + 4, &inf, 4);
  EXPECT_NE(problemOf(resealed(nan)).find("not finite"), std::string::npos);
  // The store's first and last slots swapped whole (positions, velocities, ids, owners,
  // list reference): every particle is consistent, but the reference positions no longer
  // come in the grid's order, so the list would not be the one the run had.
  ASSERT_EQ(bytes_.size(), idAt + 4 * n + 3 * 4 * n + 8 + 8) << "the run holds a pair list (and no contacts)";
  std::string order = bytes_;
  const auto swapSlots = [&](std::size_t base, std::size_t width) {
    std::string first = order.substr(base, width);
    order.replace(base, width, order.substr(base + width * (n - 1), width));
    order.replace(base + width * (n - 1), width, first);
  };
  for (int k = 0; k < 9; ++k) swapSlots(kHeader + 4 * n * k, 4);
  swapSlots(materialAt, 2);
  swapSlots(ownerAt, 4);
  swapSlots(idAt, 4);
  for (int k = 0; k < 3; ++k) swapSlots(idAt + 4 * n + 4 * n * k, 4);
  EXPECT_NE(problemOf(resealed(order)).find("order does not match"), std::string::npos);
}

// The bodies' contact memory (version 2) is checked as the rest is: a contact that names
// an object the scene does not have is refused; a version 1 checkpoint (no contact
// memory) is still read, its contacts starting from zero.
TEST(CheckpointContacts, AreCheckedAndAVersionOneCheckpointHasNone) {
  scene::Compiled c = scene::compile(scene::readSceneFile(example("crate-stack.scene")));
  const Model model = c.model;
  Simulation sim(model, std::move(c.state));
  for (int f = 0; f < 2; ++f) sim.advanceFrame();
  const std::size_t contacts = sim.state().contacts.size();
  ASSERT_GT(contacts, 4u) << "crates resting on each other";
  std::string bytes;
  encodeCheckpoint(sim, 7, bytes);
  constexpr std::size_t kContactBytes = 60;
  const std::size_t countAt = bytes.size() - 8 - contacts * kContactBytes - 8;
  std::uint64_t count;
  std::memcpy(&count, bytes.data() + countAt, 8);
  ASSERT_EQ(count, contacts);
  const auto restore = [&](const std::string& b) -> std::string {
    scene::Compiled fresh = scene::compile(scene::readSceneFile(example("crate-stack.scene")));
    Simulation target(model, std::move(fresh.state));
    try {
      restoreCheckpoint(target, b, 7, "x");
    } catch (const InputError& e) {
      EXPECT_TRUE(target.state().contacts.empty()) << "a refused checkpoint changes nothing";
      return e.problem();
    }
    EXPECT_EQ(target.state().bodies.size(), model.bodies.bodies.size());
    return fmt::format("accepted with {} contacts", target.state().contacts.size());
  };
  EXPECT_EQ(restore(bytes), fmt::format("accepted with {} contacts", contacts));
  // The first contact's body a set to one past the last body.
  std::string wrong = bytes;
  const auto past = static_cast<std::int32_t>(model.bodies.bodies.size());
  std::memcpy(wrong.data() + countAt + 8, &past, 4);
  EXPECT_NE(restore(resealed(wrong)).find("does not fit the scene's objects"), std::string::npos);
  // A force that is not finite.
  std::string nan = bytes;
  const double inf = std::numeric_limits<double>::infinity();
  std::memcpy(nan.data() + countAt + 8 + 12 + 3 * 8, &inf, 8);
  EXPECT_NE(restore(resealed(nan)).find("does not fit"), std::string::npos);
  // A count the bytes do not hold.
  std::string more = bytes;
  const std::uint64_t bigger = contacts + 1;
  std::memcpy(more.data() + countAt, &bigger, 8);
  EXPECT_NE(restore(resealed(more)).find("wrong size"), std::string::npos);
  // Version 1: the same bytes without the contact section.
  std::string old = bytes.substr(0, countAt) + std::string(8, '\0');
  const std::uint32_t one = 1, three = 3;
  std::memcpy(old.data() + 8, &one, 4);
  EXPECT_EQ(restore(resealed(old)), "accepted with 0 contacts");
  std::string future = bytes;
  std::memcpy(future.data() + 8, &three, 4);
  EXPECT_EQ(restore(resealed(future)), "has version 3");
}

TEST(HashBytes, EveryByteAndTheSeedMatter) {
  const std::string text(100, 'a');
  const std::uint64_t h = hashBytes(text);
  EXPECT_EQ(hashBytes(text), h);
  EXPECT_NE(hashBytes(text, 1), h);
  EXPECT_NE(hashBytes(text.substr(0, 99)), h);
  for (std::size_t i = 0; i < text.size(); ++i) {
    std::string t = text;
    t[i] = 'b';
    EXPECT_NE(hashBytes(t), h) << i;
  }
}

}  // namespace
}  // namespace softsub::solver
