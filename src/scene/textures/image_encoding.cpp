#include "scene/textures/image_encoding.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "core/image.h"

namespace pathlab {

std::optional<ImageEncoding> parseImageEncoding(const std::string& text) {
    if (text == "sRGB") return ImageEncoding{ImageEncoding::Srgb, 1};
    if (text == "linear") return ImageEncoding{ImageEncoding::Linear, 1};
    const std::string prefix = "gamma ";
    if (text.rfind(prefix, 0) != 0) return std::nullopt;
    const char* begin = text.c_str() + prefix.size();
    char* end = nullptr;
    const float g = std::strtof(begin, &end);
    if (end == begin || *end != '\0' || !(g > 0) || !std::isfinite(g)) return std::nullopt;
    return ImageEncoding{ImageEncoding::Gamma, g};
}

void reencodeTexels(Texture& texture, ImageEncoding encoding) {
    if (encoding.kind == ImageEncoding::Srgb) return;
    const auto decode = [&](float v) {
        const float code = std::clamp(linearToSrgb(v), 0.0f, 1.0f);
        return encoding.kind == ImageEncoding::Linear ? code : std::pow(code, encoding.gamma);
    };
    for (Vec3f& c : texture.texels) c = {decode(c.x), decode(c.y), decode(c.z)};
}

}  // namespace pathlab
