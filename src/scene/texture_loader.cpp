#include "scene/texture_loader.h"

#include <algorithm>
#include <cctype>
#include <cmath>
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

namespace {

// A texture is an albedo: a NaN, infinite or negative texel would be a
// colour no material can have (docs/scene-format.md), and would reach the
// image as NaN samples the renderer silently discards.
void requireValidTexels(const Texture& t, const std::string& path) {
    for (size_t i = 0; i < t.texels.size(); ++i) {
        const Vec3f c = t.texels[i];
        const bool finite = std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z);
        if (finite && c.x >= 0 && c.y >= 0 && c.z >= 0) continue;
        throw InputError("texture '" + path + "' has a " +
                         (finite ? "negative" : "NaN or infinite") + " texel at (" +
                         std::to_string(i % size_t(t.width)) + ", " +
                         std::to_string(i / size_t(t.width)) + ")");
    }
}

}  // namespace

Texture loadTexture(const std::string& path) {
    if (!std::filesystem::is_regular_file(path))
        throw InputError("texture '" + path + "' does not exist");
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    Texture t = textureFromImage(ext == ".dds" ? readDds(path) : readImage(path));
    requireValidTexels(t, path);
    return t;
}

}  // namespace pathlab
