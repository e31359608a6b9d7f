#include "sampling/sobol_bluenoise.h"

#include "core/hash.h"

namespace pathlab {

SobolBlueNoiseSampler::SobolBlueNoiseSampler(const SamplerConfig& c)
    : fallback_(c), keys_(defaultSobolBlueNoiseKeys()) {
    for (size_t pair = 0; pair < kPairStarts.size(); ++pair) {
        const uint64_t h = hashValues(c.seed, pair, 0x53424e4fu);
        offset_[pair] = {int(uint32_t(h) % uint32_t(keys_->size)),
                         int(uint32_t(h >> 32) % uint32_t(keys_->size))};
        shift_[pair] = mixBits(h);
    }
}

}  // namespace pathlab
