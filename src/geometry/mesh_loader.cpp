#include "geometry/mesh_loader.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cerrno>
#include <cmath>
#include <cctype>
#include <cstring>
#include <string_view>
#include <fstream>
#include <limits>
#include <sstream>
#include <unordered_map>
#include <vector>

#include <assimp/DefaultIOSystem.h>
#include <assimp/IOStream.hpp>
#include <assimp/Importer.hpp>
#include <assimp/MemoryIOWrapper.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <fmt/format.h>

#include "core/error.h"

namespace softsub::geometry {
namespace {

namespace fs = std::filesystem;
using Mat4 = Eigen::Matrix4d;

Mat4 toEigen(const aiMatrix4x4& m) {
  Mat4 out;
  for (unsigned r = 0; r < 4; ++r)
    for (unsigned c = 0; c < 4; ++c) out(r, c) = static_cast<double>(m[r][c]);
  return out;
}

/// "mesh 2 'Cube'" (the name when the file gives one), for messages about a vertex.
std::string meshLabel(unsigned index, const aiMesh& mesh) {
  return mesh.mName.length > 0 ? fmt::format("mesh {} '{}'", index, mesh.mName.C_Str()) : fmt::format("mesh {}", index);
}

/// Hash of a position's exact bit pattern (after folding -0 onto +0), for welding.
struct PositionHash {
  std::size_t operator()(const std::array<double, 3>& p) const {
    std::uint64_t h = 0x9e3779b97f4a7c15ull;
    for (double x : p) h = (h ^ std::bit_cast<std::uint64_t>(x + 0.0)) * 0x100000001b3ull;
    return static_cast<std::size_t>(h ^ (h >> 29));
  }
};

/// Collects triangles from every node instance, welding equal positions as it goes.
class MeshBuilder {
 public:
  explicit MeshBuilder(std::string file) : file_(std::move(file)) {}

  [[nodiscard]] const std::string& file() const { return file_; }

  /// Appends `mesh` placed by `transform`.
  void add(const aiMesh& mesh, unsigned meshIndex, const Mat4& transform) {
    const bool mirrored = transform.topLeftCorner<3, 3>().determinant() < 0;
    std::vector<std::uint32_t> local(mesh.mNumVertices);
    for (unsigned i = 0; i < mesh.mNumVertices; ++i) {
      const aiVector3D& p = mesh.mVertices[i];
      const Vec3 raw(static_cast<double>(p.x), static_cast<double>(p.y), static_cast<double>(p.z));
      const Vec3 v = (transform * raw.homogeneous()).head<3>();
      if (!raw.allFinite() || !v.allFinite())
        throw InputError(
            {file_, 0, "mesh"},
            fmt::format("vertex {} of {} is not finite ({}, {}, {}){}", i, meshLabel(meshIndex, mesh), raw.x(),
                        raw.y(), raw.z(), raw.allFinite() ? " after its node's transform" : ""),
            "finite coordinates");
      local[i] = weld(v);
    }
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      if (face.mNumIndices != 3) {
        ++otherPrimitives_;
        continue;
      }
      std::array<std::uint32_t, 3> t{};
      bool inRange = true;
      for (unsigned k = 0; k < 3; ++k) {
        if (face.mIndices[k] >= mesh.mNumVertices) {
          inRange = false;
          break;
        }
        t[k] = local[face.mIndices[k]];
      }
      if (!inRange) {
        ++outOfRange_;
        continue;
      }
      if (mirrored) std::swap(t[1], t[2]);
      if (isDegenerate(t)) {
        ++degenerate_;
        continue;
      }
      mesh_.triangles.push_back(t);
    }
  }

  /// The mesh without unused vertices; warnings and counts go to `report`.
  TriangleMesh finish(MeshLoadReport* report) {
    compact();
    if (report != nullptr) {
      report->droppedTriangles += degenerate_ + outOfRange_;
      if (degenerate_ > 0)
        report->warnings.push_back(
            fmt::format("dropped {} degenerate triangle(s) (a repeated vertex or zero area)", degenerate_));
      if (outOfRange_ > 0)
        report->warnings.push_back(
            fmt::format("dropped {} triangle(s) with a vertex index out of range", outOfRange_));
      if (otherPrimitives_ > 0)
        report->warnings.push_back(fmt::format("ignored {} point or line primitive(s)", otherPrimitives_));
    }
    if (mesh_.triangles.empty()) {
      // Say what there was instead, so "no triangles" is not a mystery.
      std::string left;
      const auto add = [&](std::size_t n, const char* what) {
        if (n > 0) left += fmt::format("{}{} {}", left.empty() ? "" : ", ", n, what);
      };
      add(degenerate_, "degenerate triangle(s) dropped");
      add(outOfRange_, "triangle(s) with a vertex index out of range dropped");
      add(otherPrimitives_, "point or line primitive(s) ignored");
      throw InputError({file_, 0, "mesh"},
                       left.empty() ? std::string("the mesh has no triangles")
                                    : fmt::format("the mesh has no triangles ({})", left),
                       "at least one triangle with non-zero area");
    }
    if (const std::size_t turned = orientConsistently(mesh_); turned > 0 && report != nullptr)
      report->warnings.push_back(fmt::format(
          "turned {} triangle(s) wound against their neighbours (the winding most of their part of the "
          "mesh has was kept)",
          turned));
    const MeshEdges edges = countEdges(mesh_);
    // A closed mesh wound inward as a whole (authored so, or mirrored by hand): turned
    // outward, so that what is written from it (an object's OBJ beside the frames) has
    // its normals out. The whole mesh's volume decides, not each part's: a hollow mesh's
    // cavity, wound inward, stays so.
    if (edges.boundary == 0 && edges.nonManifold == 0) {
      double volume6 = 0;  // six times the signed volume
      for (const auto& t : mesh_.triangles)
        volume6 += mesh_.vertices[t[0]].dot(mesh_.vertices[t[1]].cross(mesh_.vertices[t[2]]));
      if (volume6 < 0) {
        for (auto& t : mesh_.triangles) std::swap(t[1], t[2]);
        if (report != nullptr)
          report->warnings.push_back(
              "the closed mesh's triangles face inward (its volume is negative): turned to face outward");
      }
    }
    if (report != nullptr) {
      if (edges.nonManifold > 0)
        report->warnings.push_back(fmt::format(
            "{} edge(s) are shared by more than two triangles (non-manifold): kept; inside and outside "
            "of a fill are decided by a majority of three ray directions",
            edges.nonManifold));
    }
    return std::move(mesh_);
  }

 private:
  std::uint32_t weld(const Vec3& v) {
    const std::array<double, 3> key{v.x() + 0.0, v.y() + 0.0, v.z() + 0.0};
    const auto [it, added] = index_.try_emplace(key, static_cast<std::uint32_t>(mesh_.vertices.size()));
    if (added) {
      if (mesh_.vertices.size() >= std::numeric_limits<std::uint32_t>::max())
        throw InputError({file_, 0, "mesh"}, "the mesh has too many vertices", "fewer than 2^32");
      mesh_.vertices.push_back(v);
    }
    return it->second;
  }

  /// A repeated vertex, or an area that is zero to rounding.
  [[nodiscard]] bool isDegenerate(const std::array<std::uint32_t, 3>& t) const {
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) return true;
    const Vec3 e1 = mesh_.vertices[t[1]] - mesh_.vertices[t[0]];
    const Vec3 e2 = mesh_.vertices[t[2]] - mesh_.vertices[t[0]];
    const double scale = std::max(e1.squaredNorm(), e2.squaredNorm());
    return !(e1.cross(e2).norm() > 1e-12 * scale);
  }

  void compact() {
    constexpr std::uint32_t unused = std::numeric_limits<std::uint32_t>::max();
    std::vector<std::uint32_t> remap(mesh_.vertices.size(), unused);
    std::vector<Vec3> kept;
    for (auto& t : mesh_.triangles)
      for (std::uint32_t& i : t) {
        if (remap[i] == unused) {
          remap[i] = static_cast<std::uint32_t>(kept.size());
          kept.push_back(mesh_.vertices[i]);
        }
        i = remap[i];
      }
    mesh_.vertices = std::move(kept);
  }

  std::string file_;
  TriangleMesh mesh_;
  std::unordered_map<std::array<double, 3>, std::uint32_t, PositionHash> index_;
  std::size_t degenerate_ = 0;
  std::size_t outOfRange_ = 0;
  std::size_t otherPrimitives_ = 0;
};

void addNode(const aiScene& scene, const aiNode& node, const Mat4& parent, MeshBuilder& out, int depth) {
  // A malformed file could nest (or loop) nodes without end; real scenes are shallow.
  if (depth > 1000)
    throw InputError({out.file(), 0, "mesh"}, "the node tree is too deep", "at most 1000 levels");
  const Mat4 transform = parent * toEigen(node.mTransformation);
  for (unsigned i = 0; i < node.mNumMeshes; ++i) {
    const unsigned m = node.mMeshes[i];
    if (m < scene.mNumMeshes && scene.mMeshes[m] != nullptr) out.add(*scene.mMeshes[m], m, transform);
  }
  for (unsigned i = 0; i < node.mNumChildren; ++i)
    if (node.mChildren[i] != nullptr) addNode(scene, *node.mChildren[i], transform, out, depth + 1);
}

/// Refuses what cannot or should not be read, before assimp sees the file.
std::uintmax_t checkReadable(const fs::path& file, const std::string& name) {
  std::error_code ec;
  const fs::file_status status = fs::status(file, ec);
  if (ec || !fs::exists(status))
    throw IoError(
        fmt::format("{}: cannot read the mesh: {}", name, ec ? ec.message() : std::string("no such file")));
  if (fs::is_directory(status)) throw IoError(fmt::format("{}: cannot read the mesh: it is a folder", name));
  const std::uintmax_t size = fs::file_size(file, ec);
  if (ec) throw IoError(fmt::format("{}: cannot read the mesh: {}", name, ec.message()));
  if (size > kMaxMeshFileBytes)
    throw InputError({name, 0, "mesh"}, fmt::format("the file is {} bytes", size), "at most 1 GiB");
  errno = 0;
  std::ifstream probe(file, std::ios::binary);
  if (!probe)
    throw IoError(fmt::format("{}: cannot read the mesh: {}", name,
                              errno != 0 ? std::strerror(errno) : "cannot open the file"));
  return size;
}

/// `text` in lower case (ASCII): file extensions and magic words.
std::string lowerCase(std::string text) {
  for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return text;
}

/// assimp's PLY reader reserves memory for the element counts the header declares, so a
/// few-byte file claiming billions of vertices would exhaust memory. Every element with
/// a property takes at least one byte, so the counts cannot add up to more than the file.
void checkPlyCounts(const fs::path& file, const std::string& name, std::uintmax_t size) {
  std::ifstream in(file, std::ios::binary);
  std::string line;
  // assimp reads a .ply file as PLY whatever it holds, and recognises PLY by a "ply" in
  // any case whatever the extension; its reader then hung on a header that began "Ply"
  // (found by the fuzzer: fuzz/regressions/mesh_loader/ply-capital-magic-hang). So a
  // file that is PLY to assimp must begin with the exact magic line, and its header is
  // checked.
  if (!std::getline(in, line)) return;
  if (lowerCase(file.extension().string()) != ".ply" && lowerCase(line.substr(0, 3)) != "ply") return;
  while (!line.empty() && (line.back() == '\r' || line.back() == ' ' || line.back() == '\t')) line.pop_back();
  if (line != "ply")
    throw InputError({name, 1, "mesh"}, "a PLY file's first line is not 'ply'", "the line 'ply', in lower case");
  std::string element;
  std::uintmax_t count = 0;
  std::uintmax_t declared = 0;
  bool hasProperty = false;
  auto close = [&] {
    if (hasProperty) declared += count;
  };
  // assimp's PLY reader loops without end on some malformed headers (found by the fuzzer:
  // fuzz/regressions/mesh_loader/ply-header-hang), so the header must be lines of the
  // known keywords ending with end_header.
  // Each line is checked whole, not only its keyword: assimp's PLY reader corrupts its
  // heap on a property line with a garbled type (found by the fuzzer:
  // fuzz/regressions/mesh_loader/ply-garbled-property-heap).
  bool ended = false, format = false, inElement = false;
  int lines = 0;
  const auto isType = [](const std::string& w) {
    static const char* const kTypes[] = {"char",  "uchar",  "short",   "ushort",  "int",    "uint",
                                         "float", "double", "int8",    "uint8",   "int16",  "uint16",
                                         "int32", "uint32", "float32", "float64"};
    return std::any_of(std::begin(kTypes), std::end(kTypes), [&](const char* k) { return w == k; });
  };
  for (; lines < 10000 && std::getline(in, line); ++lines) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const int at = lines + 2;  // the file's line number
    const auto bad = [&](const std::string& what, const std::string& allowed) {
      return InputError({name, at, "mesh"}, what, allowed);
    };
    if (std::any_of(line.begin(), line.end(), [](char ch) { return static_cast<unsigned char>(ch) < 0x20 && ch != '\t'; }))
      throw bad("this line of the PLY header holds a control character", "printable text in the header");
    std::istringstream fields(line);
    std::vector<std::string> words;
    for (std::string w; fields >> w;) words.push_back(w);
    const std::string word = words.empty() ? std::string() : words[0];
    if (word == "end_header") {
      ended = true;
      break;
    }
    if (word == "format") {
      if (format) throw bad("the PLY header has a second format line", "one format line");
      if (words.size() != 3 || (words[1] != "ascii" && words[1] != "binary_little_endian" && words[1] != "binary_big_endian"))
        throw bad("this format line is not 'format <ascii|binary_little_endian|binary_big_endian> <version>'",
                  "format ascii 1.0, format binary_little_endian 1.0, format binary_big_endian 1.0");
      format = true;
    } else if (word == "element") {
      close();
      if (words.size() != 3 || words[2].find_first_not_of("0123456789") != std::string::npos)
        throw bad("this element line is not 'element <name> <count>'", "element <name> <count of digits>");
      element = words[1];
      count = 0;
      for (char ch : words[2]) {
        if (count > size) break;
        count = count * 10 + static_cast<std::uintmax_t>(ch - '0');
      }
      hasProperty = false;
      inElement = true;
    } else if (word == "property") {
      const bool list = words.size() == 5 && words[1] == "list" && isType(words[2]) && isType(words[3]);
      if (!list && !(words.size() == 3 && isType(words[1])))
        throw bad("this property line is not 'property <type> <name>' or 'property list <type> <type> <name>'",
                  "types char, uchar, short, ushort, int, uint, float, double (or int8 .. float64)");
      if (!inElement) throw bad("this property comes before any element", "property lines after an element line");
      hasProperty = true;
    } else if (word != "comment" && word != "obj_info" && !word.empty()) {
      throw bad("this line of the PLY header is not a header line",
                "format, comment, obj_info, element, property and end_header lines");
    }
  }
  if (!ended)
    throw InputError({name, 0, "mesh"},
                     lines >= 10000 ? std::string("the PLY header has more than 10000 lines")
                                    : std::string("the PLY header has no end_header line"),
                     "a PLY header ending with end_header");
  close();
  if (declared > size)
    throw InputError({name, 0, "mesh"},
                     fmt::format("the PLY header declares more elements than a {}-byte file can hold", size),
                     "element counts that fit in the file");
}

/// A binary STL (80-byte header, a 32-bit triangle count, 50 bytes per triangle) whose
/// count does not fit the file: assimp would otherwise fall back to reading it as ASCII
/// and fail with a puzzling message. ASCII files (starting with "solid" and holding
/// "facet") are left to assimp.
void checkStlCounts(const fs::path& file, const std::string& name, std::uintmax_t size) {
  if (lowerCase(file.extension().string()) != ".stl" || size < 84) return;
  std::ifstream in(file, std::ios::binary);
  std::array<char, 84> head{};
  if (!in.read(head.data(), head.size())) return;
  if (std::string_view(head.data(), 5) == "solid") {
    std::string start(512, '\0');
    in.seekg(0);
    in.read(start.data(), static_cast<std::streamsize>(start.size()));
    start.resize(static_cast<std::size_t>(in.gcount()));
    if (start.find("facet") != std::string::npos) return;  // ASCII STL
  }
  std::uint32_t count = 0;
  for (int k = 3; k >= 0; --k) count = (count << 8) | static_cast<unsigned char>(head[80 + static_cast<std::size_t>(k)]);
  const std::uintmax_t need = 84 + std::uintmax_t{50} * count;
  if (need > size)
    throw InputError({name, 0, "mesh"},
                     fmt::format("the binary STL header declares {} triangles, {} bytes, but the file has {}",
                                 count, need, size),
                     "a triangle count that fits the file (84 + 50 bytes a triangle)");
}

/// Every face of every mesh has indices, each a vertex of its mesh, and every vertex is
/// finite.
void checkFaces(const aiScene& scene, const std::string& name) {
  for (unsigned m = 0; m < scene.mNumMeshes; ++m) {
    const aiMesh* mesh = scene.mMeshes[m];
    if (mesh == nullptr) continue;
    if (mesh->mNumVertices > 0 && mesh->mVertices == nullptr)
      throw InputError({name, 0, "mesh"}, fmt::format("mesh {} has vertices without positions", m),
                       "vertex positions");
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace& face = mesh->mFaces[f];
      if (face.mNumIndices == 0 || face.mIndices == nullptr)
        throw InputError({name, 0, "mesh"}, fmt::format("face {} of mesh {} has no vertex indices", f, m),
                         "faces of at least one vertex index each");
      for (unsigned k = 0; k < face.mNumIndices; ++k)
        if (face.mIndices[k] >= mesh->mNumVertices)
          throw InputError({name, 0, "mesh"},
                           fmt::format("face {} of mesh {} uses vertex {}, but the mesh has {}", f, m,
                                       face.mIndices[k], mesh->mNumVertices),
                           "vertex indices below the vertex count");
    }
    // Before post-processing: joining identical vertices compares positions, and a NaN
    // one can be merged into another, leaving a degenerate triangle instead of this error.
    for (unsigned i = 0; i < mesh->mNumVertices; ++i) {
      const aiVector3D& p = mesh->mVertices[i];
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
        throw InputError({name, 0, "mesh"},
                         fmt::format("vertex {} of {} is not finite ({}, {}, {})", i, meshLabel(m, *mesh), p.x,
                                     p.y, p.z),
                         "finite coordinates");
    }
  }
}

// An MTL file read as if it had no UTF-8 byte-order mark (Windows editors save one).
// Offsets count from after the mark; the stream it wraps is its own (assimp's Close
// deletes this one).
class WithoutByteOrderMark : public Assimp::IOStream {
 public:
  explicit WithoutByteOrderMark(Assimp::IOStream* inner) : inner_(inner) {}
  ~WithoutByteOrderMark() override { delete inner_; }
  WithoutByteOrderMark(const WithoutByteOrderMark&) = delete;
  WithoutByteOrderMark& operator=(const WithoutByteOrderMark&) = delete;
  size_t Read(void* buffer, size_t size, size_t count) override { return inner_->Read(buffer, size, count); }
  size_t Write(const void* buffer, size_t size, size_t count) override {
    return inner_->Write(buffer, size, count);
  }
  aiReturn Seek(size_t offset, aiOrigin origin) override {
    return inner_->Seek(origin == aiOrigin_SET ? offset + kMark : offset, origin);
  }
  size_t Tell() const override { return inner_->Tell() - kMark; }
  size_t FileSize() const override { return inner_->FileSize() - kMark; }
  void Flush() override { inner_->Flush(); }

 private:
  static constexpr size_t kMark = 3;
  Assimp::IOStream* inner_;
};

// A stream over text it owns (the text is a base, so it is there before the stream's
// pointer to it).
struct TextHolder {
  std::string text;
};
class OwnedText : private TextHolder, public Assimp::MemoryIOStream {
 public:
  explicit OwnedText(std::string t)
      : TextHolder{std::move(t)},
        MemoryIOStream(reinterpret_cast<const std::uint8_t*>(text.data()), text.size(), false) {}
};

bool isBlank(char c) { return c == ' ' || c == '\t'; }

}  // namespace

std::string objForAssimp(std::string_view text) {
  if (text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);
  std::string out;
  out.reserve(text.size());
  bool continued = false;  // the last line ended with a backslash: this one is part of it
  while (!text.empty()) {
    const std::size_t end = text.find('\n');
    std::string_view line = text.substr(0, end);
    text.remove_prefix(end == std::string_view::npos ? text.size() : end + 1);
    const bool newline = end != std::string_view::npos;
    std::size_t at = 0;
    while (at < line.size() && isBlank(line[at])) ++at;
    const bool part = continued;
    {
      std::string_view body = line;
      if (!body.empty() && body.back() == '\r') body.remove_suffix(1);
      continued = !body.empty() && body.back() == '\\';
    }
    if (part) {  // the rest of a continued line: as it is
      out += line;
      if (newline) out += '\n';
      continue;
    }
    line.remove_prefix(at);  // assimp skipped an indented line (and shifted the vertex numbers after it)
    at = 0;
    std::size_t keywordEnd = at;
    while (keywordEnd < line.size() && !isBlank(line[keywordEnd]) && line[keywordEnd] != '\r') ++keywordEnd;
    const std::string_view keyword = line.substr(at, keywordEnd - at);
    if (keyword == "v" || keyword == "vt" || keyword == "vn" || keyword == "f" || keyword == "l" ||
        keyword == "p") {
      const bool carriageReturn = !line.empty() && line.back() == '\r';
      if (const std::size_t hash = line.find('#'); hash != std::string_view::npos)
        line = line.substr(0, hash);
      else if (carriageReturn) line.remove_suffix(1);
      // The fields after the keyword: exactly four on a v line drops the fourth.
      if (keyword == "v") {
        std::array<std::size_t, 5> begins{};
        std::size_t fields = 0, q = keywordEnd;
        while (q < line.size()) {
          while (q < line.size() && isBlank(line[q])) ++q;
          if (q >= line.size()) break;
          if (fields < begins.size()) begins[fields] = q;
          ++fields;
          while (q < line.size() && !isBlank(line[q])) ++q;
        }
        if (fields == 4) line = line.substr(0, begins[3]);
      }
      out += line;
      if (carriageReturn) out += '\r';
    } else {
      out += line;
    }
    if (newline) out += '\n';
  }
  return out;
}

namespace {

// Assimp's file system: OBJ files read through objForAssimp, MTL files past a
// byte-order mark.
class MeshIOSystem : public Assimp::DefaultIOSystem {
 public:
  Assimp::IOStream* Open(const char* file, const char* mode) override {
    Assimp::IOStream* stream = DefaultIOSystem::Open(file, mode);
    const std::string ext = lowerCase(fs::path(file).extension().string());
    if (stream == nullptr || (ext != ".obj" && ext != ".mtl") ||
        std::string_view(mode).find('r') == std::string_view::npos)
      return stream;
    if (ext == ".obj") {
      std::string raw(stream->FileSize(), '\0');
      const std::size_t got = raw.empty() ? 0 : stream->Read(raw.data(), 1, raw.size());
      raw.resize(got);
      delete stream;
      std::string clean = objForAssimp(raw);
      raw = std::string();  // a file of up to 1 GiB: not three copies at once
      return new OwnedText(std::move(clean));
    }
    unsigned char head[3] = {};
    if (stream->Read(head, 1, 3) == 3 && head[0] == 0xEF && head[1] == 0xBB && head[2] == 0xBF) {
      auto* past = new WithoutByteOrderMark(stream);
      past->Seek(0, aiOrigin_SET);
      return past;
    }
    stream->Seek(0, aiOrigin_SET);
    return stream;
  }
};

/// Assimp's file access for one mesh file: the files the mesh refers to (a glTF's
/// buffers, an OBJ's material library) are opened only inside `root`; the others are
/// refused and remembered, so that the error can name them.
class ConfinedIOSystem : public MeshIOSystem {
 public:
  explicit ConfinedIOSystem(fs::path root) : root_(std::move(root)) {}
  bool Exists(const char* file) const override { return allowed(file) && DefaultIOSystem::Exists(file); }
  Assimp::IOStream* Open(const char* file, const char* mode) override {
    return allowed(file) ? MeshIOSystem::Open(file, mode) : nullptr;
  }
  /// The refused paths, each quoted (and where a link took it).
  [[nodiscard]] const std::vector<std::string>& refused() const { return refused_; }

 private:
  bool allowed(const char* file) const {
    std::error_code ec;
    const fs::path target = fs::weakly_canonical(fs::path(file), ec);
    const fs::path rel = ec ? fs::path() : target.lexically_relative(root_);
    if (!rel.empty() && *rel.begin() != ".." && rel != ".") return true;
    // Only files that are there are named: assimp also probes names of its own making
    // (a material library's name cut short, the folder itself) that no one wrote.
    const fs::path given = fs::path(file).lexically_normal();
    std::error_code missing;
    if (!fs::is_regular_file(given, missing)) return false;
    // Quoted; with where it leads when a symbolic link takes it there (the name alone,
    // inside the folder, looks allowed).
    std::error_code absent;
    const fs::path plain = fs::absolute(given, absent).lexically_normal();
    const std::string shown = !ec && !absent && plain != target
                                  ? fmt::format("'{}' (a link to '{}')", given.string(), target.string())
                                  : fmt::format("'{}'", given.string());
    if (std::find(refused_.begin(), refused_.end(), shown) == refused_.end()) refused_.push_back(shown);
    return false;
  }
  fs::path root_;
  mutable std::vector<std::string> refused_;  // Exists is const in assimp's interface
};

}  // namespace

std::size_t orientConsistently(TriangleMesh& mesh) {
  // Each edge's uses (count) and its first two, as (triangle, +1 if the triangle runs it
  // from the lower vertex to the higher, -1 otherwise); only edges with exactly two uses
  // join triangles.
  const std::size_t n = mesh.triangles.size();
  struct Use {
    std::uint32_t triangle;
    std::int32_t direction;
  };
  struct Edge {
    std::uint32_t count = 0;
    std::array<Use, 2> uses{};
  };
  std::unordered_map<std::uint64_t, Edge> edges;
  edges.reserve(n * 2);
  for (std::uint32_t t = 0; t < n; ++t)
    for (std::size_t k = 0; k < 3; ++k) {
      const std::uint32_t a = mesh.triangles[t][k], b = mesh.triangles[t][(k + 1) % 3];
      if (a == b) continue;
      Edge& e = edges[edgeKey(a, b)];
      if (e.count < 2) e.uses[e.count] = Use{t, a < b ? 1 : -1};
      ++e.count;
    }
  // Neighbours through shared edges, and whether the two run it the same way (then one
  // of them must turn).
  std::vector<std::uint32_t> first(n + 1, 0);
  for (const auto& [key, e] : edges)
    if (e.count == 2) {
      ++first[e.uses[0].triangle + 1];
      ++first[e.uses[1].triangle + 1];
    }
  for (std::size_t t = 0; t < n; ++t) first[t + 1] += first[t];
  std::vector<std::pair<std::uint32_t, bool>> next(first[n]);
  std::vector<std::uint32_t> fill(first.begin(), first.end() - 1);
  for (const auto& [key, e] : edges)
    if (e.count == 2) {
      const bool same = e.uses[0].direction == e.uses[1].direction;
      next[fill[e.uses[0].triangle]++] = {e.uses[1].triangle, same};
      next[fill[e.uses[1].triangle]++] = {e.uses[0].triangle, same};
    }
  // Breadth-first over each part: turn[u] = turn[t] xor same.
  std::vector<std::int8_t> turn(n, -1);
  std::vector<std::uint32_t> part;
  std::size_t turned = 0;
  for (std::uint32_t seed = 0; seed < n; ++seed) {
    if (turn[seed] >= 0) continue;
    part.assign(1, seed);
    turn[seed] = 0;
    bool orientable = true;
    for (std::size_t q = 0; q < part.size(); ++q) {
      const std::uint32_t t = part[q];
      for (std::uint32_t e = first[t]; e < first[t + 1]; ++e) {
        const auto [u, same] = next[e];
        const std::int8_t want = static_cast<std::int8_t>(turn[t] ^ (same ? 1 : 0));
        if (turn[u] < 0) {
          turn[u] = want;
          part.push_back(u);
        } else if (turn[u] != want) {
          orientable = false;
        }
      }
    }
    if (!orientable) continue;
    std::size_t flips = 0;
    for (const std::uint32_t t : part) flips += static_cast<std::size_t>(turn[t]);
    const std::int8_t flip = flips * 2 > part.size() ? 0 : 1;  // the majority keeps its winding
    for (const std::uint32_t t : part)
      if (turn[t] == flip) {
        std::swap(mesh.triangles[t][1], mesh.triangles[t][2]);
        ++turned;
      }
  }
  return turned;
}

MeshEdges countEdges(const TriangleMesh& mesh) {
  std::unordered_map<std::uint64_t, std::uint32_t> uses;
  uses.reserve(mesh.triangles.size() * 2);
  for (const auto& t : mesh.triangles)
    for (std::size_t k = 0; k < 3; ++k) {
      const std::uint32_t a = t[k];
      const std::uint32_t b = t[(k + 1) % 3];
      if (a == b) continue;
      ++uses[edgeKey(a, b)];
    }
  MeshEdges out;
  for (const auto& [edge, n] : uses) {
    if (n == 1) ++out.boundary;
    if (n > 2) ++out.nonManifold;
  }
  return out;
}

std::string openMeshWarning(const MeshEdges& edges) {
  if (edges.boundary == 0) return {};
  return fmt::format(
      "the mesh is not closed ({} edge(s) belong to one triangle only): inside is decided by a majority "
      "of three ray directions; for a shell, fill the surface instead",
      edges.boundary);
}

TriangleMesh loadMesh(const fs::path& file, MeshLoadReport* report, const fs::path& confineTo) {
  const std::string name = file.string();
  const std::uintmax_t size = checkReadable(file, name);
  if (size == 0) throw InputError({name, 0, "mesh"}, "the mesh has no triangles (the file is empty)");
  checkPlyCounts(file, name, size);
  checkStlCounts(file, name, size);

  Assimp::Importer importer;
  ConfinedIOSystem* confined = nullptr;
  if (!confineTo.empty()) {
    std::error_code ec;
    fs::path root = fs::weakly_canonical(confineTo, ec);
    if (ec) root = confineTo;
    confined = new ConfinedIOSystem(root);
    importer.SetIOHandler(confined);  // the importer owns it from here
  } else {
    importer.SetIOHandler(new MeshIOSystem);
  }
  // Only steps that reshape what the file holds: nothing invents geometry (no normals,
  // hole filling or smoothing). SortByPType puts points and lines in meshes of their own,
  // which MeshBuilder skips; they are not removed here, so a file of points alone is
  // reported as having no triangles rather than as an assimp failure.
  // The file is read without post-processing and checked first: assimp's steps trust the
  // faces and abort the process on one without indices (found by the fuzzer:
  // fuzz/regressions/mesh_loader/ply-empty-faces-abort).
  const auto cannotParse = [&] {
    // A refusal is named first (it is the likely cause), with assimp's own words after it.
    if (confined != nullptr && !confined->refused().empty())
      return InputError({name, 0, "mesh"},
                        fmt::format("the mesh refers to {}, outside the scene's folder '{}' (a scene reads "
                                    "files only inside its folder; assimp: {})",
                                    confined->refused().front(), confineTo.string(),
                                    importer.GetErrorString()[0] != '\0' ? importer.GetErrorString() : "no reason given"),
                        "meshes whose own references (a glTF's buffers and images, an OBJ's material "
                        "library) lie in the scene's folder too: a scene and its folder are moved as a "
                        "whole");
    const std::string why = importer.GetErrorString();
    return InputError({name, 0, "mesh"},
                      fmt::format("cannot parse the file: {}", why.empty() ? "unknown error" : why),
                      "a mesh file assimp reads (OBJ, PLY, STL, glTF, FBX, ...)");
  };
  if (importer.ReadFile(name, 0) == nullptr) throw cannotParse();
  checkFaces(*importer.GetScene(), name);
  const aiScene* scene =
      importer.ApplyPostProcessing(aiProcess_Triangulate | aiProcess_JoinIdenticalVertices | aiProcess_SortByPType);
  if (scene == nullptr) throw cannotParse();

  MeshBuilder builder(name);
  if (scene->mRootNode != nullptr) {
    addNode(*scene, *scene->mRootNode, Mat4::Identity(), builder, 0);
  } else {
    for (unsigned m = 0; m < scene->mNumMeshes; ++m)
      if (scene->mMeshes[m] != nullptr) builder.add(*scene->mMeshes[m], m, Mat4::Identity());
  }
  TriangleMesh out = builder.finish(report);
  if (report != nullptr && confined != nullptr && !confined->refused().empty()) {
    // Each refused path named (the first few): each is a file to move into the folder.
    const std::vector<std::string>& refused = confined->refused();
    std::string names;
    const std::size_t shown = std::min<std::size_t>(refused.size(), 4);
    for (std::size_t k = 0; k < shown; ++k)
      names += fmt::format("{}{}", k == 0 ? "" : k + 1 == shown && shown == refused.size() ? " and " : ", ",
                           refused[k]);
    if (shown < refused.size()) names += fmt::format(" and {} more", refused.size() - shown);
    report->warnings.push_back(fmt::format(
        "did not read {}, which the mesh refers to: outside the scene's folder (a scene reads files only "
        "inside its folder)",
        names));
  }
  return out;
}

}  // namespace softsub::geometry
