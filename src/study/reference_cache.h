// References: one high-spp render per scene and settings, kept in a
// content-addressed cache (cacheDirectory()/references/KEY.exr + KEY.json) so
// that every later study with the same scene and settings reuses it.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/image.h"
#include "render/render_scene.h"
#include "render/renderer.h"
#include "scene/scene.h"
#include "study/cell_metrics.h"
#include "study/spec.h"

namespace pathlab {

struct Reference {
    Image image;
    double seconds = 0;  // of the render that made it, perhaps in an earlier study
    NoiseFloor noise;
    float exposure = 0;
    std::string cacheKey;
    int64_t edgePixels = 0;  // of the mask the region floors were measured over
};

// Bumped whenever the renderer's output for the same inputs changes, so stale
// references are never reused (7: a reference is the sum of its sample
// ranges, reference_ranges.h).
inline constexpr const char* kReferenceCacheVersion = "pathlab-reference-7";

// Hash of what determines the reference's pixels: the scene as loaded (camera,
// materials, textures, geometry), the scene file's bytes for a file scene, the
// resolution, depth, Russian roulette, and the reference's spp, sampler and seed.
std::string referenceCacheKey(const SceneDescription& scene, const StudyScene& source,
                              const StudySpec& spec);

// Hash of the scene alone, as loaded (the part of referenceCacheKey that does
// not depend on the spec): what a study records per scene so that --resume
// can refuse a scene whose contents changed since the study began.
std::string sceneContentHash(const SceneDescription& scene, const StudyScene& source);

class ReferenceCache {
  public:
    explicit ReferenceCache(std::filesystem::path directory);
    // The cache under cacheDirectory() ($PATHLAB_CACHE and friends).
    static ReferenceCache standard();

    const std::filesystem::path& directory() const { return directory_; }
    bool contains(const std::string& key) const;
    // Nullopt when absent or unreadable (a damaged entry is rendered again).
    std::optional<Reference> load(const std::string& key) const;
    // Image first, metadata last: an entry whose metadata exists is complete.
    void store(const Reference& reference, const StudyScene& scene, const StudySpec& spec) const;

  private:
    std::filesystem::path imagePath(const std::string& key) const;
    std::filesystem::path metadataPath(const std::string& key) const;
    std::filesystem::path directory_;
};

// The settings every image of a study shares, the reference's and the cells'
// alike (resolution, path depth, roulette, threads), so the two cannot drift
// apart; the caller sets the sampler, spp and seed.
RenderSettings studyRenderSettings(const StudySpec& spec, int threads);

}  // namespace pathlab
