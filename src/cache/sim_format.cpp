#include "cache/sim_format.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <iterator>
#include <stdexcept>
#include <unordered_set>

#include <fmt/format.h>
#include <pugixml.hpp>

#include "cache/atomic_file.h"
#include "cache/message.h"
#include "core/error.h"
#include "core/xml_text.h"

namespace softsub::cache {
namespace {

// ---------------------------------------------------------------------------------------
// Writing

void appendFluid(std::string& out, const FluidSnapshot& fluid) {
  const std::size_t n = fluid.count();
  if (fluid.positions.size() != 3 * n) {
    throw std::invalid_argument(fmt::format("encodeSim: fluid '{}' has {} ids but {} coordinates",
                                            fluid.name, n, fluid.positions.size()));
  }
  auto it = std::back_inserter(out);
  out += "  <Fluid>\n    <Name>";
  appendXmlEscaped(out, fluid.name, "Fluid/Name");
  fmt::format_to(it, "</Name>\n    <ParticleNumber>{}</ParticleNumber>\n    <Particles>\n", n);
  const float* p = fluid.positions.data();
  // `{}` is the shortest text that reads back to the same float: positions round-trip
  // bit for bit through std::from_chars.
  for (std::size_t k = 0; k < n; ++k, p += 3) fmt::format_to(it, "{} {} {}\n", p[0], p[1], p[2]);
  out += "    </Particles>\n  </Fluid>\n";
}

void appendObject(std::string& out, const SimObject& object) {
  auto it = std::back_inserter(out);
  out += "  <Object>\n    <Name>";
  appendXmlEscaped(out, object.name, "Object/Name");
  fmt::format_to(it, "</Name>\n    <UniformScale>{}</UniformScale>\n", object.uniformScale);
  fmt::format_to(it, "    <Position>{} {} {}</Position>\n", object.position[0], object.position[1],
                 object.position[2]);
  fmt::format_to(it, "    <Rotation>{} {} {} {}</Rotation>\n", object.rotation[0],
                 object.rotation[1], object.rotation[2], object.rotation[3]);
  out += "    <Filename>";
  appendXmlEscaped(out, object.filename, "Object/Filename");
  out += "</Filename>\n  </Object>\n";
}

// ---------------------------------------------------------------------------------------
// Reading

constexpr std::string_view kWhitespace = " \t\n\r";

bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }

/// from_chars refuses a leading '+', which hand-edited files may contain.
std::string_view dropPlus(std::string_view token) {
  if (token.size() > 1 && token[0] == '+' && token[1] != '-' && token[1] != '+') {
    token.remove_prefix(1);
  }
  return token;
}

template <class T>
bool parseNumber(std::string_view token, T& value) {
  token = dropPlus(token);
  const char* end = token.data() + token.size();
  const auto [ptr, ec] = std::from_chars(token.data(), end, value);
  if (ec != std::errc() || ptr != end) return false;
  if constexpr (std::is_floating_point_v<T>) return std::isfinite(value);
  return true;
}

std::string_view trim(std::string_view s) {
  const auto first = s.find_first_not_of(kWhitespace);
  if (first == std::string_view::npos) return {};
  return s.substr(first, s.find_last_not_of(kWhitespace) - first + 1);
}

/// Parses one `.sim` document; every error names the file, line and element.
class SimReader {
 public:
  SimReader(std::string_view text, const std::string& fileName) : text_(text), file_(fileName) {}

  SimFile read() {
    pugi::xml_document doc;
    // parse_fragment keeps text outside the root, parse_pi, parse_declaration and
    // parse_doctype what may follow it (pugixml drops them all otherwise): readRoot
    // refuses anything but comments and white space after the root, and text before it.
    const pugi::xml_parse_result parsed =
        doc.load_buffer(text_.data(), text_.size(),
                        pugi::parse_default | pugi::parse_fragment | pugi::parse_pi |
                            pugi::parse_declaration | pugi::parse_doctype,
                        pugi::encoding_utf8);
    if (!parsed) {
      fail(parsed.offset, "", fmt::format("malformed XML: {}", parsed.description()),
           "a well-formed XML document");
    }
    SimFile result;
    readRoot(doc, result);
    return result;
  }

 private:
  [[noreturn]] void fail(std::ptrdiff_t offset, std::string element, std::string problem,
                         std::string allowed = {}) const {
    throw InputError({file_, lineAt(offset), std::move(element)}, std::move(problem),
                     std::move(allowed));
  }
  [[noreturn]] void fail(const pugi::xml_node& node, std::string element, std::string problem,
                         std::string allowed = {}) const {
    fail(node.offset_debug(), std::move(element), std::move(problem), std::move(allowed));
  }

  int lineAt(std::ptrdiff_t offset) const {
    if (offset < 0) return 0;
    const auto end = static_cast<std::size_t>(
        std::min<std::ptrdiff_t>(offset, static_cast<std::ptrdiff_t>(text_.size())));
    return 1 + static_cast<int>(std::count(text_.begin(),
                                           text_.begin() + static_cast<std::ptrdiff_t>(end), '\n'));
  }

  void readRoot(const pugi::xml_document& doc, SimFile& result) {
    const pugi::xml_node root = doc.document_element();
    if (!root || std::string_view(root.name()) != "Simulation") {
      fail(root ? root.offset_debug() : 0, root ? root.name() : "",
           "the root element is not <Simulation>", "<Simulation version=\"1\" ...>");
    }
    bool afterRoot = false;
    for (pugi::xml_node n = doc.first_child(); n; n = n.next_sibling()) {
      if (n == root) {
        afterRoot = true;
      } else if (n.type() == pugi::node_element) {
        fail(n, n.name(), "second root element", "one <Simulation>");
      } else if (n.type() == pugi::node_pcdata || n.type() == pugi::node_cdata) {
        // At its first character that is not white space (the node starts before it).
        const std::size_t at =
            text_.find_first_not_of(kWhitespace, static_cast<std::size_t>(n.offset_debug()));
        fail(static_cast<std::ptrdiff_t>(at), "Simulation", "text outside the root element",
             "one <Simulation> element and no text around it");
      } else if (afterRoot) {
        const char* what = n.type() == pugi::node_pi            ? "a processing instruction"
                           : n.type() == pugi::node_declaration ? "an XML declaration"
                                                                : "a DOCTYPE declaration";
        fail(n, "Simulation", fmt::format("{} after the root element", what),
             "nothing but comments and white space after </Simulation>");
      }
    }
    bool haveVersion = false, haveFrame = false, haveTime = false;
    for (const pugi::xml_attribute& a : root.attributes()) {
      const std::string_view name = a.name();
      const std::string_view value = trim(a.value());
      if (name == "version") {
        if (value != "1") {
          fail(root, "Simulation",
               fmt::format("unsupported version '{}'", detail::excerpt(a.value())), "1");
        }
        haveVersion = true;
      } else if (name == "frame") {
        if (!parseNumber(value, result.frame.frame) || result.frame.frame < 0) {
          fail(root, "Simulation", fmt::format("bad frame '{}'", detail::excerpt(a.value())),
               "an integer >= 0");
        }
        haveFrame = true;
      } else if (name == "time") {
        if (!parseNumber(value, result.frame.time)) {
          fail(root, "Simulation", fmt::format("bad time '{}'", detail::excerpt(a.value())),
               "a finite number");
        }
        haveTime = true;
      } else {
        fail(root, "Simulation", fmt::format("unknown attribute '{}'", detail::excerpt(name)),
             "version, frame, time");
      }
    }
    for (const auto& [have, attribute] :
         {std::pair{haveVersion, "version"}, std::pair{haveFrame, "frame"},
          std::pair{haveTime, "time"}}) {
      if (!have) {
        fail(root, "Simulation", fmt::format("missing attribute '{}'", attribute),
             "version, frame and time are required");
      }
    }

    std::unordered_set<std::string> fluidNames, objectNames;
    for (const pugi::xml_node& child : root.children()) {
      if (child.type() == pugi::node_pcdata || child.type() == pugi::node_cdata) {
        if (!trim(child.value()).empty()) fail(child, "Simulation", "unexpected text", "elements");
        continue;
      }
      if (child.type() != pugi::node_element) continue;
      const std::string_view name = child.name();
      if (name == "Fluid") {
        FluidSnapshot& fluid = result.frame.fluids.emplace_back(readFluid(child));
        if (!fluidNames.insert(fluid.name).second) {
          fail(child, "Fluid/Name",
               fmt::format("duplicate fluid name '{}'", detail::excerpt(fluid.name)),
               "unique names");
        }
      } else if (name == "Object") {
        SimObject& object = result.frame.objects.emplace_back(readObject(child));
        if (!objectNames.insert(object.name).second) {
          fail(child, "Object/Name",
               fmt::format("duplicate object name '{}'", detail::excerpt(object.name)),
               "unique names");
        }
      } else {
        fail(child, std::string(name), "unknown element", "<Fluid>, <Object>");
      }
    }
  }

  /// The element's text; refuses child elements. Uses `storage` only when the text is
  /// split (CDATA sections, comments), so the large particle list is never copied.
  std::string_view textOf(const pugi::xml_node& node, const std::string& element,
                          std::string& storage) const {
    std::string_view single;
    int pieces = 0;
    for (const pugi::xml_node& c : node.children()) {
      if (c.type() == pugi::node_element) fail(c, element, "unexpected child element", "text only");
      if (c.type() != pugi::node_pcdata && c.type() != pugi::node_cdata) continue;
      if (pieces++ == 0) {
        single = c.value();
      } else {
        if (pieces == 2) storage.assign(single);
        storage += c.value();
      }
    }
    return pieces > 1 ? std::string_view(storage) : single;
  }

  /// Children of `node` by name; each allowed name at most once, unknown names refused.
  template <std::size_t N>
  std::array<pugi::xml_node, N> childrenOf(const pugi::xml_node& node, std::string_view parent,
                                           const std::array<std::string_view, N>& names,
                                           std::string_view allowed) const {
    std::array<pugi::xml_node, N> found{};
    for (const pugi::xml_node& c : node.children()) {
      if (c.type() == pugi::node_pcdata || c.type() == pugi::node_cdata) {
        if (!trim(c.value()).empty()) fail(c, std::string(parent), "unexpected text", "elements");
        continue;
      }
      if (c.type() != pugi::node_element) continue;
      const auto it = std::find(names.begin(), names.end(), std::string_view(c.name()));
      const std::string element = fmt::format("{}/{}", parent, c.name());
      if (it == names.end()) fail(c, element, "unknown element", std::string(allowed));
      pugi::xml_node& slot = found[static_cast<std::size_t>(it - names.begin())];
      if (slot) fail(c, element, "element given twice", "once");
      slot = c;
    }
    return found;
  }

  FluidSnapshot readFluid(const pugi::xml_node& node) {
    static constexpr std::array<std::string_view, 3> kNames{"Name", "ParticleNumber", "Particles"};
    const auto [nameNode, numberNode, particlesNode] =
        childrenOf(node, "Fluid", kNames, "Name, ParticleNumber, Particles");
    if (!nameNode || !numberNode || !particlesNode) {
      fail(node, "Fluid", "missing element", "Name, ParticleNumber and Particles are required");
    }
    FluidSnapshot fluid;
    std::string storage;
    fluid.name = std::string(textOf(nameNode, "Fluid/Name", storage));
    if (trim(fluid.name).empty()) fail(nameNode, "Fluid/Name", "empty name", "a non-empty name");

    const std::string_view numberText = trim(textOf(numberNode, "Fluid/ParticleNumber", storage));
    std::uint64_t declared = 0;
    if (!parseNumber(numberText, declared)) {
      fail(numberNode, "Fluid/ParticleNumber",
           fmt::format("bad count '{}'", detail::excerpt(numberText)), "an integer >= 0");
    }

    const std::string_view values = textOf(particlesNode, "Fluid/Particles", storage);
    // Each number takes at least two characters (digit and separator): never reserve more
    // than the text can hold, whatever the declared count says.
    const std::uint64_t most = values.size() / 2 + 1;
    fluid.positions.reserve(static_cast<std::size_t>(std::min(declared, most / 3 + 1) * 3));
    const pugi::xml_node textNode = particlesNode.first_child();
    std::size_t pos = 0;
    while (true) {
      while (pos < values.size() && isSpace(values[pos])) ++pos;
      if (pos == values.size()) break;
      std::size_t end = pos;
      while (end < values.size() && !isSpace(values[end])) ++end;
      float v = 0;
      if (!parseNumber(values.substr(pos, end - pos), v)) {
        const int line =
            lineAt(textNode.offset_debug()) +
            static_cast<int>(std::count(values.begin(),
                                        values.begin() + static_cast<std::ptrdiff_t>(pos), '\n'));
        throw InputError({file_, line, "Fluid/Particles"},
                         fmt::format("bad coordinate '{}' in fluid '{}'",
                                     detail::excerpt(values.substr(pos, end - pos)),
                                     detail::excerpt(fluid.name)),
                         "finite numbers within float range");
      }
      fluid.positions.push_back(v);
      pos = end;
    }
    if (fluid.positions.size() % 3 != 0) {
      fail(particlesNode, "Fluid/Particles",
           fmt::format("{} numbers is not a whole number of x y z positions",
                       fluid.positions.size()),
           "three numbers per particle");
    }
    const std::size_t n = fluid.positions.size() / 3;
    if (declared != n) {
      fail(numberNode, "Fluid/ParticleNumber",
           fmt::format("ParticleNumber is {} but Particles holds {} positions", declared, n),
           "ParticleNumber equal to the number of positions");
    }
    fluid.ids.resize(n);
    for (std::size_t k = 0; k < n; ++k) fluid.ids[k] = static_cast<std::uint32_t>(k);
    fluid.velocities.assign(3 * n, 0.0F);
    return fluid;
  }

  template <std::size_t N>
  std::array<double, N> readVector(const pugi::xml_node& node, const std::string& element) {
    std::string storage;
    const std::string_view text = textOf(node, element, storage);
    std::array<double, N> v{};
    std::size_t count = 0, pos = 0;
    while (true) {
      while (pos < text.size() && isSpace(text[pos])) ++pos;
      if (pos == text.size()) break;
      std::size_t end = pos;
      while (end < text.size() && !isSpace(text[end])) ++end;
      double x = 0;
      if (count == N || !parseNumber(text.substr(pos, end - pos), x)) {
        fail(node, element, fmt::format("bad value '{}'", detail::excerpt(trim(text))),
             fmt::format("{} finite numbers", N));
      }
      v[count++] = x;
      pos = end;
    }
    if (count != N) {
      fail(node, element, fmt::format("bad value '{}'", detail::excerpt(trim(text))),
           fmt::format("{} finite numbers", N));
    }
    return v;
  }

  SimObject readObject(const pugi::xml_node& node) {
    static constexpr std::array<std::string_view, 5> kNames{"Name", "UniformScale", "Position",
                                                            "Rotation", "Filename"};
    const auto [nameNode, scaleNode, positionNode, rotationNode, fileNode] =
        childrenOf(node, "Object", kNames, "Name, UniformScale, Position, Rotation, Filename");
    if (!nameNode || !positionNode || !rotationNode) {
      fail(node, "Object", "missing element", "Name, Position and Rotation are required");
    }
    SimObject object;
    std::string storage;
    object.name = std::string(textOf(nameNode, "Object/Name", storage));
    if (trim(object.name).empty()) fail(nameNode, "Object/Name", "empty name", "a non-empty name");
    if (scaleNode) {
      object.uniformScale = readVector<1>(scaleNode, "Object/UniformScale")[0];
      if (!(object.uniformScale > 0)) {
        fail(scaleNode, "Object/UniformScale", "scale is not positive", "a number > 0");
      }
    }
    object.position = readVector<3>(positionNode, "Object/Position");
    object.rotation = readVector<4>(rotationNode, "Object/Rotation");
    const auto& q = object.rotation;
    const double norm = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    if (!(std::abs(norm - 1) <= 1e-3)) {
      fail(rotationNode, "Object/Rotation", fmt::format("quaternion length {} is not 1", norm),
           "a unit quaternion w x y z");
    }
    if (fileNode) object.filename = std::string(textOf(fileNode, "Object/Filename", storage));
    return object;
  }

  std::string_view text_;
  const std::string& file_;
};

}  // namespace

void encodeSimInto(std::string& out, const FrameSnapshot& frame) {
  const std::vector<SimObject>& objects = frame.objects;
  out.clear();
  std::size_t particles = 0;
  for (const FluidSnapshot& f : frame.fluids) particles += f.count();
  out.reserve(256 + 160 * (frame.fluids.size() + objects.size()) + 40 * particles);
  fmt::format_to(std::back_inserter(out),
                 "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
                 "<Simulation version=\"1\" frame=\"{}\" time=\"{}\">\n",
                 frame.frame, frame.time);
  for (const SimObject& object : objects) appendObject(out, object);
  for (const FluidSnapshot& fluid : frame.fluids) appendFluid(out, fluid);
  out += "</Simulation>\n";
}

std::string encodeSim(const FrameSnapshot& frame) {
  std::string out;
  encodeSimInto(out, frame);
  return out;
}

SimFile decodeSim(std::string_view text, const std::string& fileName) {
  return SimReader(text, fileName).read();
}

SimFile readSimFile(const std::filesystem::path& path) {
  return decodeSim(readFileBytes(path), path.string());
}

}  // namespace softsub::cache
