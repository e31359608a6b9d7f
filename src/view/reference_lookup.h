// The reference `pathlab view` measures its live error against, found in the
// study's reference cache (study/reference_cache.h): an entry made by a study,
// or by the page, of the same scene as loaded and the same image settings.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "render/render_scene.h"
#include "study/reference_cache.h"
#include "study/spec.h"

namespace pathlab::view {

// What a reference must share with the view's image.
struct ReferenceTarget {
    std::string scene;  // as the view names it: a built-in name or a path
    Vec2i size{0, 0};   // resolved: never 0×0
    int maxDepth = 8;
    bool russianRoulette = true;
    std::string lightSampler{};  // "": the scene's own, as a study without light_sampler
    bool spectral = false;

    bool operator==(const ReferenceTarget& o) const {
        return scene == o.scene && size.x == o.size.x && size.y == o.size.y &&
               maxDepth == o.maxDepth && russianRoulette == o.russianRoulette &&
               lightSampler == o.lightSampler && spectral == o.spectral;
    }
};

// The scene as a study spec names it: a built-in by its name, a file by its
// stem and absolute path (study/spec.cpp), so that the cache keys agree.
StudyScene studySceneOf(const std::string& scene);

// The study spec whose reference is `target` at `spp` from `sampler` and
// `seed` (by default the study's: independent, kDefaultReferenceSeed).
StudySpec referenceSpecFor(const ReferenceTarget& target, int spp,
                           const std::string& sampler = ReferenceSpec{}.sampler,
                           uint64_t seed = kDefaultReferenceSeed);

struct FoundReference {
    Reference reference;
    int spp = 0;
    std::string sampler;
};

// The cached reference of `scene` (as loaded) for `target` with the most
// samples, or nullopt. An entry counts only when its key, recomputed from the
// scene and settings, is the one it was stored under: the same renderer
// version, scene contents, size, depth, roulette, light sampler and colour.
std::optional<FoundReference> findCachedReference(const ReferenceCache& cache,
                                                  const RenderScene& scene,
                                                  const ReferenceTarget& target);

}  // namespace pathlab::view
