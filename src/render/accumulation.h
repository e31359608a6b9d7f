// One sampler's progressive render of a scene: passes that each bring every
// pixel to a higher sample count (`pathlab view`, the Python module's
// render_progressive). A progressive sampler (SamplerInfo) adds only the new
// samples to running sums kept between passes (RenderSettings::resume); any
// other is rendered afresh at the pass's count, since its first samples depend
// on the count it was built for. Either way the image after a pass is, bit for
// bit, `pathlab render` of the same scene, sampler, seed and spp.
#pragma once

#include <cstdint>

#include "core/image.h"
#include "render/renderer.h"

namespace pathlab {

class Accumulation {
  public:
    // `settings` holds everything but samplesPerPixel, prefixSpp and resume.
    explicit Accumulation(RenderSettings settings);

    // Renders until every pixel has `targetSpp` samples (more than spp()).
    // Throws RenderCancelled when settings.control cancels it, and then
    // starts over: spp() is 0 and the image empty.
    void advance(const RenderScene& scene, int targetSpp);

    bool progressive() const { return progressive_; }
    int spp() const { return spp_; }
    const Image& image() const { return image_; }
    const Image& varianceOfMean() const { return variance_; }
    // The last pass's statistics: its paths and time only.
    const RenderStats& lastPass() const { return lastPass_; }
    uint64_t paths() const { return paths_; }    // traced since the start
    double seconds() const { return seconds_; }  // spent rendering since the start

  private:
    RenderSettings settings_;
    bool progressive_;
    RunningSums sums_;
    int spp_ = 0;
    Image image_, variance_;
    RenderStats lastPass_;
    uint64_t paths_ = 0;
    double seconds_ = 0;
};

}  // namespace pathlab
