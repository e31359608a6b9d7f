// PMD v4, little-endian (0 A.D.'s source/graphics/ModelDef.cpp is the
// authority): "PSMD", u32 version, u32 size of the rest of the file; u32
// vertex count, u32 UV-set count; per vertex 3 f32 position, 3 f32 normal,
// 2 f32 per UV set, 4 u8 bone indices, 4 f32 bone weights; u32 face count and
// 3 u16 indices per face; then bones and prop points, which we do not need.
#include "scene/pmd_loader.h"

#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <vector>

#include "core/error.h"

namespace pathlab {
namespace {

class Reader {
  public:
    Reader(std::span<const uint8_t> bytes, const std::string& source)
        : bytes_(bytes), source_(source) {}

    size_t remaining() const { return bytes_.size() - pos_; }

    void need(size_t n, const char* what) const {
        if (remaining() < n)
            throw InputError("PMD file '" + source_ + "' is truncated (reading " + what + ")");
    }
    uint32_t u32(const char* what) {
        need(4, what);
        const uint8_t* p = bytes_.data() + pos_;
        pos_ += 4;
        return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
    }
    uint16_t u16(const char* what) {
        need(2, what);
        const uint8_t* p = bytes_.data() + pos_;
        pos_ += 2;
        return uint16_t(p[0] | p[1] << 8);
    }
    float f32(const char* what) {
        const uint32_t bits = u32(what);
        float f;
        std::memcpy(&f, &bits, 4);
        if (!std::isfinite(f))
            throw InputError("PMD file '" + source_ + "' has a non-finite " + what);
        return f;
    }
    void skip(size_t n, const char* what) {
        need(n, what);
        pos_ += n;
    }

  private:
    std::span<const uint8_t> bytes_;
    const std::string& source_;
    size_t pos_ = 0;
};

}  // namespace

Mesh parsePmd(std::span<const uint8_t> bytes, const std::string& source) {
    auto bad = [&](const std::string& what) {
        return InputError("PMD file '" + source + "' " + what);
    };
    Reader in(bytes, source);
    in.need(4, "magic");
    if (std::memcmp(bytes.data(), "PSMD", 4) != 0) throw bad("does not start with 'PSMD'");
    in.skip(4, "magic");
    const uint32_t version = in.u32("version");
    if (version != 4) throw bad("has version " + std::to_string(version) + ", expected 4");
    const uint32_t dataSize = in.u32("data size");
    if (dataSize != in.remaining())
        throw bad("declares " + std::to_string(dataSize) + " bytes of data but has " +
                  std::to_string(in.remaining()));

    const uint32_t vertexCount = in.u32("vertex count");
    const uint32_t uvSets = in.u32("UV set count");
    if (uvSets > 16) throw bad("declares " + std::to_string(uvSets) + " UV sets");
    const size_t vertexSize = 12 + 12 + 8 * size_t(uvSets) + 4 + 16;
    // Check the counts against the file length before allocating, so a corrupt
    // count cannot ask for gigabytes.
    if (size_t(vertexCount) > in.remaining() / vertexSize)
        throw bad("declares " + std::to_string(vertexCount) + " vertices, more than it holds");
    if (vertexCount > 65536) throw bad("has more vertices than 16-bit indices can address");

    Mesh mesh;
    mesh.name = "pmd";
    mesh.positions.resize(vertexCount);
    mesh.normals.resize(vertexCount);
    if (uvSets > 0) mesh.uvs.resize(vertexCount);
    for (uint32_t i = 0; i < vertexCount; ++i) {
        Vec3f& p = mesh.positions[i];
        p.x = in.f32("position"), p.y = in.f32("position"), p.z = in.f32("position");
        Vec3f& n = mesh.normals[i];
        n.x = in.f32("normal"), n.y = in.f32("normal"), n.z = in.f32("normal");
        if (dot(n, n) == 0) throw bad("has a zero normal at vertex " + std::to_string(i));
        n = normalize(n);
        for (uint32_t s = 0; s < uvSets; ++s) {
            const float u = in.f32("UV"), v = in.f32("UV");
            // PMD's v runs bottom-up (OpenGL's convention); ours top-down. With
            // v flipped, the wolf's UV triangles cover exactly the islands of
            // its texture atlas; unflipped, a third of them fall into the gaps.
            if (s == 0) mesh.uvs[i] = {u, 1.0f - v};
        }
        in.skip(4, "bone indices");
        for (int w = 0; w < 4; ++w) in.f32("bone weight");
    }

    const uint32_t faceCount = in.u32("face count");
    if (size_t(faceCount) > in.remaining() / 6)
        throw bad("declares " + std::to_string(faceCount) + " faces, more than it holds");
    if (faceCount == 0) throw bad("has no faces");
    mesh.indices.resize(size_t(faceCount) * 3);
    for (size_t i = 0; i < mesh.indices.size(); ++i) {
        const uint16_t index = in.u16("face");
        if (index >= vertexCount)
            throw bad("has vertex index " + std::to_string(index) + " out of range in face " +
                      std::to_string(i / 3) + " (" + std::to_string(vertexCount) + " vertices)");
        mesh.indices[i] = index;
    }
    return mesh;
}

Mesh readPmd(const std::string& path) {
    std::ifstream file(path, std::ios::binary);
    if (!file) throw InputError("cannot open PMD file '" + path + "'");
    const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(file)),
                                     std::istreambuf_iterator<char>());
    if (file.bad()) throw InputError("cannot read PMD file '" + path + "'");
    return parsePmd(bytes, path);
}

}  // namespace pathlab
