#include "study/reference_cache.h"

#include <algorithm>
#include <fstream>
#include <nlohmann/json.hpp>
#include <type_traits>

#include "core/error.h"
#include "core/json_null.h"
#include "core/paths.h"
#include "render/renderer.h"
#include "study/content_hash.h"
#include "study/files.h"

namespace pathlab {
namespace fs = std::filesystem;
namespace {

// Plain arrays of floats or integers, so no padding bytes reach the hash.
template <typename T>
void hashArray(ContentHash& h, const std::vector<T>& v) {
    static_assert(sizeof(T) % 4 == 0 && std::is_trivially_copyable_v<T>);
    h.integer(v.size());
    if (!v.empty()) h.bytes(v.data(), v.size() * sizeof(T));
}

void hashVec(ContentHash& h, Vec3f v) {
    h.real(v.x);
    h.real(v.y);
    h.real(v.z);
}

void hashMaterials(ContentHash& h, const SceneDescription& s) {
    h.integer(s.materials.size());
    for (const Material& m : s.materials) {
        h.integer(uint64_t(m.type));
        hashVec(h, m.albedo);
        h.integer(uint64_t(int64_t(m.texture)));
        h.real(m.ior);
        hashVec(h, m.eta);
        hashVec(h, m.k);
        h.real(m.roughness);
    }
    h.integer(s.textures.size());
    for (const Texture& t : s.textures) {
        h.integer(uint64_t(t.width));
        h.integer(uint64_t(t.height));
        hashArray(h, t.texels);
    }
}

void hashGeometry(ContentHash& h, const SceneDescription& s) {
    h.integer(s.meshes.size());
    for (const Mesh& m : s.meshes) {
        hashArray(h, m.positions);
        hashArray(h, m.normals);
        hashArray(h, m.uvs);
        hashArray(h, m.indices);
        h.integer(uint64_t(int64_t(m.material)));
        hashVec(h, m.emission);
        h.integer(m.twoSided);
    }
    h.integer(s.spheres.size());
    for (const Sphere& sp : s.spheres) {
        hashVec(h, sp.center);
        h.real(sp.radius);
        h.integer(uint64_t(int64_t(sp.material)));
    }
    hashVec(h, s.environment);
    // Only when there are any, so that scenes without them keep their hashes.
    if (!s.punctualLights.empty()) h.integer(s.punctualLights.size());
    for (const PunctualLight& l : s.punctualLights) {
        h.integer(uint64_t(l.type));
        hashVec(h, l.position);
        hashVec(h, l.direction);
        hashVec(h, l.intensity);
        hashVec(h, l.radiance);
        h.real(l.cosFalloffStart);
        h.real(l.cosFalloffEnd);
    }
    if (const EnvironmentImage& env = s.environmentMap; !env.empty()) {
        h.integer(uint64_t(env.width));
        hashArray(h, env.texels);
        for (int c = 0; c < 3; ++c) hashVec(h, env.toWorld[c]);
        h.integer(env.uniformSampling);
    }
}

nlohmann::json readJson(const fs::path& path) {
    std::ifstream in(path);
    return nlohmann::json::parse(in);  // throws on a damaged file
}

// The loaded description covers built-in scenes and their assets (the
// wolf's mesh and texture) as well as files and what they include.
void hashScene(ContentHash& h, const SceneDescription& scene, const StudyScene& source) {
    const Camera& c = scene.camera;
    hashVec(h, c.eye);
    hashVec(h, c.target);
    hashVec(h, c.up);
    h.real(c.fovY);
    hashMaterials(h, scene);
    hashGeometry(h, scene);
    if (source.source != source.name) h.file(source.source);  // a file scene
}

}  // namespace

std::string sceneContentHash(const SceneDescription& scene, const StudyScene& source) {
    ContentHash h;
    hashScene(h, scene, source);
    return h.hex();
}

std::string referenceCacheKey(const SceneDescription& scene, const StudyScene& source,
                              const StudySpec& spec) {
    ContentHash h;
    h.text(kReferenceCacheVersion);
    hashScene(h, scene, source);
    h.integer(uint64_t(spec.resolution.x));
    h.integer(uint64_t(spec.resolution.y));
    h.integer(uint64_t(spec.maxDepth));
    h.integer(spec.russianRoulette);
    h.integer(uint64_t(spec.rouletteDepth));
    h.integer(uint64_t(spec.reference.spp));
    h.text(spec.reference.sampler);
    h.integer(spec.reference.seed);
    // Only when set, so that the keys of studies without it stay as they were.
    if (!spec.lightSampler.empty()) h.text("light_sampler " + spec.lightSampler);
    if (spec.spectral) h.text("spectral");
    if (spec.wavelengths != spectral::WavelengthSampling::Visible)
        h.text(std::string("wavelengths ") + spectral::wavelengthSamplingName(spec.wavelengths));
    // The ranges' sums are added in range order: their number is in the bits.
    if (spec.reference.ranges) h.text("reference ranges " + std::to_string(spec.reference.ranges));
    return h.hex();
}

ReferenceCache::ReferenceCache(fs::path directory) : directory_(std::move(directory)) {}

ReferenceCache ReferenceCache::standard() {
    return ReferenceCache(cacheDirectory() / "references");
}

fs::path ReferenceCache::imagePath(const std::string& key) const {
    return directory_ / (key + ".exr");
}

fs::path ReferenceCache::metadataPath(const std::string& key) const {
    return directory_ / (key + ".json");
}

bool ReferenceCache::contains(const std::string& key) const {
    std::error_code ec;
    return fs::is_regular_file(metadataPath(key), ec) && fs::is_regular_file(imagePath(key), ec);
}

std::optional<Reference> ReferenceCache::load(const std::string& key) const {
    if (!contains(key)) return std::nullopt;
    try {
        const nlohmann::json meta = readJson(metadataPath(key));
        Reference r;
        r.image = readImage(imagePath(key).string());
        r.seconds = meta.at("seconds").get<double>();
        r.noise.mse = meta.at("noise_mse").get<double>();
        r.noise.relmse = meta.at("noise_relmse").get<double>();
        // Entries written before the floors by region lack these keys: they
        // are rendered again (null: the region has no pixels).
        r.noise.mseEdge = optionalNumber(meta.at("noise_mse_edge"));
        r.noise.mseRest = optionalNumber(meta.at("noise_mse_rest"));
        r.edgePixels = meta.at("edge_pixels").get<int64_t>();
        r.exposure = meta.at("exposure").get<float>();
        r.cacheKey = key;
        if (meta.at("cache_key").get<std::string>() != key) return std::nullopt;
        return r;
    } catch (const std::exception&) {
        return std::nullopt;
    }
}

void ReferenceCache::store(const Reference& r, const StudyScene& scene,
                           const StudySpec& spec) const {
    std::error_code ec;
    fs::create_directories(directory_, ec);
    writeImage(imagePath(r.cacheKey).string(), r.image);
    const std::string wavelengthsName = spectral::wavelengthSamplingName(spec.wavelengths);
    const nlohmann::json meta = {{"cache_key", r.cacheKey},
                                 {"version", kReferenceCacheVersion},
                                 {"scene", scene.name},
                                 {"scene_source", scene.source},
                                 {"width", spec.resolution.x},
                                 {"height", spec.resolution.y},
                                 {"max_depth", spec.maxDepth},
                                 {"russian_roulette", spec.russianRoulette},
                                 {"roulette_depth", spec.rouletteDepth},
                                 {"spectral", spec.spectral},
                                 {"wavelengths", wavelengthsName},
                                 {"light_sampler", spec.lightSampler},
                                 {"ranges", spec.reference.ranges},
                                 {"spp", spec.reference.spp},
                                 {"sampler", spec.reference.sampler},
                                 {"seed", spec.reference.seed},
                                 {"seconds", r.seconds},
                                 {"noise_mse", r.noise.mse},
                                 {"noise_relmse", r.noise.relmse},
                                 {"noise_mse_edge", orNull<nlohmann::json>(r.noise.mseEdge)},
                                 {"noise_mse_rest", orNull<nlohmann::json>(r.noise.mseRest)},
                                 {"edge_pixels", r.edgePixels},
                                 {"exposure", r.exposure},
                                 {"created_at", isoTimestampUtc()},
                                 {"git_commit", sourceGitCommit()}};
    writeTextFileAtomic(metadataPath(r.cacheKey), meta.dump(2) + "\n");
}

RenderSettings studyRenderSettings(const StudySpec& spec, int threads) {
    RenderSettings s;
    s.resolution = spec.resolution;
    s.maxDepth = spec.maxDepth;
    s.russianRoulette = spec.russianRoulette;
    s.rouletteDepth = spec.rouletteDepth;
    s.spectral = spec.spectral;
    s.wavelengths = spec.wavelengths;
    s.threads = threads;
    return s;
}

}  // namespace pathlab
