// The general camera (render/camera_model.h): pbrt-v4's perspective and
// orthographic cameras against hand-computed rays, the thin lens's focus, the
// dimension layout with and without a lens, and renders that depend on the
// lens — out-of-focus edges against their exact blur, and bit-identical
// images for any thread count.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>

#include "core/hash.h"
#include "render/batched_paths.h"
#include "render/camera_model.h"
#include "render/camera_samples.h"
#include "render/path_integrator.h"
#include "render/renderer.h"
#include "scene/builtin_scenes.h"

namespace pathlab {
namespace {

void expectNear(Vec3f a, Vec3f b, float tolerance, const std::string& what) {
    EXPECT_NEAR(a.x, b.x, tolerance) << what;
    EXPECT_NEAR(a.y, b.y, tolerance) << what;
    EXPECT_NEAR(a.z, b.z, tolerance) << what;
}

// pbrt-v4's `Scale -1 1 1  LookAt 1 2 3  1 2 4  0 1 0`: LookAt's camera x
// is world +x, and the scale mirrors it.
Camera mirroredPbrtCamera() {
    Camera c;
    c.pbrtFrame = true;
    c.eye = {1, 2, 3};
    c.axisX = {-1, 0, 0};
    c.axisY = {0, 1, 0};
    c.axisZ = {0, 0, 1};
    c.fov = 90;
    return c;
}

TEST(CameraModel, PerspectiveRaysFollowPbrtRasterAndScreen) {
    // 4×2: the default screen window is [−2, 2] × [−1, 1] and tan(45°) = 1,
    // so raster (x, y) looks along camera (x − 2, 1 − y, 1).
    Camera c = mirroredPbrtCamera();
    const ProjectiveCamera mirrored(c, {4, 2});
    const struct {
        Vec2f raster;
        Vec3f cameraDirection;
    } cases[] = {{{0.5f, 0.5f}, {-1.5f, 0.5f, 1}},
                 {{3.5f, 1.5f}, {1.5f, -0.5f, 1}},
                 {{2, 1}, {0, 0, 1}},
                 {{0, 0}, {-2, 1, 1}}};
    for (const auto& k : cases) {
        const Vec3f d = normalize(k.cameraDirection);
        const CameraRay r = mirrored.ray(k.raster, {0.5f, 0.5f});
        expectNear(r.origin, {1, 2, 3}, 0, "origin");
        // Mirrored: camera x is world −x.
        expectNear(r.direction, {-d.x, d.y, d.z}, 1e-6f, "mirrored direction");
    }
    c.axisX = {1, 0, 0};
    const ProjectiveCamera plain(c, {4, 2});
    const Vec3f d = normalize(Vec3f(-1.5f, 0.5f, 1));
    expectNear(plain.ray({0.5f, 0.5f}, {0.5f, 0.5f}).direction, d, 1e-6f, "unmirrored");
    // Raster x grows with screen x; raster y grows downwards.
    EXPECT_LT(plain.ray({1, 1}, {}).direction.x, plain.ray({3, 1}, {}).direction.x);
    EXPECT_GT(mirrored.ray({1, 1}, {}).direction.x, mirrored.ray({3, 1}, {}).direction.x);
    EXPECT_GT(plain.ray({2, 0.2f}, {}).direction.y, plain.ray({2, 1.8f}, {}).direction.y);
}

TEST(CameraModel, ScreenWindowAndFrameAspect) {
    Camera c = mirroredPbrtCamera();
    c.axisX = {1, 0, 0};
    // Portrait 2×4: the fov spans the shorter side, x: [−1, 1] × [−2, 2].
    const ScreenWindow portrait = pbrtScreenWindow(c, {2, 4});
    EXPECT_EQ(portrait.xmin, -1);
    EXPECT_EQ(portrait.xmax, 1);
    EXPECT_EQ(portrait.ymin, -2);
    EXPECT_EQ(portrait.ymax, 2);
    const ProjectiveCamera tall(c, {2, 4});
    // The left edge's middle is 45° off axis (fov/2), the top's middle atan 2.
    expectNear(tall.ray({0, 2}, {}).direction, normalize(Vec3f(-1, 0, 1)), 1e-6f, "left edge");
    expectNear(tall.ray({1, 0}, {}).direction, normalize(Vec3f(0, 2, 1)), 1e-6f, "top edge");
    // frameaspectratio overrides the image's: 0.5 on a square image.
    c.frameAspectRatio = 0.5f;
    const ScreenWindow framed = pbrtScreenWindow(c, {4, 4});
    EXPECT_EQ(framed.xmax, 1);
    EXPECT_EQ(framed.ymax, 2);
    c.frameAspectRatio = 3;
    EXPECT_EQ(pbrtScreenWindow(c, {4, 4}).xmin, -3);
    EXPECT_EQ(pbrtScreenWindow(c, {4, 4}).ymin, -1);
    // An explicit window, fov 60° (tan 30° = 0.57735) on 8×2: raster (0, 0)
    // is screen (−1, ½), raster (8, 2) is (3, −½).
    c.frameAspectRatio = 0;
    c.fov = 60;
    const float window[4] = {-1, 3, -0.5f, 0.5f};
    std::copy(window, window + 4, c.screenWindow);
    const ProjectiveCamera explicitWindow(c, {8, 2});
    const float t = std::tan(kPi / 6);
    expectNear(explicitWindow.ray({0, 0}, {}).direction, normalize(Vec3f(-t, 0.5f * t, 1)), 1e-6f,
               "window corner");
    expectNear(explicitWindow.ray({8, 2}, {}).direction, normalize(Vec3f(3 * t, -0.5f * t, 1)),
               1e-6f, "opposite corner");
}

TEST(CameraModel, OrthographicRaysStartOnTheScreenWindow) {
    Camera c = mirroredPbrtCamera();
    c.projection = Projection::Orthographic;
    // A frame turned 90° about y, with a scaled x axis: the origin moves
    // along axisX·sx + axisY·sy, every ray runs along axisZ.
    c.axisX = {0, 0, 2};
    c.axisY = {0, 1, 0};
    c.axisZ = {-1, 0, 0};
    const ProjectiveCamera ortho(c, {4, 2});
    EXPECT_FALSE(ortho.sharedOrigin());
    const CameraRay a = ortho.ray({0.5f, 0.5f}, {});  // screen (−1.5, ½)
    expectNear(a.origin, {1, 2.5f, 0}, 1e-6f, "origin");
    expectNear(a.direction, {-1, 0, 0}, 0, "direction");
    const CameraRay b = ortho.ray({4, 0}, {});  // screen (2, 1)
    expectNear(b.origin, {1, 3, 7}, 1e-6f, "corner origin");
    expectNear(b.direction, {-1, 0, 0}, 0, "corner direction");
}

// An orthonormal frame turned away from the world axes.
void setTurnedFrame(Camera& c) {
    const Vec3f z = normalize(Vec3f(1, 0.5f, 2));
    const Vec3f x = normalize(cross(Vec3f(0, 1, 0), z));
    c.axisX = x, c.axisY = cross(z, x), c.axisZ = z;
    c.eye = {-3, 1, 0.5f};
}

TEST(CameraModel, ThinLensFocusesEveryLensSampleOnOnePoint) {
    for (Projection projection : {Projection::Perspective, Projection::Orthographic}) {
        Camera c = mirroredPbrtCamera();
        setTurnedFrame(c);
        c.projection = projection;
        c.fov = 50;
        c.lensRadius = 0.3f;
        c.focalDistance = 7;
        const ProjectiveCamera camera(c, {32, 24});
        EXPECT_TRUE(camera.hasLens());
        EXPECT_FALSE(camera.sharedOrigin());
        for (Vec2f film : {Vec2f{0.5f, 0.5f}, Vec2f{16, 12}, Vec2f{31.2f, 3.7f}}) {
            // Where the ray meets the plane of focus, camera z = 7.
            const auto focusPoint = [&](const CameraRay& r) {
                const float t =
                    (c.focalDistance - dot(r.origin - c.eye, c.axisZ)) / dot(r.direction, c.axisZ);
                return r.origin + r.direction * t;
            };
            const CameraRay centre = camera.ray(film, {0.5f, 0.5f});
            const Vec3f sharp = focusPoint(centre);
            float spread = 0;
            for (int i = 0; i < 16; ++i)
                for (int j = 0; j < 16; ++j) {
                    const Vec2f u{(float(i) + 0.3f) / 16, (float(j) + 0.6f) / 16};
                    const CameraRay r = camera.ray(film, u);
                    // The origin lies on the lens disk around the pinhole
                    // ray's origin, in the camera's z = 0 plane.
                    const Vec3f offset = r.origin - centre.origin;
                    EXPECT_NEAR(dot(offset, c.axisZ), 0, 1e-5f);
                    EXPECT_LE(length(offset), c.lensRadius * 1.0001f);
                    spread = std::max(spread, length(offset));
                    expectNear(focusPoint(r), sharp, 2e-5f * 7 * 4, "focus");
                    EXPECT_NEAR(length(r.direction), 1, 1e-6f);
                }
            EXPECT_GT(spread, 0.25f) << "the lens samples cover the lens";
        }
    }
}

TEST(CameraModel, PbrtFrameOfTheClassicCameraGivesItsRays) {
    // A classic camera and the pbrt frame it amounts to (x = image right,
    // y = image up, z = forward, fov across the shorter side) agree on every
    // film position: the raster conventions are the same.
    const Camera classic = cornellBoxScene().camera;
    Camera pbrt = classic;
    pbrt.pbrtFrame = true;
    const Vec3f forward = normalize(classic.target - classic.eye);
    const Vec3f right = normalize(cross(forward, classic.up));
    pbrt.axisX = right, pbrt.axisY = cross(right, forward), pbrt.axisZ = forward;
    pbrt.fov = classic.fovY;
    const Vec2i res{48, 32};
    const CameraModel a(classic, res), b(pbrt, res);
    EXPECT_TRUE(a.isPinhole());
    EXPECT_FALSE(b.isPinhole());
    for (float y = 0; y <= 32; y += 3.7f)
        for (float x = 0; x <= 48; x += 5.3f) {
            const CameraRay ra = a.centralRay({x, y}), rb = b.centralRay({x, y});
            expectNear(ra.origin, rb.origin, 0, "origin");
            expectNear(ra.direction, rb.direction, 2e-6f, "direction");
        }
}

// A sampler that records every (sample index, dimension) it is asked for and
// answers a hash of them: a pure function of (pixel, index, dimension), as a
// sampler must be.
struct RecordingSampler {
    std::map<std::pair<int, int>, int> drawn;  // (index, dimension) → times
    int index = 0, dimension = 0;
    int samplesPerPixel() const { return 64; }
    void startPixelSample(Vec2i, int i, int d) { index = i, dimension = d; }
    float get1D() {
        ++drawn[{index, dimension}];
        const uint64_t h = hashValues(uint64_t(index), uint64_t(dimension++), 77u);
        return std::min(float(h >> 40) * 0x1p-24f, kOneMinusEpsilon);
    }
    Vec2f get2D() {
        const float a = get1D();
        return {a, get1D()};
    }
    Vec2f getPixel2D() { return get2D(); }
};

// The dimensions the renderer's camera samples and paths draw for 24
// samples of one pixel of the Cornell box seen through `camera`, by the
// batched or the one-at-a-time integrator.
std::map<std::pair<int, int>, int> drawnDimensions(const Camera& camera, bool batch) {
    SceneDescription desc = cornellBoxScene();
    desc.camera = camera;
    const RenderScene scene(desc);
    const Vec2i res{16, 16}, pixel{7, 9};
    const CameraModel model(camera, res);
    const FilterSampler filter(PixelFilter{});
    RecordingSampler sampler;
    IntegratorSettings settings;
    settings.firstBounce = dims::firstBounce(model.hasLens());
    settings.batchPaths = batch;
    const int count = 24;
    Vec3f origins[kBatchSamples], dirs[kBatchSamples], L[kBatchSamples];
    float weights[kBatchSamples];
    SurfaceInteraction si[kBatchSamples];
    bool found[kBatchSamples];
    for (int p0 = 0; p0 < count; p0 += kCameraPacketSamples)
        drawCameraSamples(model, filter, sampler, pixel, p0, kCameraPacketSamples, origins + p0,
                          dirs + p0, weights + p0);
    for (int k = 0; k < count; ++k) found[k] = scene.intersect(origins[k], dirs[k], &si[k]);
    PathCounters counters;
    if (batch)
        estimateRadianceBatch(scene, dirs, found, si, count, sampler, pixel, 0, settings, counters,
                              L);
    else
        for (int k = 0; k < count; ++k)
            L[k] = estimateRadiance(scene, origins[k], dirs[k], found[k], si[k], sampler, pixel, k,
                                    settings, counters);
    return sampler.drawn;
}

TEST(CameraModel, LensDimensionsFollowThePixelsAndShiftThePaths) {
    const Camera classic = cornellBoxScene().camera;
    Camera pinhole = classic;
    pinhole.pbrtFrame = true;
    const Vec3f forward = normalize(classic.target - classic.eye);
    const Vec3f right = normalize(cross(forward, classic.up));
    pinhole.axisX = right, pinhole.axisY = cross(right, forward), pinhole.axisZ = forward;
    pinhole.fov = classic.fovY;
    Camera lens = pinhole;
    lens.lensRadius = 20;
    lens.focalDistance = 800;
    const Camera* cameras[] = {&classic, &pinhole, &lens};
    for (bool batch : {false, true}) {
        for (const Camera* camera : cameras) {
            const bool hasLens = camera == &lens;
            const int first = hasLens ? 4 : 2;
            const auto drawn = drawnDimensions(*camera, batch);
            for (const auto& [key, times] : drawn) {
                const auto [index, dim] = key;
                EXPECT_EQ(times, 1) << "index " << index << " dimension " << dim;
                if (dim < first) continue;  // the pixel, then the lens
                // The Cornell box is Lambertian with one light: no light
                // choice (+0) and no lobe (+3) is ever drawn.
                const int offset = (dim - first) % dims::kDimsPerBounce;
                EXPECT_NE(offset, dims::kLightChoice) << "dimension " << dim;
                EXPECT_NE(offset, dims::kBsdfLobe) << "dimension " << dim;
            }
            for (int k = 0; k < 24; ++k) {
                EXPECT_EQ(drawn.count({k, 0}), 1u) << "sample " << k;
                EXPECT_EQ(drawn.count({k, 1}), 1u) << "sample " << k;
                // The lens's dimensions exist only with a lens (dimension 3
                // is otherwise vertex 0's light point).
                EXPECT_EQ(drawn.count({k, 2}), hasLens ? 1u : 0u) << "sample " << k;
                // Every camera ray lands on a diffuse wall: vertex 0 samples
                // the light at first + 1, first + 2.
                EXPECT_EQ(drawn.count({k, first + dims::kLightPoint}), 1u) << "sample " << k;
                EXPECT_EQ(drawn.count({k, first + dims::kLightPoint + 1}), 1u) << "sample " << k;
            }
        }
    }
}

// A two-sided emitter of radiance 1 filling the half-plane x > 0 at z = 2,
// seen by a pbrt camera at the origin looking down +z (16×4, fov 40°, so the
// screen window is [−4, 4] × [−1, 1] and a pixel spans ½ in screen x),
// focused at z = 1 through a lens of radius ½; max depth 0.
SceneDescription defocusedEdge(float lensRadius) {
    SceneDescription s;
    s.materials.push_back(Material{"black", MaterialType::Diffuse, Vec3f(0.0f)});
    Mesh m;
    m.positions = {{0, -50, 2}, {50, -50, 2}, {50, 50, 2}, {0, 50, 2}};
    m.indices = {0, 1, 2, 0, 2, 3};
    m.emission = Vec3f(1.0f);
    m.twoSided = true;
    s.meshes.push_back(m);
    s.camera.pbrtFrame = true;
    s.camera.eye = {0, 0, 0};
    s.camera.fov = 40;
    s.camera.lensRadius = lensRadius;
    s.camera.focalDistance = 1;
    s.resolution = {16, 4};
    return s;
}

// The exact value of column i of defocusedEdge(R): the ray from lens point
// (lx, ly) through screen x = sx meets z = 2 at x = 2·tan(20°)·sx − lx, so
// the fraction of the lens disk that sees the emitter is P(lx < c), c =
// 2·tan(20°)·sx, averaged over the pixel's sx (a midpoint rule in double).
double defocusedEdgeValue(int column, double R) {
    const double t = std::tan(20 * M_PI / 180);
    const int steps = 20000;
    double sum = 0;
    for (int k = 0; k < steps; ++k) {
        const double sx = -4 + 0.5 * (column + (k + 0.5) / steps);
        const double c = std::clamp(2 * t * sx / R, -1.0, 1.0);
        sum += 0.5 + (c * std::sqrt(1 - c * c) + std::asin(c)) / M_PI;
    }
    return sum / steps;
}

TEST(LensRender, DefocusedEdgeMatchesItsExactBlur) {
    const double R = 0.5;
    const RenderScene scene(defocusedEdge(float(R)));
    RenderSettings s;
    s.maxDepth = 0;
    s.samplesPerPixel = 256;
    const RenderOutput out = render(scene, s);
    int blurred = 0;
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 16; ++x) {
            const double expected = defocusedEdgeValue(x, R);
            const double got = out.image.at(x, y).x;
            // Each sample sees the emitter or not: a binomial proportion.
            const double se = std::sqrt(expected * (1 - expected) / s.samplesPerPixel);
            EXPECT_NEAR(got, expected, 5 * se + 1e-6) << "pixel " << x << ", " << y;
            blurred += expected > 0.01 && expected < 0.99;
        }
    EXPECT_EQ(blurred, 4 * 4) << "four columns are in the blur";
    // Without the lens the edge is sharp: it falls between columns 7 and 8.
    const RenderOutput pinhole = render(RenderScene(defocusedEdge(0)), s);
    for (int x = 0; x < 16; ++x) EXPECT_EQ(pinhole.image.at(x, 1).x, x < 8 ? 0.0f : 1.0f);
}

TEST(LensRender, SamplersStratifyTheLensWithThePixel) {
    // The lens position is the sampler's dimensions 2 and 3, drawn with the
    // pixel's 0 and 1: a sampler whose first four dimensions are well
    // distributed together integrates the blur far better than independent
    // numbers. (Were the lens drawn from anywhere else, the gap would close.)
    const double R = 0.5;
    const RenderScene scene(defocusedEdge(float(R)));
    const auto blurError = [&](const std::string& sampler) {
        double squared = 0;
        int n = 0;
        for (uint64_t seed = 0; seed < 4; ++seed) {
            RenderSettings s;
            s.sampler = sampler;
            s.seed = seed;
            s.maxDepth = 0;
            s.samplesPerPixel = 64;
            const RenderOutput out = render(scene, s);
            for (int y = 0; y < 4; ++y)
                for (int x = 6; x < 10; ++x) {
                    const double e = out.image.at(x, y).x - defocusedEdgeValue(x, R);
                    squared += e * e, ++n;
                }
        }
        return squared / n;
    };
    const double independent = blurError("independent");
    for (const char* sampler : {"sobol-xor", "halton-owen"}) {
        const double error = blurError(sampler);
        EXPECT_LT(error, 0.25 * independent) << sampler;
        std::printf("%s: %.3g of independent's squared error\n", sampler, error / independent);
    }
}

// The Cornell box through a pbrt camera with a thin lens, a Gaussian filter
// and a crop window.
SceneDescription lensCornell() {
    SceneDescription desc = cornellBoxScene();
    const Camera classic = desc.camera;
    Camera& c = desc.camera;
    c.pbrtFrame = true;
    const Vec3f forward = normalize(classic.target - classic.eye);
    const Vec3f right = normalize(cross(forward, classic.up));
    c.axisX = right, c.axisY = cross(right, forward), c.axisZ = forward;
    c.fov = classic.fovY;
    c.lensRadius = 15;
    c.focalDistance = 700;
    desc.film.filter = defaultPixelFilter(FilterType::Gaussian);
    const float crop[4] = {0.1f, 0.9f, 0.05f, 1};
    std::copy(crop, crop + 4, desc.film.cropWindow);
    desc.resolution = {37, 29};  // tiles of unequal size
    return desc;
}

TEST(LensRender, IdenticalBytesForAnyThreadCount) {
    const RenderScene scene(lensCornell());
    for (const char* sampler : {"independent", "zsobol"}) {
        std::vector<float> image, variance;
        for (int threads : {1, 2, 8}) {
            RenderSettings s;
            s.sampler = sampler;
            s.samplesPerPixel = 8;
            s.threads = threads;
            s.seed = 5;
            const RenderOutput out = render(scene, s);
            if (image.empty()) {
                image = out.image.rgb, variance = out.varianceOfMean.rgb;
                continue;
            }
            ASSERT_EQ(0, std::memcmp(image.data(), out.image.rgb.data(), image.size() * 4))
                << sampler << " with " << threads << " threads";
            ASSERT_EQ(
                0, std::memcmp(variance.data(), out.varianceOfMean.rgb.data(), variance.size() * 4))
                << sampler << " with " << threads << " threads";
        }
    }
}

TEST(LensRender, BatchedPathsAreTheOneAtATimePathsBitForBit) {
    // With a lens the camera rays start at different points and vertex 0's
    // dimensions move up by two: both integrators must still agree.
    for (Projection projection : {Projection::Perspective, Projection::Orthographic}) {
        SceneDescription desc = lensCornell();
        desc.camera.projection = projection;
        if (projection == Projection::Orthographic) {
            // Screen units are world units: a window over the box's front.
            const float window[4] = {-300, 300, -300, 300};
            std::copy(window, window + 4, desc.camera.screenWindow);
        }
        const RenderScene scene(desc);
        RenderSettings s;
        s.sampler = "halton-owen";
        s.samplesPerPixel = 16;
        s.resolution = {20, 14};
        const RenderOutput batched = render(scene, s);
        s.batchPaths = false;
        const RenderOutput single = render(scene, s);
        EXPECT_EQ(0, std::memcmp(batched.image.rgb.data(), single.image.rgb.data(),
                                 batched.image.rgb.size() * 4));
        double sum = 0;
        for (float v : batched.image.rgb) sum += v;
        EXPECT_GT(sum, 0) << "the camera sees the lit box";
    }
}

}  // namespace
}  // namespace pathlab
