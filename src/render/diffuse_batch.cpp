#include "render/diffuse_batch.h"

#include <immintrin.h>

#include <cstring>

#include "core/simd_target.h"

namespace pathlab {

// Four lanes at a time with SSE (every x86-64), and eight with AVX2 where the
// processor has it (chosen at run time): the same operations either way, so
// the same bits (core/simd_target.h: AVX2 without FMA, so rounding stays that
// of the scalar code).
namespace sse {
namespace {
using F = float __attribute__((vector_size(16)));
using I = int __attribute__((vector_size(16)));
constexpr int kWidth = 4;
F sqrtV(F x) {
    return F(_mm_sqrt_ps(__m128(x)));
}
#include "render/diffuse_batch_lanes.inc"
}  // namespace
}  // namespace sse

PATHLAB_AVX2_BEGIN
namespace avx2 {
namespace {
using F = float __attribute__((vector_size(32)));
using I = int __attribute__((vector_size(32)));
constexpr int kWidth = 8;
static_assert(kWidth == kBatchLanes, "one AVX2 pass shades a whole batch");
F sqrtV(F x) {
    return F(_mm256_sqrt_ps(__m256(x)));
}
#include "render/diffuse_batch_lanes.inc"
}  // namespace
void shadeRgb(const AreaLight* light, float epsilon, const DiffuseBatchInput& in,
              DiffuseBatchOutput& out) {
    shadeLanes<3>(light, epsilon, in, 0, out);
}
void shadeSpectral(const AreaLight* light, float epsilon, const DiffuseBatchInput& in,
                   DiffuseBatchOutput& out) {
    shadeLanes<kMaxBatchChannels>(light, epsilon, in, 0, out);
}
}  // namespace avx2
PATHLAB_AVX2_END

bool batchUsesAvx2() {
    return cpuHasAvx2();
}

void shadeDiffuseBatch(const AreaLight* light, float epsilon, const DiffuseBatchInput& in,
                       int lanes, DiffuseBatchOutput& out, BatchIsa isa) {
    if (isa == BatchIsa::Best && batchUsesAvx2()) return avx2::shadeRgb(light, epsilon, in, out);
    for (int k = 0; k < lanes; k += sse::kWidth) sse::shadeLanes<3>(light, epsilon, in, k, out);
}

void shadeDiffuseBatchSpectral(const AreaLight* light, float epsilon, const DiffuseBatchInput& in,
                               int lanes, DiffuseBatchOutput& out, BatchIsa isa) {
    if (isa == BatchIsa::Best && batchUsesAvx2())
        return avx2::shadeSpectral(light, epsilon, in, out);
    for (int k = 0; k < lanes; k += sse::kWidth)
        sse::shadeLanes<kMaxBatchChannels>(light, epsilon, in, k, out);
}

}  // namespace pathlab
