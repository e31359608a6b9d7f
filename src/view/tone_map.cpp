#include "view/tone_map.h"

#include <png.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace pathlab::view {

float toneMapValue(float linear, float scale, ToneMap toneMap) {
    float v = linear * scale;
    if (!(v > 0)) return 0;  // also NaN
    switch (toneMap) {
        case ToneMap::Linear:
            return std::min(v, 1.0f);
        case ToneMap::Srgb:
            return linearToSrgb(std::min(v, 1.0f));
        case ToneMap::Aces: {
            const float a = 2.51f, b = 0.03f, c = 2.43f, d = 0.59f, e = 0.14f;
            v = std::isfinite(v) ? (v * (a * v + b)) / (v * (c * v + d) + e) : 1.0f;
            return linearToSrgb(std::clamp(v, 0.0f, 1.0f));
        }
    }
    return 0;
}

std::string encodeDisplayPng(const Image& image, float exposure, ToneMap toneMap) {
    const float scale = std::exp2(exposure);
    std::vector<unsigned char> pixels(image.rgb.size());
    for (size_t i = 0; i < pixels.size(); ++i)
        pixels[i] = (unsigned char)std::lround(toneMapValue(image.rgb[i], scale, toneMap) * 255);
    png_image png{};
    png.version = PNG_IMAGE_VERSION;
    png.width = png_uint_32(image.width);
    png.height = png_uint_32(image.height);
    png.format = PNG_FORMAT_RGB;
    png.flags = PNG_IMAGE_FLAG_FAST;  // streamed every pass: speed over size
    png_alloc_size_t size = PNG_IMAGE_PNG_SIZE_MAX(png);
    std::string bytes(size, '\0');
    if (!png_image_write_to_memory(&png, bytes.data(), &size, 0, pixels.data(), 0, nullptr))
        throw std::runtime_error(std::string("PNG encoder: ") + png.message);
    bytes.resize(size);
    return bytes;
}

}  // namespace pathlab::view
