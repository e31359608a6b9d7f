// The one entry point from a scene's name or file to a SceneDescription.
#pragma once

#include <string>
#include <vector>

#include "scene/scene.h"

namespace pathlab {

struct SceneLoadOptions {
    // pbrt-v4 files: substitute what pathlab does not support, with a warning
    // on stderr for each and a summary line (pbrt::ImportOptions::lenient).
    bool lenient = false;
};

// "cornell-box" and "wolf" are built in; anything else is a file path:
//   .json  pathlab's scene format (docs/scene-format.md);
//   .obj   a bare OBJ/MTL model (see loadObjScene);
//   .pbrt  a pbrt-v4 scene (docs/pbrt-format.md).
// The result is validated (validateScene). Throws InputError with one line
// for an unknown name, a missing or unreadable file, or a bad scene.
SceneDescription loadScene(const std::string& nameOrPath, const SceneLoadOptions& options = {});

// An OBJ/MTL model as a scene: the camera frames its bounding sphere from the
// +z side, a little above and to the right (fovY 40°); the model's own
// emitters light it, or, when it has none, a constant white environment of
// radiance 1 (an overcast sky that shows the shape). 512×512.
SceneDescription loadObjScene(const std::string& path);

// The names loadScene accepts without a file.
std::vector<std::string> builtinSceneNames();

}  // namespace pathlab
