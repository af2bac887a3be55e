#pragma once
/// Helpers shared by the scene tests: wrapping snippets into scenes and finding lines.
#include <gtest/gtest.h>
#include <stdlib.h>

#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>

#include "core/error.h"
#include "scene/reader.h"

namespace softsub::scene::testing {

/// 1-based line of the first line containing marker, 0 if none.
inline int lineOf(std::string_view text, std::string_view marker) {
  const std::size_t at = text.find(marker);
  if (at == std::string_view::npos) return 0;
  int line = 1;
  for (std::size_t i = 0; i < at; ++i) line += text[i] == '\n' ? 1 : 0;
  return line;
}

/// A fluid element that is valid on its own (a 2x2x2 box fill).
inline std::string validFluid(std::string_view name) {
  return "<Fluid><Name>" + std::string(name) +
         "</Name><Fill><Shape>box</Shape><Max>2 2 2</Max></Fill></Fluid>\n";
}

/// "<Scene version="1">" + body + "</Scene>", each on its own lines.
inline std::string sceneWith(std::string_view body) {
  return "<Scene version=\"1\">\n" + std::string(body) + "\n</Scene>\n";
}

/// Reads text expecting an InputError; fails the test if none comes.
inline InputError readError(std::string_view text, const ReadOptions& options = {}) {
  try {
    (void)readSceneText(text, "t.scene", options);
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "no InputError for:\n" << text;
  return InputError({}, "none");
}

/// A fresh folder under the system's temporary folder, removed with its contents.
class TempFolder {
 public:
  TempFolder() {
    std::string pattern =
        (std::filesystem::temp_directory_path() / "softsub-scene-XXXXXX").string();
    if (mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("mkdtemp failed");
    path_ = pattern;
  }
  ~TempFolder() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TempFolder(const TempFolder&) = delete;
  TempFolder& operator=(const TempFolder&) = delete;
  [[nodiscard]] const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

/// Reads the scene file expecting an InputError; fails the test when it reads.
inline InputError readFileError(const std::filesystem::path& scene, const ReadOptions& options = {}) {
  try {
    (void)readSceneFile(scene.string(), options);
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "accepted " << scene;
  return InputError({}, "");
}

}  // namespace softsub::scene::testing
