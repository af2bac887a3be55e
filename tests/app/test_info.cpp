// `softsub info` on each kind of file it knows, and on one it does not.
#include <fstream>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "app_test_util.h"

namespace softsub::apptest {
namespace {

void expectContains(const std::string& text, const std::string& part) {
  EXPECT_NE(text.find(part), std::string::npos) << "'" << part << "' not in\n" << text;
}

/// Runs two-fluids for 2 frames into tmp/o and returns tmp/o.
fs::path runTwoFluids(const TempDir& tmp) {
  const RunResult r = runSoftsub(
      "run -q --frames 2 --out " + quote(tmp / "o") + " " + quote(examplesDir() / "two-fluids.scene"), tmp.path());
  EXPECT_EQ(r.code, 0) << r.err;
  return tmp / "o";
}

TEST(Info, SceneListsFluidsCountsParametersAndInteractions) {
  TempDir tmp;
  const RunResult r = runSoftsub("info " + quote(examplesDir() / "two-fluids.scene"), tmp.path());
  ASSERT_EQ(r.code, 0) << r.err;
  expectContains(r.out, "48 frames at 24 fps");
  expectContains(r.out, "8 substeps");
  expectContains(r.out, "symplectic-euler");
  expectContains(r.out, "environment: box x [-7, 7]  y [0, 30]  z [-7, 7]");
  expectContains(r.out, "fluids: 2, 1,728 particles in all");
  expectContains(r.out, "syrup: 864 particles");
  expectContains(r.out, "oil: 864 particles");
  expectContains(r.out, "Viscosity 3");
  expectContains(r.out, "ParticleMass 0.5");
  expectContains(r.out, "pair syrup / oil: Linear (AtZero 60, Cutoff 1.6, Min 0, Max 60)");
  expectContains(r.out, "bounds x [");
}

TEST(Info, SceneListsObjectsTheirParticlesAndTheFluidObjectFunction) {
  TempDir tmp;
  const RunResult r = runSoftsub("info " + quote(examplesDir() / "interactions.scene"), tmp.path());
  ASSERT_EQ(r.code, 0) << r.err;
  expectContains(r.out, "fluids: 2, 480 particles in all");  // body particles are not fluid
  expectContains(r.out, "objects: 3, ");
  expectContains(r.out, "table: box, ");
  expectContains(r.out, "particles of diameter 0.5, static, mass 1");
  expectContains(r.out, "ball: sphere, ");
  expectContains(r.out, "dynamic, mass 8");
  expectContains(r.out, "fluid/object: Linear (AtZero 5, Cutoff 1.5, Min 0, Max 5); Damping 0, RelativeVelocity 2");
  expectContains(r.out, "pair oil / box: Linear (AtZero 6, Cutoff 2");
}

TEST(Info, SceneWithoutEnvironmentSaysSo) {
  TempDir tmp;
  std::ofstream(tmp / "free.scene")
      << "<Scene version=\"1\"><Fluid><Name>a</Name><NumberOfParticles>1</NumberOfParticles>"
         "<Particles>1 2 3</Particles></Fluid></Scene>\n";
  const RunResult r = runSoftsub("info free.scene", tmp.path());
  ASSERT_EQ(r.code, 0) << r.err;
  expectContains(r.out, "environment: none");
  expectContains(r.out, "a: 1 particles (1 explicit, 0 fills), bounds x [1, 1]  y [2, 2]  z [3, 3]");
}

TEST(Info, SimPdcAndPlyPrintCountsAndBounds) {
  TempDir tmp;
  const fs::path out = runTwoFluids(tmp);
  const RunResult sim = runSoftsub("info " + quote(out / "two-fluids.0002.sim"), tmp.path());
  ASSERT_EQ(sim.code, 0) << sim.err;
  expectContains(sim.out, "frame 2, time 0.0833333 s, 2 fluids, 1,728 particles");
  expectContains(sim.out, "syrup: 864 particles, bounds x [");
  expectContains(sim.out, "oil: 864 particles, bounds x [");

  const RunResult pdc = runSoftsub("info " + quote(out / "pdc" / "oilShape.500.pdc"), tmp.path());
  ASSERT_EQ(pdc.code, 0) << pdc.err;
  expectContains(pdc.out, "version 1, byte order 1, 864 particles");
  expectContains(pdc.out, "position: vector array, 2,592 values");
  expectContains(pdc.out, "particleId: double array, 864 values");
  expectContains(pdc.out, "position bounds x [");

  const RunResult ply = runSoftsub("info " + quote(out / "ply" / "two-fluids.0002.ply"), tmp.path());
  ASSERT_EQ(ply.code, 0) << ply.err;
  expectContains(ply.out, "binary_little_endian, 1,728 vertices");
  expectContains(ply.out, "frame 2");
  expectContains(ply.out, "fluid 0 syrup: 864 particles");
  expectContains(ply.out, "fluid 1 oil: 864 particles");
}

TEST(Info, UnknownExtensionIsBadInput) {
  TempDir tmp;
  std::ofstream(tmp / "notes.txt") << "hello\n";
  const RunResult r = runSoftsub("info notes.txt", tmp.path());
  EXPECT_EQ(r.code, 2);
  expectContains(r.err, "error: notes.txt");
  expectContains(r.err, "unknown file extension '.txt'");
  expectContains(r.err, ".scene, .sim, .pdc, .ply");
}

TEST(Info, MissingOrBrokenFiles) {
  TempDir tmp;
  EXPECT_EQ(runSoftsub("info missing.sim", tmp.path()).code, 3);
  std::ofstream(tmp / "broken.sim") << "<Simulation";
  const RunResult broken = runSoftsub("info broken.sim", tmp.path());
  EXPECT_EQ(broken.code, 2) << broken.err;
  expectContains(broken.err, "broken.sim");
  std::ofstream(tmp / "broken.pdc") << "PDC";
  EXPECT_EQ(runSoftsub("info broken.pdc", tmp.path()).code, 2);
}

}  // namespace
}  // namespace softsub::apptest
