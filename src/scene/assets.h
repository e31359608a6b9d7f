// Where the data of the scenes that are not built from code (the wolf) lives,
// and how it is obtained when it is nowhere on this machine.
#pragma once

#include <filesystem>

namespace pathlab {

struct WolfAssets {
    std::filesystem::path mesh;     // wolf.pmd
    std::filesystem::path texture;  // the game's animal_wolf_grey.dds, else a .png of it
};

// Looks for wolf/wolf.pmd and wolf/animal_wolf_grey.{dds,png} in, in order:
// $PATHLAB_ASSETS (when set), cacheDirectory()/assets. When neither has them,
// extracts the two files from Debian's 0ad-data package into the cache (one
// line on stderr; a 1.4 GB download, the package is not installed) — see
// docs/scenes.md. Throws InputError when that fails.
WolfAssets locateWolfAssets();

// The same search without the download; false when not found.
bool findWolfAssets(WolfAssets& out);

}  // namespace pathlab
