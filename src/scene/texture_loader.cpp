#include "scene/texture_loader.h"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "core/error.h"
#include "scene/dds.h"

namespace pathlab {

Texture textureFromImage(const Image& image) {
    Texture t;
    t.width = image.width;
    t.height = image.height;
    t.texels.resize(image.pixelCount());
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x)
            t.texels[size_t(y) * image.width + x] = image.at(x, y);
    return t;
}

Texture loadTexture(const std::string& path) {
    if (!std::filesystem::is_regular_file(path))
        throw InputError("texture '" + path + "' does not exist");
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return textureFromImage(ext == ".dds" ? readDds(path) : readImage(path));
}

}  // namespace pathlab
