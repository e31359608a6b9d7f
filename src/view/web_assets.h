// The page `pathlab view` serves (src/view/web), compiled into the program by
// src/view/embed_web.cmake so that no file is read at run time.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace pathlab::view {

struct WebAsset {
    const char* path;  // "/index.html"
    const unsigned char* data;
    size_t size;
};

const std::vector<WebAsset>& webAssets();

}  // namespace pathlab::view
