// Reading EXR files written by other programs: their data window may start
// anywhere, negative coordinates included, and the pixels must land at the
// image's (0, 0) onwards.
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfOutputFile.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <vector>

#include "cli_runner.h"
#include "core/image.h"

namespace pathlab {
namespace {

// A w×h RGB file whose data window starts at `origin`; pixel (x, y) of the
// window holds (x, y, x + 10·y) counted from the window's corner.
void writeOffsetExr(const std::string& path, Imath::V2i origin, int w, int h) {
    const Imath::Box2i window(origin, origin + Imath::V2i(w - 1, h - 1));
    Imf::Header header(Imath::Box2i({0, 0}, {w - 1, h - 1}), window);
    for (const char* name : {"R", "G", "B"})
        header.channels().insert(name, Imf::Channel(Imf::FLOAT));
    std::vector<float> rgb(size_t(3) * w * h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            float* p = &rgb[3 * (size_t(y) * w + x)];
            p[0] = float(x), p[1] = float(y), p[2] = float(x + 10 * y);
        }
    Imf::OutputFile file(path.c_str(), header);
    Imf::FrameBuffer fb;
    const size_t xs = 3 * sizeof(float), ys = xs * w;
    const char* names[3] = {"R", "G", "B"};
    for (int c = 0; c < 3; ++c)
        fb.insert(names[c], Imf::Slice::Make(Imf::FLOAT, rgb.data() + c, window, xs, ys));
    file.setFrameBuffer(fb);
    file.writePixels(h);
}

TEST(ImageIo, ExrDataWindowAnywhereReadsFromTheCorner) {
    const auto dir = testing::scratchDirectory("image-io");
    const int w = 7, h = 5;
    // Negative origins made the reader's base pointer wrap around before it
    // was offset in integer arithmetic (a fuzzer found it under UBSan).
    for (const Imath::V2i& origin : {Imath::V2i(0, 0), Imath::V2i(3, 2), Imath::V2i(-4, -9),
                                     Imath::V2i(-1000000, 5), Imath::V2i(20, -1000000000)}) {
        SCOPED_TRACE(::testing::Message() << "origin " << origin.x << ", " << origin.y);
        const std::string path = (dir / "offset.exr").string();
        writeOffsetExr(path, origin, w, h);
        const Image img = readImage(path);
        ASSERT_EQ(img.width, w);
        ASSERT_EQ(img.height, h);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const float* p = &img.rgb[3 * (size_t(y) * w + x)];
                EXPECT_EQ(p[0], float(x));
                EXPECT_EQ(p[1], float(y));
                EXPECT_EQ(p[2], float(x + 10 * y));
            }
    }
    std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace pathlab
