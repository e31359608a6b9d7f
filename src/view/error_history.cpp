#include "view/error_history.h"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "metrics/image_metrics.h"

namespace pathlab::view {
namespace {

// As a study measures its cells (study/cell_metrics.cpp): HDR-ꟻLIP over the
// reference's automatic exposure range.
flip::Options liveFlipOptions() {
    flip::Options options;
    options.mode = flip::Mode::Hdr;
    return options;
}

}  // namespace

ErrorHistory::ErrorHistory(std::shared_ptr<const Image> reference)
    : reference_(std::move(reference)),
      flip_(std::make_unique<flip::PreparedReference>(*reference_, liveFlipOptions())) {}

ErrorHistory::~ErrorHistory() = default;

void ErrorHistory::measure(int sppA, const Image& a, int sppB, const Image* b) {
    ErrorPoint p;
    p.spp = sppA;
    p.sppB = b ? sppB : 0;
    p.mseA = meanSquaredError(*reference_, a);
    p.flipA = flip_->evaluate(a).stats.mean;
    if (b) {
        p.mseB = meanSquaredError(*reference_, *b);
        p.flipB = flip_->evaluate(*b).stats.mean;
    }
    points_.push_back(p);
    while (nextSpp_ <= std::max(p.spp, p.sppB)) nextSpp_ *= 2;
}

namespace {

// The relative squared error as relMSE sums it (metrics/image_metrics.h),
// per pixel, mapped to [0, 1] by its log10 over four decades.
std::vector<float> relativeSquaredErrorMap(const Image& reference, const Image& test) {
    std::vector<float> map(reference.pixelCount());
    for (size_t i = 0; i < map.size(); ++i) {
        double e = 0;
        for (int c = 0; c < 3; ++c) {
            const double r = reference.rgb[3 * i + c], d = test.rgb[3 * i + c] - r;
            e += d * d / (r * r + kRelMseEpsilon);
        }
        const double decades = std::log10(std::max(e / 3, 1e-30)) + 4;
        map[i] = float(std::clamp(decades / 4, 0.0, 1.0));
    }
    return map;
}

}  // namespace

std::vector<float> ErrorHistory::errorMap(const Image& test, ErrorMapKind kind) const {
    if (kind == ErrorMapKind::Flip) return flip_->errorMap(test);
    return relativeSquaredErrorMap(*reference_, test);
}

void ErrorHistory::clear() {
    points_.clear();
    nextSpp_ = 1;
}

nlohmann::json errorJson(const std::vector<ErrorPoint>& points, bool hasB) {
    using nlohmann::json;
    json spp = json::array(), mseA = json::array(), flipA = json::array(), sppB = json::array(),
         mseB = json::array(), flipB = json::array();
    for (const ErrorPoint& p : points) {
        spp.push_back(p.spp);
        mseA.push_back(p.mseA), flipA.push_back(p.flipA);
        if (hasB) sppB.push_back(p.sppB), mseB.push_back(p.mseB), flipB.push_back(p.flipB);
    }
    return json{{"spp", spp},
                {"a", {{"mse", mseA}, {"flip", flipA}}},
                {"b", {{"spp", sppB}, {"mse", mseB}, {"flip", flipB}}}};
}

}  // namespace pathlab::view
