#pragma once
/// Writing a SceneDesc as a .scene file: every field explicitly (defaults too), numbers in
/// shortest round-trip form, so that reading the text back gives the same description.
#include <string>

#include "scene/scene_desc.h"

namespace softsub::scene {

/// The scene as .scene text. For a valid description d (one the reader can produce:
/// fills carry only their own shape's fields), readSceneText(writeSceneText(d)) == d.
std::string writeSceneText(const SceneDesc& scene);

/// Writes the scene to path through a temporary file in the same folder and a rename,
/// so path holds the old scene or the whole new one. Throws IoError on failure.
void writeSceneFile(const SceneDesc& scene, const std::string& path);

}  // namespace softsub::scene
