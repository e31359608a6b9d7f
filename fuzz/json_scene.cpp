// Fuzzes the JSON scene parser (docs/scene-format.md) with the validation every
// loaded scene gets, and checks that a valid scene without textures, written
// by sceneToJson, reads back as a valid scene with as many materials, meshes
// and spheres.
// Files the scene names resolve against a scratch directory that holds one
// small OBJ, "tri.obj".
#include "scene/json_scene.h"

#include <cstdio>
#include <cstdlib>
#include <string>

#include "core/error.h"
#include "fuzz_util.h"
#include "scene/validate.h"

namespace {

const std::filesystem::path& sceneDir() {
    static const std::filesystem::path dir = [] {
        pathlab::fuzz::writeScratchFile("tri.obj",
                                        "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\n");
        return pathlab::fuzz::scratchDir();
    }();
    return dir;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace pathlab;
    const std::string text(fuzz::asText(data, size));
    SceneDescription scene;
    try {
        scene = parseJsonScene(text, sceneDir(), "fuzz.json");
        validateScene(scene, "fuzz.json");
    } catch (const InputError&) {
        return 0;
    }
    for (const Material& m : scene.materials)
        if (m.texture >= 0) return 0;  // textures have no file to write
    const std::string written = sceneToJson(scene);
    SceneDescription again;
    try {
        again = parseJsonScene(written, sceneDir(), "fuzz.json");
        validateScene(again, "fuzz.json");
    } catch (const InputError& e) {
        std::fprintf(stderr, "a written scene does not read back: %s\n%s", e.what(),
                     written.c_str());
        std::abort();
    }
    if (again.materials.size() != scene.materials.size() ||
        again.meshes.size() != scene.meshes.size() ||
        again.spheres.size() != scene.spheres.size()) {
        std::fprintf(stderr, "a written scene reads back with other counts:\n%s", written.c_str());
        std::abort();
    }
    return 0;
}
