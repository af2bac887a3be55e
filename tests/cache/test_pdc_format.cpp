// Maya PDC: the bytes checked field by field by a minimal big-endian reader written here,
// independent of the module's decoder; then the decoder's round trip and its refusals.
#include <cmath>
#include <cstring>

#include <gtest/gtest.h>

#include "cache/atomic_file.h"
#include "cache/cache_test_support.h"
#include "cache/pdc_format.h"
#include "core/error.h"

namespace softsub::cache {
namespace {

using test::makeFluid;

/// The simplest possible big-endian cursor, sharing no code with pdc_format.cpp.
struct Cursor {
  const std::string& bytes;
  std::size_t pos = 0;

  std::uint64_t take(int n) {
    EXPECT_LE(pos + static_cast<std::size_t>(n), bytes.size()) << "read past the end";
    std::uint64_t v = 0;
    for (int i = 0; i < n; ++i) v = v * 256 + static_cast<unsigned char>(bytes.at(pos++));
    return v;
  }
  std::int32_t int32() { return static_cast<std::int32_t>(static_cast<std::uint32_t>(take(4))); }
  double float64() {
    const std::uint64_t bits = take(8);
    double d = 0;
    std::memcpy(&d, &bits, sizeof d);
    return d;
  }
  std::string text(std::size_t n) {
    std::string s = bytes.substr(pos, n);
    pos += n;
    return s;
  }
};

void expectAttributeHeader(Cursor& c, const std::string& name, std::int32_t type) {
  EXPECT_EQ(c.int32(), static_cast<std::int32_t>(name.size()));
  EXPECT_EQ(c.text(name.size()), name);
  EXPECT_EQ(c.int32(), type);
}

TEST(PdcFormat, BytesMatchTheMayaLayoutFieldByField) {
  std::mt19937 rng(3);
  const FluidSnapshot fluid = makeFluid("honey", 17, 5, rng, /*wild=*/true);
  const std::string bytes = encodePdc(fluid);
  const std::size_t n = fluid.count();
  EXPECT_EQ(bytes.size(), 28 + (4 + 8 + 4 + 24 * n) + (4 + 8 + 4 + 24 * n) + (4 + 10 + 4 + 8 * n) +
                              (4 + 8 + 4 + 8 * n) + (4 + 5 + 4 + 24 * n));

  Cursor c{bytes};
  EXPECT_EQ(c.text(4), "PDC ");
  EXPECT_EQ(c.int32(), 1);  // version
  EXPECT_EQ(c.int32(), 1);  // byte order
  EXPECT_EQ(c.int32(), 0);  // extra 1
  EXPECT_EQ(c.int32(), 0);  // extra 2
  EXPECT_EQ(c.int32(), 17);
  EXPECT_EQ(c.int32(), 5);

  expectAttributeHeader(c, "position", 5);
  for (std::size_t i = 0; i < 3 * n; ++i)
    ASSERT_EQ(c.float64(), static_cast<double>(fluid.positions[i]));
  expectAttributeHeader(c, "velocity", 5);
  for (std::size_t i = 0; i < 3 * n; ++i)
    ASSERT_EQ(c.float64(), static_cast<double>(fluid.velocities[i]));
  expectAttributeHeader(c, "particleId", 3);
  for (std::size_t k = 0; k < n; ++k) ASSERT_EQ(c.float64(), static_cast<double>(fluid.ids[k]));
  expectAttributeHeader(c, "radiusPP", 3);
  for (std::size_t k = 0; k < n; ++k) ASSERT_EQ(c.float64(), 0.15000000596046448);  // 0.3f / 2
  expectAttributeHeader(c, "rgbPP", 5);
  for (std::size_t k = 0; k < n; ++k) {
    ASSERT_EQ(c.float64(), 0.25);
    ASSERT_EQ(c.float64(), 0.5);
    ASSERT_EQ(c.float64(), 1.0);
  }
  EXPECT_EQ(c.pos, bytes.size());
}

TEST(PdcFormat, KnownValueHasKnownBytes) {
  FluidSnapshot f;
  f.ids = {1};
  f.positions = {1.0F, -2.0F, 0.5F};
  f.velocities = {0, 0, 0};
  const std::string bytes = encodePdc(f);
  // "PDC " 00000001 00000001 00000000 00000000 00000001 00000005, then "position".
  const std::string head(
      "PDC \0\0\0\1\0\0\0\1\0\0\0\0\0\0\0\0\0\0\0\1\0\0\0\5\0\0\0\x08position\0\0\0\5", 44);
  EXPECT_EQ(bytes.substr(0, 44), head);
  EXPECT_EQ(bytes.substr(44, 8), std::string("\x3f\xf0\0\0\0\0\0\0", 8));  // 1.0
  EXPECT_EQ(bytes.substr(52, 8), std::string("\xc0\x00\0\0\0\0\0\0", 8));  // -2.0
  EXPECT_EQ(bytes.substr(60, 8), std::string("\x3f\xe0\0\0\0\0\0\0", 8));  // 0.5
}

TEST(PdcFormat, DecoderRoundTrip) {
  std::mt19937 rng(4);
  FluidSnapshot fluid = makeFluid("oil", 100, 0, rng, true);
  fluid.colour = {0.1F, 0.2F, 0.3F};
  fluid.particleSize = 2.0F;
  const PdcFile file = decodePdc(encodePdc(fluid), "oil.pdc");
  EXPECT_EQ(file.version, 1);
  EXPECT_EQ(file.byteOrder, 1);
  EXPECT_EQ(file.count, 100);
  ASSERT_EQ(file.attributes.size(), 5U);
  const std::vector<std::pair<std::string, PdcType>> expected = {
      {"position", PdcType::VectorArray},
      {"velocity", PdcType::VectorArray},
      {"particleId", PdcType::DoubleArray},
      {"radiusPP", PdcType::DoubleArray},
      {"rgbPP", PdcType::VectorArray}};
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(file.attributes[i].name, expected[i].first);
    EXPECT_EQ(file.attributes[i].type, expected[i].second);
  }
  const PdcAttribute* position = file.find("position");
  ASSERT_NE(position, nullptr);
  ASSERT_EQ(position->values.size(), 300U);
  for (std::size_t i = 0; i < 300; ++i) {
    ASSERT_EQ(static_cast<float>(position->values[i]), fluid.positions[i]);
  }
  EXPECT_EQ(file.find("radiusPP")->values, std::vector<double>(100, 1.0));
  EXPECT_EQ(file.find("rgbPP")->values[2], static_cast<double>(0.3F));
  EXPECT_EQ(file.find("particleId")->values[99], 198.0);  // ids 0, 2, 4, ...
  EXPECT_EQ(file.find("missing"), nullptr);
}

TEST(PdcFormat, EmptyFluidIsAValidFile) {
  FluidSnapshot f;
  f.name = "empty";
  const PdcFile file = decodePdc(encodePdc(f), "e.pdc");
  EXPECT_EQ(file.count, 0);
  ASSERT_EQ(file.attributes.size(), 5U);
  for (const PdcAttribute& a : file.attributes) EXPECT_TRUE(a.values.empty());
}

/// Big-endian builder for hand-made PDC files in the tests below.
struct Builder {
  std::string bytes;
  Builder& i32(std::int64_t v) {
    for (int s = 24; s >= 0; s -= 8)
      bytes += static_cast<char>((static_cast<std::uint32_t>(v) >> s) & 0xff);
    return *this;
  }
  Builder& f64(double d) {
    std::uint64_t bits = 0;
    std::memcpy(&bits, &d, sizeof d);
    for (int s = 56; s >= 0; s -= 8) bytes += static_cast<char>((bits >> s) & 0xff);
    return *this;
  }
  Builder& str(const std::string& s) {
    bytes += s;
    return *this;
  }
  Builder& header(std::int64_t count, std::int64_t attributes) {
    return str("PDC ").i32(1).i32(1).i32(0).i32(0).i32(count).i32(attributes);
  }
  Builder& attribute(const std::string& name, std::int32_t type) {
    return i32(static_cast<std::int64_t>(name.size())).str(name).i32(type);
  }
};

TEST(PdcFormat, DecoderReadsAllSixMayaTypes) {
  Builder b;
  b.header(2, 6);
  b.attribute("lifespan", 0).i32(-7);
  b.attribute("ages", 1).i32(3).i32(-4);
  b.attribute("mass", 2).f64(2.5);
  b.attribute("wind", 4).f64(1).f64(2).f64(3);
  b.attribute("radius", 3).f64(0.5).f64(0.25);
  b.attribute("position", 5).f64(1).f64(2).f64(3).f64(4).f64(5).f64(6);
  const PdcFile file = decodePdc(b.bytes, "six.pdc");
  ASSERT_EQ(file.attributes.size(), 6U);
  EXPECT_EQ(file.find("lifespan")->type, PdcType::Int);
  EXPECT_EQ(file.find("lifespan")->values, std::vector<double>{-7});
  EXPECT_EQ(file.find("ages")->type, PdcType::IntArray);
  EXPECT_EQ(file.find("ages")->values, (std::vector<double>{3, -4}));
  EXPECT_EQ(file.find("mass")->values, std::vector<double>{2.5});
  EXPECT_EQ(file.find("wind")->type, PdcType::Vector);
  EXPECT_EQ(file.find("wind")->values, (std::vector<double>{1, 2, 3}));
  EXPECT_EQ(file.find("radius")->values, (std::vector<double>{0.5, 0.25}));
  EXPECT_EQ(file.find("position")->values, (std::vector<double>{1, 2, 3, 4, 5, 6}));
}

void expectRefused(const std::string& bytes, const std::string& why) {
  try {
    static_cast<void>(decodePdc(bytes, "bad.pdc"));
    ADD_FAILURE() << "accepted: " << why;
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, "bad.pdc") << why;
  }
}

TEST(PdcFormat, TruncatedAndGarbageInputIsRefused) {
  std::mt19937 rng(5);
  const std::string good = encodePdc(makeFluid("f", 4, 0, rng));
  for (std::size_t cut = 0; cut < good.size(); ++cut) expectRefused(good.substr(0, cut), "cut");
  expectRefused(good + "x", "trailing byte");
  expectRefused("", "empty");
  expectRefused("PDX " + good.substr(4), "magic");
  std::string garbage(200, '\0');
  for (char& ch : garbage) ch = static_cast<char>(rng());
  expectRefused(garbage, "random bytes");
  expectRefused("PDC " + garbage, "random bytes after the magic");

  expectRefused(Builder().str("PDC ").i32(2).i32(1).i32(0).i32(0).i32(0).i32(0).bytes, "version 2");
  // A little-endian writer's header: refused with a message saying so.
  try {
    static_cast<void>(decodePdc(
        std::string("PDC \1\0\0\0\1\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0", 28), "le.pdc"));
    ADD_FAILURE() << "little-endian accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("little-endian"), std::string::npos) << e.what();
  }
  expectRefused(Builder().header(-1, 0).bytes, "negative count");
  expectRefused(Builder().header(1, -1).bytes, "negative attribute count");
  expectRefused(Builder().header(1, 1).attribute("x", 6).f64(1).bytes, "type 6");
  expectRefused(Builder().header(1, 1).i32(0).i32(2).f64(1).bytes, "empty name");
  expectRefused(Builder().header(1, 1).i32(1000).str("x").i32(2).f64(1).bytes, "name too long");
  expectRefused(Builder().header(1, 2).attribute("m", 2).f64(1).attribute("m", 2).f64(1).bytes,
                "duplicate attribute");
  // Non-finite doubles, as the .sim and PLY readers refuse them (info showed a file with
  // NaN positions as fine): the second particle's y, and an infinite double.
  try {
    static_cast<void>(decodePdc(Builder()
                                    .header(2, 1)
                                    .attribute("position", 5)
                                    .f64(0)
                                    .f64(0)
                                    .f64(0)
                                    .f64(1)
                                    .f64(std::nan(""))
                                    .f64(1)
                                    .bytes,
                                "nan.pdc"));
    ADD_FAILURE() << "NaN accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("non-finite value nan at particle 1"), std::string::npos)
        << e.what();
  }
  expectRefused(Builder().header(1, 1).attribute("mass", 2).f64(HUGE_VAL).bytes, "infinite double");
}

TEST(PdcFormat, HugeDeclaredCountsAreRefusedWithoutAllocating) {
  // 2^31 - 1 particles (2^31 itself is negative as int32) and many attributes, in ~100 bytes.
  Builder huge;
  huge.header(0x7fffffff, 1).attribute("position", 5);
  huge.bytes.resize(100, '\0');
  expectRefused(huge.bytes, "2^31-1 vectors");
  Builder wrapped;
  wrapped.header(0x80000000LL, 1).attribute("position", 5);
  wrapped.bytes.resize(100, '\0');
  expectRefused(wrapped.bytes, "count 2^31");
  Builder attributes;
  attributes.header(1, 0x7fffffff);
  attributes.bytes.resize(100, '\0');
  expectRefused(attributes.bytes, "2^31-1 attributes");
  Builder ints;
  ints.header(0x7fffffff, 1).attribute("ids", 1);
  ints.bytes.resize(100, '\0');
  expectRefused(ints.bytes, "2^31-1 ints");
}

TEST(PdcFormat, ReadPdcFile) {
  const test::ScratchDir dir;
  std::mt19937 rng(6);
  writeFileAtomic(dir.path() / "fShape.250.pdc", encodePdc(makeFluid("f", 3, 0, rng)));
  EXPECT_EQ(readPdcFile(dir.path() / "fShape.250.pdc").count, 3);
  EXPECT_THROW(static_cast<void>(readPdcFile(dir.path() / "none.pdc")), IoError);
}

}  // namespace
}  // namespace softsub::cache
