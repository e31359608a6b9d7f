// A decoder for the DDS textures 0 A.D. ships (DXT1 and DXT5 block
// compression), so the wolf's texture can be used straight from the game data.
#pragma once

#include <cstdint>
#include <span>
#include <string>

#include "core/image.h"

namespace pathlab {

// Decodes the top mip level's colour (alpha is dropped), treating the stored
// 8-bit values as sRGB and returning linear RGB, top row first. Throws
// InputError for anything but a well-formed DXT1/DXT5 DDS file.
Image readDds(const std::string& path);
Image decodeDds(std::span<const uint8_t> bytes, const std::string& source);

}  // namespace pathlab
