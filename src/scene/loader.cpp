#include "scene/loader.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "core/error.h"
#include "scene/builtin_scenes.h"
#include "scene/json_scene.h"
#include "scene/mesh_utils.h"
#include "scene/obj_loader.h"
#include "scene/pbrt/importer.h"
#include "scene/validate.h"

namespace pathlab {
namespace fs = std::filesystem;

std::vector<std::string> builtinSceneNames() {
    return {"cornell-box", "wolf"};
}

SceneDescription loadObjScene(const std::string& path) {
    SceneDescription scene;
    scene.name = fs::path(path).stem().string();
    appendObj(scene, path);
    const Bounds3f b = sceneBounds(scene);
    if (b.empty()) throw InputError("OBJ file '" + path + "' has no faces");
    const bool lit = std::any_of(scene.meshes.begin(), scene.meshes.end(),
                                 [](const Mesh& m) { return !isBlack(m.emission); });
    if (!lit) scene.environment = Vec3f(1.0f);
    scene.camera.fovY = 40;
    // A distance at which the bounding sphere fits the vertical field of view.
    const float radius = std::max(0.5f * length(b.extent()), 1e-6f);
    const float distance = radius / std::sin(0.5f * scene.camera.fovY * kPi / 180.0f);
    scene.camera.target = b.center();
    scene.camera.eye = b.center() + normalize(Vec3f(0.3f, 0.35f, 1.0f)) * distance;
    scene.camera.up = {0, 1, 0};
    return scene;
}

namespace {

SceneDescription loadPbrtScene(const std::string& path, const SceneLoadOptions& options) {
    pbrt::ImportResult r = pbrt::importPbrtFile(path, {options.lenient});
    for (const std::string& note : r.notes) std::fprintf(stderr, "pathlab: %s\n", note.c_str());
    for (const std::string& w : r.warnings) std::fprintf(stderr, "pathlab: %s\n", w.c_str());
    if (!r.warnings.empty())
        std::fprintf(stderr, "pathlab: %s: %zu unsupported feature%s substituted (--lenient)\n",
                     path.c_str(), r.warnings.size(), r.warnings.size() == 1 ? "" : "s");
    return std::move(r.scene);
}

}  // namespace

SceneDescription loadScene(const std::string& nameOrPath, const SceneLoadOptions& options) {
    SceneDescription scene;
    if (nameOrPath == "cornell-box") {
        scene = cornellBoxScene();
    } else if (nameOrPath == "wolf") {
        scene = wolfScene();
    } else {
        std::error_code ec;
        if (!fs::exists(nameOrPath, ec))
            throw InputError(
                "unknown scene '" + nameOrPath +
                "': neither a built-in scene (cornell-box, wolf) nor an existing file");
        if (!fs::is_regular_file(nameOrPath, ec))
            throw InputError("scene '" + nameOrPath + "' is not a regular file");
        std::string ext = fs::path(nameOrPath).extension().string();
        std::transform(ext.begin(), ext.end(), ext.begin(),
                       [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
        if (ext == ".json")
            scene = loadJsonScene(nameOrPath);
        else if (ext == ".obj")
            scene = loadObjScene(nameOrPath);
        else if (ext == ".pbrt")
            scene = loadPbrtScene(nameOrPath, options);
        else
            throw InputError("scene file '" + nameOrPath + "' has an unsupported type '" + ext +
                             "' (expected .json, .obj or .pbrt)");
    }
    validateScene(scene, nameOrPath);
    return scene;
}

}  // namespace pathlab
