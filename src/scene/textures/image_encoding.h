// The colour encoding of an 8-bit image texture (pbrt-v4's ColorEncoding:
// "sRGB", "linear", "gamma G"): how its code values become linear values.
// readImage decodes PNG as sRGB; reencodeTexels turns those values into what
// another encoding gives the same code values.
#pragma once

#include <optional>
#include <string>

#include "scene/scene.h"

namespace pathlab {

struct ImageEncoding {
    enum Kind { Srgb, Linear, Gamma } kind = Srgb;
    float gamma = 1;
};

// "sRGB", "linear" or "gamma G" (G a positive number); nullopt otherwise.
std::optional<ImageEncoding> parseImageEncoding(const std::string& text);

// Texels decoded as sRGB (readImage's PNG) decoded instead by `encoding`:
// code value c = linearToSrgb(v), then c (linear) or c^G (gamma G).
void reencodeTexels(Texture& texture, ImageEncoding encoding);

}  // namespace pathlab
