// The per-pixel keys of `sobol-bluenoise` and the optimiser that arranges them.
//
// Heitz, Belcour, Ostromoukhov, Coeurjolly & Iehl 2019, "A Low-Discrepancy
// Sampler that Distributes Monte Carlo Errors as a Blue Noise in Screen Space"
// (SIGGRAPH Talks): every pixel of a tile draws the same Owen-scrambled Sobol'
// pair, but with its own ranking key (which Sobol' points it takes, in which
// order) and scrambling key; the keys are chosen offline so that the errors of
// neighbouring pixels cancel — the error image is blue noise.
//
// Here a pixel's key is four 32-bit words: the seed of a nested (Owen)
// scramble of the sample index's bits, a ranking offset t XORed onto the
// scrambled index, and the Owen seeds of the two coordinates. The nested
// scramble maps the first 2^k indices to one aligned block of 2^k Sobol'
// indices whatever k, so each pixel's first 2^k samples are a (0,k,2)-net;
// the XOR keeps blocks blocks, and its bit j picks which half of the
// 2^(j+1)-point block the first 2^j samples are — the ranking of the paper,
// which XORs the index with its key. (Under a plain XOR rank the three pairs
// of a pixel, all drawing Sobol' dims 0,1, would differ by a constant digital
// shift, C(i ⊕ r₁) = C(i ⊕ r₂) ⊕ C(r₁ ⊕ r₂), tying a sample's pixel position,
// light point and BSDF direction together; the nested scramble per pair unties
// them, as `sobol-owen`'s index shuffle does.)
//
// The optimiser (our own; the paper anneals keys per pixel against the energy
// of Georgiev & Fajardo 2016, a tile per spp) works from the top level down,
// as the paper's ranking keys refine a tile made for the largest spp:
//  1. The (rank, scramble) triples start as a seeded random pool and are only
//     permuted over the tile (so the file is checked on read to be a
//     permutation of that pool) to arrange the errors of the full 2^L-point
//     sets.
//  2. Then for j = L−1 … 0, bit j of every pixel's offset t — which half of
//     its 2^(j+1) points its first 2^j are — is chosen to arrange the errors
//     of the 2^j-point prefixes; a choice at level j leaves every level above
//     it unchanged, so each spp 1, 2, 4, …, 2^L gets a step of its own.
// A pixel's error vector e at a level holds the estimates of a set of test
// integrands — randomly oriented 2D Heaviside steps — minus their integrals.
// Both steps lower the energy
//   E = Σ_p Σ_q w(p − q) ⟨e_p, e_q⟩,   w(δ) = exp(−|δ|² / 2σ²),
// the error image's power after a Gaussian low-pass, which empties the low
// frequencies. Step 1 swaps keys a, b (Heitz & Belcour 2019, "Distributing
// Monte Carlo Errors as a Blue Noise in Screen Space by Permuting Pixel Seeds
// Between Frames", optimise by swaps too): E changes by
// 2⟨d, F_a − F_b⟩ − 2w(a−b)|d|², d = e_b − e_a, F_p = Σ_{q≠p} w(p−q) e_q.
// Step 2 replaces e_p by the other half's c: E changes by
// 2⟨c − e_p, F_p⟩ + |c|² − |e_p|² (the self term counts here, so a pixel's
// own error is not traded for its neighbours'). Greedy in both: a change is
// kept when it lowers E. Deterministic for a seed.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <vector>

#include "sampling/lowdiscrepancy.h"

namespace pathlab {

struct SobolBlueNoiseKey {
    uint32_t rank = 0;       // seeds the nested scramble of the sample index
    uint32_t scrambleX = 0;  // Owen seed of Sobol' dimension 0
    uint32_t scrambleY = 0;  // Owen seed of Sobol' dimension 1
    uint32_t offset = 0;     // XORed onto the scrambled index (the ranking)
    bool operator==(const SobolBlueNoiseKey&) const = default;
};

// Sobol' dimensions 0 and 1 of the ranked index i, Owen-scrambled by the key,
// as 32-bit fixed-point fractions (x in the low half, y in the high half).
// With O_s(v) = R(L_s(R(v))) (R the bit reversal, L_s the Laine–Karras
// permutation), C_0 = R and C_1 = R∘Z (Z the superset transform),
// x = R(L_sx(i)) and y = R(L_sy(Z(i))).
[[gnu::always_inline]] inline uint64_t sobolBlueNoiseRankedPair(const SobolBlueNoiseKey& key,
                                                                uint32_t i) {
    return reverseBits32Pair(laineKarrasPermutation(i, key.scrambleX),
                             laineKarrasPermutation(sobolSupersetTransform32(i), key.scrambleY));
}

// Sample `index` of the pair keyed by `key`: the ranked index
// i = O_rank(index) ⊕ offset.
[[gnu::always_inline]] inline uint64_t sobolBlueNoisePair(const SobolBlueNoiseKey& key,
                                                          uint32_t index) {
    return sobolBlueNoiseRankedPair(key, owenScramble(index, key.rank) ^ key.offset);
}

struct SobolBlueNoiseKeys {
    int size = 0;                        // the tile is size × size pixels
    std::vector<SobolBlueNoiseKey> key;  // row-major
    const SobolBlueNoiseKey& at(int x, int y) const { return key[size_t(y) * size + x]; }
};

// The defaults are the shipped tile's (docs/samplers.md).
struct SobolBlueNoiseOptimizer {
    int size = 128;       // tile side, a power of two
    int levels = 8;       // spp 1, 2, …, 2^levels
    int integrands = 24;  // Heaviside steps
    int passes = 40;      // swap proposals per pixel for the 2^levels sets
    int sweeps = 3;       // passes over the tile per ranking bit
    double sigma = 2.0;   // the energy's Gaussian, in pixels
    int swapRadius = 8;   // partners within this Chebyshev distance
    uint64_t seed = 0x5342534eULL;
    // Identifies the settings in the cache file: a change regenerates it.
    uint64_t fingerprint() const;
};

// The seeded pool of keys the optimiser permutes (size² of them, offset 0).
std::vector<SobolBlueNoiseKey> sobolBlueNoiseKeyPool(const SobolBlueNoiseOptimizer& settings);

// Throws std::invalid_argument for settings the optimiser cannot use.
void checkSobolBlueNoiseSettings(const SobolBlueNoiseOptimizer& settings);

// The optimised tile.
SobolBlueNoiseKeys optimizeSobolBlueNoiseKeys(const SobolBlueNoiseOptimizer& settings);

// Reads `file` if it holds the keys these settings produce (magic, size,
// fingerprint, the keys a permutation of the pool up to offsets below
// 2^levels), else optimises them
// and writes the file atomically; an unwritable cache is not an error.
std::shared_ptr<const SobolBlueNoiseKeys> loadOrCreateSobolBlueNoiseKeys(
    const std::filesystem::path& file, const SobolBlueNoiseOptimizer& settings);

// The process-wide tile: cacheDirectory()/sobol-bluenoise-ranked-keys-128.bin.
std::shared_ptr<const SobolBlueNoiseKeys> defaultSobolBlueNoiseKeys();

}  // namespace pathlab
