#include "metrics/error_map.h"

#include "metrics/colormap.h"

namespace pathlab {

Image errorMapImage(const std::vector<float>& errors, int width, int height, ImageFormat target) {
    Image image(width, height);
    for (size_t i = 0; i < image.pixelCount(); ++i) {
        if (target == ImageFormat::Png) {
            // The PNG writer sRGB-encodes linear values; decoding magma's sRGB
            // entries first makes the encoded bytes the map's own.
            const std::array<float, 3> c = magmaSrgb(errors[i]);
            for (int k = 0; k < 3; ++k) image.rgb[3 * i + k] = srgbToLinear(c[k]);
        } else {
            for (int k = 0; k < 3; ++k) image.rgb[3 * i + k] = errors[i];
        }
    }
    return image;
}

void writeErrorMap(const std::string& path, const std::vector<float>& errors, int width,
                   int height) {
    writeImage(path, errorMapImage(errors, width, height, imageFormatFromPath(path)));
}

}  // namespace pathlab
