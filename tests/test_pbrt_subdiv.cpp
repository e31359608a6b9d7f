// pbrt-v4 "loopsubdiv" through OpenSubdiv (loopSubdivide): counts per level,
// limit positions and normals on closed, flat and open meshes, bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>
#include <utility>

#include "scene/pbrt/loop_subdivision.h"
#include "scene_test_util.h"

namespace pathlab::pbrt {
namespace {

using test::inputErrorOf;

struct Control {
    std::vector<Vec3f> p;
    std::vector<uint32_t> idx;
};

// Vertices ±x, ±y, ±z; every face counter-clockwise seen from outside.
Control octahedron() {
    Control c;
    c.p = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    c.idx = {0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5};
    return c;
}

// A 4×4-square grid in z = 0 (two triangles per square, counter-clockwise
// from +z); `lift` raises the middle vertex to make it a tent.
Control grid(float lift = 0) {
    Control c;
    for (int j = 0; j <= 4; ++j)
        for (int i = 0; i <= 4; ++i)
            c.p.push_back({float(i), float(j), i == 2 && j == 2 ? lift : 0.0f});
    for (uint32_t j = 0; j < 4; ++j)
        for (uint32_t i = 0; i < 4; ++i) {
            const uint32_t a = j * 5 + i;
            c.idx.insert(c.idx.end(), {a, a + 1, a + 6, a, a + 6, a + 5});
        }
    return c;
}

size_t edgeCount(const std::vector<uint32_t>& idx) {
    std::set<std::pair<uint32_t, uint32_t>> edges;
    for (size_t t = 0; t < idx.size(); t += 3)
        for (int k = 0; k < 3; ++k) {
            const uint32_t a = idx[t + k], b = idx[t + (k + 1) % 3];
            edges.insert({std::min(a, b), std::max(a, b)});
        }
    return edges.size();
}

// Vertices on an edge that only one triangle has.
std::set<uint32_t> boundaryVertices(const Mesh& m) {
    std::map<std::pair<uint32_t, uint32_t>, int> uses;
    for (size_t t = 0; t < m.indices.size(); t += 3)
        for (int k = 0; k < 3; ++k) {
            const uint32_t a = m.indices[t + k], b = m.indices[t + (k + 1) % 3];
            ++uses[{std::min(a, b), std::max(a, b)}];
        }
    std::set<uint32_t> out;
    for (const auto& [e, n] : uses)
        if (n == 1) out.insert({e.first, e.second});
    return out;
}

// Every triangle's (p1−p0)×(p2−p0) agrees with its vertices' normals.
void expectNormalsFollowWinding(const Mesh& m) {
    ASSERT_EQ(m.normals.size(), m.positions.size());
    for (const Vec3f& n : m.normals) EXPECT_NEAR(length(n), 1.0f, 1e-5f);
    for (size_t t = 0; t < m.triangleCount(); ++t) {
        const uint32_t a = m.indices[3 * t], b = m.indices[3 * t + 1], c = m.indices[3 * t + 2];
        const Vec3f g =
            normalize(cross(m.positions[b] - m.positions[a], m.positions[c] - m.positions[a]));
        for (uint32_t v : {a, b, c}) EXPECT_GT(dot(g, m.normals[v]), 0.5f) << "triangle " << t;
    }
}

TEST(PbrtLoopSubdiv, ClosedMeshCountsPerLevel) {
    for (const Control& c : {octahedron()}) {
        size_t v = c.p.size(), e = edgeCount(c.idx), f = c.idx.size() / 3;
        for (int level = 0; level <= 4; ++level) {
            const Mesh m = loopSubdivide(c.p, c.idx, level);
            EXPECT_EQ(m.positions.size(), v) << "level " << level;
            EXPECT_EQ(m.triangleCount(), f) << "level " << level;
            EXPECT_EQ(edgeCount(m.indices), e) << "level " << level;
            // Loop: V' = V + E, E' = 2E + 3F, F' = 4F.
            v += e;
            e = 2 * e + 3 * f;
            f *= 4;
        }
    }
}

TEST(PbrtLoopSubdiv, OctahedronLimitIsInsideTheHullAndNearlyASphere) {
    const Control c = octahedron();
    const Mesh m = loopSubdivide(c.p, c.idx, 4);
    float rMin = 2, rMax = 0, xMax = 0;
    for (const Vec3f& p : m.positions) {
        // The octahedron's convex hull is |x| + |y| + |z| <= 1.
        EXPECT_LE(std::abs(p.x) + std::abs(p.y) + std::abs(p.z), 1.0f + 1e-5f);
        rMin = std::min(rMin, length(p));
        rMax = std::max(rMax, length(p));
        xMax = std::max(xMax, p.x);
    }
    // The limit of the control vertex (1, 0, 0), of valence n = 4, is
    // (1 − nγ)·v + γ·(its ring, which sums to 0) with γ = 1/(n + 3/(8β)) and
    // Loop's β(4) = 31/256: 96/220. (pbrt-v4's β = 3/(8n) would give 1/2.)
    EXPECT_NEAR(xMax, 96.0f / 220, 1e-6f);
    // Shrunk well inside the control vertices (radius 1) and round: the
    // octahedron's own radius varies from 1/√3 to 1 (a ratio of 1.73), the
    // limit's from 0.408 to 0.436 (1.07).
    EXPECT_LE(rMax, 96.0f / 220 + 1e-6f);
    EXPECT_GT(rMin, 0.4f);
    EXPECT_LT(rMax / rMin, 1.08f);
    for (size_t i = 0; i < m.positions.size(); ++i)
        EXPECT_GT(dot(m.normals[i], normalize(m.positions[i])), 0.9f) << "vertex " << i;
    expectNormalsFollowWinding(m);
}

TEST(PbrtLoopSubdiv, ReversedWindingReversesTheNormals) {
    Control c = octahedron();
    for (size_t t = 0; t < c.idx.size(); t += 3) std::swap(c.idx[t + 1], c.idx[t + 2]);
    const Mesh m = loopSubdivide(c.p, c.idx, 2);
    for (size_t i = 0; i < m.positions.size(); ++i)
        EXPECT_LT(dot(m.normals[i], normalize(m.positions[i])), -0.9f) << "vertex " << i;
    expectNormalsFollowWinding(m);
}

// The limit of a vertex of valence 6 is v/2 + (sum of its ring)/12 (Loop
// 1987; pbrt-v4's limit rule gives the same at valence 6).
TEST(PbrtLoopSubdiv, RegularVertexLimitPosition) {
    Control c;
    c.p.push_back({0, 0, 1});
    for (int k = 0; k < 6; ++k)
        c.p.push_back({std::cos(float(k) * kPi / 3), std::sin(float(k) * kPi / 3), 0});
    for (uint32_t k = 0; k < 6; ++k) c.idx.insert(c.idx.end(), {0, 1 + k, 1 + (k + 1) % 6});
    const Mesh m = loopSubdivide(c.p, c.idx, 0);
    ASSERT_EQ(m.positions.size(), 7u);
    EXPECT_NEAR(m.positions[0].z, 0.5f, 1e-6f);
    EXPECT_NEAR(m.positions[0].x, 0.0f, 1e-6f);
    EXPECT_NEAR(m.normals[0].z, 1.0f, 1e-6f);  // by symmetry, along +z
}

TEST(PbrtLoopSubdiv, FlatMeshStaysFlatWithThePlaneNormal) {
    const Control c = grid();
    const Mesh m = loopSubdivide(c.p, c.idx, 3);
    EXPECT_EQ(m.triangleCount(), 32u * 64u);
    for (size_t i = 0; i < m.positions.size(); ++i) {
        EXPECT_EQ(m.positions[i].z, 0.0f) << "vertex " << i;
        EXPECT_NEAR(m.normals[i].z, 1.0f, 1e-6f) << "vertex " << i;
        // Within the square (its corners are rounded off, not pinned).
        EXPECT_GE(m.positions[i].x, -1e-5f);
        EXPECT_LE(m.positions[i].x, 4 + 1e-5f);
    }
    expectNormalsFollowWinding(m);
}

TEST(PbrtLoopSubdiv, OpenMeshBoundaryStaysInItsPlane) {
    const Control c = grid(1.5f);  // a tent whose rim lies in z = 0
    const Mesh m = loopSubdivide(c.p, c.idx, 3);
    const std::set<uint32_t> rim = boundaryVertices(m);
    EXPECT_EQ(rim.size(), 16u * 8u);  // 16 rim edges, each split in 8
    for (uint32_t v : rim) EXPECT_NEAR(m.positions[v].z, 0.0f, 1e-6f) << "vertex " << v;
    // The top is the limit of the raised vertex (valence 6, ring at z = 0):
    // 1.5/2, as in RegularVertexLimitPosition.
    float top = 0;
    for (const Vec3f& p : m.positions) top = std::max(top, p.z);
    EXPECT_NEAR(top, 0.75f, 1e-6f);
    expectNormalsFollowWinding(m);
}

TEST(PbrtLoopSubdiv, UnusedControlVerticesAreLeftOut) {
    Control c = octahedron();
    c.p.push_back({5, 5, 5});
    const Mesh m = loopSubdivide(c.p, c.idx, 1);
    EXPECT_EQ(m.positions.size(), 18u);
    for (const Vec3f& p : m.positions) EXPECT_LT(length(p), 1.0f);
}

// pbrt-v4 assumes a manifold, consistently wound mesh; OpenSubdiv marks what
// is not (an edge of three triangles, a bow-tie vertex, a flipped triangle)
// and sharpens it. Whatever the surface, the result must be a valid mesh.
TEST(PbrtLoopSubdiv, NonManifoldControlMeshStillGivesAValidMesh) {
    const std::vector<Vec3f> p{{0, 0, 0},    {1, 0, 0},  {0.5f, 1, 0}, {0.5f, -1, 0},
                               {0.5f, 0, 1}, {-1, 1, 0}, {-1, -1, 0}};
    const std::vector<uint32_t> idx{0, 1, 2, 1, 0, 3, 0, 1, 4, 0, 5, 6, 2, 1, 4};
    for (int levels : {0, 1, 3}) {
        const Mesh m = loopSubdivide(p, idx, levels);
        EXPECT_EQ(m.triangleCount(), size_t(5) << (2 * levels));
        for (const Vec3f& q : m.positions)
            EXPECT_TRUE(std::isfinite(q.x) && std::isfinite(q.y) && std::isfinite(q.z));
        ASSERT_EQ(m.normals.size(), m.positions.size());
        for (const Vec3f& n : m.normals) EXPECT_NEAR(length(n), 1.0f, 1e-5f);
        for (uint32_t i : m.indices) EXPECT_LT(i, m.positions.size());
    }
}

TEST(PbrtLoopSubdiv, BadInputIsAnInputError) {
    const Control c = octahedron();
    auto msg = [](const std::vector<Vec3f>& p, const std::vector<uint32_t>& idx, int levels) {
        return inputErrorOf([&] { loopSubdivide(p, idx, levels); });
    };
    std::vector<uint32_t> idx = c.idx;
    idx[4] = 6;
    EXPECT_NE(msg(c.p, idx, 2).find("index 6 is out of range (6 vertices)"), std::string::npos);
    idx = c.idx;
    idx[4] = idx[3];
    EXPECT_NE(msg(c.p, idx, 2).find("triangle 1 is degenerate"), std::string::npos);
    idx = c.idx;
    idx.pop_back();
    EXPECT_NE(msg(c.p, idx, 2).find("not a positive multiple of 3"), std::string::npos);
    EXPECT_NE(msg(c.p, {}, 2).find("not a positive multiple of 3"), std::string::npos);
    EXPECT_NE(msg(c.p, c.idx, -1).find("outside [0, 10]"), std::string::npos);
    EXPECT_NE(msg(c.p, c.idx, 11).find("outside [0, 10]"), std::string::npos);
    std::vector<Vec3f> p = c.p;
    p[2].y = NAN;
    EXPECT_NE(msg(p, c.idx, 1).find("vertex 2 has a non-finite position"), std::string::npos);
    // 8 · 4^10 = 2^23 triangles is allowed in principle; 2^21 faces · 4^4 is not.
    std::vector<uint32_t> many;
    for (int k = 0; k < (1 << 21); ++k) many.insert(many.end(), {0, 2, 4});
    EXPECT_NE(msg(c.p, many, 4).find("more than 2^28 triangles"), std::string::npos);
}

}  // namespace
}  // namespace pathlab::pbrt
