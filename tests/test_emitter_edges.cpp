// The emitter-edge mask against the Cornell box's light projected by hand.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "render/emitter_edges.h"
#include "scene/builtin_scenes.h"

namespace pathlab {
namespace {

// Film position (pixels) of world point p through the camera of camera.h:
// direction ∝ forward − right·t·a + up·t + right·(2ta/W)·x − up·(2t/H)·y.
Vec2f project(const Camera& c, Vec2i res, Vec3f p) {
    const Vec3f f = normalize(c.target - c.eye), r = normalize(cross(f, c.up)), u = cross(r, f);
    const double t = std::tan(double(c.fovY) * M_PI / 360.0), a = double(res.x) / res.y;
    const Vec3f d = p - c.eye;
    const double s = 1.0 / dot(d, f);
    const double x = (dot(d, r) * s + t * a) / (2 * t * a / res.x);
    const double y = (t - dot(d, u) * s) / (2 * t / res.y);
    return {float(x), float(y)};
}

// Length of segment ab inside the square [x, x+1] × [y, y+1] (Liang–Barsky).
double lengthInside(Vec2f a, Vec2f b, int x, int y) {
    double t0 = 0, t1 = 1;
    const double d[2] = {double(b.x) - a.x, double(b.y) - a.y};
    const double lo[2] = {double(x) - a.x, double(y) - a.y};
    const double hi[2] = {double(x) + 1 - a.x, double(y) + 1 - a.y};
    for (int k = 0; k < 2; ++k) {
        if (d[k] == 0) {
            if (lo[k] > 0 || hi[k] < 0) return 0;
            continue;
        }
        double e0 = lo[k] / d[k], e1 = hi[k] / d[k];
        if (e0 > e1) std::swap(e0, e1);
        t0 = std::max(t0, e0), t1 = std::min(t1, e1);
    }
    return t1 > t0 ? (t1 - t0) * std::hypot(d[0], d[1]) : 0;
}

TEST(EmitterEdges, CornellBoxLightOutlineByHand) {
    const SceneDescription desc = cornellBoxScene();
    const Vec2i res{256, 256};
    const RenderScene scene(desc);
    const std::vector<uint8_t> mask = emitterEdgePixels(scene, res);
    // The light quad (MISSION.md) as the camera sees it.
    const std::array<Vec3f, 4> corners = {Vec3f{343, 548, 227}, Vec3f{343, 548, 332},
                                          Vec3f{213, 548, 332}, Vec3f{213, 548, 227}};
    std::array<Vec2f, 4> film;
    for (int k = 0; k < 4; ++k) film[k] = project(desc.camera, res, corners[k]);
    // Its front edge lies 3% of a pixel into row 27, its back edge in row 36.
    EXPECT_NEAR(film[0].y, 27.031, 0.002);
    EXPECT_EQ(int(film[1].y), 36);
    int flagged = 0;
    for (int y = 0; y < res.y; ++y) {
        for (int x = 0; x < res.x; ++x) {
            double longest = 0;
            for (int k = 0; k < 4; ++k)
                longest = std::max(longest, lengthInside(film[k], film[(k + 1) % 4], x, y));
            const bool edge = mask[size_t(y) * res.x + x];
            flagged += edge;
            // Every pixel the outline crosses by more than a probe spacing is
            // found; no pixel it does not touch is.
            if (longest > 1.0 / 16) {
                EXPECT_TRUE(edge) << "missed pixel " << x << "," << y;
            }
            if (longest == 0) {
                EXPECT_FALSE(edge) << "pixel " << x << "," << y;
            }
        }
    }
    // Two rows under the front and back edges and the two slanted sides.
    EXPECT_GT(flagged, 88);
    EXPECT_LT(flagged, 130);
}

TEST(EmitterEdges, SameMaskForAnyThreadCount) {
    const RenderScene scene(cornellBoxScene());
    std::vector<uint8_t> one, two;
    {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
        one = emitterEdgePixels(scene, {64, 48});
    }
    {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
        two = emitterEdgePixels(scene, {64, 48});
    }
    EXPECT_EQ(one, two);
    EXPECT_GT(std::count(one.begin(), one.end(), uint8_t(1)), 0);
}

TEST(EmitterEdges, NoneWhereNoEmitterIsInView) {
    SceneDescription desc = cornellBoxScene();
    desc.camera.target = {278, 0, 300};  // down at the floor, narrowly
    desc.camera.fovY = 10;
    const RenderScene scene(desc);
    const std::vector<uint8_t> mask = emitterEdgePixels(scene, {32, 32});
    EXPECT_EQ(std::count(mask.begin(), mask.end(), uint8_t(1)), 0);
    EXPECT_THROW(emitterEdgePixels(scene, {0, 32}), std::invalid_argument);
}

}  // namespace
}  // namespace pathlab
