// A reader for 0 A.D.'s PMD model format, version 4 (the wolf's mesh).
#pragma once

#include <cstdint>
#include <span>
#include <string>

#include "scene/scene.h"

namespace pathlab {

// Reads a PMD v4 file into a mesh with positions, normals, the first UV set
// (v flipped to our top-row-first convention) and triangles, in the stored
// bind pose (skinning is ignored). Throws
// InputError naming the file when it cannot be read, is not PMD v4, disagrees
// with its own sizes, has an index out of range or a non-finite value.
Mesh readPmd(const std::string& path);

// The same for bytes already in memory; `source` names them in errors.
Mesh parsePmd(std::span<const uint8_t> bytes, const std::string& source);

}  // namespace pathlab
