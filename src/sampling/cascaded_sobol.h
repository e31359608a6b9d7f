// `cascaded-sobol`: Paulin, Coeurjolly, Iehl, Bonneel, Keller & Ostromoukhov
// 2021, "Cascaded Sobol' Sampling" (ACM TOG 40(6), SIGGRAPH Asia).
//
// Padding (sobol-owen, pmj02) stratifies each 2D draw on its own and leaves
// every other pair of dimensions random. The cascade chains the dimensions
// instead: a pixel's N = 2^m points are built one dimension after the other,
// and the value a point has in dimension j chooses the Sobol' index of its
// value in dimension j + 1. With x_j's top m bits equal to the van der Corput
// value of an m-bit index a_j, the next dimension is Sobol' dimension 1 of the
// same index (§4 of the paper):
//   x_0     = O_0(vdC(i))                              i the sample index
//   a_j     = the m-bit index whose vdC is x_j's top m bits
//   x_{j+1} = O_{j+1}(Sobol'_1(a_j))
// where O_j is a nested uniform (Owen) scramble seeded by (pixel, j, seed).
// Since x_j's top m bits take every value once over the N points, the pair
// (x_j, x_{j+1}) is, to m bits, the Sobol' (0,m,2)-net with its second
// coordinate Owen-scrambled: every consecutive pair of dimensions — the pixel
// position, a light point, a BSDF direction, and also the pairs across draws
// and across path vertices that padding leaves random — is a (0,m,2)-net, and
// every dimension is stratified into N intervals. Only the top m bits of x_j
// choose the next index: the scramble randomises the bits below them (the
// paper's "Owen scrambling at finer levels"), which makes every point
// uniformly distributed in every dimension — unbiased.
//
// The price is the one the paper names: the construction is for N = 2^m
// points, not a sequence (the first 2^k < N points are not nets in the
// consecutive pairs past the first), so the sampler is built for
// N = 2^⌈log2 spp⌉ and is not progressive. The paper also optimises the
// initial scrambles (its §5); here they are random.
//
// Computed in the bit-reversed domain, where the Owen scramble is the
// Laine–Karras permutation L_s (owenScramble(v, s) = R(L_s(R(v)))) and
// Sobol' dimension 1 is R∘Z (Z the superset transform): with n_j = R(x_j),
//   n_0 = L_{s_0}(i),   n_{j+1} = L_{s_{j+1}}(Z(n_j mod 2^m)),
// one mask, five shift-XORs and a hash per dimension. Dimension d needs the
// d before it: each of the last kBatchSamples samples of the pixel keeps its
// chain (the renderer draws a sample's dimensions in increasing order, a
// batch of samples at a time), so a draw extends the chain by the
// dimensions since the sample's last draw.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/hash.h"
#include "sampling/lowdiscrepancy.h"
#include "sampling/pixel_dimension_cache.h"
#include "sampling/sampler.h"

namespace pathlab {

class CascadedSobolSampler {
  public:
    explicit CascadedSobolSampler(const SamplerConfig& c)
        : spp_(c.samplesPerPixel),
          seed_(c.seed),
          indexMask_(indexMask(c.samplesPerPixel)),
          chains_(size_t(kBatchSamples) * kChainDimensions) {}

    int samplesPerPixel() const { return spp_; }
    void startPixelSample(Vec2i p, int index, int dim) {
        if (p.x != pixel_.x || p.y != pixel_.y) {
            pixel_ = p, pixelHash_ = hashValues(p.x, p.y, seed_), seeds_.clear();
            chainIndex_.fill(-1);
        }
        slot_ = size_t(unsigned(index) % unsigned(kBatchSamples));
        if (chainIndex_[slot_] != index) chainIndex_[slot_] = index, chainLength_[slot_] = 0;
        dimension_ = dim;
    }
    float get1D() { return value(dimension_++); }
    Vec2f get2D() {
        const int d = dimension_;
        dimension_ += 2;
        const float x = value(d);
        return {x, value(d + 1)};
    }
    Vec2f getPixel2D() { return get2D(); }

    // The definition the draws must equal (for tests): dimension `dim` of
    // sample `index` of `pixel`, built from the Sobol' matrices and
    // owenScramble, dimension after dimension from 0.
    static float definition(Vec2i pixel, uint64_t seed, int spp, uint32_t index, int dim);

  private:
    float value(int d) { return fixedPointToFloat(reverseBits32(reversedValue(d))); }
    // n_d of the current sample (see the top of the file), from its chain.
    uint32_t reversedValue(int d) {
        uint32_t* chain = chains_.data() + slot_ * kChainDimensions;
        int& length = chainLength_[slot_];
        if (d < length) return chain[d];
        if (length == 0) {
            // x_0 = O_0(vdC(i)) = R(L_{s_0}(i)).
            chain[0] = laineKarrasPermutation(uint32_t(chainIndex_[slot_]), seed(0));
            length = 1;
        }
        uint32_t n = chain[length - 1];
        for (int k = length; k <= d; ++k) {
            n = cascade(n, indexMask_, seed(k));
            if (k < kChainDimensions) chain[k] = n;
        }
        length = d + 1 < kChainDimensions ? d + 1 : kChainDimensions;
        return n;
    }

  public:
    // One step of the cascade in the reversed domain: n_{j+1} from n_j.
    [[gnu::always_inline]] static uint32_t cascade(uint32_t n, uint32_t mask, uint32_t seed) {
        return laineKarrasPermutation(sobolSupersetTransform32(n & mask), seed);
    }
    // 2^⌈log2 spp⌉ − 1: the bits of x_j that choose the next index.
    static uint32_t indexMask(int spp) {
        const int m = log2Ceil(uint64_t(spp > 1 ? spp : 1));
        return m >= 32 ? ~0u : (uint32_t(1) << m) - 1;
    }
    // The Owen seed of dimension d in the pixel whose hash is pixelHash.
    static uint32_t seedOf(uint64_t pixelHash, int d) {
        return foldSeed(mixBits(pixelHash ^ (uint64_t(d) << 40 | 0x43)));
    }

  private:
    uint32_t seed(int d) {
        return seeds_.get(d, [&] { return seedOf(pixelHash_, d); });
    }

    // A path of depth 8 draws 58 dimensions; deeper ones extend the chain
    // from its last kept value every time.
    static constexpr int kChainDimensions = 64;
    int spp_;
    uint64_t seed_;
    uint32_t indexMask_;
    Vec2i pixel_{-1, -1};
    uint64_t pixelHash_ = 0;
    PixelDimensionCache<uint32_t, kChainDimensions> seeds_;
    size_t slot_ = 0;
    int dimension_ = 0;
    // Per sample slot (index mod kBatchSamples): the sample, how many of its
    // dimensions are kept, and their values n_0, n_1, … (kChainDimensions a
    // slot, on the heap: 16 KiB would make every AnySampler that large).
    std::array<int, kBatchSamples> chainIndex_{};
    std::array<int, kBatchSamples> chainLength_{};
    std::vector<uint32_t> chains_;
};

}  // namespace pathlab
