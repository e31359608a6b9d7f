// Reading image files into scene textures.
#pragma once

#include <string>

#include "core/image.h"
#include "scene/scene.h"

namespace pathlab {

Texture textureFromImage(const Image& image);

// PNG (sRGB, decoded to linear), EXR and PFM (linear) through readImage, and
// DXT1/DXT5 DDS (sRGB). Throws InputError naming the file otherwise, and for
// a NaN, infinite or negative texel.
Texture loadTexture(const std::string& path);

}  // namespace pathlab
