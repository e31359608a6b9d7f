// pbrt-v4 scene files (docs/pbrt-format.md lists the supported subset,
// directive by directive). Our own reader, written after pbrt-v4's file-format
// documentation and its parser (src/pbrt/parser.cpp, scene.cpp).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace pathlab::pbrt {

struct ImportOptions {
    // Strict (false): anything pbrt-v4 supports and pathlab does not is an
    // InputError "FILE:LINE:COL: …" naming it. Lenient: each is substituted
    // (an unknown material by diffuse grey, an unsupported light or shape
    // dropped, an unknown parameter ignored) with a warning.
    bool lenient = false;
    // A scene whose shapes would make more triangles than this is refused
    // (a loopsubdiv's levels multiply its faces by 4 each).
    size_t maxTriangles = size_t(1) << 31;
};

struct ImportResult {
    SceneDescription scene;
    std::vector<std::string> warnings;  // one line each, "FILE:LINE:COL: warning: …"
    std::vector<std::string> notes;     // harmless things ignored (Option, filename, …)
};

// Reads FILE.pbrt and what it includes. Throws InputError with one line for
// any error. The scene is not yet validated (loadScene does that).
ImportResult importPbrtFile(const std::string& path, const ImportOptions& options = {});

// The same for text in memory (tests, fuzzing); `fileName` names it in errors
// and relative paths resolve against `baseDir`.
ImportResult importPbrtText(const std::string& text, const std::string& fileName,
                            const std::string& baseDir, const ImportOptions& options = {});

}  // namespace pathlab::pbrt
