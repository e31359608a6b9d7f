#include "core/paths.h"

#include <cstdlib>

namespace pathlab {

std::filesystem::path cacheDirectory() {
    std::filesystem::path dir;
    if (const char* p = std::getenv("PATHLAB_CACHE"); p && *p) {
        dir = p;
    } else if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x) {
        dir = std::filesystem::path(x) / "pathlab";
    } else if (const char* h = std::getenv("HOME"); h && *h) {
        dir = std::filesystem::path(h) / ".cache" / "pathlab";
    } else {
        dir = std::filesystem::path(".cache") / "pathlab";
    }
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    return dir;
}

}  // namespace pathlab
