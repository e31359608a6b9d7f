#include "view/reference_lookup.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "scene/loader.h"

namespace pathlab::view {
namespace fs = std::filesystem;
namespace {

struct Candidate {
    std::string key, sampler;
    int spp = 0;
    uint64_t seed = 0;
    int ranges = 0;  // a study's [reference] ranges; 0 (or absent): automatic
};

// The entry's metadata when it describes a reference for `target` of this
// scene source (the key is checked by the caller).
std::optional<Candidate> candidateOf(const fs::path& metadata, const StudyScene& source,
                                     const ReferenceTarget& target) {
    try {
        std::ifstream in(metadata);
        const nlohmann::json m = nlohmann::json::parse(in);
        if (m.at("version") != kReferenceCacheVersion || m.at("scene_source") != source.source ||
            m.at("width") != target.size.x || m.at("height") != target.size.y ||
            m.at("max_depth") != target.maxDepth ||
            m.at("russian_roulette") != target.russianRoulette ||
            m.at("roulette_depth") != kDefaultRouletteDepth)
            return std::nullopt;
        return Candidate{m.at("cache_key").get<std::string>(), m.at("sampler").get<std::string>(),
                         m.at("spp").get<int>(), m.at("seed").get<uint64_t>(),
                         m.value("ranges", 0)};
    } catch (const std::exception&) {
        return std::nullopt;  // another file, or a damaged one: not ours
    }
}

}  // namespace

StudyScene studySceneOf(const std::string& scene) {
    const std::vector<std::string> builtins = builtinSceneNames();
    if (std::find(builtins.begin(), builtins.end(), scene) != builtins.end()) return {scene, scene};
    const fs::path p(scene);
    return {p.stem().string(), fs::absolute(p).lexically_normal().string()};
}

StudySpec referenceSpecFor(const ReferenceTarget& target, int spp, const std::string& sampler,
                           uint64_t seed) {
    StudySpec spec;
    spec.resolution = target.size;
    spec.maxDepth = target.maxDepth;
    spec.russianRoulette = target.russianRoulette;
    spec.rouletteDepth = kDefaultRouletteDepth;
    spec.lightSampler = target.lightSampler;
    spec.spectral = target.spectral;
    spec.reference.spp = spp, spec.reference.sampler = sampler, spec.reference.seed = seed;
    return spec;
}

std::optional<FoundReference> findCachedReference(const ReferenceCache& cache,
                                                  const RenderScene& scene,
                                                  const ReferenceTarget& target) {
    const StudyScene source = studySceneOf(target.scene);
    std::optional<Candidate> best;
    std::error_code ec;
    for (const fs::directory_entry& e : fs::directory_iterator(cache.directory(), ec)) {
        if (e.path().extension() != ".json") continue;
        const std::optional<Candidate> c = candidateOf(e.path(), source, target);
        if (!c || (best && best->spp >= c->spp)) continue;
        StudySpec spec = referenceSpecFor(target, c->spp, c->sampler, c->seed);
        spec.reference.ranges = c->ranges;
        if (referenceCacheKey(scene.description(), source, spec) == c->key) best = c;
    }
    if (!best) return std::nullopt;
    std::optional<Reference> loaded = cache.load(best->key);
    if (!loaded) return std::nullopt;
    return FoundReference{std::move(*loaded), best->spp, best->sampler};
}

}  // namespace pathlab::view
