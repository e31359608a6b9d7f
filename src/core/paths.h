// Where pathlab keeps files it generates once and reuses (blue-noise textures,
// scene assets, reference renders).
#pragma once

#include <filesystem>

namespace pathlab {

// $PATHLAB_CACHE if set, else $XDG_CACHE_HOME/pathlab, else ~/.cache/pathlab,
// else .cache/pathlab in the working directory. Created on first use.
std::filesystem::path cacheDirectory();

}  // namespace pathlab
