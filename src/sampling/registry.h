// The sampler registry: every strategy by its CLI name. The renderer is a
// template over the sampler type; AnySampler is the closed set of types it is
// instantiated for, dispatched once per tile with std::visit. Adding a sampler
// means adding its header here and a line in registry.cpp — nothing in the
// integrator changes.
#pragma once

#include <string>
#include <variant>
#include <vector>

#include "sampling/blue_noise.h"
#include "sampling/cascaded_sobol.h"
#include "sampling/halton.h"
#include "sampling/independent.h"
#include "sampling/pmj02.h"
#include "sampling/sampler.h"
#include "sampling/sobol.h"
#include "sampling/sobol_bluenoise.h"
#include "sampling/standard.h"
#include "sampling/stratified.h"

namespace pathlab {

using AnySampler =
    std::variant<StandardSampler, HaltonSampler, RandomDigitHaltonSampler, OwenHaltonSampler,
                 BlueNoiseSampler, IndependentSampler, StratifiedSampler, SobolSampler,
                 XorSobolSampler, GlobalOwenSobolSampler, OwenSobolSampler, ZSobolSampler,
                 SobolBlueNoiseSampler, Pmj02Sampler, CascadedSobolSampler>;

struct SamplerInfo {
    std::string name;
    std::string description;  // one line
    int nativeDimensions;     // 0 = unbounded
    bool randomized;          // does the seed change its output?
    // Does sample i come out the same whatever samplesPerPixel the sampler
    // was built for? Then the first N samples of an M-spp render are exactly
    // an N-spp render, and a study renders all of a sampler's spp at once.
    // Not so where the pattern is laid out for the whole count: stratified
    // (strata per spp), zsobol (the Morton index holds log2 spp bits), pmj02
    // (tables and index shuffle of 2^ceil(log2 spp) points).
    bool progressive;
};

// All samplers, in the order `pathlab samplers` lists them.
const std::vector<SamplerInfo>& samplerInfos();

// The sampler called `name`; throws InputError like makeSampler when unknown.
const SamplerInfo& samplerInfo(const std::string& name);

// Does a bounce's 2D draw (light point, BSDF direction) start at dimension d?
inline bool startsLayoutPair(int d) {
    if (d < dims::kFirstBounce) return false;
    const int offset = (d - dims::kFirstBounce) % dims::kDimsPerBounce;
    return offset == dims::kLightPoint || offset == dims::kBsdfDirection;
}

// The dimensions (i, j) of sample `index` at `pixel`, drawn the way the
// renderer draws them: dimensions (0, 1) through getPixel2D(), a pair the
// layout draws as 2D (light point, BSDF direction) through get2D(), anything
// else as two 1D draws. Used by `pathlab points` and the tests.
template <typename S>
Vec2f sampleDimensions(S& sampler, Vec2i pixel, int index, int i, int j) {
    if (i == dims::kPixel && j == dims::kPixel + 1) {
        sampler.startPixelSample(pixel, index, 0);
        return sampler.getPixel2D();
    }
    if (j == i + 1 && startsLayoutPair(i)) {
        sampler.startPixelSample(pixel, index, i);
        return sampler.get2D();
    }
    if (i == j + 1 && (startsLayoutPair(j) || j == dims::kPixel)) {
        const Vec2f swapped = sampleDimensions(sampler, pixel, index, j, i);
        return {swapped.y, swapped.x};
    }
    const auto one = [&](int d) {
        if (d < dims::kFirstBounce) {
            sampler.startPixelSample(pixel, index, 0);
            const Vec2f p = sampler.getPixel2D();
            return d == 0 ? p.x : p.y;
        }
        sampler.startPixelSample(pixel, index, d);
        return sampler.get1D();
    };
    const float x = one(i);
    return {x, one(j)};
}

// Throws InputError naming the unknown sampler and listing the known ones.
AnySampler makeSampler(const std::string& name, const SamplerConfig& config);

}  // namespace pathlab
