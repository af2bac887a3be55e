// PNG encoding round trip through libpng and refusal of non-PNG bytes.
#include <gtest/gtest.h>

#include "core/error.h"
#include "render/image.h"

namespace softsub::render {
namespace {

TEST(Png, RoundTripKeepsEveryPixel) {
  Image a;
  a.width = 7;
  a.height = 5;
  for (int i = 0; i < 7 * 5 * 3; ++i) a.rgb.push_back(static_cast<std::uint8_t>((i * 37) % 256));
  const std::string bytes = encodePng(a);
  ASSERT_GT(bytes.size(), 8u);
  EXPECT_EQ(bytes.substr(1, 3), "PNG");
  const Image b = decodePng(bytes, "mem.png");
  EXPECT_EQ(b.width, 7);
  EXPECT_EQ(b.height, 5);
  EXPECT_EQ(b.rgb, a.rgb);
  EXPECT_EQ(b.at(6, 4)[2], a.at(6, 4)[2]);
}

TEST(Png, RefusesOtherBytesAndTruncation) {
  EXPECT_THROW((void)decodePng("not a picture", "x.png"), InputError);
  Image a;
  a.width = 16;
  a.height = 16;
  a.rgb.assign(16 * 16 * 3, 200);
  const std::string bytes = encodePng(a);
  EXPECT_THROW((void)decodePng(std::string_view(bytes).substr(0, bytes.size() / 2), "cut.png"), InputError);
}

TEST(Png, RefusesABufferOfTheWrongSize) {
  Image a;
  a.width = 4;
  a.height = 4;
  a.rgb.assign(10, 0);
  EXPECT_THROW((void)encodePng(a), std::invalid_argument);
}

}  // namespace
}  // namespace softsub::render
