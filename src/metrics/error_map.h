// Writing FLIP error maps.
#pragma once

#include <string>
#include <vector>

#include "core/image.h"

namespace pathlab {

// The error map as an image: for PNG targets each pixel is coloured with the
// magma map (written so the PNG holds magma's sRGB values exactly); for EXR and
// PFM targets the raw error is stored in all three channels, for analysis.
Image errorMapImage(const std::vector<float>& errors, int width, int height, ImageFormat target);

// Writes the error map atomically (no partial file on failure); throws
// InputError when `path` cannot be written.
void writeErrorMap(const std::string& path, const std::vector<float>& errors, int width,
                   int height);

}  // namespace pathlab
