// The PMD reader: the real wolf, and every way a PMD file can be broken.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <vector>

#include "scene/assets.h"
#include "scene/mesh_utils.h"
#include "scene/pmd_loader.h"
#include "scene/texture_loader.h"
#include "scene_test_util.h"

namespace pathlab {
namespace {

using test::inputErrorOf;

// A minimal PMD v4 writer for synthetic files.
struct PmdWriter {
    std::vector<uint8_t> body;
    void u32(uint32_t v) {
        for (int i = 0; i < 4; ++i) body.push_back(uint8_t(v >> (8 * i)));
    }
    void u16(uint16_t v) { body.push_back(uint8_t(v)), body.push_back(uint8_t(v >> 8)); }
    void f32(float f) {
        uint32_t bits;
        std::memcpy(&bits, &f, 4);
        u32(bits);
    }
    std::vector<uint8_t> file(uint32_t version = 4) const {
        std::vector<uint8_t> out = {'P', 'S', 'M', 'D'};
        auto put = [&](uint32_t v) {
            for (int i = 0; i < 4; ++i) out.push_back(uint8_t(v >> (8 * i)));
        };
        put(version);
        put(uint32_t(body.size()));
        out.insert(out.end(), body.begin(), body.end());
        return out;
    }
};

// One triangle; `position0` lets a test poison a coordinate, `index2` an index.
std::vector<uint8_t> tinyPmd(float position0 = 0.0f, uint16_t index2 = 2) {
    PmdWriter w;
    w.u32(3);  // vertices
    w.u32(1);  // UV sets
    const float p[3][3] = {{position0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    for (int v = 0; v < 3; ++v) {
        for (float c : p[v]) w.f32(c);
        w.f32(0), w.f32(0), w.f32(1);            // normal
        w.f32(0.25f * v), w.f32(0.75f);          // UV
        w.u32(0xFFFFFFFF);                       // bone indices
        w.f32(0), w.f32(0), w.f32(0), w.f32(0);  // weights
    }
    w.u32(1);  // faces
    w.u16(0), w.u16(1), w.u16(index2);
    w.u32(0);  // bones
    w.u32(0);  // prop points
    return w.file();
}

TEST(PmdLoader, ReadsSyntheticFile) {
    const Mesh m = parsePmd(tinyPmd(), "tiny");
    ASSERT_EQ(m.positions.size(), 3u);
    ASSERT_EQ(m.triangleCount(), 1u);
    EXPECT_EQ(m.positions[1].x, 1.0f);
    EXPECT_EQ(m.normals[2].z, 1.0f);
    EXPECT_EQ(m.uvs[2].x, 0.5f);
    EXPECT_EQ(m.uvs[2].y, 0.25f);  // v flipped: PMD's runs bottom-up
    EXPECT_EQ(m.indices, (std::vector<uint32_t>{0, 1, 2}));
}

TEST(PmdLoader, RejectsEveryTruncation) {
    const std::vector<uint8_t> full = tinyPmd();
    for (size_t n = 0; n < full.size(); ++n) {
        std::vector<uint8_t> cut(full.begin(), full.begin() + n);
        EXPECT_THROW(parsePmd(cut, "cut"), InputError) << "length " << n;
    }
}

TEST(PmdLoader, RejectsTruncationWithConsistentSizeField) {
    // The size field rewritten to match, so only the counts betray the cut.
    std::vector<uint8_t> f = tinyPmd();
    f.resize(20 + 3 * 52 - 10);  // 52 bytes per vertex with one UV set
    const uint32_t size = uint32_t(f.size() - 12);
    std::memcpy(&f[8], &size, 4);
    EXPECT_NE(inputErrorOf([&] { parsePmd(f, "x"); }).find("vertices"), std::string::npos);
}

TEST(PmdLoader, RejectsBadMagicAndVersion) {
    std::vector<uint8_t> f = tinyPmd();
    f[0] = 'X';
    EXPECT_NE(inputErrorOf([&] { parsePmd(f, "x"); }).find("PSMD"), std::string::npos);
    PmdWriter w;
    w.u32(0);
    EXPECT_NE(inputErrorOf([&] { parsePmd(w.file(3), "x"); }).find("version 3"), std::string::npos);
}

TEST(PmdLoader, RejectsIndexOutOfRange) {
    EXPECT_NE(inputErrorOf([] { parsePmd(tinyPmd(0.0f, 3), "x"); }).find("out of range"),
              std::string::npos);
}

TEST(PmdLoader, RejectsNonFiniteValues) {
    EXPECT_THROW(parsePmd(tinyPmd(std::numeric_limits<float>::quiet_NaN()), "x"), InputError);
    EXPECT_THROW(parsePmd(tinyPmd(std::numeric_limits<float>::infinity()), "x"), InputError);
}

TEST(PmdLoader, RejectsHugeCountsWithoutAllocating) {
    PmdWriter w;
    w.u32(0x7FFFFFFF);
    w.u32(1);
    EXPECT_THROW(parsePmd(w.file(), "x"), InputError);
}

TEST(PmdLoader, MissingFile) {
    EXPECT_THROW(readPmd("/nonexistent/wolf.pmd"), InputError);
}

TEST(PmdLoader, ReadsTheWolf) {
    WolfAssets assets;
    if (!findWolfAssets(assets)) GTEST_SKIP() << "wolf data not found (set PATHLAB_ASSETS)";
    const Mesh m = readPmd(assets.mesh.string());
    EXPECT_EQ(m.positions.size(), 564u);
    EXPECT_EQ(m.triangleCount(), 696u);
    ASSERT_EQ(m.normals.size(), 564u);
    ASSERT_EQ(m.uvs.size(), 564u);
    const Bounds3f b = meshBounds(m);
    EXPECT_NEAR(b.lo.x, -0.40, 0.01);
    EXPECT_NEAR(b.hi.x, 0.40, 0.01);
    EXPECT_NEAR(b.lo.y, 0.0, 0.01);
    EXPECT_NEAR(b.hi.y, 2.29, 0.01);
    EXPECT_NEAR(b.lo.z, -1.84, 0.01);
    EXPECT_NEAR(b.hi.z, 1.57, 0.01);
    for (size_t i = 0; i < m.positions.size(); ++i) {
        EXPECT_NEAR(length(m.normals[i]), 1.0f, 1e-5f);
        EXPECT_GE(m.uvs[i].x, 0.0f);
        EXPECT_LE(m.uvs[i].x, 1.0f);
        EXPECT_GE(m.uvs[i].y, 0.0f);
        EXPECT_LE(m.uvs[i].y, 1.0f);
    }
}

// The texture atlas has black gaps between its islands: with the UVs read
// the right way up, (nearly) no triangle's interior samples them.
TEST(PmdLoader, WolfUvsLandOnTheTextureAtlas) {
    WolfAssets assets;
    if (!findWolfAssets(assets)) GTEST_SKIP() << "wolf data not found (set PATHLAB_ASSETS)";
    const Mesh m = readPmd(assets.mesh.string());
    const Texture tex = loadTexture(assets.texture.string());
    size_t black = 0, total = 0;
    for (size_t t = 0; t < m.triangleCount(); ++t) {
        for (auto [a, b] : {std::pair{0.2f, 0.2f}, {0.6f, 0.2f}, {0.2f, 0.6f}, {0.33f, 0.33f}}) {
            const Vec2f p = m.uvs[m.indices[3 * t]], q = m.uvs[m.indices[3 * t + 1]],
                        r = m.uvs[m.indices[3 * t + 2]];
            const Vec2f uv{(1 - a - b) * p.x + a * q.x + b * r.x,
                           (1 - a - b) * p.y + a * q.y + b * r.y};
            black += maxComponent(tex.lookup(uv)) < 1e-4f;
            ++total;
        }
    }
    EXPECT_LT(black, total / 25) << black << " of " << total << " samples in the atlas's gaps";
}

TEST(PmdLoader, RejectsTheWolfTruncated) {
    WolfAssets assets;
    if (!findWolfAssets(assets)) GTEST_SKIP() << "wolf data not found (set PATHLAB_ASSETS)";
    std::ifstream in(assets.mesh, std::ios::binary);
    std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)),
                               std::istreambuf_iterator<char>());
    for (size_t n : {size_t(0), size_t(11), bytes.size() / 2, bytes.size() - 1}) {
        std::vector<uint8_t> cut(bytes.begin(), bytes.begin() + n);
        EXPECT_THROW(parsePmd(cut, "wolf"), InputError) << n;
    }
    // Corrupting one face index to point past the vertices.
    std::vector<uint8_t> bad = bytes;
    const size_t faces = 20 + 564 * (12 + 12 + 8 + 4 + 16) + 4;
    bad[faces] = 0xFF, bad[faces + 1] = 0xFF;
    EXPECT_THROW(parsePmd(bad, "wolf"), InputError);
}

}  // namespace
}  // namespace pathlab
