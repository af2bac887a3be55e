// PLY point clouds: the exact header, the binary records read back by hand, the decoder
// on other layouts (ascii, big-endian, doubles, faces), and refusal of what it cannot read.
#include <cstring>

#include <gtest/gtest.h>

#include "cache/atomic_file.h"
#include "cache/cache_test_support.h"
#include "cache/ply_format.h"
#include "core/error.h"

namespace softsub::cache {
namespace {

using test::makeFrame;

const char* const kHeaderTail =
    "property float x\nproperty float y\nproperty float z\n"
    "property float vx\nproperty float vy\nproperty float vz\n"
    "property uint id\nproperty int fluid\n"
    "property uchar red\nproperty uchar green\nproperty uchar blue\n"
    "end_header\n";

TEST(PlyFormat, HeaderIsTheDocumentedText) {
  const FrameSnapshot frame = makeFrame();
  const std::string bytes = encodePly(frame);
  const std::string header = std::string(
                                 "ply\n"
                                 "format binary_little_endian 1.0\n"
                                 "comment softsub frame 10 time 0.4166666666666667\n"
                                 "comment fluid 0 honey\n"
                                 "comment fluid 1 oil\n"
                                 "element vertex 8\n") +
                             kHeaderTail;
  ASSERT_GE(bytes.size(), header.size());
  EXPECT_EQ(bytes.substr(0, header.size()), header);
  EXPECT_EQ(bytes.size(), header.size() + 8 * 35);
}

/// Little-endian field reader sharing no code with ply_format.cpp.
struct LittleCursor {
  const std::string& bytes;
  std::size_t pos;
  std::uint32_t u32() {
    std::uint32_t v = 0;
    for (int i = 3; i >= 0; --i)
      v = v * 256 + static_cast<unsigned char>(bytes.at(pos + static_cast<std::size_t>(i)));
    pos += 4;
    return v;
  }
  float f32() {
    const std::uint32_t bits = u32();
    float f = 0;
    std::memcpy(&f, &bits, sizeof f);
    return f;
  }
  unsigned u8() { return static_cast<unsigned char>(bytes.at(pos++)); }
};

TEST(PlyFormat, BinaryRecordsHoldTheSnapshotValues) {
  const FrameSnapshot frame = makeFrame();
  const std::string bytes = encodePly(frame);
  LittleCursor c{bytes, bytes.find("end_header\n") + 11};
  for (std::size_t f = 0; f < frame.fluids.size(); ++f) {
    const FluidSnapshot& fluid = frame.fluids[f];
    for (std::size_t k = 0; k < fluid.count(); ++k) {
      for (int i = 0; i < 3; ++i)
        EXPECT_EQ(c.f32(), fluid.positions[3 * k + static_cast<std::size_t>(i)]);
      for (int i = 0; i < 3; ++i)
        EXPECT_EQ(c.f32(), fluid.velocities[3 * k + static_cast<std::size_t>(i)]);
      EXPECT_EQ(c.u32(), fluid.ids[k]);
      EXPECT_EQ(c.u32(), f);
      const std::vector<unsigned> rgb{c.u8(), c.u8(), c.u8()};
      // honey (0.25, 0.5, 1) and oil (1, 0, 0.123): rounded, not truncated.
      EXPECT_EQ(rgb, f == 0 ? (std::vector<unsigned>{64, 128, 255})
                            : (std::vector<unsigned>{255, 0, 31}));
    }
  }
  EXPECT_EQ(c.pos, bytes.size());
}

TEST(PlyFormat, DecoderRoundTrip) {
  const FrameSnapshot frame = makeFrame();
  const PlyCloud cloud = decodePly(encodePly(frame), "f.ply");
  EXPECT_EQ(cloud.format, "binary_little_endian");
  EXPECT_TRUE(cloud.hasFrame);
  EXPECT_EQ(cloud.frame, 10);
  EXPECT_EQ(cloud.time, frame.time);
  EXPECT_EQ(cloud.fluidNames, (std::vector<std::string>{"honey", "oil"}));
  EXPECT_EQ(cloud.vertexCount, 8U);
  ASSERT_EQ(cloud.properties.size(), 11U);
  EXPECT_EQ(cloud.properties[6].name, "id");
  EXPECT_EQ(cloud.properties[6].type, PlyScalar::UInt32);
  EXPECT_EQ(cloud.properties[8].type, PlyScalar::UInt8);
  const PlyProperty* y = cloud.find("y");
  const PlyProperty* fluid = cloud.find("fluid");
  const PlyProperty* id = cloud.find("id");
  ASSERT_TRUE(y && fluid && id);
  EXPECT_EQ(static_cast<float>(y->values[4]), frame.fluids[1].positions[3 * 1 + 1]);
  EXPECT_EQ(fluid->values, (std::vector<double>{0, 0, 0, 1, 1, 1, 1, 1}));
  EXPECT_EQ(id->values[3], 100.0);
}

TEST(PlyFormat, NamesWithSpacesAndEmptyFramesRoundTrip) {
  FrameSnapshot frame;
  frame.fluids.push_back(FluidSnapshot{});
  frame.fluids[0].name = "maple syrup ";
  const PlyCloud cloud = decodePly(encodePly(frame), "e.ply");
  EXPECT_EQ(cloud.vertexCount, 0U);
  EXPECT_EQ(cloud.fluidNames, std::vector<std::string>{"maple syrup "});
  frame.fluids[0].name = "two\nlines";
  EXPECT_THROW(static_cast<void>(encodePly(frame)), InputError);
}

TEST(PlyFormat, ReadsAsciiWithOtherOrderTypesAndFaces) {
  const std::string text =
      "ply\r\n"
      "format ascii 1.0\r\n"
      "comment made by hand\r\n"
      "obj_info whatever\r\n"
      "element vertex 3\r\n"
      "property uchar red\r\n"
      "property double z\r\n"
      "property float32 x\r\n"
      "property list uchar int extra\r\n"
      "property int16 y\r\n"
      "element face 1\r\n"
      "property list uchar int vertex_indices\r\n"
      "end_header\r\n"
      "255 0.5 -1 2 7 8 -3\r\n"
      "0 1e-3 2 0 4\r\n"
      "12 -2.25 3.5 1 9 5\r\n"
      "3 0 1 2\r\n";
  const PlyCloud cloud = decodePly(text, "hand.ply");
  EXPECT_EQ(cloud.format, "ascii");
  EXPECT_FALSE(cloud.hasFrame);
  EXPECT_EQ(cloud.comments, std::vector<std::string>{"made by hand"});
  EXPECT_EQ(cloud.vertexCount, 3U);
  ASSERT_EQ(cloud.properties.size(), 4U);  // the list is skipped
  EXPECT_EQ(cloud.find("x")->values, (std::vector<double>{-1, 2, 3.5}));
  EXPECT_EQ(cloud.find("y")->values, (std::vector<double>{-3, 4, 5}));
  EXPECT_EQ(cloud.find("z")->values, (std::vector<double>{0.5, 1e-3, -2.25}));
  EXPECT_EQ(cloud.find("red")->values, (std::vector<double>{255, 0, 12}));
  EXPECT_EQ(cloud.find("z")->type, PlyScalar::Float64);
}

TEST(PlyFormat, ReadsBigEndianBinary) {
  std::string bytes =
      "ply\nformat binary_big_endian 1.0\nelement vertex 2\n"
      "property double x\nproperty float y\nproperty short z\nproperty char w\nend_header\n";
  const auto put = [&](std::uint64_t v, int n) {
    for (int i = n - 1; i >= 0; --i) bytes += static_cast<char>((v >> (8 * i)) & 0xff);
  };
  for (int k = 0; k < 2; ++k) {
    double x = 1.5 + k;
    float y = -0.25F * static_cast<float>(k + 1);
    std::uint64_t xb = 0;
    std::uint32_t yb = 0;
    std::memcpy(&xb, &x, 8);
    std::memcpy(&yb, &y, 4);
    put(xb, 8);
    put(yb, 4);
    put(static_cast<std::uint16_t>(-300 + k), 2);
    put(static_cast<std::uint8_t>(-5), 1);
  }
  const PlyCloud cloud = decodePly(bytes, "be.ply");
  EXPECT_EQ(cloud.find("x")->values, (std::vector<double>{1.5, 2.5}));
  EXPECT_EQ(cloud.find("y")->values, (std::vector<double>{-0.25, -0.5}));
  EXPECT_EQ(cloud.find("z")->values, (std::vector<double>{-300, -299}));
  EXPECT_EQ(cloud.find("w")->values, (std::vector<double>{-5, -5}));
}

void expectRefused(const std::string& bytes, const std::string& why) {
  try {
    static_cast<void>(decodePly(bytes, "bad.ply"));
    ADD_FAILURE() << "accepted: " << why;
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, "bad.ply") << why;
  }
}

TEST(PlyFormat, RefusesTruncatedGarbageAndUnreadableHeaders) {
  const std::string good = encodePly(makeFrame());
  for (std::size_t cut = 0; cut < good.size(); ++cut) expectRefused(good.substr(0, cut), "cut");
  expectRefused(good + "x", "trailing byte");
  expectRefused(std::string(300, '\x7f'), "garbage");
  const std::string start = "ply\nformat ascii 1.0\n";
  expectRefused("ply\nformat binary_middle_endian 1.0\nend_header\n", "format");
  expectRefused("ply\nformat ascii 2.0\nend_header\n", "format version");
  expectRefused(
      "ply\nelement vertex 0\nproperty float x\nproperty float y\nproperty float z\nend_header\n",
      "no format");
  expectRefused(start + "element vertex 1\nproperty half x\nend_header\n0\n", "unknown type");
  expectRefused(start + "element vertex 1\nproperty float x\nproperty float y\nend_header\n0 0\n",
                "no z");
  expectRefused(start + "element face 0\nend_header\n", "no vertex");
  expectRefused(start + "property float x\nend_header\n", "property before element");
  expectRefused(start +
                    "element vertex 1\nproperty float x\nproperty float y\nproperty float z\n"
                    "property float x\nend_header\n1 2 3 4\n",
                "duplicate property");
  expectRefused(start + "element vertex 1\nbogus line\nend_header\n", "unknown line");
  const std::string xyz = "property float x\nproperty float y\nproperty float z\nend_header\n";
  expectRefused(start + "element vertex 1\n" + xyz + "1 2\n", "ascii ends early");
  expectRefused(start + "element vertex 1\n" + xyz + "1 2 nan\n", "ascii nan");
  expectRefused(start + "element vertex 1\n" + xyz + "1 2 3 4\n", "ascii extra value");
  expectRefused(start +
                    "element vertex 1\nproperty uchar x\nproperty float y\nproperty float z\n"
                    "end_header\n256 0 0\n",
                "uchar out of range");
  expectRefused(start +
                    "element vertex 1\nproperty int x\nproperty float y\nproperty float z\n"
                    "end_header\n1.5 0 0\n",
                "fractional int");
  try {
    static_cast<void>(decodePly(start + "element vertex 2\n" + xyz + "1 2 3\n4 x 6\n", "line.ply"));
    ADD_FAILURE() << "bad ascii value accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().line, 9);  // "4 x 6"
  }
}

TEST(PlyFormat, HugeDeclaredCountsAreRefusedWithoutAllocating) {
  for (const char* format : {"binary_little_endian", "ascii"}) {
    for (const char* count : {"2147483648", "18446744073709551615", "100000"}) {
      std::string bytes = std::string("ply\nformat ") + format + " 1.0\nelement vertex " + count +
                          "\nproperty float x\nproperty float y\nproperty float z\nend_header\n";
      bytes.resize(std::max<std::size_t>(bytes.size(), 100), '0');
      expectRefused(bytes, std::string(format) + " " + count);
    }
  }
  expectRefused("ply\nformat ascii 1.0\nelement vertex 99999999999999999999999\nend_header\n",
                "count beyond 64 bits");
}

TEST(PlyFormat, ReadPlyFile) {
  const test::ScratchDir dir;
  writeFileAtomic(dir.path() / "a.ply", encodePly(makeFrame()));
  EXPECT_EQ(readPlyFile(dir.path() / "a.ply").vertexCount, 8U);
  EXPECT_THROW(static_cast<void>(readPlyFile(dir.path() / "b.ply")), IoError);
}

}  // namespace
}  // namespace softsub::cache
