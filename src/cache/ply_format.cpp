#include "cache/ply_format.h"

#include <algorithm>
#include <array>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstring>
#include <iterator>
#include <limits>
#include <stdexcept>

#include <fmt/format.h>

#include "cache/atomic_file.h"
#include "cache/message.h"
#include "core/error.h"

namespace softsub::cache {
namespace {

// ---------------------------------------------------------------------------------------
// Writing

constexpr std::size_t kVertexBytes = 6 * 4 + 4 + 4 + 3;  // 6 floats, uint, int, 3 uchar

/// Sequential little-endian writer into a buffer sized in advance.
class LittleEndianWriter {
 public:
  explicit LittleEndianWriter(char* p) : p_(p) {}
  void u32(std::uint32_t v) {
    for (int shift = 0; shift < 32; shift += 8) *p_++ = static_cast<char>((v >> shift) & 0xffU);
  }
  void f32(float v) { u32(std::bit_cast<std::uint32_t>(v)); }
  void u8(std::uint8_t v) { *p_++ = static_cast<char>(v); }
  [[nodiscard]] const char* position() const { return p_; }

 private:
  char* p_;
};

std::uint8_t colourByte(float c) {
  if (!(c > 0)) return 0;  // also NaN
  if (c >= 1) return 255;
  return static_cast<std::uint8_t>(std::lround(c * 255.0F));
}

/// A fluid name as it goes into a header comment: one line, so no control characters.
void checkCommentName(const std::string& name) {
  for (const char c : name) {
    const auto u = static_cast<unsigned char>(c);
    if (u < 0x20 || u == 0x7f) {
      throw InputError({"", 0, "Fluid/Name"},
                       fmt::format("fluid name contains control character {:#04x}", u),
                       "names without control characters");
    }
  }
}

// ---------------------------------------------------------------------------------------
// Reading

enum class Format { Ascii, BinaryLittle, BinaryBig };

struct HeaderProperty {
  std::string name;
  bool isList = false;
  PlyScalar countType = PlyScalar::UInt8;  ///< lists only
  PlyScalar type = PlyScalar::Float32;     ///< the value, or the list's item type
};

struct HeaderElement {
  std::string name;
  std::uint64_t count = 0;
  std::vector<HeaderProperty> properties;
  int line = 0;
};

constexpr std::array<std::pair<std::string_view, PlyScalar>, 16> kScalarNames{{
    {"char", PlyScalar::Int8},
    {"int8", PlyScalar::Int8},
    {"uchar", PlyScalar::UInt8},
    {"uint8", PlyScalar::UInt8},
    {"short", PlyScalar::Int16},
    {"int16", PlyScalar::Int16},
    {"ushort", PlyScalar::UInt16},
    {"uint16", PlyScalar::UInt16},
    {"int", PlyScalar::Int32},
    {"int32", PlyScalar::Int32},
    {"uint", PlyScalar::UInt32},
    {"uint32", PlyScalar::UInt32},
    {"float", PlyScalar::Float32},
    {"float32", PlyScalar::Float32},
    {"double", PlyScalar::Float64},
    {"float64", PlyScalar::Float64},
}};

constexpr std::string_view kScalarList =
    "char/int8, uchar/uint8, short/int16, ushort/uint16, int/int32, uint/uint32, "
    "float/float32, double/float64";

std::size_t scalarSize(PlyScalar t) {
  switch (t) {
    case PlyScalar::Int8:
    case PlyScalar::UInt8: return 1;
    case PlyScalar::Int16:
    case PlyScalar::UInt16: return 2;
    case PlyScalar::Int32:
    case PlyScalar::UInt32:
    case PlyScalar::Float32: return 4;
    case PlyScalar::Float64: return 8;
  }
  return 0;
}

bool isFloat(PlyScalar t) { return t == PlyScalar::Float32 || t == PlyScalar::Float64; }

std::pair<double, double> scalarRange(PlyScalar t) {
  switch (t) {
    case PlyScalar::Int8: return {-128, 127};
    case PlyScalar::UInt8: return {0, 255};
    case PlyScalar::Int16: return {-32768, 32767};
    case PlyScalar::UInt16: return {0, 65535};
    case PlyScalar::Int32: return {-2147483648.0, 2147483647.0};
    case PlyScalar::UInt32: return {0, 4294967295.0};
    case PlyScalar::Float32:
      return {-std::numeric_limits<float>::max(), std::numeric_limits<float>::max()};
    case PlyScalar::Float64:
      return {-std::numeric_limits<double>::max(), std::numeric_limits<double>::max()};
  }
  return {0, 0};
}

bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }

std::vector<std::string_view> splitWords(std::string_view line) {
  std::vector<std::string_view> words;
  std::size_t pos = 0;
  while (true) {
    while (pos < line.size() && isSpace(line[pos])) ++pos;
    if (pos == line.size()) break;
    std::size_t end = pos;
    while (end < line.size() && !isSpace(line[end])) ++end;
    words.push_back(line.substr(pos, end - pos));
    pos = end;
  }
  return words;
}

template <class T>
bool parseWhole(std::string_view s, T& value) {
  const char* end = s.data() + s.size();
  const auto [ptr, ec] = std::from_chars(s.data(), end, value);
  return ec == std::errc() && ptr == end;
}

/// Reads one PLY file: the header as text lines, then the body in its declared format.
class PlyReader {
 public:
  PlyReader(std::string_view bytes, const std::string& file) : bytes_(bytes), file_(file) {}

  PlyCloud read() {
    readHeader();
    readBody();
    return std::move(cloud_);
  }

 private:
  [[noreturn]] void failLine(int line, std::string element, std::string problem,
                             std::string allowed = {}) const {
    throw InputError({file_, line, std::move(element)}, std::move(problem), std::move(allowed));
  }
  /// A body error: a line number for ascii, a byte offset for binary.
  [[noreturn]] void failBody(const std::string& element, std::string problem,
                             std::string allowed = {}) const {
    if (format_ == Format::Ascii) {
      const int line =
          1 + static_cast<int>(std::count(
                  bytes_.begin(), bytes_.begin() + static_cast<std::ptrdiff_t>(pos_), '\n'));
      failLine(line, element, std::move(problem), std::move(allowed));
    }
    failLine(0, element, fmt::format("at byte {}: {}", pos_, problem), std::move(allowed));
  }

  /// The next header line without its line break; refuses a header with no end_header.
  std::string_view nextLine() {
    const std::size_t nl = bytes_.find('\n', pos_);
    if (nl == std::string_view::npos) {
      failLine(line_ + 1, "header", "the header has no end_header line", "a complete PLY header");
    }
    std::string_view line = bytes_.substr(pos_, nl - pos_);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    pos_ = nl + 1;
    ++line_;
    return line;
  }

  PlyScalar scalarType(std::string_view word) const {
    for (const auto& [name, type] : kScalarNames) {
      if (name == word) return type;
    }
    failLine(line_, "property", fmt::format("unknown type '{}'", detail::excerpt(word)),
             std::string(kScalarList));
  }

  void readComment(std::string_view text) {
    cloud_.comments.emplace_back(text);
    const std::vector<std::string_view> words = splitWords(text);
    if (words.size() == 5 && words[0] == "softsub" && words[1] == "frame" && words[3] == "time") {
      std::int64_t frame = 0;
      double time = 0;
      if (parseWhole(words[2], frame) && parseWhole(words[4], time)) {
        cloud_.hasFrame = true;
        cloud_.frame = frame;
        cloud_.time = time;
      }
    } else if (text.starts_with("fluid ")) {
      // `fluid <index> <name>`: the name is the rest of the line, spaces included.
      const std::string_view rest = text.substr(6);
      const std::size_t space = rest.find(' ');
      std::size_t index = 0;
      if (space != std::string_view::npos && parseWhole(rest.substr(0, space), index) &&
          index == cloud_.fluidNames.size()) {
        cloud_.fluidNames.emplace_back(rest.substr(space + 1));
      }
    }
  }

  void readHeader() {
    if (nextLine() != "ply")
      failLine(1, "header", "not a PLY file (first line is not 'ply')", "ply");
    bool haveFormat = false;
    while (true) {
      const std::string_view line = nextLine();
      const std::vector<std::string_view> w = splitWords(line);
      if (w.empty()) continue;
      if (w[0] == "end_header") {
        if (w.size() != 1)
          failLine(line_, "end_header", "text after end_header", "end_header alone");
        break;
      }
      if (w[0] == "comment") {
        std::string_view text = line.substr(line.find("comment") + 7);
        if (!text.empty() && (text[0] == ' ' || text[0] == '\t')) text.remove_prefix(1);
        readComment(text);
      } else if (w[0] == "obj_info") {
        continue;
      } else if (w[0] == "format") {
        if (w.size() != 3 || w[2] != "1.0") {
          failLine(line_, "format", fmt::format("bad format line '{}'", detail::excerpt(line)),
                   "format <kind> 1.0");
        }
        if (w[1] == "ascii") {
          format_ = Format::Ascii;
        } else if (w[1] == "binary_little_endian") {
          format_ = Format::BinaryLittle;
        } else if (w[1] == "binary_big_endian") {
          format_ = Format::BinaryBig;
        } else {
          failLine(line_, "format", fmt::format("unknown format '{}'", detail::excerpt(w[1])),
                   "ascii, binary_little_endian, binary_big_endian");
        }
        cloud_.format = std::string(w[1]);
        haveFormat = true;
      } else if (w[0] == "element") {
        HeaderElement e;
        if (w.size() != 3 || !parseWhole(w[2], e.count)) {
          failLine(line_, "element", fmt::format("bad element line '{}'", detail::excerpt(line)),
                   "element <name> <count>");
        }
        e.name = std::string(w[1]);
        e.line = line_;
        for (const HeaderElement& other : elements_) {
          if (other.name == e.name)
            failLine(line_, "element", "element declared twice", "unique names");
        }
        elements_.push_back(std::move(e));
      } else if (w[0] == "property") {
        if (elements_.empty())
          failLine(line_, "property", "property before any element", "element first");
        HeaderProperty p;
        if (w.size() == 3) {
          p.type = scalarType(w[1]);
          p.name = std::string(w[2]);
        } else if (w.size() == 5 && w[1] == "list") {
          p.isList = true;
          p.countType = scalarType(w[2]);
          p.type = scalarType(w[3]);
          if (isFloat(p.countType))
            failLine(line_, "property", "list count of float type", "an integer type");
          p.name = std::string(w[4]);
        } else {
          failLine(line_, "property", fmt::format("bad property line '{}'", detail::excerpt(line)),
                   "property <type> <name> or property list <count type> <type> <name>");
        }
        for (const HeaderProperty& other : elements_.back().properties) {
          if (other.name == p.name)
            failLine(line_, "property", "property declared twice", "unique names");
        }
        elements_.back().properties.push_back(std::move(p));
      } else {
        failLine(line_, "header", fmt::format("unknown header line '{}'", detail::excerpt(line)),
                 "format, comment, obj_info, element, property, end_header");
      }
    }
    if (!haveFormat) failLine(line_, "header", "no format line", "format <kind> 1.0");
    const auto vertex = std::find_if(elements_.begin(), elements_.end(),
                                     [](const HeaderElement& e) { return e.name == "vertex"; });
    if (vertex == elements_.end())
      failLine(line_, "header", "no vertex element", "element vertex <count>");
    for (const char* axis : {"x", "y", "z"}) {
      if (std::none_of(vertex->properties.begin(), vertex->properties.end(),
                       [&](const HeaderProperty& p) { return !p.isList && p.name == axis; })) {
        failLine(vertex->line, "vertex", fmt::format("no scalar property '{}'", axis),
                 "a point cloud with x, y and z");
      }
    }
  }

  /// Refuses an element whose declared count the remaining bytes cannot hold, before
  /// anything is allocated for it.
  void checkFits(const HeaderElement& e) const {
    std::uint64_t least = 0;  // bytes (binary) or characters (ascii) per item at least
    for (const HeaderProperty& p : e.properties) {
      least += format_ == Format::Ascii ? 2 : scalarSize(p.isList ? p.countType : p.type);
    }
    const std::uint64_t left = bytes_.size() - pos_ + (format_ == Format::Ascii ? 1 : 0);
    if (least > 0 && e.count > left / least) {
      failBody(e.name,
               fmt::format("{} {} elements cannot fit in the {} bytes left", e.count, e.name,
                           bytes_.size() - pos_),
               "a complete PLY file");
    }
  }

  double binaryValue(PlyScalar t, const std::string& element) {
    const std::size_t size = scalarSize(t);
    if (size > bytes_.size() - pos_) failBody(element, "file ends early", "a complete PLY file");
    std::uint64_t bits = 0;
    for (std::size_t i = 0; i < size; ++i) {
      const std::size_t k = format_ == Format::BinaryLittle ? size - 1 - i : i;
      bits = (bits << 8) | static_cast<unsigned char>(bytes_[pos_ + k]);
    }
    pos_ += size;
    switch (t) {
      case PlyScalar::Int8: return static_cast<std::int8_t>(static_cast<std::uint8_t>(bits));
      case PlyScalar::UInt8: return static_cast<std::uint8_t>(bits);
      case PlyScalar::Int16: return static_cast<std::int16_t>(static_cast<std::uint16_t>(bits));
      case PlyScalar::UInt16: return static_cast<std::uint16_t>(bits);
      case PlyScalar::Int32: return static_cast<std::int32_t>(static_cast<std::uint32_t>(bits));
      case PlyScalar::UInt32: return static_cast<std::uint32_t>(bits);
      case PlyScalar::Float32: return std::bit_cast<float>(static_cast<std::uint32_t>(bits));
      case PlyScalar::Float64: return std::bit_cast<double>(bits);
    }
    return 0;
  }

  double asciiValue(PlyScalar t, const std::string& element) {
    while (pos_ < bytes_.size() && isSpace(bytes_[pos_])) ++pos_;
    if (pos_ == bytes_.size()) failBody(element, "file ends early", "a complete PLY file");
    std::size_t end = pos_;
    while (end < bytes_.size() && !isSpace(bytes_[end])) ++end;
    const std::string_view token = bytes_.substr(pos_, end - pos_);
    double v = 0;
    const auto [lo, hi] = scalarRange(t);
    if (!parseWhole(token, v) || !(v >= lo && v <= hi) || (!isFloat(t) && v != std::floor(v))) {
      failBody(
          element, fmt::format("bad value '{}'", detail::excerpt(token)),
          fmt::format("a finite {} value", isFloat(t) ? "floating-point" : "integer in range"));
    }
    pos_ = end;
    return v;
  }

  double value(PlyScalar t, const std::string& element) {
    return format_ == Format::Ascii ? asciiValue(t, element) : binaryValue(t, element);
  }

  void readBody() {
    for (const HeaderElement& e : elements_) {
      checkFits(e);
      const bool isVertex = e.name == "vertex";
      std::vector<double*> targets(e.properties.size(), nullptr);
      if (isVertex) {
        cloud_.vertexCount = static_cast<std::size_t>(e.count);
        for (const HeaderProperty& p : e.properties) {
          if (!p.isList)
            cloud_.properties.push_back({p.name, p.type, std::vector<double>(cloud_.vertexCount)});
        }
        std::size_t k = 0;
        for (std::size_t i = 0; i < e.properties.size(); ++i) {
          if (!e.properties[i].isList) targets[i] = cloud_.properties[k++].values.data();
        }
      }
      if (e.properties.empty()) continue;  // no data at all, whatever the count
      for (std::uint64_t item = 0; item < e.count; ++item) {
        for (std::size_t i = 0; i < e.properties.size(); ++i) {
          const HeaderProperty& p = e.properties[i];
          if (p.isList) {
            const double length = value(p.countType, e.name);
            if (length < 0)
              failBody(e.name, fmt::format("negative list length {}", length), ">= 0");
            for (std::uint64_t j = 0; j < static_cast<std::uint64_t>(length); ++j) {
              static_cast<void>(value(p.type, e.name));
            }
            continue;
          }
          const double v = value(p.type, e.name);
          if (targets[i] != nullptr) {
            if (!std::isfinite(v)) {
              failBody(e.name, fmt::format("non-finite value of '{}' at vertex {}", p.name, item),
                       "finite numbers");
            }
            targets[i][item] = v;
          }
        }
      }
    }
    if (format_ == Format::Ascii) {
      while (pos_ < bytes_.size() && isSpace(bytes_[pos_])) ++pos_;
    }
    if (pos_ != bytes_.size()) {
      failBody("end",
               fmt::format("{} unexpected bytes after the last element", bytes_.size() - pos_),
               "nothing after the last element");
    }
  }

  std::string_view bytes_;
  const std::string& file_;
  std::size_t pos_ = 0;
  int line_ = 0;
  Format format_ = Format::Ascii;
  std::vector<HeaderElement> elements_;
  PlyCloud cloud_;
};

}  // namespace

const PlyProperty* PlyCloud::find(std::string_view name) const {
  for (const PlyProperty& p : properties) {
    if (p.name == name) return &p;
  }
  return nullptr;
}

void encodePlyInto(std::string& out, const FrameSnapshot& frame) {
  std::size_t total = 0;
  for (const FluidSnapshot& fluid : frame.fluids) {
    const std::size_t n = fluid.count();
    if (fluid.positions.size() != 3 * n || fluid.velocities.size() != 3 * n) {
      throw std::invalid_argument(
          fmt::format("encodePly: fluid '{}' has {} ids, {} position and {} velocity components",
                      fluid.name, n, fluid.positions.size(), fluid.velocities.size()));
    }
    checkCommentName(fluid.name);
    total += n;
  }
  out.clear();
  auto it = std::back_inserter(out);
  fmt::format_to(it, "ply\nformat binary_little_endian 1.0\ncomment softsub frame {} time {}\n",
                 frame.frame, frame.time);
  for (std::size_t f = 0; f < frame.fluids.size(); ++f) {
    fmt::format_to(it, "comment fluid {} {}\n", f, frame.fluids[f].name);
  }
  fmt::format_to(it,
                 "element vertex {}\n"
                 "property float x\nproperty float y\nproperty float z\n"
                 "property float vx\nproperty float vy\nproperty float vz\n"
                 "property uint id\nproperty int fluid\n"
                 "property uchar red\nproperty uchar green\nproperty uchar blue\n"
                 "end_header\n",
                 total);
  const std::size_t headerSize = out.size();
  out.resize(headerSize + total * kVertexBytes);
  LittleEndianWriter w(out.data() + headerSize);
  for (std::size_t f = 0; f < frame.fluids.size(); ++f) {
    const FluidSnapshot& fluid = frame.fluids[f];
    const std::array<std::uint8_t, 3> rgb{colourByte(fluid.colour[0]), colourByte(fluid.colour[1]),
                                          colourByte(fluid.colour[2])};
    for (std::size_t k = 0; k < fluid.count(); ++k) {
      for (int c = 0; c < 3; ++c) w.f32(fluid.positions[3 * k + static_cast<std::size_t>(c)]);
      for (int c = 0; c < 3; ++c) w.f32(fluid.velocities[3 * k + static_cast<std::size_t>(c)]);
      w.u32(fluid.ids[k]);
      w.u32(static_cast<std::uint32_t>(f));
      for (const std::uint8_t c : rgb) w.u8(c);
    }
  }
  if (w.position() != out.data() + out.size()) {
    throw std::logic_error("encodePly: size computation disagrees with the bytes written");
  }
}

std::string encodePly(const FrameSnapshot& frame) {
  std::string out;
  encodePlyInto(out, frame);
  return out;
}

PlyCloud decodePly(std::string_view bytes, const std::string& fileName) {
  return PlyReader(bytes, fileName).read();
}

PlyCloud readPlyFile(const std::filesystem::path& path) {
  return decodePly(readFileBytes(path), path.string());
}

}  // namespace softsub::cache
