#include "sampling/sampler_cost.h"

#include <chrono>

namespace pathlab {

double nanosecondsPerDimension(const std::string& sampler, int spp, Vec2i resolution, int depth,
                               int batches) {
    AnySampler any = makeSampler(sampler, SamplerConfig{spp, 1, resolution});
    volatile float sink = 0;
    int64_t paths = 0;
    const auto start = std::chrono::steady_clock::now();
    std::visit(
        [&](auto& s) {
            BatchWalk walk{spp, resolution};
            float acc = 0;
            for (int b = 0; b < batches; ++b, walk.advance()) {
                acc += drawBatchDimensions(s, walk.pixel, walk.index, walk.count(), depth);
                paths += walk.count();
            }
            sink = acc;
        },
        any);
    (void)sink;
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return seconds * 1e9 / (double(paths) * dimensionsPerPath(depth));
}

}  // namespace pathlab
