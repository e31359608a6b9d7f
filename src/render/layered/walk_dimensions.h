// Where a layered BSDF's random walks read the sampler. Every path vertex
// owns, besides its fixed block of dims::kDimsPerBounce dimensions, a block
// of kWalksPerVertex · kWalkSamplerDimensions dimensions for the walks of a
// layered BSDF there, laid out after the fixed blocks of all the vertices a
// path of maxDepth can have: the fixed layout of every other scene, and so
// its images, are unchanged. Within a vertex's block, walk w's i-th number is
// dimension layeredBase + w · kWalkSamplerDimensions + i (docs/rendering.md).
#pragma once

#include "render/layered/walk_numbers.h"
#include "sampling/sampler.h"

namespace pathlab::dims {

// The walks of one vertex, in the order of their blocks.
enum class Walk {
    LightF = 0,      // f towards the light sample (next-event estimation)
    LightPdf = 1,    // pdf towards the light sample (its MIS weight)
    Sample = 2,      // the sampled bounce's walk
    SampledPdf = 3,  // pdf of the sampled bounce (MIS when it hits a light)
};
inline constexpr int kWalksPerVertex = 4;
inline constexpr int kLayeredDimsPerVertex = kWalksPerVertex * kWalkSamplerDimensions;

// The first dimension of walk w at vertex `depth` of a path of at most
// maxDepth vertices whose first fixed block starts at `first`.
constexpr int walkBase(int depth, Walk w, int maxDepth, int first = kFirstBounce) {
    return bounceBase(maxDepth, first) + depth * kLayeredDimsPerVertex +
           int(w) * kWalkSamplerDimensions;
}

}  // namespace pathlab::dims
