#include "cache/obj_format.h"

#include <charconv>
#include <stdexcept>

#include <fmt/format.h>

#include "core/error.h"

namespace softsub::cache {

std::string encodeObj(const ObjectMesh& mesh) {
  std::string out;
  out.reserve(64 + 40 * mesh.vertices.size() + 24 * mesh.triangles.size());
  auto it = std::back_inserter(out);
  const bool withNormals = !mesh.normals.empty();
  if (withNormals && mesh.normals.size() != mesh.vertices.size())
    throw std::invalid_argument(fmt::format("OBJ of '{}': {} normals for {} vertices", mesh.name,
                                            mesh.normals.size(), mesh.vertices.size()));
  fmt::format_to(it, "# softsub {}: {} vertices, {} triangles\no {}\n",
                 mesh.comment.empty() ? std::string_view("rigid body geometry") : std::string_view(mesh.comment),
                 mesh.vertices.size(), mesh.triangles.size(), mesh.name);
  for (const auto& v : mesh.vertices) fmt::format_to(it, "v {} {} {}\n", v[0], v[1], v[2]);
  for (const auto& n : mesh.normals) fmt::format_to(it, "vn {} {} {}\n", n[0], n[1], n[2]);
  for (const auto& t : mesh.triangles) {
    for (const std::uint32_t i : t)
      if (i >= mesh.vertices.size())
        throw std::invalid_argument(fmt::format("OBJ of '{}': vertex index {} out of range", mesh.name, i));
    if (withNormals) {
      fmt::format_to(it, "f {0}//{0} {1}//{1} {2}//{2}\n", t[0] + 1, t[1] + 1, t[2] + 1);
    } else {
      fmt::format_to(it, "f {} {} {}\n", t[0] + 1, t[1] + 1, t[2] + 1);
    }
  }
  return out;
}

namespace {

// Parses `count` numbers of type T from `rest`; false if there are not exactly that many.
template <class T, std::size_t N>
bool parseNumbers(std::string_view rest, std::array<T, N>& out) {
  const char* p = rest.data();
  const char* end = rest.data() + rest.size();
  for (std::size_t k = 0; k < N; ++k) {
    while (p < end && (*p == ' ' || *p == '\t')) ++p;
    const auto [next, ec] = std::from_chars(p, end, out[k]);
    if (ec != std::errc()) return false;
    p = next;
  }
  while (p < end && (*p == ' ' || *p == '\t' || *p == '\r')) ++p;
  return p == end;
}

// Parses a face `a b c` whose corners may carry `/t`, `/t/n` or `//n` after the vertex
// number (only the vertex number is kept); false unless exactly three corners.
bool parseFace(std::string_view rest, std::array<std::uint32_t, 3>& out) {
  const char* p = rest.data();
  const char* end = rest.data() + rest.size();
  for (std::size_t k = 0; k < 3; ++k) {
    while (p < end && (*p == ' ' || *p == '\t')) ++p;
    const auto [next, ec] = std::from_chars(p, end, out[k]);
    if (ec != std::errc()) return false;
    p = next;
    while (p < end && (*p == '/' || (*p >= '0' && *p <= '9'))) ++p;
  }
  while (p < end && (*p == ' ' || *p == '\t' || *p == '\r')) ++p;
  return p == end;
}

}  // namespace

ObjectMesh decodeObj(std::string_view text, const std::string& fileName) {
  ObjectMesh mesh;
  int line = 0;
  while (!text.empty()) {
    ++line;
    const std::size_t nl = text.find('\n');
    const std::string_view row = text.substr(0, nl);
    text = nl == std::string_view::npos ? std::string_view{} : text.substr(nl + 1);
    if (row.starts_with("o ")) {
      mesh.name = std::string(row.substr(2));
    } else if (row.starts_with("v ")) {
      if (!parseNumbers(row.substr(2), mesh.vertices.emplace_back()))
        throw InputError({fileName, line, "v"}, "not three numbers", "v x y z");
    } else if (row.starts_with("vn ")) {
      if (!parseNumbers(row.substr(3), mesh.normals.emplace_back()))
        throw InputError({fileName, line, "vn"}, "not three numbers", "vn x y z");
    } else if (row.starts_with("f ")) {
      std::array<std::uint32_t, 3> f{};
      if (!parseFace(row.substr(2), f) || f[0] == 0 || f[1] == 0 || f[2] == 0)
        throw InputError({fileName, line, "f"}, "not three vertex numbers", "f a b c, 1-based");
      mesh.triangles.push_back({f[0] - 1, f[1] - 1, f[2] - 1});
    }
  }
  for (const auto& t : mesh.triangles)
    for (const std::uint32_t i : t)
      if (i >= mesh.vertices.size())
        throw InputError({fileName, 0, "f"}, fmt::format("vertex {} does not exist", i + 1),
                         fmt::format("1..{}", mesh.vertices.size()));
  return mesh;
}

std::string geometryFileName(std::string_view sceneName, std::string_view objectName) {
  return fmt::format("{}Geo/{}.obj", sceneName, objectName);
}

}  // namespace softsub::cache
