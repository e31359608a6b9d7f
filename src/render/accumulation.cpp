#include "render/accumulation.h"

#include <stdexcept>

#include "sampling/registry.h"

namespace pathlab {

Accumulation::Accumulation(RenderSettings settings)
    : settings_(std::move(settings)), progressive_(samplerInfo(settings_.sampler).progressive) {
    settings_.prefixSpp.clear();
    settings_.progress = false;
}

void Accumulation::advance(const RenderScene& scene, int targetSpp) {
    if (targetSpp <= spp_) throw std::logic_error("a pass must add samples");
    RenderSettings s = settings_;
    s.samplesPerPixel = targetSpp;
    s.resume = progressive_ ? &sums_ : nullptr;
    RenderOutput out;
    try {
        out = render(scene, s);
    } catch (const RenderCancelled&) {
        spp_ = 0, image_ = {}, variance_ = {}, sums_ = {};  // the renderer has emptied the sums
        throw;
    }
    spp_ = targetSpp;
    image_ = std::move(out.image);
    variance_ = std::move(out.varianceOfMean);
    lastPass_ = out.stats;
    paths_ += out.stats.paths;
    seconds_ += out.stats.seconds;
}

}  // namespace pathlab
