#include "sampling/registry.h"

#include <functional>

#include "core/error.h"

namespace pathlab {
namespace {

struct Entry {
    SamplerInfo info;
    std::function<AnySampler(const SamplerConfig&)> make;
};

template <typename S>
std::function<AnySampler(const SamplerConfig&)> maker() {
    return [](const SamplerConfig& c) { return AnySampler(std::in_place_type<S>, c); };
}

const std::vector<Entry>& entries() {
    static const std::vector<Entry> list = {
        {{"standard", "minimal-standard LCG (Park & Miller) via uniform_real_distribution", 0, true,
          true},
         maker<StandardSampler>()},
        {{"halton", "Halton radical inverses in prime bases, image-plane mapped, unscrambled",
          kPrimeTableSize, false, true},
         maker<HaltonSampler>()},
        {{"halton-rd", "Halton with one seeded random digit permutation per base", kPrimeTableSize,
          true, true},
         maker<RandomDigitHaltonSampler>()},
        {{"halton-owen", "Halton with hash-based nested (Owen) digit scrambling", kPrimeTableSize,
          true, true},
         maker<OwenHaltonSampler>()},
        {{"blue-noise", "void-and-cluster blue-noise texture looked up per pixel and dimension", 0,
          true, true},
         maker<BlueNoiseSampler>()},
        {{"independent", "uniform random numbers from PCG32", 0, true, true},
         maker<IndependentSampler>()},
        {{"stratified", "jittered strata per pixel and dimension pair, randomly padded", 2, true,
          false},
         maker<StratifiedSampler>()},
        {{"sobol", "global Sobol' (Joe-Kuo), image-plane mapped, unscrambled", kSobolDimensions,
          false, true},
         maker<SobolSampler>()},
        {{"sobol-xor", "global Sobol' with a random digital shift per dimension", kSobolDimensions,
          true, true},
         maker<XorSobolSampler>()},
        {{"sobol-global-owen",
          "global Sobol' with a nested (Owen) scramble per dimension, as pbrt-v4's sobol",
          kSobolDimensions, true, true},
         maker<GlobalOwenSobolSampler>()},
        {{"sobol-owen", "padded Owen-scrambled Sobol' pairs per pixel (Burley 2020)", 2, true,
          true},
         maker<OwenSobolSampler>()},
        {{"zsobol", "Morton-ordered Owen-scrambled Sobol', blue-noise error (Ahmed & Wonka 2020)",
          2, true, false},
         maker<ZSobolSampler>()},
        {{"sobol-bluenoise",
          "Owen-scrambled Sobol' with per-pixel keys optimised for blue-noise error (Heitz et al. "
          "2019)",
          2, true, true},
         maker<SobolBlueNoiseSampler>()},
        {{"pmj02", "progressive multi-jittered (0,2) sequences, padded per dimension pair", 2, true,
          false},
         maker<Pmj02Sampler>()},
        {{"cascaded-sobol",
          "Owen-scrambled Sobol' cascaded so every consecutive dimension pair is a (0,2)-net "
          "(Paulin et al. 2021)",
          0, true, false},
         maker<CascadedSobolSampler>()},
    };
    return list;
}

const Entry& entry(const std::string& name) {
    for (const Entry& e : entries())
        if (e.info.name == name) return e;
    std::string known;
    for (const Entry& e : entries()) known += (known.empty() ? "" : ", ") + e.info.name;
    throw InputError("unknown sampler '" + name + "' (known: " + known + ")");
}

}  // namespace

const std::vector<SamplerInfo>& samplerInfos() {
    static const std::vector<SamplerInfo> infos = [] {
        std::vector<SamplerInfo> v;
        for (const Entry& e : entries()) v.push_back(e.info);
        return v;
    }();
    return infos;
}

const SamplerInfo& samplerInfo(const std::string& name) {
    return entry(name).info;
}

AnySampler makeSampler(const std::string& name, const SamplerConfig& config) {
    return entry(name).make(config);
}

}  // namespace pathlab
