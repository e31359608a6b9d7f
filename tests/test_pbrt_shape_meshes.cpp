// pbrt-v4's disk and bilinear patches as triangles (tessellateDisk,
// bilinearPatchMesh): area, orientation, uvs, planar vs twisted patches.
#include <gtest/gtest.h>

#include <cmath>

#include "scene/pbrt/shape_meshes.h"
#include "scene_test_util.h"

namespace pathlab::pbrt {
namespace {

using test::inputErrorOf;

Vec3f triangleNormal(const Mesh& m, size_t t) {
    const Vec3f a = m.positions[m.indices[3 * t]], b = m.positions[m.indices[3 * t + 1]],
                c = m.positions[m.indices[3 * t + 2]];
    return cross(b - a, c - a);
}

double area(const Mesh& m) {
    double sum = 0;
    for (size_t t = 0; t < m.triangleCount(); ++t) sum += 0.5 * length(triangleNormal(m, t));
    return sum;
}

TEST(PbrtShapeMeshes, DiskAreaAndOrientation) {
    struct Case {
        float height, radius, inner, phiMax;
    };
    for (const Case& c : {Case{0, 1, 0, 360}, Case{2.5f, 3, 1, 360}, Case{-1, 2, 0.5f, 90},
                          Case{0, 1, 0, 270}, Case{0, 1, 0, 400}}) {
        const int segments = 256;
        const Mesh m = tessellateDisk(c.height, c.radius, c.inner, c.phiMax, segments);
        const double phiMax = std::min(c.phiMax, 360.0f) * M_PI / 180;
        const double exact = phiMax / 2 * (c.radius * c.radius - c.inner * c.inner);
        // A chord polygon of edge angle δ has sin(δ)/δ of the area: 1e-4 at 256.
        const double delta = 2 * M_PI / segments;
        EXPECT_NEAR(area(m), exact, exact * (1 - std::sin(delta) / delta) * 1.01 + 1e-9)
            << c.radius << " " << c.inner << " " << c.phiMax;
        EXPECT_LT(std::abs(area(m) - exact), exact * 2e-4);
        for (size_t t = 0; t < m.triangleCount(); ++t) {
            const Vec3f n = triangleNormal(m, t);
            EXPECT_GT(n.z, 0) << "triangle " << t;  // pbrt-v4's disk faces +z
            EXPECT_EQ(n.x, 0);
            EXPECT_EQ(n.y, 0);
        }
        ASSERT_EQ(m.uvs.size(), m.positions.size());
        EXPECT_TRUE(m.normals.empty());
        for (size_t i = 0; i < m.positions.size(); ++i) {
            const Vec3f p = m.positions[i];
            EXPECT_EQ(p.z, c.height);
            const float r = std::sqrt(p.x * p.x + p.y * p.y);
            EXPECT_NEAR(r, m.uvs[i].y < 0.5f ? c.radius : c.inner, 1e-5f);
            // pbrt-v4's v = (radius − r) / (radius − innerRadius).
            EXPECT_NEAR(m.uvs[i].y, (c.radius - r) / (c.radius - c.inner), 1e-5f);
            if (r > 0) {  // u = φ / phiMax
                float phi = std::atan2(p.y, p.x);
                if (phi < 0) phi += 2 * kPi;
                if (m.uvs[i].x > 0.99f && phi < 0.01f) phi += 2 * kPi;  // the seam
                EXPECT_NEAR(m.uvs[i].x, phi / phiMax, 1e-5f) << i;
            }
        }
    }
}

TEST(PbrtShapeMeshes, PartialDiskKeepsTheEdgeAngle) {
    EXPECT_EQ(tessellateDisk(0, 1, 0, 360, 64).triangleCount(), 64u);
    EXPECT_EQ(tessellateDisk(0, 1, 0, 90, 64).triangleCount(), 16u);
    EXPECT_EQ(tessellateDisk(0, 1, 0.5f, 90, 64).triangleCount(), 32u);
    EXPECT_EQ(tessellateDisk(0, 1, 0, 1, 64).triangleCount(), 1u);
}

TEST(PbrtShapeMeshes, DiskBadParametersAreInputErrors) {
    EXPECT_NE(inputErrorOf([] { tessellateDisk(0, 1, 1, 360, 64); }).find("innerradius"),
              std::string::npos);
    EXPECT_NE(inputErrorOf([] { tessellateDisk(0, 0, 0, 360, 64); }).find("innerradius"),
              std::string::npos);
    EXPECT_NE(inputErrorOf([] { tessellateDisk(0, 1, 0, 0, 64); }).find("phimax"),
              std::string::npos);
    EXPECT_NE(inputErrorOf([] { tessellateDisk(NAN, 1, 0, 360, 64); }).find("non-finite"),
              std::string::npos);
    EXPECT_NE(inputErrorOf([] { tessellateDisk(0, 1, 0, 360, 2); }).find("segments"),
              std::string::npos);
}

// p(u, v) of a patch in pbrt-v4's corner order p00 p10 p01 p11.
Vec3f bilinear(const Vec3f (&c)[4], float u, float v) {
    return (1 - u) * (1 - v) * c[0] + u * (1 - v) * c[1] + (1 - u) * v * c[2] + u * v * c[3];
}

TEST(PbrtShapeMeshes, PlanarPatchesAreTwoTriangles) {
    // A parallelogram, a planar trapezoid tilted out of every axis plane, and
    // a quad with p00 = p10 (a triangle: its zero-area half is left out).
    const std::vector<Vec3f> P{{0, 0, 0}, {2, 0, 0}, {0.5f, 1, 0}, {2.5f, 1, 0},
                               {0, 0, 0}, {4, 0, 4}, {1, 2, 1},    {3, 2, 3},
                               {1, 1, 1}, {1, 1, 1}, {0, 2, 1},    {2, 2, 1}};
    const Mesh m = bilinearPatchMesh(P, {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11}, {}, {}, 16);
    EXPECT_EQ(m.triangleCount(), 5u);
    EXPECT_EQ(m.positions.size(), 12u);
    EXPECT_TRUE(m.normals.empty());
    // Each faces pbrt-v4's (p10 − p00) × (p01 − p00).
    const Vec3f front[3] = {{0, 0, 2}, cross(P[5] - P[4], P[6] - P[4]), {0, 0, 1}};
    for (size_t t = 0; t < m.triangleCount(); ++t)
        EXPECT_GT(dot(triangleNormal(m, t), front[t < 2 ? 0 : t < 4 ? 1 : 2]), 0) << t;
    // The parallelogram's two triangles are its area exactly, with uv = (u, v).
    Mesh first = m;
    first.indices.resize(6);
    EXPECT_NEAR(area(first), 2.0, 1e-6);
    EXPECT_EQ(m.uvs[1].x, 1.0f);
    EXPECT_EQ(m.uvs[2].y, 1.0f);
}

TEST(PbrtShapeMeshes, NonConvexPlanarQuadSplitsInside) {
    // Corners in boundary order p00 p10 p11 p01 = (0,0) (4,0) (1,1) (0,4):
    // reflex at p11, so the split must run through it.
    const std::vector<Vec3f> P{{0, 0, 0}, {4, 0, 0}, {0, 4, 0}, {1, 1, 0}};
    const Mesh m = bilinearPatchMesh(P, {0, 1, 2, 3}, {}, {}, 8);
    ASSERT_EQ(m.triangleCount(), 2u);
    for (size_t t = 0; t < 2; ++t) EXPECT_GT(triangleNormal(m, t).z, 0) << t;
    EXPECT_NEAR(area(m), 4.0, 1e-6);  // 2 + 2, the quad's own area
    // (0,0) (4,0) (4,4) (3,1): reflex at p01, so the split is p10–p01.
    const std::vector<Vec3f> Q{{0, 0, 0}, {4, 0, 0}, {3, 1, 0}, {4, 4, 0}};
    const Mesh q = bilinearPatchMesh(Q, {0, 1, 2, 3}, {}, {}, 8);
    ASSERT_EQ(q.triangleCount(), 2u);
    for (size_t t = 0; t < 2; ++t) EXPECT_GT(triangleNormal(q, t).z, 0) << t;
    EXPECT_NEAR(area(q), 4.0, 1e-6);
}

TEST(PbrtShapeMeshes, TwistedPatchIsAGridOnTheSurface) {
    const Vec3f c[4] = {{0, 0, 0}, {1, 0, 1}, {0, 1, 1}, {1, 1, 0}};  // a hyperbolic paraboloid
    const std::vector<Vec3f> N{{0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {1, 0, 0}};
    const std::vector<Vec2f> uv{{0, 0}, {2, 0}, {0, 4}, {2, 4}};
    const int n = 6;
    const Mesh m = bilinearPatchMesh({c[0], c[1], c[2], c[3]}, {0, 1, 2, 3}, N, uv, n);
    ASSERT_EQ(m.positions.size(), size_t((n + 1) * (n + 1)));
    EXPECT_EQ(m.triangleCount(), size_t(2 * n * n));
    ASSERT_EQ(m.normals.size(), m.positions.size());
    ASSERT_EQ(m.uvs.size(), m.positions.size());
    for (size_t i = 0; i < m.positions.size(); ++i) {
        // Its uv (the given uvs interpolated: u·2, v·4) says where on the
        // surface it should be.
        const float u = m.uvs[i].x / 2, v = m.uvs[i].y / 4;
        const Vec3f expected = bilinear(c, u, v);
        EXPECT_NEAR(length(m.positions[i] - expected), 0.0f, 1e-6f) << i;
        EXPECT_NEAR(length(m.normals[i]), 1.0f, 1e-6f);
    }
    // Row-major: vertex (i, j) at u = i/n, v = j/n.
    EXPECT_NEAR(length(m.positions[size_t(2 + 3 * (n + 1))] - bilinear(c, 2.0f / n, 3.0f / n)), 0,
                1e-6f);
    // Every triangle faces the side of cross(∂p/∂u, ∂p/∂v) at its centre.
    for (size_t t = 0; t < m.triangleCount(); ++t) {
        Vec3f centre(0.0f);
        float u = 0, v = 0;
        for (int k = 0; k < 3; ++k) {
            centre += m.positions[m.indices[3 * t + k]] / 3;
            u += m.uvs[m.indices[3 * t + k]].x / 6;
            v += m.uvs[m.indices[3 * t + k]].y / 12;
        }
        const Vec3f dpdu = (1 - v) * (c[1] - c[0]) + v * (c[3] - c[2]);
        const Vec3f dpdv = (1 - u) * (c[2] - c[0]) + u * (c[3] - c[1]);
        EXPECT_GT(dot(triangleNormal(m, t), cross(dpdu, dpdv)), 0) << t;
    }
    // Without uvs: (u, v); without normals: none.
    const Mesh plain = bilinearPatchMesh({c[0], c[1], c[2], c[3]}, {0, 1, 2, 3}, {}, {}, n);
    EXPECT_TRUE(plain.normals.empty());
    EXPECT_NEAR(plain.uvs.back().x, 1.0f, 0);
    EXPECT_NEAR(plain.uvs.back().y, 1.0f, 0);
}

TEST(PbrtShapeMeshes, BilinearBadInputIsAnInputError) {
    const std::vector<Vec3f> P{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
    EXPECT_NE(inputErrorOf([&] {
                  bilinearPatchMesh(P, {0, 1, 2}, {}, {}, 4);
              }).find("not a multiple of 4"),
              std::string::npos);
    EXPECT_NE(inputErrorOf([&] {
                  bilinearPatchMesh(P, {0, 1, 2, 4}, {}, {}, 4);
              }).find("index 4 is out of range"),
              std::string::npos);
    EXPECT_NE(inputErrorOf([&] {
                  bilinearPatchMesh(P, {0, 1, 2, 3}, {{0, 0, 1}}, {}, 4);
              }).find("1 normals for 4 vertices"),
              std::string::npos);
    EXPECT_NE(inputErrorOf([&] {
                  bilinearPatchMesh(P, {0, 1, 2, 3}, {}, {{0, 0}}, 4);
              }).find("1 uvs for 4 vertices"),
              std::string::npos);
    EXPECT_NE(inputErrorOf([&] {
                  bilinearPatchMesh(P, {0, 1, 2, 3}, {}, {}, 0);
              }).find("tessellation"),
              std::string::npos);
    std::vector<Vec3f> bad = P;
    bad[3].x = INFINITY;
    EXPECT_NE(inputErrorOf([&] {
                  bilinearPatchMesh(bad, {0, 1, 2, 3}, {}, {}, 4);
              }).find("vertex 3 has a non-finite position"),
              std::string::npos);
}

}  // namespace
}  // namespace pathlab::pbrt
