// Fuzzes OBJ/MTL loading through loadScene (tinyobjloader, our material
// mapping, framing, validation). The input is an OBJ, optionally followed by
// a NUL byte and an MTL: they are written to mesh.obj and mesh.mtl in a
// scratch directory (the corpus's OBJs say "mtllib mesh.mtl").
#include <cstring>
#include <filesystem>
#include <string>

#include "core/error.h"
#include "fuzz_util.h"
#include "scene/loader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace pathlab;
    const std::string_view input = fuzz::asText(data, size);
    const size_t split = input.find('\0');
    const std::string obj = fuzz::writeScratchFile("mesh.obj", input.substr(0, split));
    const std::filesystem::path mtl = fuzz::scratchDir() / "mesh.mtl";
    if (split != std::string_view::npos) {
        fuzz::writeScratchFile("mesh.mtl", input.substr(split + 1));
    } else {
        std::error_code ec;
        std::filesystem::remove(mtl, ec);  // no MTL in this input
    }
    try {
        loadScene(obj);
    } catch (const InputError&) {
    }
    return 0;
}
