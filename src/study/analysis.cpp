#include "study/analysis.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "core/json_null.h"
#include "study/bias_analysis.h"

namespace pathlab {
namespace {

using Json = nlohmann::ordered_json;

// One (scene, sampler, spp): the means over its seeds.
struct SppSummary {
    int spp = 0, seeds = 0;
    double mse = 0, mseMin = 0, mseMax = 0, relmse = 0, seconds = 0;
    std::optional<double> flip;
    bool hasRelmse = false;
    // Means of the two regions' MSE, when every seed measured them.
    std::optional<double> mseEdge, mseRest;
};

struct SamplerCells {
    std::string name;
    std::map<int, std::vector<const CellRow*>> bySpp;
};

struct SceneCells {
    std::string name;
    double noiseMse = 0, noiseRelmse = 0;
    std::vector<SamplerCells> samplers;  // in the order they first appear
    // The emitter-edge region (render/emitter_edges.h): its size and the
    // noise floors of it and of the rest, when the reference recorded them.
    std::optional<int64_t> edgePixels;
    std::optional<double> noiseMseEdge, noiseMseRest;
};

// The mean over cells of a region's MSE; nullopt unless every cell has it.
std::optional<double> meanOf(const std::vector<const CellRow*>& cells,
                             std::optional<double> CellRow::*field) {
    double sum = 0;
    for (const CellRow* c : cells) {
        if (!(c->*field)) return std::nullopt;
        sum += *(c->*field);
    }
    return sum / double(cells.size());
}

SppSummary summarize(int spp, const std::vector<const CellRow*>& cells) {
    SppSummary s;
    s.spp = spp;
    s.seeds = int(cells.size());
    s.mseMin = s.mseMax = cells.front()->mse;
    double flipSum = 0;
    int flips = 0, relmses = 0;
    for (const CellRow* c : cells) {
        s.mse += c->mse;
        s.mseMin = std::min(s.mseMin, c->mse);
        s.mseMax = std::max(s.mseMax, c->mse);
        s.seconds += c->seconds;
        if (c->relmse) s.relmse += *c->relmse, ++relmses;
        if (c->flip) flipSum += *c->flip, ++flips;
    }
    s.mse /= s.seeds;
    s.seconds /= s.seeds;
    s.hasRelmse = relmses > 0;
    if (relmses) s.relmse /= relmses;
    if (flips) s.flip = flipSum / flips;
    s.mseEdge = meanOf(cells, &CellRow::mseEdge);
    s.mseRest = meanOf(cells, &CellRow::mseRest);
    return s;
}

std::vector<SceneCells> groupCells(const std::vector<CellRow>& cells,
                                   const std::vector<ReferenceRow>& references) {
    std::vector<SceneCells> scenes;
    for (const ReferenceRow& r : references)
        scenes.push_back(
            {r.scene, r.noiseMse, r.noiseRelmse, {}, r.edgePixels, r.noiseMseEdge, r.noiseMseRest});
    for (const CellRow& c : cells) {
        auto scene = std::find_if(scenes.begin(), scenes.end(),
                                  [&](const SceneCells& s) { return s.name == c.key.scene; });
        if (scene == scenes.end())
            scene = scenes.insert(scenes.end(), {c.key.scene, 0, 0, {}, {}, {}, {}});
        auto& samplers = scene->samplers;
        auto sampler = std::find_if(samplers.begin(), samplers.end(),
                                    [&](const SamplerCells& s) { return s.name == c.key.sampler; });
        if (sampler == samplers.end())
            sampler = samplers.insert(samplers.end(), {c.key.sampler, {}});
        sampler->bySpp[c.key.spp].push_back(&c);
    }
    return scenes;
}

double corrected(double value, double floor) {
    return std::max(value - floor, 0.0);
}

// Slope of log(metric − floor) against log spp, over the spp where that is positive.
std::optional<double> convergenceSlope(const std::vector<SppSummary>& curve, double floor,
                                       bool relative) {
    std::vector<double> x, y;
    for (const SppSummary& s : curve) {
        if (relative && !s.hasRelmse) continue;
        const double v = corrected(relative ? s.relmse : s.mse, floor);
        if (v <= 0) continue;
        x.push_back(std::log(double(s.spp)));
        y.push_back(std::log(v));
    }
    return leastSquaresSlope(x, y);
}

Json bySppJson(const std::vector<SppSummary>& curve, const SceneCells& scene) {
    Json out = Json::object();
    for (const SppSummary& s : curve) {
        out[std::to_string(s.spp)] = {
            {"mse", s.mse},
            {"mse_min", s.mseMin},
            {"mse_max", s.mseMax},
            {"mse_corrected", corrected(s.mse, scene.noiseMse)},
            // Below twice the floor, the reference's noise is at least half of
            // what is measured: the value says little about the sampler.
            {"below_noise_floor", s.mse < 2.0 * scene.noiseMse},
            {"relmse", s.hasRelmse ? Json(s.relmse) : Json(nullptr)},
            {"flip", orNull(s.flip)},
            {"seconds", s.seconds},
            {"seeds", s.seeds}};
    }
    return out;
}

// Per spp, a sampler's MSE over independent's, both less `floor`: `mse`
// picks the whole image's or one region's (null where either side lacks it,
// or independent's is not above the floor). Null without `independent` or a
// floor (a region the reference did not measure).
template <class Mse>
Json ratioJson(const std::vector<SppSummary>& curve, const std::vector<SppSummary>* independent,
               Mse mse, std::optional<double> floor) {
    if (!independent || !floor) return nullptr;
    Json out = Json::object();
    for (const SppSummary& s : curve) {
        auto base = std::find_if(independent->begin(), independent->end(),
                                 [&](const SppSummary& b) { return b.spp == s.spp; });
        if (base == independent->end()) continue;
        const std::optional<double> mine = mse(s), theirs = mse(*base);
        const double denominator = theirs ? corrected(*theirs, *floor) : 0.0;
        out[std::to_string(s.spp)] =
            mine && denominator > 0 ? Json(corrected(*mine, *floor) / denominator) : Json(nullptr);
    }
    return out;
}

// The emitter-edge region of a scene, and the share of independent sampling's
// MSE (less the floors) that lies on it at each spp: how much of the error a
// sampler can only remove through the pixel dimensions.
Json regionsJson(const SceneCells& scene, const std::vector<SppSummary>* independent,
                 int64_t pixels) {
    if (!scene.edgePixels || !scene.noiseMseEdge || !scene.noiseMseRest) return nullptr;
    Json share = Json::object();
    if (independent) {
        const double edgeCount = double(*scene.edgePixels), restCount = double(pixels) - edgeCount;
        for (const SppSummary& s : *independent) {
            if (!s.mseEdge || !s.mseRest) continue;
            const double edge = corrected(*s.mseEdge, *scene.noiseMseEdge) * edgeCount;
            const double rest = corrected(*s.mseRest, *scene.noiseMseRest) * restCount;
            share[std::to_string(s.spp)] =
                edge + rest > 0 ? Json(edge / (edge + rest)) : Json(nullptr);
        }
    }
    return {{"edge_pixels", *scene.edgePixels},
            {"pixels", pixels},
            {"noise_floor_mse_edge", *scene.noiseMseEdge},
            {"noise_floor_mse_rest", *scene.noiseMseRest},
            {"independent_edge_share", independent ? share : Json(nullptr)}};
}

std::vector<ErrorPoint> errorCurve(const std::vector<SppSummary>& curve) {
    std::vector<ErrorPoint> out;
    for (const SppSummary& s : curve) out.push_back({s.seconds, s.mse});
    return out;
}

Json equalTimeJson(const std::vector<SppSummary>& curve, std::optional<double> budget,
                   double floor) {
    if (!budget) return nullptr;
    const std::optional<double> mse = errorAtTime(errorCurve(curve), *budget);
    if (!mse) return nullptr;
    return {{"seconds", *budget}, {"mse", *mse}, {"mse_corrected", corrected(*mse, floor)}};
}

// Whether the curve has render times: an external renderer's cells without a
// times file have none (0), and no time-based number is made of them.
bool timed(const std::vector<SppSummary>& curve) {
    return std::any_of(curve.begin(), curve.end(),
                       [](const SppSummary& s) { return s.seconds > 0; });
}

// The image's pixel count, from any of its cells (all share the resolution).
int64_t scenePixels(const SceneCells& scene) {
    for (const SamplerCells& s : scene.samplers)
        for (const auto& [spp, cells] : s.bySpp)
            if (!cells.empty()) return int64_t(cells.front()->width) * cells.front()->height;
    return 0;
}

Json sceneJson(const SceneCells& scene, std::optional<double> budget) {
    std::map<std::string, std::vector<SppSummary>> curves;
    for (const SamplerCells& s : scene.samplers)
        for (const auto& [spp, cells] : s.bySpp) curves[s.name].push_back(summarize(spp, cells));
    const auto target = curves.find(kTargetSampler);
    const auto independent = curves.find("independent");
    const bool hasTarget = target != curves.end();
    const double targetMse = hasTarget ? target->second.back().mse : 0.0;  // 0: never reached

    const std::vector<SppSummary>* base =
        independent != curves.end() ? &independent->second : nullptr;
    const auto whole = [](const SppSummary& s) { return std::optional<double>(s.mse); };
    const auto edge = [](const SppSummary& s) { return s.mseEdge; };
    const auto rest = [](const SppSummary& s) { return s.mseRest; };
    Json samplers = Json::object();
    for (const SamplerCells& s : scene.samplers) {
        const std::vector<SppSummary>& curve = curves[s.name];
        samplers[s.name] = {
            {"slope_mse", orNull(convergenceSlope(curve, scene.noiseMse, false))},
            {"slope_relmse", orNull(convergenceSlope(curve, scene.noiseRelmse, true))},
            {"mse_ratio_to_independent", ratioJson(curve, base, whole, scene.noiseMse)},
            {"mse_ratio_by_region",
             {{"edge", ratioJson(curve, base, edge, scene.noiseMseEdge)},
              {"rest", ratioJson(curve, base, rest, scene.noiseMseRest)}}},
            {"time_to_target_seconds",
             timed(curve) ? orNull(timeToReach(errorCurve(curve), targetMse)) : Json(nullptr)},
            {"error_at_time_budget",
             timed(curve) ? equalTimeJson(curve, budget, scene.noiseMse) : Json(nullptr)},
            {"by_spp", bySppJson(curve, scene)}};
    }
    return {{"noise_floor_mse", scene.noiseMse},
            {"noise_floor_relmse", scene.noiseRelmse},
            {"target_mse", hasTarget ? Json(targetMse) : Json(nullptr)},
            {"target_spp", hasTarget ? Json(target->second.back().spp) : Json(nullptr)},
            {"regions", regionsJson(scene, base, scenePixels(scene))},
            {"samplers", samplers}};
}

// Linear interpolation in log-log space between (x0, y0) and (x1, y1), at x.
double logLogInterpolate(double x0, double y0, double x1, double y1, double x) {
    const double lx0 = std::log(x0), lx1 = std::log(x1);
    const double a = lx1 == lx0 ? 0.0 : (std::log(x) - lx0) / (lx1 - lx0);
    return std::exp(std::log(y0) + a * (std::log(y1) - std::log(y0)));
}

Json biasJson(const std::vector<CellRow>& cells) {
    Json out = Json::array();
    for (const BiasRow& r : analyzeBias(cells))
        out.push_back({{"scene", r.scene},
                       {"sampler", r.sampler},
                       {"spp", r.spp},
                       {"seeds", r.seeds},
                       {"bias", orNull(r.bias)},
                       {"ci95", orNull(r.ci95)},
                       {"biased", r.biased}});
    return out;
}

}  // namespace

std::optional<double> leastSquaresSlope(const std::vector<double>& x,
                                        const std::vector<double>& y) {
    const size_t n = std::min(x.size(), y.size());
    if (n < 2) return std::nullopt;
    double mx = 0, my = 0;
    for (size_t i = 0; i < n; ++i) mx += x[i], my += y[i];
    mx /= double(n);
    my /= double(n);
    double sxy = 0, sxx = 0;
    for (size_t i = 0; i < n; ++i) {
        sxy += (x[i] - mx) * (y[i] - my);
        sxx += (x[i] - mx) * (x[i] - mx);
    }
    if (sxx == 0) return std::nullopt;
    return sxy / sxx;
}

std::optional<double> timeToReach(const std::vector<ErrorPoint>& curve, double target) {
    if (curve.empty() || !(target > 0)) return std::nullopt;
    if (curve.front().mse <= target) return curve.front().seconds;
    for (size_t i = 0; i + 1 < curve.size(); ++i) {
        const ErrorPoint &a = curve[i], &b = curve[i + 1];
        if (a.mse > target && b.mse <= target) {
            if (a.seconds <= 0 || b.seconds <= 0 || b.mse <= 0) return b.seconds;
            // Roles swapped: seconds as a function of mse.
            return logLogInterpolate(a.mse, a.seconds, b.mse, b.seconds, target);
        }
    }
    return std::nullopt;
}

std::optional<double> errorAtTime(const std::vector<ErrorPoint>& curve, double seconds) {
    for (size_t i = 0; i < curve.size(); ++i) {
        if (curve[i].seconds == seconds) return curve[i].mse;
        if (i + 1 == curve.size()) break;
        const ErrorPoint &a = curve[i], &b = curve[i + 1];
        const bool between = (a.seconds < seconds && seconds < b.seconds) ||
                             (b.seconds < seconds && seconds < a.seconds);
        if (between && a.seconds > 0 && a.mse > 0 && b.mse > 0)
            return logLogInterpolate(a.seconds, a.mse, b.seconds, b.mse, seconds);
    }
    return std::nullopt;
}

nlohmann::ordered_json analyzeStudy(const std::vector<CellRow>& cells,
                                    const std::vector<ReferenceRow>& references,
                                    std::optional<double> timeBudgetSeconds) {
    Json scenes = Json::object();
    for (const SceneCells& scene : groupCells(cells, references))
        if (!scene.samplers.empty()) scenes[scene.name] = sceneJson(scene, timeBudgetSeconds);
    return {{"target_sampler", kTargetSampler},
            {"time_budget_seconds", orNull(timeBudgetSeconds)},
            {"mse_correction",
             "slopes, ratios and *_corrected values use mse - noise_floor_mse "
             "(clamped at 0); mse, target_mse and times use raw mse"},
            {"scenes", scenes},
            {"bias_tolerance", kBiasTolerance},
            {"bias", biasJson(cells)}};
}

}  // namespace pathlab
