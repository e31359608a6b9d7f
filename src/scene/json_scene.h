// pathlab's JSON scene format (documented in docs/scene-format.md).
#pragma once

#include <filesystem>
#include <string>

#include "scene/scene.h"

namespace pathlab {

// Reads a scene file. Paths inside it (OBJ meshes, textures) are relative to
// the file's directory. Strict: malformed JSON (reported with line and
// column), unknown or duplicate keys, wrong types, missing required fields
// and references to undefined materials are InputErrors naming the key.
SceneDescription loadJsonScene(const std::string& path);

// The same for text in memory; `source` names it in errors.
SceneDescription parseJsonScene(const std::string& text, const std::filesystem::path& baseDir,
                                const std::string& source);

// Writes `scene` in the format, meshes as indexed triangle lists. Textures
// have no file to refer to, so a textured material is an InputError.
// parseJsonScene(sceneToJson(s)) reproduces s exactly.
std::string sceneToJson(const SceneDescription& scene);

}  // namespace pathlab
