// The .sim file: exact text, bit-exact round trips, escaping, objects, and refusal of bad
// input with file, line and element.
#include <chrono>
#include <cstring>

#include <gtest/gtest.h>

#include "cache/atomic_file.h"
#include "cache/cache_test_support.h"
#include "cache/sim_format.h"
#include "core/error.h"

namespace softsub::cache {
namespace {

using test::makeFluid;
using test::makeFrame;

/// Positions equal bit for bit (so -0 differs from 0 and every subnormal counts).
void expectSameBits(const std::vector<float>& a, const std::vector<float>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(std::bit_cast<std::uint32_t>(a[i]), std::bit_cast<std::uint32_t>(b[i]))
        << "value " << i << ": " << a[i] << " vs " << b[i];
  }
}

/// Decodes `text` expecting an InputError; returns it for inspection.
InputError decodeError(const std::string& text) {
  try {
    static_cast<void>(decodeSim(text, "bad.sim"));
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "no InputError for:\n" << text;
  return InputError({}, "");
}

TEST(SimFormat, SmallFrameHasTheDocumentedText) {
  FrameSnapshot frame;
  frame.frame = 3;
  frame.time = 0.125;
  FluidSnapshot f;
  f.name = "honey";
  f.ids = {4, 9};
  f.positions = {1.5F, -2.0F, 0.1F, 0.0F, 1e-7F, 3e20F};
  f.velocities = {0, 0, 0, 0, 0, 0};
  frame.fluids.push_back(f);
  EXPECT_EQ(encodeSim(frame),
            "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
            "<Simulation version=\"1\" frame=\"3\" time=\"0.125\">\n"
            "  <Fluid>\n"
            "    <Name>honey</Name>\n"
            "    <ParticleNumber>2</ParticleNumber>\n"
            "    <Particles>\n"
            "1.5 -2 0.1\n"
            "0 1e-07 3e+20\n"
            "    </Particles>\n"
            "  </Fluid>\n"
            "</Simulation>\n");
}

TEST(SimFormat, RandomFloatsRoundTripBitExact) {
  std::mt19937 rng(42);
  FrameSnapshot frame;
  frame.frame = 1234;
  frame.time = 1234.0 / 24.0;
  frame.fluids.push_back(makeFluid("wild", 5000, 0, rng, /*wild=*/true));
  frame.fluids.push_back(makeFluid("plain", 700, 10000, rng));
  frame.fluids[0].positions[0] = -0.0F;
  frame.fluids[0].positions[1] = std::numeric_limits<float>::denorm_min();
  frame.fluids[0].positions[2] = -std::numeric_limits<float>::max();
  frame.fluids[0].positions[3] = std::numeric_limits<float>::min();

  const SimFile back = decodeSim(encodeSim(frame), "rt.sim");
  EXPECT_EQ(back.frame.frame, 1234);
  EXPECT_EQ(back.frame.time, frame.time);
  EXPECT_TRUE(back.frame.objects.empty());
  ASSERT_EQ(back.frame.fluids.size(), 2U);
  for (std::size_t i = 0; i < 2; ++i) {
    const FluidSnapshot& b = back.frame.fluids[i];
    EXPECT_EQ(b.name, frame.fluids[i].name);
    ASSERT_EQ(b.count(), frame.fluids[i].count());
    expectSameBits(b.positions, frame.fluids[i].positions);
    // The file holds no ids or velocities: file order numbering and zeros.
    for (std::size_t k = 0; k < b.count(); ++k) ASSERT_EQ(b.ids[k], k);
    EXPECT_EQ(b.velocities, std::vector<float>(3 * b.count(), 0.0F));
  }
}

TEST(SimFormat, NamesWithXmlSpecialCharactersRoundTrip) {
  std::mt19937 rng(1);
  FrameSnapshot frame;
  const std::vector<std::string> names = {
      "a<b>&\"c'd",  "x&amp;y", "]]>", " spaced ", "miel \xC3\xA9t\xC3\xA9",
      "line\nbreak", "cr\rlf"};
  for (const std::string& name : names) frame.fluids.push_back(makeFluid(name, 2, 0, rng));
  const std::string text = encodeSim(frame);
  EXPECT_EQ(text.find("a<b>"), std::string::npos);
  const SimFile back = decodeSim(text, "names.sim");
  ASSERT_EQ(back.frame.fluids.size(), names.size());
  for (std::size_t i = 0; i < names.size(); ++i) EXPECT_EQ(back.frame.fluids[i].name, names[i]);
}

TEST(SimFormat, ControlCharactersInNamesAreRefused) {
  FrameSnapshot frame;
  frame.fluids.push_back(FluidSnapshot{});
  frame.fluids[0].name = std::string("bell\x07", 5);
  EXPECT_THROW(static_cast<void>(encodeSim(frame)), InputError);
}

TEST(SimFormat, EmptyFramesAndFluidsRoundTrip) {
  FrameSnapshot frame;
  EXPECT_TRUE(decodeSim(encodeSim(frame), "e.sim").frame.fluids.empty());
  frame.fluids.push_back(FluidSnapshot{});
  frame.fluids[0].name = "none";
  const SimFile back = decodeSim(encodeSim(frame), "e.sim");
  ASSERT_EQ(back.frame.fluids.size(), 1U);
  EXPECT_EQ(back.frame.fluids[0].count(), 0U);
}

TEST(SimFormat, ObjectsRoundTripAndAreAcceptedInAnyOrder) {
  FrameSnapshot frame = makeFrame();
  std::vector<SimObject>& objects = frame.objects;
  objects.resize(2);
  objects[0] = {"bowl & lid", 1.5, {1, -2, 0.25}, {0.5, 0.5, 0.5, 0.5}, "bowlGeo/bowl.obj"};
  objects[1] = {"ball", 1, {0, 0, 0}, {1, 0, 0, 0}, ""};
  const SimFile back = decodeSim(encodeSim(frame), "o.sim");
  ASSERT_EQ(back.frame.objects.size(), 2U);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(back.frame.objects[i].name, objects[i].name);
    EXPECT_EQ(back.frame.objects[i].uniformScale, objects[i].uniformScale);
    EXPECT_EQ(back.frame.objects[i].position, objects[i].position);
    EXPECT_EQ(back.frame.objects[i].rotation, objects[i].rotation);
    EXPECT_EQ(back.frame.objects[i].filename, objects[i].filename);
  }
  EXPECT_EQ(back.frame.fluids.size(), 2U);

  const std::string handWritten =
      "<Simulation version=\"1\" frame=\"0\" time=\"0\">\n"
      "<Fluid><Name>a</Name><ParticleNumber>1</ParticleNumber><Particles>+1 2 "
      "3</Particles></Fluid>\n"
      "<Object><Name>o</Name><Rotation>1 0 0 0</Rotation><Position>1 2 3</Position></Object>\n"
      "</Simulation>";
  const SimFile mixed = decodeSim(handWritten, "mixed.sim");
  ASSERT_EQ(mixed.frame.objects.size(), 1U);
  EXPECT_EQ(mixed.frame.objects[0].uniformScale, 1.0);
  EXPECT_EQ(mixed.frame.objects[0].filename, "");
  EXPECT_EQ(mixed.frame.fluids[0].positions, (std::vector<float>{1, 2, 3}));
}

TEST(SimFormat, BadInputNamesFileLineAndElement) {
  const std::string head = "<Simulation version=\"1\" frame=\"2\" time=\"0.5\">\n";
  const auto fluid = [](const std::string& number, const std::string& particles) {
    return "<Fluid>\n<Name>f</Name>\n<ParticleNumber>" + number +
           "</ParticleNumber>\n<Particles>\n" + particles + "</Particles>\n</Fluid>\n";
  };
  const std::string tail = "</Simulation>\n";

  InputError e = decodeError(head + fluid("2", "1 2 3\n4 5 nan\n") + tail);
  EXPECT_EQ(e.where().file, "bad.sim");
  EXPECT_EQ(e.where().line, 7);  // the line holding "nan"
  EXPECT_EQ(e.where().element, "Fluid/Particles");

  e = decodeError(head + fluid("2", "1 2 3\n4 5 1e39\n") + tail);  // beyond float range
  EXPECT_EQ(e.where().line, 7);
  e = decodeError(head + fluid("1", "1 2 3x\n") + tail);
  EXPECT_EQ(e.where().element, "Fluid/Particles");
  e = decodeError(head + fluid("1", "1 2 inf\n") + tail);
  EXPECT_EQ(e.where().element, "Fluid/Particles");

  e = decodeError(head + fluid("3", "1 2 3\n4 5 6\n") + tail);
  EXPECT_EQ(e.where().element, "Fluid/ParticleNumber");
  EXPECT_EQ(e.where().line, 4);
  e = decodeError(head + fluid("2", "1 2 3\n4 5\n") + tail);
  EXPECT_EQ(e.where().element, "Fluid/Particles");
  e = decodeError(head + fluid("-1", "") + tail);
  EXPECT_EQ(e.where().element, "Fluid/ParticleNumber");
  // A huge declared count in a tiny file is a mismatch, never a huge allocation.
  e = decodeError(head + fluid("2147483648", "1 2 3\n") + tail);
  EXPECT_EQ(e.where().element, "Fluid/ParticleNumber");
  e = decodeError(head + fluid("18446744073709551615", "1 2 3\n") + tail);
  EXPECT_EQ(e.where().element, "Fluid/ParticleNumber");

  e = decodeError(head + "<Fluid>\n<Name>f</Name>\n<Colour>1 1 1</Colour>\n</Fluid>\n" + tail);
  EXPECT_EQ(e.where().element, "Fluid/Colour");
  EXPECT_EQ(e.where().line, 4);
  EXPECT_NE(e.allowed().find("ParticleNumber"), std::string::npos);
  e = decodeError(head + "<Fluid><Name>f</Name></Fluid>\n" + tail);
  EXPECT_EQ(e.where().element, "Fluid");
  e = decodeError(head + fluid("0", "") + fluid("0", "") + tail);
  EXPECT_EQ(e.where().element, "Fluid/Name");  // duplicate name
  e = decodeError(head + "<Fluid><Name>f</Name><Name>g</Name></Fluid>\n" + tail);
  EXPECT_EQ(e.where().element, "Fluid/Name");
  e = decodeError(head + "<Rigid/>\n" + tail);
  EXPECT_EQ(e.where().element, "Rigid");
  e = decodeError(head +
                  "<Object><Name>o</Name><Position>1 2</Position>"
                  "<Rotation>1 0 0 0</Rotation></Object>" +
                  tail);
  EXPECT_EQ(e.where().element, "Object/Position");
  e = decodeError(head +
                  "<Object><Name>o</Name><Position>1 2 3</Position>"
                  "<Rotation>2 0 0 0</Rotation></Object>" +
                  tail);
  EXPECT_EQ(e.where().element, "Object/Rotation");
}

TEST(SimFormat, BadRootAndMalformedXmlAreRefused) {
  EXPECT_EQ(decodeError("").where().file, "bad.sim");
  decodeError("not xml at all");
  decodeError("<Scene version=\"1\"/>");
  decodeError("<Simulation version=\"2\" frame=\"0\" time=\"0\"/>");
  decodeError("<Simulation version=\"1\" time=\"0\"/>");
  decodeError("<Simulation version=\"1\" frame=\"-3\" time=\"0\"/>");
  decodeError("<Simulation version=\"1\" frame=\"1\" time=\"nan\"/>");
  decodeError("<Simulation version=\"1\" frame=\"1\" time=\"0\" fps=\"24\"/>");
  const InputError e =
      decodeError("<Simulation version=\"1\" frame=\"1\" time=\"0\">\n\n<Fluid>\n");
  EXPECT_GE(e.where().line, 3);
  EXPECT_NE(std::string(e.what()).find("malformed XML"), std::string::npos);

  // Every truncation of a valid file is refused, never read as a shorter frame.
  const std::string good = encodeSim(makeFrame());
  for (std::size_t cut = 0; cut + 1 < good.size(); cut += 7) {
    EXPECT_THROW(static_cast<void>(decodeSim(good.substr(0, cut), "cut.sim")), InputError) << cut;
  }
}

TEST(SimFormat, ReadSimFileReadsWhatWasWritten) {
  const test::ScratchDir dir;
  const FrameSnapshot frame = makeFrame();
  writeFileAtomic(dir.path() / "s.0010.sim", encodeSim(frame));
  const SimFile back = readSimFile(dir.path() / "s.0010.sim");
  EXPECT_EQ(back.frame.frame, 10);
  expectSameBits(back.frame.fluids[1].positions, frame.fluids[1].positions);
  EXPECT_THROW(static_cast<void>(readSimFile(dir.path() / "missing.sim")), IoError);
  writeFileAtomic(dir.path() / "bad.sim", "<Simulation/>");
  try {
    static_cast<void>(readSimFile(dir.path() / "bad.sim"));
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, (dir.path() / "bad.sim").string());
  }
}

TEST(SimFormat, MillionParticlesEncodeAndDecodeQuickly) {
  std::mt19937 rng(7);
  FrameSnapshot frame;
  frame.fluids.push_back(makeFluid("big", 1'000'000, 0, rng));
  std::string text;
  const auto t0 = std::chrono::steady_clock::now();
  encodeSimInto(text, frame);
  const auto t1 = std::chrono::steady_clock::now();
  const SimFile back = decodeSim(text, "big.sim");
  const auto t2 = std::chrono::steady_clock::now();
  const double encodeSeconds = std::chrono::duration<double>(t1 - t0).count();
  const double decodeSeconds = std::chrono::duration<double>(t2 - t1).count();
  RecordProperty("encode_ms", static_cast<int>(encodeSeconds * 1000));
  RecordProperty("decode_ms", static_cast<int>(decodeSeconds * 1000));
  std::printf("1e6 particles: %zu bytes, encode %.3f s, decode %.3f s\n", text.size(),
              encodeSeconds, decodeSeconds);
  ASSERT_EQ(back.frame.fluids[0].count(), 1'000'000U);
  EXPECT_EQ(back.frame.fluids[0].positions, frame.fluids[0].positions);
#if defined(NDEBUG) && !defined(__SANITIZE_ADDRESS__)
  // Generous bound for a loaded shared machine; typical is a small fraction of it.
  EXPECT_LT(encodeSeconds, 1.0);
#endif
}

}  // namespace
}  // namespace softsub::cache
