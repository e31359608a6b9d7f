// The per-pixel keys of `sobol-bluenoise` and the optimiser that arranges them.
//
// Heitz, Belcour, Ostromoukhov, Coeurjolly & Iehl 2019, "A Low-Discrepancy
// Sampler that Distributes Monte Carlo Errors as a Blue Noise in Screen Space"
// (SIGGRAPH Talks): every pixel of a tile draws the same Owen-scrambled Sobol'
// pair, but with its own ranking key (which Sobol' points it takes, in which
// order) and scrambling key; the keys are chosen offline so that the errors of
// neighbouring pixels cancel — the error image is blue noise.
//
// Here a pixel's key is three 32-bit words: the ranking key r, the seed of a
// nested (Owen) scramble of the sample index's bits (it maps every aligned
// block of 2^k indices onto an aligned block, so each pixel's first 2^k
// samples are a (0,k,2)-net whatever r is), and the Owen seeds of the two
// coordinates. The paper XORs the index with r, which maps blocks to blocks
// too; but the pairs of one pixel draw from the same Sobol' pair, and under
// XOR ranks their unscrambled points differ by a constant digital shift
// (C(i ⊕ r₁) = C(i ⊕ r₂) ⊕ C(r₁ ⊕ r₂)) — the pixel position, light point and
// BSDF direction of a sample would be tied together. A nested scramble per
// pair, as `sobol-owen`'s index shuffle, unties them. The keys start as a
// seeded random pool; the optimiser only permutes them over the tile, so the
// file is checked on read to be a permutation of that pool.
//
// The optimiser (our own; the paper anneals keys per pixel against the energy
// of Georgiev & Fajardo 2016): for every key, the estimates of a set of test
// integrands — randomly oriented 2D Heaviside steps — from its first 1, 2, 4,
// …, 2^L points form an error vector e (each level's block scaled to unit
// variance over the pool, so every spp counts alike). The energy is
//   E = Σ_p Σ_{q≠p} w(p − q) ⟨e_p, e_q⟩,   w(δ) = exp(−|δ|² / 2σ²),
// the error image's power after a Gaussian low-pass (the Σ_p |e_p|² term of
// that power is fixed under permutation): minimising it empties the low
// frequencies. Swapping keys a, b changes E by 2⟨d, F_a − F_b⟩ − 2w(a−b)|d|²,
// d = e_b − e_a, F_p = Σ_{q≠p} w(p−q) e_q — two dot products per proposal
// (Heitz & Belcour 2019, "Distributing Monte Carlo Errors as a Blue Noise in
// Screen Space by Permuting Pixel Seeds Between Frames", optimise by swaps
// too). Greedy: a swap is kept when it lowers E. Deterministic for a seed.
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
    bool operator==(const SobolBlueNoiseKey&) const = default;
};

// Sample `index` of the pair keyed by `key`, as 32-bit fixed-point fractions
// (x in the low half, y in the high half): Sobol' dimensions 0 and 1 of the
// ranked index i = O_rank(index), Owen-scrambled. With O_s(v) = R(L_s(R(v)))
// (R the bit reversal, L_s the Laine–Karras permutation), C_0 = R and C_1 =
// R∘Z (Z the superset transform), x = R(L_sx(i)) and y = R(L_sy(Z(i))).
[[gnu::always_inline]] inline uint64_t sobolBlueNoisePair(const SobolBlueNoiseKey& key,
                                                          uint32_t index) {
    const uint32_t i = owenScramble(index, key.rank);
    return reverseBits32Pair(laineKarrasPermutation(i, key.scrambleX),
                             laineKarrasPermutation(sobolSupersetTransform32(i), key.scrambleY));
}

struct SobolBlueNoiseKeys {
    int size = 0;                        // the tile is size × size pixels
    std::vector<SobolBlueNoiseKey> key;  // row-major
    const SobolBlueNoiseKey& at(int x, int y) const { return key[size_t(y) * size + x]; }
};

// The defaults are the shipped tile's: chosen by measuring the tile's
// low-frequency error power at 1–256 spp against the optimiser's time
// (docs/samplers.md): spp up to 16, 24 steps, a wide kernel and 40 proposals
// per pixel, about 3 s.
struct SobolBlueNoiseOptimizer {
    int size = 128;       // tile side, a power of two
    int levels = 4;       // spp 1, 2, …, 2^levels
    int integrands = 24;  // Heaviside steps per level
    int passes = 40;      // swap proposals per pixel
    double sigma = 2.0;   // the energy's Gaussian, in pixels
    int swapRadius = 8;   // partners within this Chebyshev distance
    uint64_t seed = 0x5342534eULL;
    // Identifies the settings in the cache file: a change regenerates it.
    uint64_t fingerprint() const;
};

// The seeded pool of keys the optimiser permutes (size² of them).
std::vector<SobolBlueNoiseKey> sobolBlueNoiseKeyPool(const SobolBlueNoiseOptimizer& settings);

// The optimised tile.
SobolBlueNoiseKeys optimizeSobolBlueNoiseKeys(const SobolBlueNoiseOptimizer& settings);

// Reads `file` if it holds the keys these settings produce (magic, size,
// fingerprint, and the keys a permutation of the pool), else optimises them
// and writes the file atomically; an unwritable cache is not an error.
std::shared_ptr<const SobolBlueNoiseKeys> loadOrCreateSobolBlueNoiseKeys(
    const std::filesystem::path& file, const SobolBlueNoiseOptimizer& settings);

// The process-wide tile: cacheDirectory()/sobol-bluenoise-keys-128.bin.
std::shared_ptr<const SobolBlueNoiseKeys> defaultSobolBlueNoiseKeys();

}  // namespace pathlab
