#include "view/status_json.h"

namespace pathlab::view {

nlohmann::json statusJson(const SessionStatus& status) {
    const ViewSettings& s = status.settings;
    nlohmann::json j{
        {"scene", s.scene},
        {"sampler", s.sampler},
        {"compare", s.compare.empty() ? nlohmann::json() : nlohmann::json(s.compare)},
        {"seed", s.seed},
        {"spp", status.spp},
        {"spp_b", s.compare.empty() ? nlohmann::json() : nlohmann::json(status.sppB)},
        {"equal", equalByName(s.equal)},
        {"width", status.width},
        {"height", status.height},
        {"paths_per_second", status.pathsPerSecond},
        {"elapsed", status.elapsed},
        {"running", status.running},
        {"paused", s.paused},
        {"max_depth", s.maxDepth},
        {"russian_roulette", s.russianRoulette},
        {"light_sampler",
         s.lightSampler.empty() ? nlohmann::json() : nlohmann::json(s.lightSampler)},
        {"spectral", s.spectral},
        {"max_spp", s.maxSpp},
        {"exposure", s.exposure},
        {"tone_map", toneMapName(s.toneMap)},
        {"generation", status.generation},
        {"reference", status.reference},
        {"reference_source", status.referenceSource.empty()
                                 ? nlohmann::json()
                                 : nlohmann::json(status.referenceSource)},
        {"reference_spp",
         status.referenceSpp > 0 ? nlohmann::json(status.referenceSpp) : nlohmann::json()},
        {"reference_progress", status.referenceProgress >= 0
                                   ? nlohmann::json(status.referenceProgress)
                                   : nlohmann::json()},
        {"reference_error",
         status.referenceError.empty() ? nlohmann::json() : nlohmann::json(status.referenceError)},
        {"error", status.error.empty() ? nlohmann::json() : nlohmann::json(status.error)},
    };
    return j;
}

}  // namespace pathlab::view
