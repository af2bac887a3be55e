#pragma once
/// An RGB picture and its PNG encoding (libpng): what the renderer reads back and what
/// `softsub render`, `run --preview` and the viewer's screenshots write.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace softsub::render {

/// 8-bit RGB pixels, rows top to bottom.
struct Image {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgb;  ///< 3 * width * height bytes

  /// The pixel at column x, row y (0, 0 is the top left).
  [[nodiscard]] const std::uint8_t* at(int x, int y) const {
    return rgb.data() + 3 * (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                             static_cast<std::size_t>(x));
  }
};

/// The PNG file bytes of `image` (8-bit RGB, no interlace).
[[nodiscard]] std::string encodePng(const Image& image);

/// Decodes PNG bytes into 8-bit RGB (alpha dropped, grey expanded, 16-bit reduced).
/// Throws InputError naming `fileName` when the bytes are not a PNG.
[[nodiscard]] Image decodePng(std::string_view bytes, const std::string& fileName);

}  // namespace softsub::render
