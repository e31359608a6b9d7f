// Light selection (render/light_sampling/): each strategy's probabilities sum
// to one and match how often choose() picks each light; the light BVH's
// probability of a light is the product of the branch probabilities on its
// path; renders with every strategy converge to the same image; the BVH beats
// uniform selection on the many-light scene; and the choice is deterministic.
#include <gtest/gtest.h>

#include <boost/math/distributions/chi_squared.hpp>
#include <cstring>
#include <random>

#include "core/error.h"
#include "render/light_sampling/light_chooser.h"
#include "render/renderer.h"
#include "scene/json_scene.h"
#include "scene/loader.h"
#include "scene_test_util.h"

namespace pathlab {
namespace {

using test::inputErrorOf;

const std::string kManyLights = std::string(PATHLAB_SOURCE_DIR) + "/scenes/pbrt/many-lights.pbrt";

// The many-light scene plus one light of every other kind: a point light, a
// spot light, a distant light and a constant environment.
SceneDescription manyLightsWithEveryKind() {
    SceneDescription desc = loadScene(kManyLights);
    PunctualLight point;
    point.position = {1, 3, 4};
    point.intensity = {2, 2, 1.5f};
    PunctualLight spot;
    spot.type = PunctualLightType::Spot;
    spot.position = {-3, 4, 6};
    spot.direction = normalize(Vec3f(0.2f, -1, 0.1f));
    spot.intensity = {5, 3, 2};
    setSpotCone(spot, 30, 8);
    PunctualLight sun;
    sun.type = PunctualLightType::Distant;
    sun.direction = normalize(Vec3f(0.3f, -1, 0.5f));
    sun.radiance = {0.5f, 0.45f, 0.4f};
    desc.punctualLights = {point, spot, sun};
    desc.environment = Vec3f(0.05f);
    return desc;
}

struct Receiver {
    Vec3f p, n;
};
// On the floor facing up, under the hanging plate, in the air with no normal,
// and on the back wall.
const Receiver kReceivers[] = {{{-3, 0, 1}, {0, 1, 0}},
                               {{1, 0, 9}, {0, 1, 0}},
                               {{0, 2, 5}, {0, 0, 0}},
                               {{4, 3, 18}, {0, 0, -1}}};

// Pearson's chi-square p-value of the counts against the probabilities,
// pooling lights expected fewer than 5 times.
double chiSquarePValue(const std::vector<double>& observed, const std::vector<double>& pmf,
                       int draws) {
    double chi2 = 0, pooledObserved = 0, pooledExpected = 0;
    int dof = -1;
    for (size_t i = 0; i < pmf.size(); ++i) {
        const double e = pmf[i] * draws;
        if (e < 5) {
            pooledObserved += observed[i], pooledExpected += e;
            continue;
        }
        chi2 += (observed[i] - e) * (observed[i] - e) / e, ++dof;
    }
    if (pooledExpected >= 5) {
        chi2 +=
            (pooledObserved - pooledExpected) * (pooledObserved - pooledExpected) / pooledExpected;
        ++dof;
    } else if (pooledObserved > 0 && pooledExpected == 0) {
        return 0;  // a light chosen that should never be
    }
    if (dof < 1) return 1;
    return boost::math::cdf(boost::math::complement(boost::math::chi_squared(dof), chi2));
}

TEST(LightSelection, PmfSumsToOneAndMatchesChoiceFrequency) {
    const SceneDescription desc = manyLightsWithEveryKind();
    for (LightSelection s : {LightSelection::Uniform, LightSelection::Power, LightSelection::Bvh}) {
        const LightSet lights(desc, desc.camera.target, LightSampling::Area, s);
        const LightChooser& chooser = lights.chooser();
        ASSERT_EQ(chooser.size(), 200u + 4u);
        for (const Receiver& r : kReceivers) {
            std::vector<double> pmf(chooser.size());
            double sum = 0;
            for (size_t i = 0; i < pmf.size(); ++i) sum += pmf[i] = chooser.pmf(r.p, r.n, i);
            // The BVH may find no light at all where every light of a subtree
            // it entered faces away (pbrt-v4's does the same): the pmfs then sum
            // to the probability of finding one, and the last bin counts misses.
            if (s == LightSelection::Bvh) {
                EXPECT_LE(sum, 1.0 + 1e-4);
                EXPECT_GT(sum, 0.9);
            } else {
                EXPECT_NEAR(sum, 1.0, 1e-4) << lightSelectionName(s);
            }
            pmf.push_back(std::max(0.0, 1 - sum));
            constexpr int kDraws = 200000;
            std::mt19937 rng(7);
            std::uniform_real_distribution<float> uniform(0, 1);
            std::vector<double> observed(pmf.size(), 0);
            for (int k = 0; k < kDraws; ++k) {
                const auto c = chooser.choose(r.p, r.n, std::min(uniform(rng), kOneMinusEpsilon));
                if (!c) {
                    observed.back() += 1;
                    continue;
                }
                // The probability reported with a choice is the light's pmf.
                ASSERT_FLOAT_EQ(c->pmf, float(pmf[size_t(c->light)]));
                observed[size_t(c->light)] += 1;
            }
            // Šidák-corrected 1% over the 12 tests of this loop.
            EXPECT_GT(chiSquarePValue(observed, pmf, kDraws), 1 - std::pow(0.99, 1.0 / 12))
                << lightSelectionName(s) << " at " << r.p.x << "," << r.p.y << "," << r.p.z;
        }
    }
}

// Walks the tree from the outside: for every leaf, the product of
// importance(child) / (importance(child) + importance(sibling)) on its path.
void leafProducts(const LightBvh& bvh, int node, double product, Vec3f p, Vec3f n,
                  std::vector<double>& out) {
    const auto& nodes = bvh.nodes();
    const LightBvh::Node& x = nodes[size_t(node)];
    if (x.leaf) {
        out[size_t(x.childOrLight)] = product;
        return;
    }
    const double i0 = nodes[size_t(node + 1)].bounds.importance(p, n);
    const double i1 = nodes[size_t(x.childOrLight)].bounds.importance(p, n);
    const double sum = i0 + i1;
    leafProducts(bvh, node + 1, sum > 0 ? product * i0 / sum : 0, p, n, out);
    leafProducts(bvh, x.childOrLight, sum > 0 ? product * i1 / sum : 0, p, n, out);
}

TEST(LightBvh, PmfIsTheProductOfBranchProbabilities) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(-1, 1);
    std::vector<LightBounds> lights;
    for (int i = 0; i < 300; ++i) {
        LightBounds b;
        const Vec3f c{5 * u(rng), 5 * u(rng), 5 * u(rng)};
        b.bounds.extend(c), b.bounds.extend(c + Vec3f(0.2f * std::abs(u(rng)), 0.1f, 0.15f));
        b.phi = 1 + 10 * std::abs(u(rng));
        b.normals = {normalize(Vec3f(u(rng), u(rng), u(rng)) + Vec3f(0, 0, 0.01f)), 1};
        b.twoSided = i % 7 == 0;
        lights.push_back(b);
    }
    const LightBvh bvh(lights);
    EXPECT_EQ(bvh.nodes().size(), 2 * lights.size() - 1);  // a binary tree of 300 leaves
    EXPECT_LT(bvh.depth(), 40);
    for (const Receiver& r : kReceivers) {
        std::vector<double> product(lights.size(), -1);
        leafProducts(bvh, 0, 1, r.p, r.n, product);
        for (size_t i = 0; i < lights.size(); ++i) {
            ASSERT_GE(product[i], 0) << "light " << i << " has no leaf";
            EXPECT_NEAR(bvh.pmf(r.p, r.n, int(i)), product[i], 1e-6 + 1e-4 * product[i]) << i;
        }
    }
}

TEST(LightBounds, UnionHoldsBothBoxesAndCones) {
    LightBounds a, b;
    a.bounds.extend({0, 0, 0}), a.bounds.extend({1, 1, 1});
    b.bounds.extend({2, -1, 0}), b.bounds.extend({3, 0, 0.5f});
    a.phi = 1, b.phi = 2;
    a.normals = {{0, 0, 1}, std::cos(0.3f)};
    b.normals = {normalize(Vec3f(1, 0, 1)), std::cos(0.2f)};
    const LightBounds u = unionBounds(a, b);
    EXPECT_FLOAT_EQ(u.phi, 3);
    EXPECT_EQ(u.bounds.lo.x, 0);
    EXPECT_EQ(u.bounds.lo.y, -1);
    EXPECT_EQ(u.bounds.hi.x, 3);
    // Each cone's axis tilted to its edge in both directions lies within the union.
    for (const LightBounds* x : {&a, &b})
        for (float side : {-1.0f, 1.0f}) {
            const float t = std::acos(x->normals.cosTheta) * side;
            const Vec3f w = x->normals.w;
            const Vec3f axis = normalize(cross(w, Vec3f(0, 1, 0)));
            const Vec3f edge = w * std::cos(t) + cross(axis, w) * std::sin(t);
            EXPECT_GE(dot(edge, u.normals.w), u.normals.cosTheta - 1e-5f);
        }
}

RenderSettings smallRender(int spp, uint64_t seed = 0) {
    RenderSettings s;
    s.sampler = "zsobol";
    s.samplesPerPixel = spp;
    s.seed = seed;
    s.resolution = {40, 30};
    s.maxDepth = 3;
    s.threads = 2;
    return s;
}

RenderOutput renderWith(SceneDescription desc, LightSelection s, const RenderSettings& settings) {
    desc.defaults.lightSampler = lightSelectionName(s);
    return render(RenderScene(std::move(desc)), settings);
}

TEST(LightSelection, StrategiesConvergeToTheSameImage) {
    const SceneDescription desc = manyLightsWithEveryKind();
    const RenderOutput power = renderWith(desc, LightSelection::Power, smallRender(64));
    for (LightSelection s : {LightSelection::Uniform, LightSelection::Bvh}) {
        const RenderOutput other = renderWith(desc, s, smallRender(64, 1));
        for (int c = 0; c < 3; ++c) {
            double a = 0, b = 0, var = 0;
            for (size_t i = size_t(c); i < power.image.rgb.size(); i += 3) {
                a += power.image.rgb[i], b += other.image.rgb[i];
                var += power.varianceOfMean.rgb[i] + other.varianceOfMean.rgb[i];
            }
            // Five standard errors of the difference of the two means.
            EXPECT_NEAR(a, b, 5 * std::sqrt(var)) << lightSelectionName(s) << " channel " << c;
        }
    }
}

// MSE over the pixels that see lit surfaces, not an emitter (reference below
// 1 in every channel): the emitters' own antialiasing noise is the same for
// every strategy and would drown the difference.
double litSurfaceMse(const Image& reference, const Image& image) {
    double sum = 0;
    size_t count = 0;
    for (size_t i = 0; i < image.rgb.size(); i += 3) {
        if (reference.rgb[i] >= 1 || reference.rgb[i + 1] >= 1 || reference.rgb[i + 2] >= 1)
            continue;
        for (size_t c = i; c < i + 3; ++c) {
            const double d = double(image.rgb[c]) - reference.rgb[c];
            sum += d * d;
        }
        count += 3;
    }
    return sum / double(count);
}

TEST(LightSelection, BvhHasLowerErrorThanUniformAndPowerOnManyLights) {
    const SceneDescription desc = loadScene(kManyLights);
    const Image reference = renderWith(desc, LightSelection::Bvh, smallRender(1024, 9)).image;
    const auto mse = [&](LightSelection s) {
        return litSurfaceMse(reference, renderWith(desc, s, smallRender(16)).image);
    };
    const double uniform = mse(LightSelection::Uniform), power = mse(LightSelection::Power);
    const double bvh = mse(LightSelection::Bvh);
    EXPECT_LT(bvh, 0.5 * uniform) << "bvh " << bvh << " uniform " << uniform;
    EXPECT_LT(bvh, power) << "bvh " << bvh << " power " << power;
}

TEST(LightSelection, BvhImageIsTheSameWhateverTheThreadCount) {
    const SceneDescription desc = manyLightsWithEveryKind();
    RenderSettings one = smallRender(8);
    one.threads = 1;
    const Image a = renderWith(desc, LightSelection::Bvh, one).image;
    const Image b = renderWith(desc, LightSelection::Bvh, smallRender(8)).image;
    ASSERT_EQ(a.rgb.size(), b.rgb.size());
    EXPECT_EQ(0, std::memcmp(a.rgb.data(), b.rgb.data(), a.rgb.size() * sizeof(float)));
}

TEST(LightSelection, UnknownNamesAreRefusedNamingTheOption) {
    EXPECT_EQ(inputErrorOf([] { parseLightSelection("bhv", "--light-sampler"); }),
              "--light-sampler must be one of uniform, power, bvh, got 'bhv'");
    EXPECT_EQ(parseLightSelection("", "x"), LightSelection::Power);
    EXPECT_EQ(parseLightSelection("bvh", "x"), LightSelection::Bvh);
}

TEST(LightSelection, JsonSceneKeyIsReadWrittenAndChecked) {
    const auto scene = [](const std::string& sampler) {
        return R"({"camera": {"eye": [0, 1, 5], "target": [0, 0, 0], "fovY": 40},
          "lightSampler": ")" +
               sampler + R"(", "materials": {"m": {"type": "diffuse"}},
          "spheres": [{"center": [0, 0, 0], "radius": 1, "material": "m"}]})";
    };
    const SceneDescription s = parseJsonScene(scene("bvh"), ".", "t.json");
    EXPECT_EQ(s.defaults.lightSampler, "bvh");
    EXPECT_EQ(parseJsonScene(sceneToJson(s), ".", "again.json").defaults.lightSampler, "bvh");
    EXPECT_EQ(inputErrorOf([&] { parseJsonScene(scene("tree"), ".", "t.json"); }),
              "t.json: lightSampler: expected one of uniform, power, bvh, got 'tree'");
}

}  // namespace
}  // namespace pathlab
