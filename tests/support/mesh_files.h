#pragma once
// Mesh files written by tests (the loader, mesh fills, `softsub fill`).
#include <filesystem>
#include <fstream>
#include <string>

namespace softsub::scenarios {

/// Writes `text` to `file`, creating its folder.
inline void writeTextFile(const std::filesystem::path& file, const std::string& text) {
  std::filesystem::create_directories(file.parent_path());
  std::ofstream out(file, std::ios::binary);
  out << text;
}

/// A closed box [0,a]^3 as an OBJ with quads, counter-clockwise from outside.
inline std::string boxObj(double a) {
  std::string s;
  for (int k = 0; k < 8; ++k) {
    s += "v " + std::to_string(k & 1 ? a : 0) + ' ' + std::to_string(k & 2 ? a : 0) + ' ' +
         std::to_string(k & 4 ? a : 0) + '\n';
  }
  return s + "f 1 5 7 3\nf 2 4 8 6\nf 1 2 6 5\nf 3 7 8 4\nf 1 3 4 2\nf 5 6 8 7\n";
}

}  // namespace softsub::scenarios
