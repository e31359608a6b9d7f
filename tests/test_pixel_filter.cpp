// Pixel filters (render/pixel_filter.h) and the weighted film: pbrt-v4's
// filter values, the samplers' densities by chi-square, their weights, and
// renders whose every pixel is known (a scene of constant radiance) or must
// equal another render bit for bit.
#include <gtest/gtest.h>

#include <boost/math/distributions/chi_squared.hpp>
#include <cmath>
#include <cstring>
#include <functional>
#include <random>

#include "core/error.h"
#include "image_test_util.h"
#include "render/pixel_filter.h"
#include "render/renderer.h"
#include "scene/builtin_scenes.h"
#include "scene_test_util.h"

namespace pathlab {
namespace {

PixelFilter filterOf(FilterType type) {
    return defaultPixelFilter(type);
}

TEST(PixelFilter, DefaultsArePbrtV4s) {
    EXPECT_EQ(filterOf(FilterType::Box).radius.x, 0.5f);
    EXPECT_EQ(filterOf(FilterType::Gaussian).radius.y, 1.5f);
    EXPECT_EQ(filterOf(FilterType::Gaussian).sigma, 0.5f);
    EXPECT_EQ(filterOf(FilterType::Mitchell).radius.x, 2.0f);
    EXPECT_FLOAT_EQ(filterOf(FilterType::Mitchell).b, 1 / 3.0f);
    EXPECT_EQ(filterOf(FilterType::Lanczos).radius.x, 4.0f);
    EXPECT_EQ(filterOf(FilterType::Lanczos).tau, 3.0f);
    EXPECT_EQ(filterOf(FilterType::Triangle).radius.y, 2.0f);
}

TEST(PixelFilter, ValuesMatchPbrtAtHandComputedPoints) {
    // Gaussian σ = ½, r = 1.5: (g(x) − g(1.5))·(g(y) − g(1.5)) with
    // g(0) = 1/√(π/2) = 0.797885, g(1.5) = g(0)·e^−4.5 = 0.008864.
    const PixelFilter g = filterOf(FilterType::Gaussian);
    EXPECT_NEAR(evaluateFilter(g, {0, 0}), 0.622554, 1e-6);
    EXPECT_NEAR(evaluateFilter(g, {0.5f, 1.0f}), 0.0470889, 1e-6);
    EXPECT_NEAR(evaluateFilter(g, {0.3f, -0.7f}), 0.191089, 1e-6);
    EXPECT_EQ(evaluateFilter(g, {1.6f, 0}), 0.0f);
    // Mitchell B = C = ⅓, r = 2: M(0) = 8/9, M(1) = 1/18, M(½) = 0.534722,
    // M(1.5) = −0.034722 (a negative lobe).
    const PixelFilter m = filterOf(FilterType::Mitchell);
    EXPECT_NEAR(evaluateFilter(m, {0, 0}), 64.0 / 81, 1e-6);
    EXPECT_NEAR(evaluateFilter(m, {1, 0}), 8.0 / 162, 1e-6);
    EXPECT_NEAR(evaluateFilter(m, {1.5f, 0.5f}), -0.0185667, 1e-6);
    EXPECT_EQ(evaluateFilter(m, {2.5f, 0}), 0.0f);
    // Lanczos τ = 3, r = 4: sinc(½)·sinc(⅙) = (2/π)·(3/π) = 0.607927.
    const PixelFilter l = filterOf(FilterType::Lanczos);
    EXPECT_NEAR(evaluateFilter(l, {0.5f, 0}), 6 / (kPi * kPi), 1e-6);
    EXPECT_NEAR(evaluateFilter(l, {1.5f, 0.25f}), -0.120244, 1e-6);
    EXPECT_EQ(evaluateFilter(l, {4.5f, 0}), 0.0f);
    // Triangle r = 2 and box r = ½.
    EXPECT_FLOAT_EQ(evaluateFilter(filterOf(FilterType::Triangle), {0.5f, -1}), 1.5f);
    EXPECT_EQ(evaluateFilter(filterOf(FilterType::Box), {0.5f, -0.5f}), 1.0f);
    EXPECT_EQ(evaluateFilter(filterOf(FilterType::Box), {0.51f, 0}), 0.0f);
}

// Pearson's chi-square of `count` offsets draw(u) (uniform u from a fixed
// seed) against |f|, integrated over an n × n grid of bins by a midpoint
// rule; bins expected to get fewer than 5 samples are pooled.
double filterChiSquarePValue(const PixelFilter& f, const std::function<Vec2f(Vec2f)>& draw, int n,
                             int count) {
    const Vec2f r = f.radius;
    std::vector<double> observed(size_t(n * n), 0.0), expected(observed.size(), 0.0);
    std::mt19937 rng(12345);
    std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
    for (int i = 0; i < count; ++i) {
        const Vec2f u{std::min(uniform(rng), kOneMinusEpsilon),
                      std::min(uniform(rng), kOneMinusEpsilon)};
        const Vec2f p = draw(u);
        EXPECT_LE(std::abs(p.x), r.x);
        EXPECT_LE(std::abs(p.y), r.y);
        const int bx = std::clamp(int((p.x + r.x) / (2 * r.x) * float(n)), 0, n - 1);
        const int by = std::clamp(int((p.y + r.y) / (2 * r.y) * float(n)), 0, n - 1);
        observed[size_t(by * n + bx)] += 1;
    }
    const int sub = 16;
    double total = 0;
    for (int by = 0; by < n; ++by)
        for (int bx = 0; bx < n; ++bx) {
            double sum = 0;
            for (int j = 0; j < sub; ++j)
                for (int i = 0; i < sub; ++i) {
                    const float x =
                        -r.x + 2 * r.x * (float(bx) + (float(i) + 0.5f) / sub) / float(n);
                    const float y =
                        -r.y + 2 * r.y * (float(by) + (float(j) + 0.5f) / sub) / float(n);
                    sum += std::abs(evaluateFilter(f, {x, y}));
                }
            expected[size_t(by * n + bx)] = sum;
            total += sum;
        }
    double chi2 = 0, pooledObserved = 0, pooledExpected = 0;
    int dof = -1;
    for (size_t k = 0; k < observed.size(); ++k) {
        const double e = expected[k] / total * count;
        if (e < 5) {
            pooledObserved += observed[k], pooledExpected += e;
            continue;
        }
        chi2 += (observed[k] - e) * (observed[k] - e) / e;
        ++dof;
    }
    if (pooledExpected > 5) {
        chi2 +=
            (pooledObserved - pooledExpected) * (pooledObserved - pooledExpected) / pooledExpected;
        ++dof;
    } else if (pooledObserved > 10) {
        return 0;  // samples where |f| is (nearly) zero
    }
    return 1 - boost::math::cdf(boost::math::chi_squared(dof), chi2);
}

TEST(FilterSampling, PositionsFollowAbsoluteFilterValue) {
    PixelFilter wideBox = filterOf(FilterType::Box);
    wideBox.radius = {1.5f, 0.75f};
    PixelFilter narrowGaussian = filterOf(FilterType::Gaussian);
    narrowGaussian.radius = {1.0f, 2.0f};
    narrowGaussian.sigma = 0.4f;
    PixelFilter lanczos = filterOf(FilterType::Lanczos);
    lanczos.radius = {2, 2};
    const PixelFilter filters[] = {filterOf(FilterType::Box),
                                   wideBox,
                                   filterOf(FilterType::Triangle),
                                   filterOf(FilterType::Gaussian),
                                   narrowGaussian,
                                   filterOf(FilterType::Mitchell),
                                   lanczos};
    int i = 0;
    for (const PixelFilter& f : filters) {
        const FilterSampler sampler(f);
        const auto draw = [&](Vec2f u) { return sampler.sample(u).p; };
        // 7 tests: Šidák-corrected 1% overall.
        EXPECT_GT(filterChiSquarePValue(f, draw, 16, 200000), 1 - std::pow(0.99, 1.0 / 7))
            << "filter " << i;
        ++i;
    }
}

TEST(FilterSampling, ChiSquareHasPower) {
    // The check above fails a sampler that is wrong: a box's positions judged
    // against Mitchell's |f| on the same domain, a Gaussian drawn with the
    // wrong sigma, and Catmull–Rom's positions squeezed by a fifth in x.
    PixelFilter box = filterOf(FilterType::Box);
    box.radius = {2, 2};
    const FilterSampler boxSampler(box);
    EXPECT_LT(filterChiSquarePValue(
                  filterOf(FilterType::Mitchell), [&](Vec2f u) { return boxSampler.sample(u).p; },
                  16, 20000),
              1e-6);
    PixelFilter square = filterOf(FilterType::Gaussian);
    square.radius = {1.5f, 1.5f};
    square.sigma = 0.3f;
    PixelFilter wide = square;
    wide.sigma = 0.6f;
    const FilterSampler wideSampler(wide);
    EXPECT_LT(filterChiSquarePValue(
                  square, [&](Vec2f u) { return wideSampler.sample(u).p; }, 16, 20000),
              1e-6);
    PixelFilter catmullRom = filterOf(FilterType::Mitchell);
    catmullRom.b = 0, catmullRom.c = 0.5f;
    const FilterSampler catmullRomSampler(catmullRom);
    EXPECT_LT(filterChiSquarePValue(
                  catmullRom,
                  [&](Vec2f u) {
                      const Vec2f p = catmullRomSampler.sample(u).p;
                      return Vec2f{p.x * 0.8f, p.y};
                  },
                  16, 20000),
              1e-6);
}

TEST(FilterSampling, WeightsArePbrtsTabulatedValueOverDensity) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
    for (FilterType type : {FilterType::Box, FilterType::Triangle}) {
        const FilterSampler s(filterOf(type));
        for (int i = 0; i < 1000; ++i) EXPECT_EQ(s.sample({uniform(rng), uniform(rng)}).weight, 1);
    }
    for (FilterType type : {FilterType::Gaussian, FilterType::Mitchell, FilterType::Lanczos}) {
        const FilterSampler s(filterOf(type));
        ASSERT_NE(s.table(), nullptr);
        const float absIntegral = s.table()->integral();
        int negative = 0;
        for (int i = 0; i < 20000; ++i) {
            const FilterSample fs = s.sample({uniform(rng), uniform(rng)});
            const float f = s.tabulatedValue(fs.p);
            // f/pdf with pdf = |f|/∫|f̃|: the weight is ±∫|f̃|, signed as f.
            ASSERT_NEAR(fs.weight, f / s.pdf(fs.p), 1e-5f * absIntegral) << int(type);
            ASSERT_NEAR(std::abs(fs.weight), absIntegral, 1e-5f * absIntegral) << int(type);
            ASSERT_EQ(fs.weight < 0, f < 0) << int(type);
            negative += fs.weight < 0;
        }
        if (type == FilterType::Gaussian)
            EXPECT_EQ(negative, 0);
        else
            EXPECT_GT(negative, 0) << "Mitchell and Lanczos have negative lobes";
    }
}

TEST(FilterSampling, MeanWeightIsTheFilterIntegral) {
    // E[w] = ∫ f̃ ≈ ∫ f: pbrt-v4's Integral() — Gaussian (erf(r/σ√2) − 2r·g(r))²,
    // Mitchell r²/4.
    const double sigma = 0.5, r = 1.5;
    const double g1 = std::exp(-r * r / (2 * sigma * sigma)) / std::sqrt(2 * M_PI * sigma * sigma);
    const double gaussian = std::pow(std::erf(r / (sigma * std::sqrt(2.0))) - 2 * r * g1, 2);
    const std::pair<FilterType, double> cases[] = {{FilterType::Gaussian, gaussian},
                                                   {FilterType::Mitchell, 1.0}};
    for (const auto& [type, integral] : cases) {
        const FilterSampler s(filterOf(type));
        std::mt19937 rng(11);
        std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
        const int n = 400000;
        double sum = 0, sumSq = 0;
        for (int i = 0; i < n; ++i) {
            const double w = s.sample({uniform(rng), uniform(rng)}).weight;
            sum += w, sumSq += w * w;
        }
        const double mean = sum / n, se = std::sqrt((sumSq / n - mean * mean) / n);
        EXPECT_NEAR(mean, integral, 5 * se + 2e-3 * integral) << int(type);
    }
}

TEST(FilterSampling, UnitBoxIsTheBoxOfRadiusOneHalfOnly) {
    EXPECT_TRUE(FilterSampler(filterOf(FilterType::Box)).unitBox());
    PixelFilter wide = filterOf(FilterType::Box);
    wide.radius = {1, 1};
    EXPECT_FALSE(FilterSampler(wide).unitBox());
    PixelFilter tri = filterOf(FilterType::Triangle);
    tri.radius = {0.5f, 0.5f};
    EXPECT_FALSE(FilterSampler(tri).unitBox());
    // The box's offsets are pbrt's lerp(u, −r, r).
    const FilterSample s = FilterSampler(wide).sample({0.25f, 0.75f});
    EXPECT_FLOAT_EQ(s.p.x, -0.5f);
    EXPECT_FLOAT_EQ(s.p.y, 0.5f);
}

TEST(FilterSampling, RejectsMeaninglessParameters) {
    PixelFilter f = filterOf(FilterType::Gaussian);
    f.radius = {0, 1};
    EXPECT_THROW(FilterSampler{f}, InputError);
    f.radius = {1, 1};
    f.sigma = 0;
    EXPECT_THROW(FilterSampler{f}, InputError);
    PixelFilter l = filterOf(FilterType::Lanczos);
    l.tau = -1;
    EXPECT_THROW(FilterSampler{l}, InputError);
}

// A closed cube [−1, 1]³ of two-sided emitters of radiance Le seen from
// inside with max depth 0: every camera ray returns exactly Le.
SceneDescription emitterCube(float Le) {
    SceneDescription s = furnaceCube(0.5f, Le);
    s.resolution = {20, 16};
    return s;
}

std::vector<PixelFilter> everyFilter() {
    std::vector<PixelFilter> filters;
    for (FilterType type : {FilterType::Box, FilterType::Triangle, FilterType::Gaussian,
                            FilterType::Mitchell, FilterType::Lanczos})
        filters.push_back(filterOf(type));
    PixelFilter wideBox = filterOf(FilterType::Box);
    wideBox.radius = {1.3f, 0.8f};
    filters.push_back(wideBox);
    PixelFilter narrowSinc = filterOf(FilterType::Lanczos);
    narrowSinc.radius = {0.5f, 0.5f};
    filters.push_back(narrowSinc);
    return filters;
}

using testing::sameBytes;

TEST(WeightedFilm, ConstantRadianceComesOutExactlyWithAnyFilter) {
    // Σ w·L / Σ w = L whatever the weights, negative ones included; with
    // L = ¼ (a power of two) every sum is exact, so is the pixel: ¼ × scale 3.
    // The crop keeps pixels ceil(20·0.1) … ceil(20·0.8) − 1 = 2 … 15 and
    // ceil(16·0.25) … 15 = 4 … 15.
    SceneDescription desc = emitterCube(0.25f);
    desc.film.scale = 3;
    const float crop[4] = {0.1f, 0.8f, 0.25f, 1};
    std::copy(crop, crop + 4, desc.film.cropWindow);
    for (const PixelFilter& f : everyFilter()) {
        desc.film.filter = f;
        const RenderScene scene(desc);
        RenderSettings s;
        s.sampler = "sobol-owen";
        s.samplesPerPixel = 16;
        s.prefixSpp = {4};
        s.maxDepth = 0;
        const RenderOutput out = render(scene, s);
        ASSERT_EQ(out.image.width, 14);
        ASSERT_EQ(out.image.height, 12);
        EXPECT_EQ(out.stats.paths, uint64_t(14 * 12 * 16));
        for (const Image* image : {&out.image, &out.prefixes[0].image})
            for (float v : image->rgb) ASSERT_EQ(v, 0.75f) << int(f.type);
        for (float v : out.varianceOfMean.rgb) ASSERT_EQ(v, 0.0f) << int(f.type);
    }
}

TEST(WeightedFilm, BoxAndTriangleAreThePlainMeanBitForBit) {
    // Through the weighted film (every weight 1) the image is the plain
    // mean's, bit for bit, prefixes included; its variance estimate agrees.
    for (FilterType type : {FilterType::Box, FilterType::Triangle}) {
        SceneDescription desc = cornellBoxScene();
        desc.film.filter = filterOf(type);
        const RenderScene scene(desc);
        for (const char* sampler : {"independent", "sobol-owen"}) {
            RenderSettings s;
            s.sampler = sampler;
            s.samplesPerPixel = 16;
            s.prefixSpp = {4, 8};
            s.resolution = {24, 20};
            s.maxDepth = 4;
            const RenderOutput plain = render(scene, s);
            s.weightedFilm = true;
            const RenderOutput weighted = render(scene, s);
            EXPECT_TRUE(sameBytes(plain.image, weighted.image)) << sampler << int(type);
            for (size_t k = 0; k < plain.prefixes.size(); ++k)
                EXPECT_TRUE(sameBytes(plain.prefixes[k].image, weighted.prefixes[k].image))
                    << sampler << " prefix " << k;
            for (size_t i = 0; i < plain.varianceOfMean.rgb.size(); ++i)
                ASSERT_NEAR(plain.varianceOfMean.rgb[i], weighted.varianceOfMean.rgb[i],
                            1e-9 + 1e-5 * plain.varianceOfMean.rgb[i])
                    << sampler;
        }
    }
}

TEST(WeightedFilm, PrefixesAndCropsAreTheRendersTheyStandFor) {
    // With a Gaussian filter, a prefix of a progressive sampler's render is
    // the render of fewer samples, and a cropped render is the full image's
    // window — every pixel depends on its own samples only — bit for bit.
    SceneDescription desc = cornellBoxScene();
    desc.film.filter = filterOf(FilterType::Gaussian);
    RenderSettings s;
    s.sampler = "sobol-owen";
    s.samplesPerPixel = 16;
    s.resolution = {24, 20};
    s.maxDepth = 4;
    s.prefixSpp = {4};
    const RenderOutput full = render(RenderScene(desc), s);
    s.samplesPerPixel = 4;
    s.prefixSpp = {};
    EXPECT_TRUE(sameBytes(full.prefixes[0].image, render(RenderScene(desc), s).image));
    const float crop[4] = {0.3f, 0.71f, 0.5f, 0.9f};  // pixels 8 … 17 × 10 … 17
    std::copy(crop, crop + 4, desc.film.cropWindow);
    s.samplesPerPixel = 16;
    const RenderOutput cropped = render(RenderScene(desc), s);
    ASSERT_EQ(cropped.image.width, 10);
    ASSERT_EQ(cropped.image.height, 8);
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 10; ++x)
            for (int c = 0; c < 3; ++c)
                ASSERT_EQ(cropped.image.at(x, y)[c], full.image.at(x + 8, y + 10)[c]);
}

TEST(WeightedFilm, ScaleMultipliesImageAndVariance) {
    for (FilterType type : {FilterType::Box, FilterType::Mitchell}) {
        SceneDescription desc = cornellBoxScene();
        desc.film.filter = filterOf(type);
        RenderSettings s;
        s.samplesPerPixel = 8;
        s.resolution = {16, 12};
        s.maxDepth = 3;
        const RenderOutput one = render(RenderScene(desc), s);
        desc.film.scale = 2;  // a power of two: exactly twice
        const RenderOutput two = render(RenderScene(desc), s);
        for (size_t i = 0; i < one.image.rgb.size(); ++i) {
            ASSERT_EQ(two.image.rgb[i], 2 * one.image.rgb[i]);
            ASSERT_EQ(two.varianceOfMean.rgb[i], 4 * one.varianceOfMean.rgb[i]);
        }
        desc.film.scale = 0;
        EXPECT_THROW(render(RenderScene(desc), s), InputError);
    }
}

TEST(WeightedFilm, GaussianFilterStaysUnbiasedInTheFurnace) {
    // Constant radiance 1/(1 − a) everywhere in a white furnace: the
    // filtered image has the same mean, within its own error estimate.
    SceneDescription desc = emitterCube(1);
    desc.materials[0].albedo = Vec3f(0.5f);
    desc.film.filter = filterOf(FilterType::Gaussian);
    RenderSettings s;
    s.samplesPerPixel = 32;
    s.maxDepth = 100;
    const RenderOutput out = render(RenderScene(desc), s);
    double sum = 0, var = 0;
    for (size_t i = 0; i < out.image.rgb.size(); ++i)
        sum += out.image.rgb[i], var += out.varianceOfMean.rgb[i];
    const double n = double(out.image.rgb.size());
    EXPECT_GT(var, 0);
    EXPECT_NEAR(sum / n, 2.0, 5 * std::sqrt(var) / n * std::sqrt(3.0) + 1e-3);
}

TEST(Crop, RejectsAnEmptyWindow) {
    SceneDescription desc = emitterCube(1);
    const float crop[4] = {0.5f, 0.51f, 0, 1};  // ceil(10) … ceil(10.2) − 1 of 20: one column
    std::copy(crop, crop + 4, desc.film.cropWindow);
    RenderSettings s;
    s.samplesPerPixel = 1;
    EXPECT_EQ(render(RenderScene(desc), s).image.width, 1);
    desc.film.cropWindow[1] = 0.5f;
    EXPECT_THROW(render(RenderScene(desc), s), InputError);
}

}  // namespace
}  // namespace pathlab
