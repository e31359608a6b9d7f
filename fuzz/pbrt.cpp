// Fuzzes the pbrt-v4 importer (tokenizer, parameter lists, directives, the
// graphics state) strictly and leniently, then the validation every loaded
// scene gets. Files a scene names resolve against a scratch directory holding
// a small include file and a small PLY mesh.
#include <string>

#include "core/error.h"
#include "fuzz_util.h"
#include "scene/pbrt/importer.h"
#include "scene/validate.h"

namespace {

const std::string& sceneDir() {
    static const std::string dir = [] {
        pathlab::fuzz::writeScratchFile(
            "tri.pbrt", "Shape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0]\n");
        pathlab::fuzz::writeScratchFile("tri.ply",
                                        "ply\nformat ascii 1.0\nelement vertex 3\n"
                                        "property float x\nproperty float y\nproperty float z\n"
                                        "element face 1\nproperty list uchar int vertex_indices\n"
                                        "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
        return pathlab::fuzz::scratchDir().string();
    }();
    return dir;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace pathlab;
    const std::string text(fuzz::asText(data, size));
    for (bool lenient : {false, true}) {
        try {
            // A budget of triangles keeps subdivision from outgrowing the fuzzer's time.
            pbrt::ImportResult r =
                pbrt::importPbrtText(text, "fuzz.pbrt", sceneDir(), {lenient, 200000});
            validateScene(r.scene, "fuzz.pbrt");
        } catch (const InputError&) {
        }
    }
    return 0;
}
