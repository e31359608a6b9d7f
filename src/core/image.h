// Linear RGB float images and their file formats: OpenEXR (linear HDR), PNG
// (sRGB, 8 or 16 bit) and PFM. Every writer is atomic: the file appears
// complete under its name, or not at all.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "core/math.h"

namespace pathlab {

struct Image {
    int width = 0, height = 0;
    std::vector<float> rgb;  // row-major, top row first, 3 floats per pixel, linear

    Image() = default;
    Image(int w, int h) : width(w), height(h), rgb(size_t(w) * size_t(h) * 3, 0.0f) {}
    size_t pixelCount() const { return size_t(width) * size_t(height); }
    Vec3f at(int x, int y) const {
        const float* p = &rgb[(size_t(y) * width + x) * 3];
        return {p[0], p[1], p[2]};
    }
    void set(int x, int y, Vec3f c) {
        float* p = &rgb[(size_t(y) * width + x) * 3];
        p[0] = c.x, p[1] = c.y, p[2] = c.z;
    }
};

// The largest width and height pathlab renders or reads.
constexpr int kMaxImageSide = 16384;

enum class ImageFormat { Exr, Png, Pfm };

// The format implied by a file name's extension (case-insensitive); throws
// InputError for anything else.
ImageFormat imageFormatFromPath(const std::string& path);

// Reads EXR (R,G,B or Y channels as float), PNG (sRGB decoded to linear) or PFM.
// Throws InputError naming the file and the problem, also for an image wider
// or taller than kMaxImageSide (checked before allocating).
Image readImage(const std::string& path);

// Writes the format given by the extension. PNG is sRGB-encoded, clamped to
// [0,1] after multiplying by 2^exposure. The file is encoded in memory and
// written with writeFileAtomic: it is complete and on disk once its name
// exists. Throws InputError naming the target and the cause (e.g. "no space
// left on device writing 'x.exr'"); never leaves a partial file behind.
void writeImage(const std::string& path, const Image& image, float exposure = 0.0f);

// The bytes of the file writeImage would write (a server sends them as is).
std::string encodeImage(const Image& image, ImageFormat format, float exposure = 0.0f);

// Fails early (InputError) when `path` cannot be created: missing directory or
// no permission. Used before long computations so no work is lost.
void checkWritable(const std::string& path);
// The same for a file of any kind: only its directory is checked.
void checkDirectoryWritable(const std::string& path);

float srgbToLinear(float v);
float linearToSrgb(float v);

}  // namespace pathlab
