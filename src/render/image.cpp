#include "render/image.h"

#include <csetjmp>
#include <cstring>
#include <memory>
#include <stdexcept>

#include <png.h>

#include "core/error.h"

namespace softsub::render {

namespace {

void appendBytes(png_structp png, png_bytep data, png_size_t length) {
  auto* out = static_cast<std::string*>(png_get_io_ptr(png));
  out->append(reinterpret_cast<const char*>(data), length);
}

void noFlush(png_structp) {}

struct Reader {
  std::string_view bytes;
  std::size_t offset = 0;
};

void readBytes(png_structp png, png_bytep data, png_size_t length) {
  auto* r = static_cast<Reader*>(png_get_io_ptr(png));
  if (r->bytes.size() - r->offset < length) png_error(png, "truncated file");
  std::memcpy(data, r->bytes.data() + r->offset, length);
  r->offset += length;
}

// libpng reports errors by longjmp; the message is kept here before the jump.
void onError(png_structp png, png_const_charp message) {
  auto* text = static_cast<std::string*>(png_get_error_ptr(png));
  *text = message;
  png_longjmp(png, 1);
}

void onWarning(png_structp, png_const_charp) {}

}  // namespace

std::string encodePng(const Image& image) {
  if (image.width <= 0 || image.height <= 0 ||
      image.rgb.size() != 3 * static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height))
    throw std::invalid_argument("encodePng: pixel buffer does not match the size");
  auto out = std::make_unique<std::string>();  // behind a pointer: see decodePng
  std::string error;
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &error, onError, onWarning);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (png == nullptr || info == nullptr) {
    png_destroy_write_struct(&png, nullptr);
    throw std::bad_alloc();
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    throw std::runtime_error("PNG encoding failed: " + error);
  }
  png_set_write_fn(png, out.get(), appendBytes, noFlush);
  png_set_IHDR(png, info, static_cast<png_uint_32>(image.width), static_cast<png_uint_32>(image.height), 8,
               PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_set_compression_level(png, 6);
  png_write_info(png, info);
  for (int y = 0; y < image.height; ++y)
    png_write_row(png, const_cast<png_bytep>(image.at(0, y)));
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return std::move(*out);
}

Image decodePng(std::string_view bytes, const std::string& fileName) {
  if (bytes.size() < 8 || png_sig_cmp(reinterpret_cast<png_const_bytep>(bytes.data()), 0, 8) != 0)
    throw InputError({fileName, 0, "PNG"}, "not a PNG file", "a PNG picture");
  std::string error;
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &error, onError, onWarning);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (png == nullptr || info == nullptr) {
    png_destroy_read_struct(&png, nullptr, nullptr);
    throw std::bad_alloc();
  }
  // Objects changed after setjmp live behind a pointer set before it (a longjmp leaves
  // locals changed in between indeterminate).
  auto image = std::make_unique<Image>();
  Reader reader{bytes, 0};
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, &info, nullptr);
    throw InputError({fileName, 0, "PNG"}, "unreadable PNG: " + error, "a complete PNG picture");
  }
  png_set_read_fn(png, &reader, readBytes);
  png_read_info(png, info);
  png_set_strip_16(png);
  png_set_strip_alpha(png);
  png_set_palette_to_rgb(png);
  png_set_expand_gray_1_2_4_to_8(png);
  png_set_gray_to_rgb(png);
  png_read_update_info(png, info);
  const png_uint_32 w = png_get_image_width(png, info);
  const png_uint_32 h = png_get_image_height(png, info);
  if (w == 0 || h == 0 || w > 65536 || h > 65536 || png_get_rowbytes(png, info) != 3 * w)
    png_error(png, "unsupported size or layout");
  image->width = static_cast<int>(w);
  image->height = static_cast<int>(h);
  image->rgb.resize(3 * static_cast<std::size_t>(w) * h);
  for (png_uint_32 y = 0; y < h; ++y)
    png_read_row(png, image->rgb.data() + 3 * static_cast<std::size_t>(w) * y, nullptr);
  png_read_end(png, nullptr);
  png_destroy_read_struct(&png, &info, nullptr);
  return std::move(*image);
}

}  // namespace softsub::render
