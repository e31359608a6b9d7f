#include "sampling/sampler_cost.h"

#include <chrono>

namespace pathlab {

double nanosecondsPerDimension(const std::string& sampler, int spp, Vec2i resolution, int depth,
                               int packets) {
    AnySampler any = makeSampler(sampler, SamplerConfig{spp, 1, resolution});
    volatile float sink = 0;
    int64_t paths = 0;
    const auto start = std::chrono::steady_clock::now();
    std::visit(
        [&](auto& s) {
            int x = 0, y = 0, index = 0;
            float acc = 0;
            for (int p = 0; p < packets; ++p) {
                const int count = std::min(kCostPacket, spp - index);
                acc += drawPacketDimensions(s, Vec2i{x, y}, index, count, depth);
                paths += count;
                if ((index += count) == spp) {
                    index = 0;
                    if (++x == resolution.x) x = 0, y = (y + 1) % resolution.y;
                }
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
