// Cache file names: frame tags, Maya ticks at common frame rates, and the folder layout.
#include <cmath>
#include <stdexcept>

#include <gtest/gtest.h>

#include "cache/naming.h"
#include "core/error.h"

namespace softsub::cache {
namespace {

TEST(Naming, FrameTagIsZeroPaddedToFourDigits) {
  EXPECT_EQ(frameTag(0), "0000");
  EXPECT_EQ(frameTag(7), "0007");
  EXPECT_EQ(frameTag(120), "0120");
  EXPECT_EQ(frameTag(9999), "9999");
  EXPECT_EQ(frameTag(12345), "12345");
  EXPECT_THROW(static_cast<void>(frameTag(-1)), std::invalid_argument);
}

TEST(Naming, TicksAt24FpsAre250PerFrame) {
  EXPECT_EQ(pdcTicks(0, 24), 0);
  EXPECT_EQ(pdcTicks(1, 24), 250);
  EXPECT_EQ(pdcTicks(10, 24), 2500);  // the seed's particle1Shape.2500.pdc
  EXPECT_EQ(pdcTicks(1000, 24), 250000);
}

TEST(Naming, TicksAt25And30Fps) {
  EXPECT_EQ(pdcTicks(1, 25), 240);
  EXPECT_EQ(pdcTicks(25, 25), 6000);
  EXPECT_EQ(pdcTicks(1, 30), 200);
  EXPECT_EQ(pdcTicks(30, 30), 6000);
}

TEST(Naming, TicksAtNtscFilmRateAreRoundedAndIncreasing) {
  // 6000 / 23.976 = 250.2502...: rounded per frame, never accumulated.
  EXPECT_EQ(pdcTicks(1, 23.976), 250);
  EXPECT_EQ(pdcTicks(2, 23.976), 501);  // 500.5005
  EXPECT_EQ(pdcTicks(4, 23.976), 1001);
  EXPECT_EQ(pdcTicks(24, 23.976), 6006);
  for (const double fps : {23.976, 24.0, 25.0, 29.97, 30.0, 60.0, 120.0}) {
    for (std::int64_t f = 1; f < 2000; ++f) {
      ASSERT_GT(pdcTicks(f, fps), pdcTicks(f - 1, fps)) << "fps " << fps << " frame " << f;
    }
  }
}

TEST(Naming, TicksRefuseBadArguments) {
  EXPECT_THROW(static_cast<void>(pdcTicks(-1, 24)), std::invalid_argument);
  EXPECT_THROW(static_cast<void>(pdcTicks(1, 0)), std::invalid_argument);
  EXPECT_THROW(static_cast<void>(pdcTicks(1, -24)), std::invalid_argument);
  EXPECT_THROW(static_cast<void>(pdcTicks(1, std::nan(""))), std::invalid_argument);
}

TEST(Naming, PathsFollowTheFolderLayout) {
  const std::filesystem::path dir = "out/demoSim";
  EXPECT_EQ(simPath(dir, "demo", 7), dir / "demo.0007.sim");
  EXPECT_EQ(plyPath(dir, "demo", 12345), dir / "ply" / "demo.12345.ply");
  EXPECT_EQ(pdcPath(dir, "honey", 10, 24), dir / "pdc" / "honeyShape.2500.pdc");
  EXPECT_EQ(pdcPath(dir, "honey", 3, 30), dir / "pdc" / "honeyShape.600.pdc");
  EXPECT_EQ(pdcPath(dir, "my honey", 0, 24), dir / "pdc" / "my honeyShape.0.pdc");
}

TEST(Naming, NamesThatWouldLeaveTheFolderAreRefused) {
  for (const char* bad : {"", "a/b", "..\\x", "a\nb", "tab\there"}) {
    EXPECT_THROW(static_cast<void>(pdcPath("out", bad, 1, 24)), InputError) << bad;
    EXPECT_THROW(static_cast<void>(simPath("out", bad, 1)), InputError) << bad;
  }
  try {
    static_cast<void>(pdcPath("out", "a/b", 1, 24));
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().element, "Fluid/Name");
    EXPECT_NE(e.allowed().find('/'), std::string::npos);
  }
}

}  // namespace
}  // namespace softsub::cache
