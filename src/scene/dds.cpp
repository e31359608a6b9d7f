// DDS layout: "DDS ", a 124-byte header (height at byte 12, width at 16, the
// pixel format's FourCC at 84), then the blocks of the top mip level at 128.
// Each 4×4 block stores two RGB565 end points and 2-bit indices choosing
// between them and two interpolated colours; DXT5 puts 8 bytes of alpha in
// front. Interpolation follows the D3D specification's 4-colour mode (DXT5
// always, DXT1 when colour0 > colour1; otherwise 3 colours and black).
#include "scene/dds.h"

#include <cstring>
#include <fstream>
#include <iterator>
#include <vector>

#include "core/error.h"

namespace pathlab {
namespace {

uint32_t le32(const uint8_t* p) {
    return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
}

struct Rgb8 {
    int r, g, b;
};

Rgb8 unpack565(uint16_t c) {
    const int r = (c >> 11) & 31, g = (c >> 5) & 63, b = c & 31;
    return {(r << 3) | (r >> 2), (g << 2) | (g >> 4), (b << 3) | (b >> 2)};
}

Rgb8 mix(Rgb8 a, Rgb8 b, int wa, int wb, int d) {
    return {(wa * a.r + wb * b.r) / d, (wa * a.g + wb * b.g) / d, (wa * a.b + wb * b.b) / d};
}

}  // namespace

Image decodeDds(std::span<const uint8_t> bytes, const std::string& source) {
    if (bytes.size() < 128 || std::memcmp(bytes.data(), "DDS ", 4) != 0 || le32(&bytes[4]) != 124)
        throw InputError("'" + source + "' is not a DDS file");
    const uint32_t height = le32(&bytes[12]), width = le32(&bytes[16]);
    const char* fourCC = reinterpret_cast<const char*>(&bytes[84]);
    int blockSize;
    if (std::memcmp(fourCC, "DXT1", 4) == 0)
        blockSize = 8;
    else if (std::memcmp(fourCC, "DXT5", 4) == 0)
        blockSize = 16;
    else
        throw InputError("DDS file '" + source + "' is not DXT1 or DXT5 compressed");
    if (width == 0 || height == 0 || width > 16384 || height > 16384)
        throw InputError("DDS file '" + source + "' has an invalid size");
    const size_t bw = (width + 3) / 4, bh = (height + 3) / 4;
    if (bytes.size() - 128 < bw * bh * blockSize)
        throw InputError("DDS file '" + source + "' is truncated");

    Image img(static_cast<int>(width), static_cast<int>(height));
    float toLinear[256];
    for (int i = 0; i < 256; ++i) toLinear[i] = srgbToLinear(i / 255.0f);
    const uint8_t* block = bytes.data() + 128;
    for (size_t by = 0; by < bh; ++by) {
        for (size_t bx = 0; bx < bw; ++bx, block += blockSize) {
            const uint8_t* colour = block + (blockSize - 8);  // skip DXT5's alpha
            const uint16_t c0 = uint16_t(colour[0] | colour[1] << 8);
            const uint16_t c1 = uint16_t(colour[2] | colour[3] << 8);
            Rgb8 palette[4];
            palette[0] = unpack565(c0);
            palette[1] = unpack565(c1);
            if (blockSize == 16 || c0 > c1) {
                palette[2] = mix(palette[0], palette[1], 2, 1, 3);
                palette[3] = mix(palette[0], palette[1], 1, 2, 3);
            } else {
                palette[2] = mix(palette[0], palette[1], 1, 1, 2);
                palette[3] = {0, 0, 0};
            }
            for (int y = 0; y < 4; ++y) {
                const uint8_t row = colour[4 + y];
                for (int x = 0; x < 4; ++x) {
                    const size_t px = bx * 4 + x, py = by * 4 + y;
                    if (px >= width || py >= height) continue;
                    const Rgb8 c = palette[(row >> (2 * x)) & 3];
                    img.set(int(px), int(py), {toLinear[c.r], toLinear[c.g], toLinear[c.b]});
                }
            }
        }
    }
    return img;
}

Image readDds(const std::string& path) {
    std::ifstream file(path, std::ios::binary);
    if (!file) throw InputError("cannot open '" + path + "'");
    const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(file)),
                                     std::istreambuf_iterator<char>());
    return decodeDds(bytes, path);
}

}  // namespace pathlab
