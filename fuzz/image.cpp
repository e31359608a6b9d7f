// Fuzzes the image readers behind `pathlab compare`: readImage on EXR, PNG and
// PFM. The input's first bytes choose the file's extension (the EXR or PNG
// signature, else .pfm), so every reader sees inputs that reach past its
// signature check. As in OpenEXR's own fuzzers, EXR data windows are limited
// to 512×512: a header claiming the largest image pathlab accepts would
// otherwise make every such input allocate gigabytes, which is expected
// behaviour for a genuine file of that size, not a bug.
#include "core/image.h"

#include <ImfHeader.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "core/error.h"
#include "fuzz_util.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace pathlab;
    static const uint8_t exrMagic[4] = {0x76, 0x2f, 0x31, 0x01};
    static const uint8_t pngMagic[4] = {0x89, 'P', 'N', 'G'};
    static const bool limited = [] {
        Imf::Header::setMaxImageSize(512, 512);
        Imf::Header::setMaxTileSize(512, 512);
        return true;
    }();
    (void)limited;
    const char* name = "image.pfm";
    if (size >= 4 && std::memcmp(data, exrMagic, 4) == 0) name = "image.exr";
    if (size >= 4 && std::memcmp(data, pngMagic, 4) == 0) name = "image.png";
    const std::string path = fuzz::writeScratchFile(name, fuzz::asText(data, size));
    try {
        const Image img = readImage(path);
        if (img.width <= 0 || img.height <= 0 || img.rgb.size() != img.pixelCount() * 3) {
            std::fprintf(stderr, "readImage returned a %dx%d image with %zu floats\n", img.width,
                         img.height, img.rgb.size());
            std::abort();
        }
    } catch (const InputError&) {
    }
    return 0;
}
