#include "core/image.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <png.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "core/atomic_file.h"
#include "core/error.h"

namespace pathlab {
namespace {

std::string lowerExtension(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext;
}

// Refuses sizes no image of pathlab's can have before anything is allocated
// for them (a corrupt or hostile header must not exhaust memory).
void checkImageSize(const std::string& path, int64_t w, int64_t h) {
    if (w > kMaxImageSide || h > kMaxImageSide)
        throw InputError("image '" + path + "' is " + std::to_string(w) + "x" + std::to_string(h) +
                         ", larger than the " + std::to_string(kMaxImageSide) + "x" +
                         std::to_string(kMaxImageSide) + " pathlab reads");
}

Image readExr(const std::string& path) {
    try {
        Imf::InputFile file(path.c_str());
        const Imath::Box2i dw = file.header().dataWindow();
        // In 64 bits: a window from −2³¹ to 2³¹−1 is 2³² wide.
        const int64_t w64 = int64_t(dw.max.x) - dw.min.x + 1,
                      h64 = int64_t(dw.max.y) - dw.min.y + 1;
        if (w64 <= 0 || h64 <= 0) throw InputError("image '" + path + "' is empty");
        checkImageSize(path, w64, h64);
        const int w = int(w64), h = int(h64);
        Image img(w, h);
        const Imf::ChannelList& channels = file.header().channels();
        const bool hasRgb =
            channels.findChannel("R") && channels.findChannel("G") && channels.findChannel("B");
        const bool hasY = channels.findChannel("Y") != nullptr;
        if (!hasRgb && !hasY) throw InputError("image '" + path + "' has no R,G,B or Y channels");
        // The library addresses pixel (x, y) as base + x·xs + y·ys with data
        // window coordinates, which may be anywhere (negative too). Slice::Make
        // offsets the base by the window's origin in integer arithmetic: a
        // pointer moved outside its buffer here would be undefined behaviour.
        Imf::FrameBuffer fb;
        const size_t xs = 3 * sizeof(float), ys = xs * w;
        const char* names[3] = {"R", "G", "B"};
        for (int c = 0; c < 3; ++c) {
            const char* name = hasRgb ? names[c] : "Y";
            if (!hasRgb && c > 0) break;
            fb.insert(name, Imf::Slice::Make(Imf::FLOAT, img.rgb.data() + c, dw, xs, ys));
        }
        file.setFrameBuffer(fb);
        file.readPixels(dw.min.y, dw.max.y);
        if (!hasRgb)
            for (size_t i = 0; i < img.pixelCount(); ++i)
                img.rgb[3 * i + 1] = img.rgb[3 * i + 2] = img.rgb[3 * i];
        return img;
    } catch (const InputError&) {
        throw;
    } catch (const std::exception& e) {
        throw InputError("cannot read EXR '" + path + "': " + e.what());
    }
}

// The encoders build the whole file in memory; writeImage then writes it in
// one go, so a failure is reported with its cause (errno) for the target.
// An Imf::OStream into a string reserved at the file's expected size.
// Imf::StdOSStream's std::ostringstream doubles its buffer as the pixels
// arrive and str() copies the whole file once more: at 512×512 several 3 MB
// copies and their page faults, about 5% of a 1-spp render's time. The
// writer seeks back once, to fill in the line offset table.
class StringOStream final : public Imf::OStream {
  public:
    explicit StringOStream(size_t expectedBytes) : Imf::OStream("memory") {
        bytes_.reserve(expectedBytes);
    }
    void write(const char c[], int n) override {
        const size_t end = pos_ + size_t(n);
        if (pos_ == bytes_.size()) {
            bytes_.append(c, size_t(n));
        } else {
            if (end > bytes_.size()) bytes_.resize(end);
            std::memcpy(bytes_.data() + pos_, c, size_t(n));
        }
        pos_ = end;
    }
    uint64_t tellp() override { return pos_; }
    void seekp(uint64_t pos) override { pos_ = size_t(pos); }
    std::string take() { return std::move(bytes_); }

  private:
    std::string bytes_;
    size_t pos_ = 0;
};

std::string encodeExr(const Image& img) {
    Imf::Header header(img.width, img.height);
    // Uncompressed: a rendered float image is noise in its low mantissa bits,
    // which ZIP shrinks by 2–3% (256² Cornell-box renders and a 4096-spp
    // reference) at 30 ms per 256² image against 2–5 ms without, and a study
    // writes one per cell. PIZ shrinks them by 0.5% in twice ZIP's time.
    header.compression() = Imf::NO_COMPRESSION;
    for (const char* name : {"R", "G", "B"})
        header.channels().insert(name, Imf::Channel(Imf::FLOAT));
    // Uncompressed scan lines: a y coordinate, a size and the line's floats
    // each, one 8-byte offset per line, and the header.
    const size_t lineBytes = 8 + size_t(img.width) * 3 * sizeof(float);
    StringOStream stream(size_t(img.height) * (lineBytes + 8) + 4096);
    {
        Imf::OutputFile file(stream, header);
        Imf::FrameBuffer fb;
        char* base = reinterpret_cast<char*>(const_cast<float*>(img.rgb.data()));
        const size_t xs = 3 * sizeof(float), ys = xs * img.width;
        fb.insert("R", Imf::Slice(Imf::FLOAT, base, xs, ys));
        fb.insert("G", Imf::Slice(Imf::FLOAT, base + sizeof(float), xs, ys));
        fb.insert("B", Imf::Slice(Imf::FLOAT, base + 2 * sizeof(float), xs, ys));
        file.setFrameBuffer(fb);
        file.writePixels(img.height);
    }  // the file's destructor completes it (the line offset table)
    return stream.take();
}

Image readPng(const std::string& path) {
    png_image png{};
    png.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_file(&png, path.c_str()))
        throw InputError("cannot read PNG '" + path + "': " + png.message);
    // 16-bit files are decoded by libpng to linear 16-bit; 8-bit ones keep their
    // sRGB code values, decoded here with the exact sRGB transfer function.
    if (png.width > uint32_t(kMaxImageSide) || png.height > uint32_t(kMaxImageSide)) {
        png_image_free(&png);
        checkImageSize(path, int64_t(png.width), int64_t(png.height));
    }
    const bool sixteen = (png.format & PNG_FORMAT_FLAG_LINEAR) != 0;
    png.format = sixteen ? PNG_FORMAT_LINEAR_RGB : PNG_FORMAT_RGB;
    Image img(static_cast<int>(png.width), static_cast<int>(png.height));
    std::vector<unsigned char> buf(PNG_IMAGE_SIZE(png));
    if (!png_image_finish_read(&png, nullptr, buf.data(), 0, nullptr)) {
        std::string msg = png.message;
        png_image_free(&png);
        throw InputError("cannot read PNG '" + path + "': " + msg);
    }
    if (sixteen) {
        const auto* p = reinterpret_cast<const uint16_t*>(buf.data());
        for (size_t i = 0; i < img.rgb.size(); ++i) img.rgb[i] = p[i] / 65535.0f;
    } else {
        float table[256];
        for (int i = 0; i < 256; ++i) table[i] = srgbToLinear(i / 255.0f);
        for (size_t i = 0; i < img.rgb.size(); ++i) img.rgb[i] = table[buf[i]];
    }
    return img;
}

std::string encodePng(const Image& img, float exposure) {
    const float scale = std::exp2(exposure);
    std::vector<unsigned char> buf(img.rgb.size());
    for (size_t i = 0; i < buf.size(); ++i) {
        float v = img.rgb[i] * scale;
        v = std::isfinite(v) ? std::clamp(v, 0.0f, 1.0f) : 0.0f;
        buf[i] = static_cast<unsigned char>(std::lround(linearToSrgb(v) * 255.0f));
    }
    png_image png{};
    png.version = PNG_IMAGE_VERSION;
    png.width = static_cast<png_uint_32>(img.width);
    png.height = static_cast<png_uint_32>(img.height);
    png.format = PNG_FORMAT_RGB;
    // Fast zlib settings: a 256² view encodes in about 13 ms instead of 25–35,
    // for files from 35% smaller to 45% larger (noisy renders grow, flat error
    // maps shrink). One encoding into a buffer of the largest possible size:
    // png_image_write_get_memory_size would encode the image a second time.
    png.flags = PNG_IMAGE_FLAG_FAST;
    png_alloc_size_t size = PNG_IMAGE_PNG_SIZE_MAX(png);
    std::string bytes(size, '\0');
    if (!png_image_write_to_memory(&png, bytes.data(), &size, 0, buf.data(), 0, nullptr))
        throw std::runtime_error(std::string("PNG encoder: ") + png.message);
    bytes.resize(size);
    return bytes;
}

// PFM (Portable Float Map): "PF\n w h\n scale\n" then bottom-to-top rows of
// float triples; a negative scale means little-endian.
Image readPfm(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError("cannot open '" + path + "'");
    std::string magic;
    int w = 0, h = 0;
    double scale = 0;
    in >> magic >> w >> h >> scale;
    if (!in || (magic != "PF" && magic != "Pf") || w <= 0 || h <= 0 || scale == 0)
        throw InputError("'" + path + "' is not a valid PFM file (bad header)");
    checkImageSize(path, w, h);
    in.get();  // the single whitespace byte after the header
    const int channels = magic == "PF" ? 3 : 1;
    // Before allocating: a few bytes claiming a large image are refused here.
    std::error_code ec;
    const auto fileSize = std::filesystem::file_size(path, ec);
    if (ec || fileSize < uint64_t(in.tellg()) + uint64_t(w) * h * channels * sizeof(float))
        throw InputError("'" + path + "' is truncated");
    std::vector<float> data(size_t(w) * h * channels);
    in.read(reinterpret_cast<char*>(data.data()), std::streamsize(data.size() * sizeof(float)));
    if (in.gcount() != std::streamsize(data.size() * sizeof(float)))
        throw InputError("'" + path + "' is truncated");
    if (scale > 0)  // big-endian data
        for (float& f : data) {
            uint32_t u;
            std::memcpy(&u, &f, 4);
            u = __builtin_bswap32(u);
            std::memcpy(&f, &u, 4);
        }
    Image img(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c)
                img.rgb[(size_t(y) * w + x) * 3 + c] =
                    data[(size_t(h - 1 - y) * w + x) * channels + (channels == 3 ? c : 0)];
    return img;
}

std::string encodePfm(const Image& img) {
    std::string bytes =
        "PF\n" + std::to_string(img.width) + " " + std::to_string(img.height) + "\n-1\n";
    for (int y = img.height - 1; y >= 0; --y)
        bytes.append(reinterpret_cast<const char*>(&img.rgb[size_t(y) * img.width * 3]),
                     size_t(img.width) * 3 * sizeof(float));
    return bytes;
}

}  // namespace

float srgbToLinear(float v) {
    return v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f);
}

float linearToSrgb(float v) {
    return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
}

ImageFormat imageFormatFromPath(const std::string& path) {
    const std::string ext = lowerExtension(path);
    if (ext == ".exr") return ImageFormat::Exr;
    if (ext == ".png") return ImageFormat::Png;
    if (ext == ".pfm") return ImageFormat::Pfm;
    throw InputError("unsupported image type '" + ext + "' for '" + path +
                     "' (expected .exr, .png or .pfm)");
}

Image readImage(const std::string& path) {
    const ImageFormat format = imageFormatFromPath(path);
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec))
        throw InputError("image '" + path + "' does not exist or is not a file");
    switch (format) {
        case ImageFormat::Exr:
            return readExr(path);
        case ImageFormat::Png:
            return readPng(path);
        case ImageFormat::Pfm:
            return readPfm(path);
    }
    throw InputError("unsupported image '" + path + "'");
}

void checkWritable(const std::string& path) {
    imageFormatFromPath(path);
    checkDirectoryWritable(path);
}

void checkDirectoryWritable(const std::string& path) {
    std::filesystem::path p(path);
    std::filesystem::path dir = p.parent_path().empty() ? "." : p.parent_path();
    std::error_code ec;
    if (!std::filesystem::is_directory(dir, ec))
        throw InputError("cannot write '" + path + "': " +
                         (std::filesystem::exists(dir, ec)
                              ? "'" + dir.string() + "' is not a directory"
                              : "directory '" + dir.string() + "' does not exist"));
    if (access(dir.c_str(), W_OK) != 0)
        throw InputError("cannot write '" + path + "': no permission to write in '" + dir.string() +
                         "'");
}

std::string encodeImage(const Image& image, ImageFormat format, float exposure) {
    switch (format) {
        case ImageFormat::Exr:
            return encodeExr(image);
        case ImageFormat::Png:
            return encodePng(image, exposure);
        case ImageFormat::Pfm:
            return encodePfm(image);
    }
    return {};
}

void writeImage(const std::string& path, const Image& image, float exposure) {
    const ImageFormat format = imageFormatFromPath(path);
    checkWritable(path);
    writeFileAtomic(path, encodeImage(image, format, exposure));
}

}  // namespace pathlab
