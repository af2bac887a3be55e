#include "scene/reader.h"

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <map>
#include <pugixml.hpp>
#include <stdexcept>
#include <utility>

#include "core/error.h"
#include "core/names.h"
#include "geometry/fill.h"
#include "geometry/mass_properties.h"
#include "geometry/mesh_loader.h"
#include "scene/fill.h"
#include "scene/schema.h"
#include "scene/value_text.h"
#include "scene/xml_checks.h"

namespace softsub::scene {

namespace {

constexpr std::string_view kPathAllowed = "a path inside the scene's folder, e.g. honeyGeo/blob.obj";
constexpr std::string_view kOneFunction =
    "exactly one of Linear, LennardJones, LennardJonesForce, Curve";

bool isNameChar(char c) {
  return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' ||
         c == '-';
}

bool validName(std::string_view s) {
  return !s.empty() && s.size() <= kMaxNameLength && std::all_of(s.begin(), s.end(), isNameChar);
}

// The problem with a name that is too long (kMaxNameLength), or empty for one that is not.
std::string lengthProblem(std::string_view s) {
  if (s.size() <= kMaxNameLength) return {};
  return fmt::format(
      "the name is {} bytes long: its output file names (with frame numbers, extensions and "
      "the temporary name of an atomic write) would pass the system's 255-byte limit",
      s.size());
}

// An object's name becomes part of file names: the rule of cache::checkFileNamePart (not
// empty, not '.' or '..', no '/', '\\' or control character), checked here so a bad name
// is an error at its line.
constexpr std::string_view kObjectNameAllowed =
    "a non-empty name of at most 100 bytes (UTF-8) without '/', '\\' or control characters, other than '.' "
    "and '..'";
static_assert(kMaxNameLength == 100, "kObjectNameAllowed and the schema's Name rules say 100");
bool usableObjectName(std::string_view s) {
  return !s.empty() && s != "." && s != ".." && s.size() <= kMaxNameLength &&
         std::none_of(s.begin(), s.end(), [](char c) {
           const auto u = static_cast<unsigned char>(c);
           return c == '/' || c == '\\' || u < 0x20 || u == 0x7f;
         });
}

// The largest extent of a box, 0 for an empty one.
double largestExtent(const Aabb& box) {
  if (box.empty()) return 0;
  return std::max({box.hi[0] - box.lo[0], box.hi[1] - box.lo[1], box.hi[2] - box.lo[2]});
}

template <class S>
const FieldInfo& infoOf(std::string_view tag) {
  for (const auto& f : fieldsOf<S>()) {
    if (f.tag == tag) return f;
  }
  throw std::logic_error("no field " + std::string(tag));
}

std::uint64_t saturatingAdd(std::uint64_t a, std::uint64_t b) {
  return b > UINT64_MAX - a ? UINT64_MAX : a + b;
}

// ---------------------------------------------------------------------------------------

// The text being read: file name, line table, options; raises InputErrors.
class Context {
 public:
  Context(std::string_view text, std::string file, std::filesystem::path base,
          const ReadOptions& readOptions)
      : options(readOptions), baseDir(std::move(base)), file_(std::move(file)) {
    // A line ends at LF, CR LF, or a CR alone (old Mac files), as XML reads them.
    lineStarts_.push_back(0);
    for (std::size_t i = 0; i < text.size(); ++i) {
      if (text[i] == '\n' || (text[i] == '\r' && (i + 1 == text.size() || text[i + 1] != '\n')))
        lineStarts_.push_back(i + 1);
    }
  }

  [[nodiscard]] int lineAt(std::ptrdiff_t offset) const {
    if (offset < 0) return 0;
    const auto it = std::upper_bound(lineStarts_.begin(), lineStarts_.end(),
                                     static_cast<std::size_t>(offset));
    return static_cast<int>(it - lineStarts_.begin());
  }
  [[nodiscard]] int lineOf(pugi::xml_node node) const { return lineAt(node.offset_debug()); }
  /// Line of the first non-blank character of a text node.
  [[nodiscard]] int textLine(pugi::xml_node text) const {
    const std::string_view v = text.value();
    const auto lead = v.substr(0, static_cast<std::size_t>(trimSpace(v).data() - v.data()));
    return lineOf(text) + static_cast<int>(std::count(lead.begin(), lead.end(), '\n'));
  }

  [[noreturn]] void fail(int line, std::string element, std::string problem,
                         std::string allowed = {}) const {
    throw InputError({file_, line, std::move(element)}, std::move(problem), std::move(allowed));
  }

  /// Adds a warning `<file>:<line>: <element>: <text>` when the caller asked for them.
  void warn(int line, const std::string& element, const std::string& text) const {
    if (options.warnings == nullptr) return;
    options.warnings->push_back(formatInputError({file_, line, element}, text, {}));
  }

  [[nodiscard]] const std::string& file() const { return file_; }

  const ReadOptions& options;
  std::filesystem::path baseDir;  ///< absolute folder relative paths resolve against

 private:
  std::string file_;
  std::vector<std::size_t> lineStarts_;
};

// The text of a value element (which has no child elements), and where each of its
// pieces of text starts in it. Text and CDATA sections are character data and join as
// they stand (XML's rule: a name or number split across them keeps its characters); a
// comment reads as a space, so `1 2 3<!-- row 2 -->4 5 6` is six numbers.
struct LeafText {
  std::string text;
  std::vector<std::pair<std::size_t, pugi::xml_node>> pieces;  // (start in text, node)
};

LeafText textOf(pugi::xml_node node) {
  LeafText out;
  for (const pugi::xml_node child : node.children()) {
    if (child.type() == pugi::node_comment && !out.text.empty()) out.text += ' ';
    if (child.type() == pugi::node_pcdata || child.type() == pugi::node_cdata) {
      out.pieces.emplace_back(out.text.size(), child);
      out.text += child.value();
    }
  }
  return out;
}

LeafText leafText(const Context& cx, pugi::xml_node node, const std::string& path) {
  for (const pugi::xml_node child : node.children())
    if (child.type() == pugi::node_element)
      cx.fail(cx.lineOf(child), path + "/" + child.name(), fmt::format("unknown element <{}>", child.name()),
              fmt::format("a value only: <{}> has no child elements", node.name()));
  return textOf(node);
}

// Parses a value element by its field's kind, checking every number and rule of the kind.
Value parseValue(const Context& cx, pugi::xml_node node, const std::string& path,
                 const FieldInfo& f) {
  Value v;
  const LeafText leaf = leafText(cx, node, path);
  const std::string& text = leaf.text;
  if (auto problem = parseValueText(f, text, v); !problem.text.empty()) {
    // The line of the token at fault: a bad number on line 5,000 of a generated
    // Particles list is named there. Line ends are counted from the start of the piece
    // of text it is in, whose parsed text holds one '\n' for each.
    int line = cx.lineOf(node);
    if (problem.offset >= 0) {
      const auto at = static_cast<std::size_t>(problem.offset);
      for (auto piece = leaf.pieces.rbegin(); piece != leaf.pieces.rend(); ++piece) {
        if (piece->first > at) continue;
        line = cx.lineOf(piece->second) +
               static_cast<int>(std::count(text.begin() + static_cast<std::ptrdiff_t>(piece->first),
                                           text.begin() + problem.offset, '\n'));
        break;
      }
    }
    cx.fail(line, path, std::move(problem.text),
            problem.allowed.empty() ? allowedText(f) : std::move(problem.allowed));
  }
  return v;
}

// The child elements one element accepts, dispatched in document order. Rejects
// unknown, refused and repeated elements, attributes and stray text; after the run,
// missing required fields.
class Children {
 public:
  using Handler = std::function<void(pugi::xml_node, const std::string& path)>;

  Children(const Context& cx, pugi::xml_node parent, std::string path)
      : cx_(cx), parent_(parent), path_(std::move(path)) {}
  Children(const Children&) = delete;
  Children& operator=(const Children&) = delete;

  // Value fields stored into target.
  template <class S>
  void fields(std::span<const Field<S>> table, S& target) {
    for (const Field<S>& f : table) {
      Entry e{f.tag, false, f.required ? allowedText(f) : std::string(), {}, {}, {}};
      e.handle = [this, &f, &target](pugi::xml_node node, const std::string& path) {
        Value v = parseValue(cx_, node, path, f);
        if (f.set != nullptr) {
          f.set(target, std::move(v));
        } else {
          derived_.insert_or_assign(f.tag, std::move(v));
        }
      };
      entries_.push_back(std::move(e));
    }
  }

  // A structural child element, as listed in the schema's elements().
  void element(std::string_view tag, Handler handle) {
    const ElementInfo* info = findElement(parent_.name(), tag);
    if (info == nullptr) throw std::logic_error(fmt::format("<{}> not in elements()", tag));
    entries_.push_back({tag, info->repeatable, {}, std::move(handle), {}, {}});
  }

  // A tag refused with a message; allowed "" means the accepted tags.
  void refuse(std::string_view tag, std::string problem, std::string allowed = {}) {
    entries_.push_back({tag, false, {}, {}, std::move(problem), std::move(allowed)});
  }

  [[nodiscard]] bool accepts(std::string_view tag) const { return find(tag) != nullptr; }

  void run() {
    for (const pugi::xml_node child : parent_.children()) {
      if (child.type() == pugi::node_pcdata || child.type() == pugi::node_cdata) {
        const std::string_view text = trimSpace(child.value());
        if (!text.empty()) {
          cx_.fail(cx_.textLine(child), selfPath(),
                   fmt::format("unexpected text {}", quote(text)),
                   fmt::format("child elements only: {}", acceptedList()));
        }
        continue;
      }
      if (child.type() != pugi::node_element) continue;  // comments, instructions
      dispatch(child);
    }
    for (const Entry& e : entries_) {
      if (!e.requiredAllowed.empty() && !seen_.contains(e.tag)) {
        cx_.fail(line(), selfPath(), fmt::format("missing required <{}>", e.tag),
                 e.requiredAllowed);
      }
    }
  }

  [[nodiscard]] const std::string& path() const { return path_; }
  /// The path naming this element itself in messages.
  [[nodiscard]] std::string selfPath() const { return path_.empty() ? std::string("Scene") : path_; }
  [[nodiscard]] int line() const { return cx_.lineOf(parent_); }
  /// Line of the first tag element, 0 when absent.
  [[nodiscard]] int lineOf(std::string_view tag) const {
    const auto it = seen_.find(tag);
    return it == seen_.end() ? 0 : it->second;
  }
  /// A derived field's value as read, null when absent.
  [[nodiscard]] const Value* derived(std::string_view tag) const {
    const auto it = derived_.find(tag);
    return it == derived_.end() ? nullptr : &it->second;
  }
  [[nodiscard]] std::string childPath(std::string_view tag) const {
    return path_.empty() ? std::string(tag) : path_ + "/" + std::string(tag);
  }

  // The element named by the later of two tags present, for cross-field messages.
  [[nodiscard]] std::pair<int, std::string> where(std::string_view first,
                                                  std::string_view second) const {
    if (lineOf(second) > 0) return {lineOf(second), childPath(second)};
    if (lineOf(first) > 0) return {lineOf(first), childPath(first)};
    return {line(), selfPath()};
  }

 private:
  struct Entry {
    std::string_view tag;
    bool repeatable = false;
    std::string requiredAllowed;  // non-empty: required, and what is allowed
    Handler handle;
    std::string refusal;  // non-empty: refused with this problem
    std::string refusalAllowed;
  };

  [[nodiscard]] const Entry* find(std::string_view tag) const {
    for (const Entry& e : entries_) {
      if (e.tag == tag) return &e;
    }
    return nullptr;
  }

  [[nodiscard]] std::vector<std::string_view> acceptedTags() const {
    std::vector<std::string_view> tags;
    for (const Entry& e : entries_) {
      if (e.refusal.empty()) tags.push_back(e.tag);
    }
    return tags;
  }

  [[nodiscard]] std::string acceptedList() const {
    std::string s;
    for (const auto t : acceptedTags()) s += (s.empty() ? "" : ", ") + std::string(t);
    return s.empty() ? std::string("none") : s;
  }

  void dispatch(pugi::xml_node child) {
    const std::string_view name = child.name();
    const std::string path = childPath(name);
    const int line = cx_.lineOf(child);
    if (const pugi::xml_attribute a = child.first_attribute()) {
      cx_.fail(line, path, fmt::format("unknown attribute '{}'", a.name()),
               "no attributes: values go inside elements");
    }
    const Entry* e = find(name);
    if (e == nullptr) {
      cx_.fail(line, path,
               fmt::format("unknown element <{}>{}", name, nearMiss(name, acceptedTags())),
               fmt::format("in <{}>: {}", parent_.name(), acceptedList()));
    }
    if (!e->refusal.empty()) {
      cx_.fail(line, path, e->refusal, e->refusalAllowed.empty() ? acceptedList() : e->refusalAllowed);
    }
    if (const auto it = seen_.find(e->tag); it != seen_.end() && !e->repeatable) {
      cx_.fail(line, path, fmt::format("<{}> is given twice (first at line {})", name, it->second),
               fmt::format("one <{}> in each <{}>", name, parent_.name()));
    }
    seen_.emplace(e->tag, line);
    e->handle(child, path);
  }

  const Context& cx_;
  pugi::xml_node parent_;
  std::string path_;
  std::vector<Entry> entries_;
  std::map<std::string_view, int> seen_;
  std::map<std::string_view, Value> derived_;
};

// The first child element named tag, trimmed text; "" when absent.
std::string childText(pugi::xml_node node, const char* tag) {
  return std::string(trimSpace(textOf(node.child(tag)).text));
}

}  // namespace

namespace {

// Reads a whole document into a SceneDesc, element by element.
class SceneReader {
 public:
  explicit SceneReader(const Context& cx) : cx_(cx) {}

  SceneDesc read(const pugi::xml_document& doc) {
    const pugi::xml_node root = findRoot(doc);
    checkRootAttributes(root);
    Children c(cx_, root, "");
    c.element("Simulation", [&](pugi::xml_node n, const std::string& p) {
      readFields(n, p, scene_.simulation);
    });
    c.element("Camera", [&](pugi::xml_node n, const std::string& p) {
      readFields(n, p, scene_.camera);
    });
    c.element("Environment", [&](pugi::xml_node n, const std::string& p) {
      readFields(n, p, scene_.environment.emplace());
    });
    c.element("Fluid", [&](pugi::xml_node n, const std::string&) { readFluid(n); });
    c.element("Object", [&](pugi::xml_node n, const std::string&) { readObject(n); });
    c.element("Interactions", [&](pugi::xml_node n, const std::string& p) {
      readInteractions(n, p);
    });
    for ([[maybe_unused]] const pugi::xml_node f : root.children("Fluid")) ++fluidElements_;
    c.run();
    checkPairs();
    checkParticleCap();
    scene_.baseDir = cx_.baseDir.string();
    scene_.file = cx_.file();
    return std::move(scene_);
  }

 private:
  struct PairSource {
    int aLine = 0;
    int bLine = 0;
    std::string path;
  };

  // Who holds a name: fluids and objects share one namespace (a Pair names either).
  struct NameOwner {
    bool object = false;
    int line = 0;  // line of its <Name>, or of the <Object> for a default name
  };

  pugi::xml_node findRoot(const pugi::xml_document& doc) const {
    pugi::xml_node root;
    for (const pugi::xml_node n : doc.children()) {
      if (n.type() == pugi::node_pcdata && !trimSpace(n.value()).empty()) {
        cx_.fail(cx_.textLine(n), "Scene", "text outside the root element", "one <Scene> element");
      }
      if (n.type() != pugi::node_element) continue;
      if (root) {
        cx_.fail(cx_.lineOf(n), n.name(), fmt::format("a second root element <{}>", n.name()),
                 "exactly one root element, <Scene>");
      }
      root = n;
    }
    if (!root) cx_.fail(1, "Scene", "no root element", "one <Scene version=\"1\"> element");
    if (std::string_view(root.name()) != "Scene") {
      cx_.fail(cx_.lineOf(root), root.name(),
               fmt::format("the root element is <{}>{}", root.name(),
                           nearMiss(root.name(), {"Scene"})),
               "<Scene version=\"1\">");
    }
    return root;
  }

  void checkRootAttributes(pugi::xml_node root) const {
    for (const pugi::xml_attribute a : root.attributes()) {
      if (std::string_view(a.name()) != "version") {
        cx_.fail(cx_.lineOf(root), "Scene", fmt::format("unknown attribute '{}'", a.name()),
                 "version");
      }
      if (std::string_view(a.value()) != "1") {
        cx_.fail(cx_.lineOf(root), "Scene",
                 fmt::format("unsupported format version {}", quote(a.value())), "version=\"1\"");
      }
    }
  }

  template <class S>
  void readFields(pugi::xml_node node, const std::string& path, S& target) {
    Children c(cx_, node, path);
    c.fields(fieldsOf<S>(), target);
    c.run();
  }

  void checkOrder(const Children& c, double lo, double hi, std::string_view loTag,
                  std::string_view hiTag) const {
    if (lo <= hi) return;
    const auto [line, element] = c.where(loTag, hiTag);
    cx_.fail(line, element, fmt::format("{} ({}) is greater than {} ({})", loTag, lo, hiTag, hi),
             fmt::format("{} <= {}", loTag, hiTag));
  }

  void readFluid(pugi::xml_node node) {
    FluidDesc fluid;
    fluid.line = cx_.lineOf(node);
    const std::string nameText = childText(node, "Name");
    const std::string label = validName(nameText)
                                  ? fmt::format("Fluid '{}'", nameText)
                                  : fmt::format("Fluid[{}]", scene_.fluids.size() + 1);
    if (scene_.fluids.size() == kMaxFluids) {
      cx_.fail(fluid.line, label,
               fmt::format("the scene has {} fluids, more than the cap of {}", fluidElements_, kMaxFluids),
               fmt::format("at most {} fluids", kMaxFluids));
    }
    meshBound_ = 0;
    Children c(cx_, node, label);
    c.fields(fieldsOf<FluidDesc>(), fluid);
    c.element("Fill", [&](pugi::xml_node n, const std::string&) {
      fluid.fills.push_back(readFill(n, fmt::format("{}/Fill[{}]", label, fluid.fills.size() + 1)));
    });
    c.run();

    if (!validName(fluid.name)) {
      const std::string tooLong = lengthProblem(fluid.name);
      cx_.fail(c.lineOf("Name"), label + "/Name",
               !tooLong.empty() ? tooLong : fmt::format("{} is not a valid fluid name", quote(fluid.name)),
               allowedText(infoOf<FluidDesc>("Name")));
    }
    claimName(fluid.name, false, c.lineOf("Name"), label + "/Name", "fluid name");
    checkOrder(c, fluid.params.minimumForce, fluid.params.maximumForce, "MinimumForce",
               "MaximumForce");
    if (const Value* n = c.derived("NumberOfParticles")) {
      const std::int64_t given = std::get<std::int64_t>(*n);
      if (static_cast<std::uint64_t>(given) != fluid.particles.size()) {
        cx_.fail(c.lineOf("NumberOfParticles"), label + "/NumberOfParticles",
                 fmt::format("NumberOfParticles is {} but <Particles> holds {} positions", given,
                             fluid.particles.size()),
                 "the number of positions in <Particles> (3 numbers each)");
      }
    }
    if (fluid.particles.empty() && fluid.fills.empty()) {
      cx_.fail(fluid.line, label, "the fluid has no particles",
               "explicit <Particles> or at least one <Fill>");
    }
    labels_.push_back(label);
    meshBounds_.push_back(meshBound_);
    scene_.fluids.push_back(std::move(fluid));
  }

  FillDesc readFill(pugi::xml_node node, const std::string& path) {
    FillDesc fill;
    fill.line = cx_.lineOf(node);
    const FieldInfo& shapeInfo = infoOf<FillDesc>("Shape");
    const pugi::xml_node shapeNode = node.child("Shape");
    if (!shapeNode) {
      cx_.fail(fill.line, path, "missing required <Shape>", allowedText(shapeInfo));
    }
    const auto shape = static_cast<FillShape>(
        std::get<std::int64_t>(parseValue(cx_, shapeNode, path + "/Shape", shapeInfo)));
    Children c(cx_, node, path);
    c.fields(fieldsOf<FillDesc>(), fill);
    c.fields(fillShapeFields(shape), fill);
    for (const FillShape other : {FillShape::Box, FillShape::Sphere, FillShape::Mesh}) {
      for (const auto& f : fillShapeFields(other)) {
        if (c.accepts(f.tag)) continue;
        c.refuse(f.tag, fmt::format("<{}> belongs to {} fills, not to {} fills", f.tag,
                                    kFillShapeNames[static_cast<int>(other)],
                                    kFillShapeNames[static_cast<int>(shape)]));
      }
    }
    c.run();
    if (shape == FillShape::Box) {
      for (int a = 0; a < 3; ++a) {
        if (fill.min[a] < fill.max[a]) continue;
        const auto [line, element] = c.where("Min", "Max");
        cx_.fail(line, element,
                 fmt::format("Min {} ({}) is not below Max {} ({})", "xyz"[a], fill.min[a],
                             "xyz"[a], fill.max[a]),
                 "Min < Max on every axis");
      }
    }
    if (shape == FillShape::Mesh) {
      checkMeshFill(c, fill, path);
      return fill;
    }
    if (fillCount(fill) == 0) {
      cx_.fail(fill.line, path, "the fill makes no particles",
               "a fill with at least one lattice point: a box at least Spacing wide on every axis");
    }
    return fill;
  }

  // A mesh fill: Spacing given, Geometry a relative path that stays inside the scene's
  // folder once symbolic links are resolved, and a mesh that loads. Its voxel bound
  // counts toward the particle cap (nothing is generated here).
  void checkMeshFill(const Children& c, const FillDesc& fill, const std::string& path) {
    if (c.lineOf("Spacing") == 0) {
      cx_.fail(fill.line, path, "missing required <Spacing>",
               "a mesh fill gives its lattice step: <Spacing>, > 0");
    }
    const geometry::TriangleMesh mesh =
        loadGeometry(fill.geometry, c.lineOf("Geometry"), path + "/Geometry", !fill.surface);
    meshBound_ = saturatingAdd(meshBound_, geometry::meshFillBound(mesh, fill.spacing));
  }

  // The mesh a <Geometry> (of a mesh fill or an object) names: a relative path that stays
  // inside the scene's folder once symbolic links are resolved, and a file that loads.
  // Every problem is an error at the <Geometry> line (element).
  // warnIfOpen: a volume fill, which needs a closed mesh to tell inside from outside.
  [[nodiscard]] geometry::TriangleMesh loadGeometry(const std::string& file, int line,
                                                    const std::string& element,
                                                    bool warnIfOpen) const {
    namespace fs = std::filesystem;
    const auto fail = [&](const std::string& problem) {
      cx_.fail(line, element, problem, std::string(kPathAllowed));
    };
    const fs::path given(file);
    if (file.empty()) fail("the mesh path is empty");
    if (given.is_absolute() || given.has_root_name() || given.has_root_directory()) {
      fail(fmt::format("{} is an absolute path", quote(file)));
    }
    const fs::path normal = given.lexically_normal();
    if (!normal.empty() && *normal.begin() == "..") {
      fail(fmt::format("{} leaves the scene's folder", quote(file)));
    }
    if (normal.empty() || normal == ".") {
      fail(fmt::format("{} names the scene's folder itself, not a mesh file", quote(file)));
    }
    std::error_code ec;
    const fs::path base = fs::weakly_canonical(cx_.baseDir, ec);
    fs::path target;
    if (!ec) target = fs::weakly_canonical(base / normal, ec);
    if (ec) fail(fmt::format("cannot resolve {}: {}", quote(file), ec.message()));
    const fs::path rel = target.lexically_relative(base);
    if (rel.empty() || *rel.begin() == ".." || rel == ".") {
      fail(fmt::format("{} resolves to '{}', outside the scene's folder (through a symbolic link)",
                       quote(file), target.string()));
    }
    geometry::TriangleMesh mesh;
    geometry::MeshLoadReport report;
    try {
      mesh = geometry::loadMesh(target, &report, base);
    } catch (const InputError& e) {
      // The loader's own "allowed" says what would fix its refusal (a glTF's buffers
      // inside the folder, finite coordinates, ...); the generic one only when it has none.
      cx_.fail(line, element, fmt::format("cannot use the mesh {}: {}", quote(file), e.problem()),
               e.allowed().empty() ? "a readable mesh file with at least one triangle (OBJ, PLY, STL, glTF, FBX...)"
                                   : e.allowed());
    } catch (const IoError& e) {
      cx_.fail(line, element, fmt::format("cannot use the mesh {}: {}", quote(file), e.what()),
               "a readable mesh file with at least one triangle (OBJ, PLY, STL, glTF, FBX...)");
    }
    if (warnIfOpen) {
      if (std::string open = geometry::openMeshWarning(geometry::countEdges(mesh)); !open.empty()) {
        report.warnings.push_back(std::move(open));
      }
    }
    for (const std::string& w : report.warnings) cx_.warn(line, element, fmt::format("mesh {}: {}", quote(file), w));
    return mesh;
  }

  // Records name as taken by a fluid or an object; a name already taken (by either) is an
  // error at line, naming element. what: "fluid name", "object name", "default object name".
  void claimName(const std::string& name, bool object, int line, const std::string& element,
                 std::string_view what) {
    const auto [it, fresh] = names_.emplace(name, NameOwner{object, line});
    if (fresh) return;
    const bool sameKind = it->second.object == object;
    cx_.fail(line, element,
             fmt::format("the {} '{}' is already used{} (line {})", what, name,
                         sameKind ? "" : (it->second.object ? " by an object" : " by a fluid"),
                         it->second.line),
             what == "default object name"
                 ? "a name no other fluid or object has: give this object its own <Name>"
                 : "a name no other fluid or object has");
  }

  // An <Object>: its fields, a name (default object<N>), and either Geometry (a mesh that
  // loads; closed when it is a dynamic mesh-shaped body) or a primitive Shape with Size.
  // Its particle bound counts toward the particle cap (nothing is generated here).
  void readObject(pugi::xml_node node) {
    ObjectDesc object;
    object.line = cx_.lineOf(node);
    const std::size_t index = scene_.objects.size() + 1;
    const std::string nameText = childText(node, "Name");
    const std::string label = usableObjectName(nameText) && nameText.size() <= 40
                                  ? fmt::format("Object '{}'", nameText)
                                  : fmt::format("Object[{}]", index);
    Children c(cx_, node, label);
    c.fields(fieldsOf<ObjectDesc>(), object);
    c.run();

    if (c.lineOf("Name") == 0) {
      object.name = fmt::format("object{}", index);
      claimName(object.name, true, object.line, label, "default object name");
    } else {
      if (!usableObjectName(object.name)) {
        const std::string tooLong = lengthProblem(object.name);
        cx_.fail(c.lineOf("Name"), label + "/Name",
                 !tooLong.empty() ? tooLong
                 : object.name == "." || object.name == ".."
                     ? fmt::format(
                           "{} is not a valid object name: it names a folder, and the name becomes part of "
                           "file names",
                           quote(object.name))
                     : fmt::format("{} is not a valid object name: it becomes part of file names",
                                   quote(object.name)),
                 std::string(kObjectNameAllowed));
      }
      claimName(object.name, true, c.lineOf("Name"), label + "/Name", "object name");
    }

    const bool hasGeometry = c.lineOf("Geometry") > 0;
    const bool hasShape = c.lineOf("Shape") > 0;
    const bool hasSize = c.lineOf("Size") > 0;
    const std::string shapeName(kObjectShapeNames[static_cast<int>(object.shape)]);
    constexpr std::string_view kBodyAllowed =
        "<Geometry> (a mesh file), or <Shape> sphere, cone, box or cylinder with <Size>";
    if (!hasGeometry && !hasShape) {
      cx_.fail(object.line, label, "the object has neither <Geometry> nor <Shape>",
               std::string(kBodyAllowed));
    }
    if (object.shape == ObjectShape::Mesh && !hasGeometry) {
      cx_.fail(c.lineOf("Shape"), label + "/Shape", "Shape mesh needs a <Geometry> mesh file",
               std::string(kBodyAllowed));
    }
    if (object.shape == ObjectShape::Mesh && hasSize) {
      cx_.fail(c.lineOf("Size"), label + "/Size",
               "a mesh object takes its size from its mesh: there is nothing to size",
               "Size only with Shape sphere, cone, box or cylinder; scale a mesh with "
               "UniformScale");
    }
    if (object.shape != ObjectShape::Mesh) {
      const std::size_t want = objectSizeCount(object.shape);
      const std::string sizeAllowed =
          fmt::format("{} {} > 0 for a {}: {}", want, want == 1 ? "number" : "numbers",
                      shapeName, objectSizeWords(object.shape));
      if (!hasSize && !hasGeometry) {
        cx_.fail(object.line, label, fmt::format("missing required <Size> for Shape {}", shapeName),
                 sizeAllowed);
      }
      if (hasSize && object.size.size() != want) {
        cx_.fail(c.lineOf("Size"), label + "/Size",
                 fmt::format("Size has {} {} but a {} takes {} ({})", object.size.size(),
                             object.size.size() == 1 ? "number" : "numbers", shapeName, want,
                             objectSizeWords(object.shape)),
                 sizeAllowed);
      }
    }

    // The body's extent, for the automatic particle size and the particle bound: the
    // mesh when there is one, else the primitive's bounding box; both scaled.
    geometry::TriangleMesh body;
    if (hasGeometry) {
      const int line = c.lineOf("Geometry");
      const std::string element = label + "/Geometry";
      body = loadGeometry(object.geometry, line, element, false);
      if (object.shape == ObjectShape::Mesh && object.isDynamic) {
        try {
          (void)geometry::meshMassProperties(body, object.mass, object.geometry);
        } catch (const InputError& e) {
          cx_.fail(line, element,
                   fmt::format("the mesh {} cannot be a dynamic body: {}", quote(object.geometry),
                               e.problem()),
                   fmt::format("{}; or <IsDynamic>false</IsDynamic>, or a primitive <Shape>",
                               e.allowed().empty() ? std::string("a closed triangle mesh")
                                                   : e.allowed()));
        }
      }
    } else {
      body.vertices = primitiveCorners(object.shape, object.size);
    }
    for (Vec3& v : body.vertices) v *= object.uniformScale;
    const double extent = largestExtent(body.bounds());
    if (!(extent <= kMaxReal)) {
      cx_.fail(c.lineOf("UniformScale") > 0 ? c.lineOf("UniformScale") : object.line,
               c.lineOf("UniformScale") > 0 ? label + "/UniformScale" : label,
               fmt::format("the scaled object is {:g} units across, too large for single precision",
                           extent),
               "an object at most 3.4e38 units across after UniformScale");
    }
    const double spacing = object.particleSize > 0 ? object.particleSize : extent / 20;
    objectBounds_.push_back(geometry::meshFillBound(body, spacing));
    objectLabels_.push_back(label);
    scene_.objects.push_back(std::move(object));
  }

  // The corners of a primitive's bounding box (axis along y for cone and cylinder).
  static std::vector<Vec3> primitiveCorners(ObjectShape shape, const std::vector<double>& size) {
    Vec3 half(0, 0, 0);
    switch (shape) {
      case ObjectShape::Mesh: return {};
      case ObjectShape::Sphere: half = Vec3(size[0], size[0], size[0]); break;
      case ObjectShape::Cone:
      case ObjectShape::Cylinder: half = Vec3(size[0], size[1] / 2, size[0]); break;
      case ObjectShape::Box: half = Vec3(size[0] / 2, size[1] / 2, size[2] / 2); break;
    }
    return {-half, half};
  }

  void readInteractions(pugi::xml_node node, const std::string& path) {
    Children c(cx_, node, path);
    c.element("FluidFluid", [&](pugi::xml_node n, const std::string& p) {
      InteractionDesc d;
      Children fc(cx_, n, p);
      fc.fields(fieldsOf<InteractionDesc>(), d);
      runWithFunction(fc, d);
      scene_.interactions.fluidFluid = std::move(d);
    });
    c.element("FluidObject", [&](pugi::xml_node n, const std::string& p) {
      // Starts from the default: a missing RelativeVelocity keeps FluidObject's own.
      InteractionDesc d = InteractionsDesc{}.fluidObject;
      Children fc(cx_, n, p);
      fc.fields(fieldsOf<InteractionDesc>(), d);
      runWithFunction(fc, d);
      scene_.interactions.fluidObject = std::move(d);
    });
    c.element("Pair", [&](pugi::xml_node n, const std::string&) { readPair(n, path); });
    c.run();
  }

  void readPair(pugi::xml_node node, const std::string& parentPath) {
    PairDesc pair;
    pair.line = cx_.lineOf(node);
    const std::string a = childText(node, "A");
    const std::string b = childText(node, "B");
    const auto labelled = [](const std::string& s) { return usableObjectName(s) && s.size() <= 40; };
    const std::string path =
        labelled(a) && labelled(b)
            ? fmt::format("{}/Pair '{}','{}'", parentPath, a, b)
            : fmt::format("{}/Pair[{}]", parentPath, scene_.interactions.pairs.size() + 1);
    Children c(cx_, node, path);
    c.fields(fieldsOf<PairDesc>(), pair);
    c.fields(fieldsOf<InteractionDesc>(), pair.interaction);
    runWithFunction(c, pair.interaction);
    pairSources_.push_back({c.lineOf("A"), c.lineOf("B"), path});
    scene_.interactions.pairs.push_back(std::move(pair));
  }

  // Runs c (a FluidFluid, FluidObject or Pair) with the function elements added; exactly
  // one is needed.
  void runWithFunction(Children& c, InteractionDesc& d) {
    std::string first;
    addFunction<forces::Linear>(c, "Linear", d, first);
    addFunction<forces::LennardJones>(c, "LennardJones", d, first);
    addFunction<forces::LennardJonesForce>(c, "LennardJonesForce", d, first);
    addFunction<forces::Curve>(c, "Curve", d, first);
    c.run();
    if (first.empty()) {
      cx_.fail(c.line(), c.path(), "missing the function element", std::string(kOneFunction));
    }
  }

  template <class F>
  void addFunction(Children& c, std::string_view tag, InteractionDesc& d, std::string& first) {
    c.element(tag, [this, &d, &first](pugi::xml_node n, const std::string& p) {
      if (!first.empty()) {
        cx_.fail(cx_.lineOf(n), p, fmt::format("a second function <{}> after <{}>", n.name(), first),
                 std::string(kOneFunction));
      }
      first = n.name();
      F f{};
      Children fc(cx_, n, p);
      fc.fields(fieldsOf<F>(), f);
      fc.run();
      checkFunction(fc, f);
      d.function = std::move(f);
    });
  }

  void checkFunction(const Children& c, const forces::Linear& f) const {
    checkOrder(c, f.min, f.max, "Min", "Max");
  }
  void checkFunction(const Children& c, const forces::LennardJones& f) const {
    checkOrder(c, f.min, f.max, "Min", "Max");
  }
  void checkFunction(const Children&, const forces::LennardJonesForce&) const {}
  void checkFunction(const Children& c, const forces::Curve& f) const {
    const std::string allowed = allowedText(infoOf<forces::Curve>("Points"));
    const auto fail = [&](const std::string& problem) {
      cx_.fail(c.lineOf("Points"), c.childPath("Points"), problem, allowed);
    };
    const std::vector<double>& p = f.points;
    if (p.size() % 2 != 0 || p.size() < 4) {
      fail(fmt::format("{} numbers do not make at least 2 (r, f) points", p.size()));
    }
    if (p[0] < 0) fail(fmt::format("the first r ({}) is negative", p[0]));
    for (std::size_t i = 2; i < p.size(); i += 2) {
      if (!(p[i] > p[i - 2])) {
        fail(fmt::format("r {} does not increase after r {} (point {})", p[i], p[i - 2], i / 2 + 1));
      }
    }
  }

  void checkPairs() const {
    std::map<std::pair<std::string, std::string>, int> seen;
    std::string fluids;
    for (const auto& f : scene_.fluids) fluids += (fluids.empty() ? "" : ", ") + f.name;
    std::string objects;
    for (const auto& o : scene_.objects) objects += (objects.empty() ? "" : ", ") + o.name;
    std::string allowed = "the Name of a fluid or an object";
    if (fluids.empty() && objects.empty()) {
      allowed += " (the scene has none)";
    } else {
      allowed += ":";
      if (!fluids.empty()) allowed += " fluids " + fluids;
      if (!objects.empty()) allowed += (fluids.empty() ? " objects " : "; objects ") + objects;
    }
    const auto isObject = [&](const std::string& name) {
      const auto it = names_.find(name);
      return it != names_.end() && it->second.object;
    };
    for (std::size_t i = 0; i < scene_.interactions.pairs.size(); ++i) {
      const PairDesc& p = scene_.interactions.pairs[i];
      const PairSource& src = pairSources_[i];
      if (!names_.contains(p.a)) {
        cx_.fail(src.aLine, src.path + "/A", fmt::format("no fluid or object is named '{}'", p.a),
                 allowed);
      }
      if (!names_.contains(p.b)) {
        cx_.fail(src.bLine, src.path + "/B", fmt::format("no fluid or object is named '{}'", p.b),
                 allowed);
      }
      if (isObject(p.a) && isObject(p.b)) {
        cx_.fail(p.line, src.path,
                 fmt::format("'{}' and '{}' are both objects: objects collide by impulses "
                             "(NormalAttenuation, TangentAttenuation), not by a function",
                             p.a, p.b),
                 "a Pair of two fluids, or of a fluid and an object");
      }
      const auto key = std::minmax(p.a, p.b);
      if (const auto [it, fresh] = seen.emplace(std::pair(key.first, key.second), p.line); !fresh) {
        cx_.fail(p.line, src.path,
                 fmt::format("the pair '{}','{}' is given twice (first at line {})", p.a, p.b,
                             it->second),
                 "one <Pair> for the same two names, in either order");
      }
    }
  }

  // The cap on particles, counted from positions, fill formulas and voxel bounds (mesh
  // fills, objects): nothing generated. Fluids first, then objects; the element where the
  // running total passes the cap is named.
  void checkParticleCap() const {
    const std::uint64_t cap = cx_.options.maxParticles;
    std::uint64_t total = 0;
    const auto count = [&] {
      return total == UINT64_MAX ? std::string("over 10^19")
                                 : std::to_string(total);
    };
    std::size_t crossing = scene_.fluids.size();
    for (std::size_t i = 0; i < scene_.fluids.size(); ++i) {
      const FluidDesc& f = scene_.fluids[i];
      total = saturatingAdd(total, f.particles.size());
      for (const FillDesc& fill : f.fills) total = saturatingAdd(total, fillCount(fill));
      total = saturatingAdd(total, meshBounds_[i]);  // mesh fills: their voxel grids
      if (total > cap && crossing == scene_.fluids.size()) crossing = i;
    }
    if (crossing < scene_.fluids.size()) {
      cx_.fail(scene_.fluids[crossing].line, labels_[crossing],
               fmt::format("the scene makes {} particles (explicit positions plus fills), more "
                           "than the cap of {}",
                           count(), cap),
               fmt::format("at most {} particles in all; --max-particles raises the cap", cap));
    }
    for (std::size_t i = 0; i < scene_.objects.size(); ++i) {
      total = saturatingAdd(total, objectBounds_[i]);
      if (total <= cap) continue;
      cx_.fail(scene_.objects[i].line, objectLabels_[i],
               fmt::format("the fluids and the objects up to this one may make {} particles "
                           "(objects filled at their ParticleSize), more than the cap of {}",
                           count(), cap),
               fmt::format("at most {} particles in all: a larger ParticleSize, or fewer or "
                           "smaller objects; --max-particles raises the cap",
                           cap));
    }
  }

  const Context& cx_;
  SceneDesc scene_;
  std::map<std::string, NameOwner> names_;  // fluid and object names
  std::vector<std::string> labels_;       // per fluid: its element path
  std::vector<std::string> objectLabels_;    // per object: its element path
  std::vector<std::uint64_t> objectBounds_;  // per object: voxel bound of its fill
  std::vector<PairSource> pairSources_;   // per pair: lines of A and B, its path
  std::size_t fluidElements_ = 0;         // <Fluid> elements of the file, for the cap's message
  std::vector<std::uint64_t> meshBounds_; // per fluid: voxel bound of its mesh fills
  std::uint64_t meshBound_ = 0;           // the fluid being read: its mesh fills' bound
};

}  // namespace

namespace {

constexpr std::string_view kWellFormed = "well-formed XML";

std::string byteCount(std::uint64_t n) {
  if (n >= (std::uint64_t{1} << 30) && n % (std::uint64_t{1} << 30) == 0) {
    return fmt::format("{} GiB", n >> 30);
  }
  if (n >= (std::uint64_t{1} << 20) && n % (std::uint64_t{1} << 20) == 0) {
    return fmt::format("{} MiB", n >> 20);
  }
  return fmt::format("{} bytes", n);
}

[[noreturn]] void refuseSize(const std::string& file, std::uint64_t size, std::uint64_t cap) {
  throw InputError({file, 0, "XML"},
                   fmt::format("the file is {} bytes, more than the cap of {}", size, byteCount(cap)),
                   fmt::format("a scene file of at most {} ({} bytes)", byteCount(cap), cap));
}

// A parse that failed: a truncated file (the parser stopped at its end with elements
// open) is said so, naming the innermost open element and its line.
[[noreturn]] void refuseParse(const Context& cx, std::string_view text,
                              const pugi::xml_parse_result& parsed, const XmlTextCheck& scan) {
  const auto at = static_cast<std::size_t>(std::max<std::ptrdiff_t>(parsed.offset, 0));
  const bool atEnd = trimSpace(text.substr(std::min(at, text.size()))).size() <= 1;
  const auto lastLine = cx.lineAt(static_cast<std::ptrdiff_t>(text.size()) - 1);
  const std::string allowed = fmt::format("{}: every element closed, ending with </Scene>", kWellFormed);
  if (!scan.unfinished.empty()) {
    cx.fail(lastLine, "XML",
            fmt::format("the file ends inside {} (opened at line {}): it is truncated ({})",
                        scan.unfinished, cx.lineAt(static_cast<std::ptrdiff_t>(scan.unfinishedOffset)),
                        parsed.description()),
            allowed);
  }
  if (atEnd && !scan.openAtEnd.empty()) {
    const OpenElement& inner = scan.openAtEnd.back();
    cx.fail(lastLine, "XML",
            fmt::format("the file ends inside <{}> (opened at line {}): it is truncated or an "
                        "element is not closed ({})",
                        inner.name, cx.lineAt(static_cast<std::ptrdiff_t>(inner.offset)),
                        parsed.description()),
            allowed);
  }
  if (parsed.status == pugi::status_end_element_mismatch && !scan.mismatchedOpen.name.empty()) {
    // pugixml says only "Start-end tags mismatch": the tags are named, with where the
    // open one started (a closing tag in another case, a missing </Fluid> found at
    // </Scene>).
    const OpenElement& end = scan.mismatchedEnd;
    const OpenElement& open = scan.mismatchedOpen;
    const bool caseOnly = equalIgnoringCase(end.name, open.name);
    cx.fail(
        cx.lineAt(static_cast<std::ptrdiff_t>(end.offset)), "XML",
        fmt::format(
            "</{}> does not close <{}> (opened at line {}){}", end.name, open.name,
            cx.lineAt(static_cast<std::ptrdiff_t>(open.offset)),
            caseOnly ? ": element names are case-sensitive" : ": an element is not closed, or closed twice"),
        fmt::format("{}: each element closed by </name> with its own name, innermost first", kWellFormed));
  }
  cx.fail(cx.lineAt(parsed.offset), "XML", fmt::format("not well-formed: {}", parsed.description()),
          std::string(kWellFormed));
}

}  // namespace

void checkFluidName(std::string_view name, const InputLocation& where) {
  if (validName(name)) return;
  const std::string tooLong = lengthProblem(name);
  throw InputError(where, !tooLong.empty() ? tooLong : fmt::format("{} is not a valid fluid name", quote(name)),
                   allowedText(infoOf<FluidDesc>("Name")));
}

SceneDesc readSceneText(std::string_view text, const std::string& fileName,
                        const ReadOptions& options) {
  if (text.size() > options.maxFileBytes) refuseSize(fileName, text.size(), options.maxFileBytes);
  if (text.starts_with("\xEF\xBB\xBF")) text.remove_prefix(3);  // UTF-8 byte order mark
  std::error_code ec;
  std::filesystem::path base = std::filesystem::path(fileName).parent_path();
  if (base.empty()) base = ".";
  base = std::filesystem::absolute(base, ec).lexically_normal();
  if (ec) base = std::filesystem::path(fileName).parent_path();
  const Context cx(text, fileName, base, options);
  // What pugixml lets through (a DTD, unknown entities, &#0;, control characters,
  // invalid UTF-8, deep nesting) is refused before it parses.
  const XmlTextCheck scan = checkXmlText(text);
  if (!scan.problem.empty()) {
    cx.fail(cx.lineAt(static_cast<std::ptrdiff_t>(scan.offset)), "XML", scan.problem, scan.allowed);
  }
  pugi::xml_document doc;
  // parse_fragment keeps text outside the root as nodes (pugixml drops it otherwise),
  // parse_comments the comments (a comment inside a value reads as a space: leafText);
  // SceneReader then insists on exactly one root element and no text around it.
  const pugi::xml_parse_result parsed =
      doc.load_buffer(text.data(), text.size(),
                      pugi::parse_default | pugi::parse_fragment | pugi::parse_comments, pugi::encoding_utf8);
  if (!parsed) refuseParse(cx, text, parsed, scan);
  return SceneReader(cx).read(doc);
}

SceneDesc readSceneFile(const std::string& path, const ReadOptions& options) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    throw IoError(fmt::format("cannot read scene file '{}': it is a directory", path));
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw IoError(fmt::format("cannot read scene file '{}': {}", path, std::strerror(errno)));
  }
  // The size is checked before anything is read (a regular file; a pipe is read up to
  // one byte past the cap).
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (!ec && size > options.maxFileBytes) refuseSize(path, size, options.maxFileBytes);
  std::string text;
  char buffer[1 << 16];
  while (in.read(buffer, sizeof buffer) || in.gcount() > 0) {
    text.append(buffer, static_cast<std::size_t>(in.gcount()));
    if (text.size() > options.maxFileBytes) refuseSize(path, text.size(), options.maxFileBytes);
  }
  if (in.bad()) {
    throw IoError(fmt::format("cannot read scene file '{}': read error", path));
  }
  return readSceneText(text, path, options);
}

}  // namespace softsub::scene
