// `pmj02`: progressive multi-jittered (0,2) sequences (Christensen, Kensler &
// Kilpatrick 2018, "Progressive Multi-Jittered Sample Sequences", EGSR).
//
// Generation. A pmj02 sequence is a progressive 2D sequence every power-of-two
// prefix of which is stratified in all elementary intervals of its size. Helmer,
// Christensen & Kensler 2021 ("Stochastic Generation of (t,s) Sample
// Sequences", EGSR) show that the stochastic pmj02 construction draws from
// exactly the distribution of Owen-scrambled base-2 (0,2)-sequences: each
// binary digit of each coordinate is flipped by an independent random choice
// made once per elementary interval. We generate the sequences that way —
// Sobol' dimensions 0 and 1 (the (0,2)-sequence), nested-scrambled per
// instance — and tabulate kInstances independent sequences of length
// 2^ceil(log2 spp) when the sampler is constructed (pbrt-v4 ships such tables
// precomputed; ours are generated and seeded). Lookups are then one table read.
//
// Use per pixel and dimension pair. Every 2D draw reads one table instance
// (chosen by hashing pixel, dimension and seed) at an index shuffled by a
// nested scramble seeded by the same hash, and applies a random digital shift. Both operations map
// elementary intervals to elementary intervals, so each pair of every pixel is
// still a pmj02 sequence; different pairs and pixels are decorrelated
// ("padding", Kollig & Keller 2002). 1D draws use the x coordinate. Native
// dimensions: 2 (one pair); past them every pair is padded the same way.
#pragma once

#include <memory>
#include <vector>

#include "sampling/lowdiscrepancy.h"
#include "sampling/sampler.h"

namespace pathlab {

struct Pmj02Tables {
    static constexpr int kInstances = 16;
    int log2Size = 0;
    std::vector<uint32_t> points;  // instance-major, (x, y) fixed-point pairs
    Pmj02Tables(int log2Size, uint64_t seed);
    const uint32_t* point(int instance, uint32_t index) const {
        return points.data() + 2 * ((size_t(instance) << log2Size) + index);
    }
};

class Pmj02Sampler {
  public:
    explicit Pmj02Sampler(const SamplerConfig& c);

    int samplesPerPixel() const { return spp_; }
    void startPixelSample(Vec2i p, int index, int dim) {
        // A path repositions several times per vertex: hash a pixel once.
        if (p.x != pixel_.x || p.y != pixel_.y)
            pixel_ = p, pixelHash_ = hashValues(p.x, p.y, seed_, 0x504du);
        index_ = static_cast<uint32_t>(index);
        dimension_ = dim;
    }
    float get1D() {
        const uint64_t h = mixBits(pixelHash_ ^ (uint64_t(dimension_++) << 32 | 1u));
        const uint32_t* pt = lookup(h);
        return fixedPointToFloat(pt[0] ^ static_cast<uint32_t>(mixBits(h)));
    }
    Vec2f get2D() {
        const uint64_t h = mixBits(pixelHash_ ^ (uint64_t(dimension_) << 32 | 2u));
        dimension_ += 2;
        const uint32_t* pt = lookup(h);
        const uint64_t shift = mixBits(h);
        return {fixedPointToFloat(pt[0] ^ static_cast<uint32_t>(shift)),
                fixedPointToFloat(pt[1] ^ static_cast<uint32_t>(shift >> 32))};
    }
    Vec2f getPixel2D() { return get2D(); }

  private:
    const uint32_t* lookup(uint64_t h) const {
        const int instance = static_cast<int>((h >> 40) % Pmj02Tables::kInstances);
        // A nested (Owen) shuffle of the index's log2Size bits: the high bits
        // of the result depend only on the high bits of the index, so aligned
        // blocks map to aligned blocks (prefixes stay pmj02), while different
        // pairs get unrelated orders (a plain XOR would tie them together).
        const uint32_t shuffled =
            log2Size_ == 0 ? 0
                           : owenScramble(index_ << (32 - log2Size_), static_cast<uint32_t>(h)) >>
                                 (32 - log2Size_);
        return tables_->point(instance, shuffled);
    }

    int spp_;
    uint64_t seed_;
    std::shared_ptr<const Pmj02Tables> tables_;
    int log2Size_ = 0;
    Vec2i pixel_{-1, -1};
    uint64_t pixelHash_ = 0;
    uint32_t index_ = 0;
    int dimension_ = 0;
};

}  // namespace pathlab
