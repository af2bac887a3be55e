#include "cache/pdc_format.h"

#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <unordered_set>

#include <fmt/format.h>

#include "cache/atomic_file.h"
#include "cache/message.h"
#include "core/error.h"

namespace softsub::cache {
namespace {

constexpr std::size_t kHeaderBytes = 28;  // magic + six int32

/// Sequential big-endian writer into a buffer sized in advance.
class BigEndianWriter {
 public:
  explicit BigEndianWriter(char* p) : p_(p) {}
  void bytes(std::string_view s) {
    std::memcpy(p_, s.data(), s.size());
    p_ += s.size();
  }
  void u32(std::uint32_t v) {
    for (int shift = 24; shift >= 0; shift -= 8) *p_++ = static_cast<char>((v >> shift) & 0xffU);
  }
  void i32(std::int32_t v) { u32(static_cast<std::uint32_t>(v)); }
  void f64(double v) {
    const auto bits = std::bit_cast<std::uint64_t>(v);
    for (int shift = 56; shift >= 0; shift -= 8) *p_++ = static_cast<char>((bits >> shift) & 0xffU);
  }
  [[nodiscard]] const char* position() const { return p_; }

 private:
  char* p_;
};

void attributeHeader(BigEndianWriter& w, std::string_view name, PdcType type) {
  w.i32(static_cast<std::int32_t>(name.size()));
  w.bytes(name);
  w.i32(static_cast<std::int32_t>(type));
}

std::size_t attributeBytes(std::string_view name, std::size_t doubles) {
  return 4 + name.size() + 4 + 8 * doubles;
}

// ---------------------------------------------------------------------------------------
// Reading

/// Sequential big-endian reader that checks every read against the bytes left.
class BigEndianReader {
 public:
  BigEndianReader(std::string_view bytes, const std::string& file) : bytes_(bytes), file_(file) {}

  [[nodiscard]] std::size_t offset() const { return pos_; }
  [[nodiscard]] std::size_t left() const { return bytes_.size() - pos_; }

  [[noreturn]] void fail(std::string element, std::string problem, std::string allowed = {}) const {
    throw InputError({file_, 0, std::move(element)}, fmt::format("at byte {}: {}", pos_, problem),
                     std::move(allowed));
  }

  void need(std::uint64_t n, const std::string& element) const {
    if (n > left()) {
      fail(element, fmt::format("file ends early: needs {} more bytes, {} left", n, left()),
           "a complete PDC file");
    }
  }
  std::string_view bytes(std::size_t n, const std::string& element) {
    need(n, element);
    const std::string_view s = bytes_.substr(pos_, n);
    pos_ += n;
    return s;
  }
  std::uint32_t u32(const std::string& element) {
    need(4, element);
    std::uint32_t v = 0;
    for (int i = 0; i < 4; ++i) v = (v << 8) | static_cast<unsigned char>(bytes_[pos_++]);
    return v;
  }
  std::int32_t i32(const std::string& element) { return static_cast<std::int32_t>(u32(element)); }
  double f64Unchecked() {
    std::uint64_t v = 0;
    for (int i = 0; i < 8; ++i) v = (v << 8) | static_cast<unsigned char>(bytes_[pos_++]);
    return std::bit_cast<double>(v);
  }

 private:
  std::string_view bytes_;
  const std::string& file_;
  std::size_t pos_ = 0;
};

/// Number of values of an attribute of `type` in a file of `count` particles.
std::uint64_t valueCount(PdcType type, std::int32_t count) {
  const auto n = static_cast<std::uint64_t>(count);
  switch (type) {
    case PdcType::Int:
    case PdcType::Double: return 1;
    case PdcType::Vector: return 3;
    case PdcType::IntArray:
    case PdcType::DoubleArray: return n;
    case PdcType::VectorArray: return 3 * n;
  }
  return 0;
}

bool isIntType(PdcType type) { return type == PdcType::Int || type == PdcType::IntArray; }

}  // namespace

const PdcAttribute* PdcFile::find(std::string_view name) const {
  for (const PdcAttribute& a : attributes) {
    if (a.name == name) return &a;
  }
  return nullptr;
}

void encodePdcInto(std::string& out, const FluidSnapshot& fluid) {
  const std::size_t n = fluid.count();
  if (fluid.positions.size() != 3 * n || fluid.velocities.size() != 3 * n) {
    throw std::invalid_argument(
        fmt::format("encodePdc: fluid '{}' has {} ids, {} position and {} velocity components",
                    fluid.name, n, fluid.positions.size(), fluid.velocities.size()));
  }
  // Maya stores the count as int32; 3 * count doubles must also fit the attribute sizes.
  if (n > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max())) {
    throw std::invalid_argument(fmt::format("encodePdc: {} particles exceed the PDC limit", n));
  }
  const std::size_t size = kHeaderBytes + attributeBytes("position", 3 * n) +
                           attributeBytes("velocity", 3 * n) + attributeBytes("particleId", n) +
                           attributeBytes("radiusPP", n) + attributeBytes("rgbPP", 3 * n);
  out.clear();
  out.resize(size);
  BigEndianWriter w(out.data());
  w.bytes("PDC ");
  w.i32(1);  // version
  w.i32(1);  // byte order: big-endian, the only one Maya reads
  w.i32(0);
  w.i32(0);
  w.i32(static_cast<std::int32_t>(n));
  w.i32(5);  // attributes

  attributeHeader(w, "position", PdcType::VectorArray);
  for (const float v : fluid.positions) w.f64(v);
  attributeHeader(w, "velocity", PdcType::VectorArray);
  for (const float v : fluid.velocities) w.f64(v);
  attributeHeader(w, "particleId", PdcType::DoubleArray);
  for (const std::uint32_t id : fluid.ids) w.f64(id);
  attributeHeader(w, "radiusPP", PdcType::DoubleArray);
  const double radius = static_cast<double>(fluid.particleSize) / 2;
  for (std::size_t k = 0; k < n; ++k) w.f64(radius);
  attributeHeader(w, "rgbPP", PdcType::VectorArray);
  for (std::size_t k = 0; k < n; ++k) {
    for (const float c : fluid.colour) w.f64(c);
  }
  if (w.position() != out.data() + out.size()) {
    throw std::logic_error("encodePdc: size computation disagrees with the bytes written");
  }
}

std::string encodePdc(const FluidSnapshot& fluid) {
  std::string out;
  encodePdcInto(out, fluid);
  return out;
}

PdcFile decodePdc(std::string_view bytes, const std::string& fileName) {
  BigEndianReader r(bytes, fileName);
  PdcFile file;
  const std::string header = "header";
  if (bytes.size() < 4 || bytes.substr(0, 4) != "PDC ") {
    r.fail(header, "not a PDC file (no \"PDC \" magic)", "a Maya particle disk cache");
  }
  r.bytes(4, header);
  file.version = r.i32(header);
  if (file.version != 1) {
    if (file.version == 0x01000000) {
      r.fail(header, "little-endian PDC file", "big-endian PDC, as Maya writes and reads");
    }
    r.fail(header, fmt::format("unsupported version {}", file.version), "1");
  }
  file.byteOrder = r.i32(header);
  file.extra1 = r.i32(header);
  file.extra2 = r.i32(header);
  file.count = r.i32(header);
  if (file.count < 0) r.fail(header, fmt::format("negative particle count {}", file.count), ">= 0");
  const std::int32_t attributeCount = r.i32(header);
  if (attributeCount < 0) {
    r.fail(header, fmt::format("negative attribute count {}", attributeCount), ">= 0");
  }
  // An attribute takes at least 9 bytes (name length, one name byte, type): a declared
  // count larger than that allows is refused before anything is reserved.
  if (static_cast<std::uint64_t>(attributeCount) * 9 > r.left()) {
    r.fail(header,
           fmt::format("{} attributes cannot fit in the {} bytes left", attributeCount, r.left()),
           "a complete PDC file");
  }
  file.attributes.reserve(static_cast<std::size_t>(attributeCount));

  std::unordered_set<std::string> seen;
  for (std::int32_t a = 0; a < attributeCount; ++a) {
    const std::string where = fmt::format("attribute {}", a);
    const std::int32_t nameLength = r.i32(where);
    if (nameLength <= 0) r.fail(where, fmt::format("name length {}", nameLength), "> 0");
    PdcAttribute attribute;
    attribute.name = std::string(r.bytes(static_cast<std::size_t>(nameLength), where));
    const std::string element = fmt::format("attribute '{}'", detail::excerpt(attribute.name));
    if (!seen.insert(attribute.name).second)
      r.fail(element, "attribute given twice", "unique names");
    const std::int32_t type = r.i32(element);
    if (type < 0 || type > 5) r.fail(element, fmt::format("unknown type {}", type), "0 to 5");
    attribute.type = static_cast<PdcType>(type);

    const std::uint64_t values = valueCount(attribute.type, file.count);
    const std::uint64_t width = isIntType(attribute.type) ? 4 : 8;
    r.need(values * width, element);  // before allocating: counts may lie
    attribute.values.resize(static_cast<std::size_t>(values));
    if (isIntType(attribute.type)) {
      for (double& v : attribute.values) v = r.i32(element);
    } else {
      for (double& v : attribute.values) v = r.f64Unchecked();
      // As the .sim and PLY readers: a non-finite value is a broken cache, not data (info
      // showed a file with NaN positions as fine, its bounds leaving them out).
      for (std::size_t k = 0; k < attribute.values.size(); ++k)
        if (!std::isfinite(attribute.values[k])) {
          const std::size_t per =
              attribute.type == PdcType::Vector || attribute.type == PdcType::VectorArray ? 3 : 1;
          r.fail(element,
                 fmt::format(
                     "non-finite value {} at particle {}", attribute.values[k],
                     attribute.type == PdcType::Double || attribute.type == PdcType::Vector ? 0 : k / per),
                 "finite numbers");
        }
    }
    file.attributes.push_back(std::move(attribute));
  }
  if (r.left() != 0) {
    r.fail("end", fmt::format("{} unexpected bytes after the last attribute", r.left()),
           "nothing after the last attribute");
  }
  return file;
}

PdcFile readPdcFile(const std::filesystem::path& path) {
  return decodePdc(readFileBytes(path), path.string());
}

}  // namespace softsub::cache
