#include "view/error_history.h"

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

void ErrorHistory::measure(int spp, const Image& a, const Image* b) {
    ErrorPoint p;
    p.spp = spp;
    p.mseA = meanSquaredError(*reference_, a);
    p.flipA = flip_->evaluate(a).stats.mean;
    if (b) {
        p.mseB = meanSquaredError(*reference_, *b);
        p.flipB = flip_->evaluate(*b).stats.mean;
    }
    points_.push_back(p);
    while (nextSpp_ <= spp) nextSpp_ *= 2;
}

void ErrorHistory::clear() {
    points_.clear();
    nextSpp_ = 1;
}

nlohmann::json errorJson(const std::vector<ErrorPoint>& points, bool hasB) {
    using nlohmann::json;
    json spp = json::array(), mseA = json::array(), flipA = json::array(), mseB = json::array(),
         flipB = json::array();
    for (const ErrorPoint& p : points) {
        spp.push_back(p.spp);
        mseA.push_back(p.mseA), flipA.push_back(p.flipA);
        if (hasB) mseB.push_back(p.mseB), flipB.push_back(p.flipB);
    }
    return json{{"spp", spp},
                {"a", {{"mse", mseA}, {"flip", flipA}}},
                {"b", {{"mse", mseB}, {"flip", flipB}}}};
}

}  // namespace pathlab::view
