// RGB to spectrum (Jakob & Hanika 2019): the optimiser's table reproduces the
// colours at its nodes, the table's lookups reproduce colours across the
// gamut, greys are constant spectra, albedo spectra are reflectances, the
// table is the same whatever the thread count, and its cache file is rebuilt
// when corrupted.
#include <gtest/gtest.h>
#include <tbb/task_arena.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "core/rng.h"
#include "spectral/cie_functions.h"
#include "spectral/colour_space.h"
#include "spectral/rgb_spectrum_table.h"

namespace pathlab::spectral {
namespace {

// The linear sRGB of reflectance `s` lit by the colour space's illuminant,
// integrated with the fine quadrature (independent of the optimiser's).
Vec3d reflectedRgb(const SigmoidPolynomial& s) {
    const RgbColourSpace& cs = linearSrgb();
    const Quadrature& q = fineQuadrature();
    Vec3d xyz{};
    for (size_t k = 0; k < q.lambda.size(); ++k) {
        const double l = q.lambda[k];
        const double w = q.weight[k] * s(float(l)) * (*cs.illuminant)(l) / cieYIntegral();
        xyz[0] += w * cieX(l), xyz[1] += w * cieY(l), xyz[2] += w * cieZ(l);
    }
    return multiply(cs.xyzToRgb, xyz);
}

double maxError(const Vec3d& a, Vec3f b) {
    return std::max({std::abs(a[0] - b.x), std::abs(a[1] - b.y), std::abs(a[2] - b.z)});
}

TEST(SpectralRgbTable, SmallTableReproducesItsNodes) {
    const RgbToSpectrumTable t = makeRgbToSpectrumTable(8);
    const int n = t.resolution;
    double worst = 0;
    // The nodes with 0.1 ≤ z ≤ 0.9 of every channel: darker ones are fitted in
    // L*a*b*, where a tiny linear error is a visible one, and at z = 1 colours
    // next to white need spectra at 1 over most of the range, a step the
    // bounded coefficients only approach.
    for (int l = 0; l < 3; ++l)
        for (int k = 0; k < n; ++k) {
            if (t.zNodes[size_t(k)] < 0.1f || t.zNodes[size_t(k)] > 0.9f) continue;
            for (int yi = 0; yi < n; ++yi)
                for (int xi = 0; xi < n; ++xi) {
                    const float z = t.zNodes[size_t(k)];
                    float rgb[3];
                    rgb[l] = z, rgb[(l + 1) % 3] = z * xi / (n - 1),
                    rgb[(l + 2) % 3] = z * yi / (n - 1);
                    const float* c = &t.coefficients[t.index(l, k, yi, xi)];
                    const Vec3f colour(rgb[0], rgb[1], rgb[2]);
                    // Saturated magentas and pure blues lie outside the
                    // sigmoid's reach (the paper's Fig. 5): skip colours on two faces.
                    if ((xi == n - 1 && yi == 0) || (xi == 0 && yi == n - 1) ||
                        (xi == 0 && yi == 0))
                        continue;
                    worst = std::max(worst, maxError(reflectedRgb({c[0], c[1], c[2]}), colour));
                }
        }
    EXPECT_LT(worst, 1e-3);
}

TEST(SpectralRgbTable, GreysAreConstantSpectra) {
    const RgbToSpectrumTable t = makeRgbToSpectrumTable(4);
    for (float v : {0.f, 0.01f, 0.18f, 0.5f, 0.9f, 1.f}) {
        const SigmoidPolynomial s = t.lookup(Vec3f(v));
        for (float lambda : {360.f, 500.f, 700.f, 830.f}) EXPECT_NEAR(s(lambda), v, 1e-6) << v;
    }
}

TEST(SpectralRgbTable, SameTableWhateverTheThreadCount) {
    const RgbToSpectrumTable many = makeRgbToSpectrumTable(6);
    tbb::task_arena one(1);
    const RgbToSpectrumTable single = one.execute([] { return makeRgbToSpectrumTable(6); });
    EXPECT_EQ(many.coefficients, single.coefficients);
}

std::string readAll(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(SpectralRgbTable, CacheIsWrittenThenReadAndRebuiltWhenCorrupt) {
    const std::filesystem::path dir = std::filesystem::temp_directory_path() /
                                      ("pathlab-rgb2spec-test-" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir);
    const std::filesystem::path file = dir / "table.bin";
    const auto made = loadOrCreateRgbToSpectrumTable(file, 5);
    const std::string bytes = readAll(file);
    ASSERT_FALSE(bytes.empty());
    // Read back: the same table.
    EXPECT_EQ(loadOrCreateRgbToSpectrumTable(file, 5)->coefficients, made->coefficients);
    // One flipped byte in the coefficients, then a truncated file: rebuilt and rewritten.
    for (const auto corrupt : {+[](std::string s) {
                                   s[s.size() / 2] ^= 0x40;
                                   return s;
                               },
                               +[](std::string s) { return s.substr(0, s.size() - 3); }}) {
        {
            std::ofstream out(file, std::ios::binary | std::ios::trunc);
            out << corrupt(bytes);
        }
        EXPECT_EQ(loadOrCreateRgbToSpectrumTable(file, 5)->coefficients, made->coefficients);
        EXPECT_EQ(readAll(file), bytes);
    }
    // A table of another resolution is not taken for this one.
    EXPECT_EQ(loadOrCreateRgbToSpectrumTable(file, 6)->resolution, 6);
    std::filesystem::remove_all(dir);
}

// The process-wide table (cached after its first use): colours over a grid
// and at random across the gamut come back from their spectra.
TEST(SpectralRgbTable, DefaultTableRoundTripsTheGamut) {
    const RgbToSpectrumTable& t = defaultRgbToSpectrumTable();
    double worst = 0;
    Vec3f worstColour;
    auto check = [&](Vec3f c) {
        const double e = maxError(reflectedRgb(t.lookup(c)), c);
        if (e > worst) worst = e, worstColour = c;
    };
    for (int r = 1; r < 10; ++r)
        for (int g = 1; g < 10; ++g)
            for (int b = 1; b < 10; ++b) check(Vec3f(r, g, b) * 0.1f);
    Pcg32 rng(17, 0);
    // Components in [0.02, 0.9]: docs/spectral.md gives the error beyond.
    for (int i = 0; i < 2000; ++i)
        check(Vec3f(0.02f, 0.02f, 0.02f) +
              0.88f * Vec3f(rng.nextFloat(), rng.nextFloat(), rng.nextFloat()));
    EXPECT_LT(worst, 1e-3) << worstColour.x << " " << worstColour.y << " " << worstColour.z;
}

TEST(SpectralRgb, OutOfRangeColoursAreClamped) {
    const SampledWavelengths w = SampledWavelengths::sampleVisible(0.4f);
    const SampledSpectrum black = albedoSpectrum(Vec3f(std::nanf(""), -1.f, 0.f), w);
    EXPECT_TRUE(black.isBlack());
    const SampledSpectrum white = albedoSpectrum(Vec3f(2.f, 1.f, 5.f), w);
    for (int i = 0; i < kSpectrumSamples; ++i) EXPECT_EQ(white[i], 1.f);
}

TEST(SpectralRgb, AlbedoSpectraAreReflectances) {
    Pcg32 rng(19, 0);
    for (int i = 0; i < 200; ++i) {
        const Vec3f c(rng.nextFloat(), rng.nextFloat(), rng.nextFloat());
        const SigmoidPolynomial s = rgbToSigmoid(c);
        EXPECT_LE(s.maxValue(), 1.f);
        const SampledWavelengths w = SampledWavelengths::sampleVisible(rng.nextFloat());
        const SampledSpectrum a = albedoSpectrum(c, w);
        for (int k = 0; k < kSpectrumSamples; ++k) {
            EXPECT_GE(a[k], 0.f);
            EXPECT_LE(a[k], s.maxValue() + 1e-6f);
        }
        // Unbounded spectra of 3c are three times those of c at half brightness's
        // scale: the same sigmoid of c / (2 max c), scaled.
        const SampledSpectrum u = unboundedSpectrum(3.f * c, w), u1 = unboundedSpectrum(c, w);
        for (int k = 0; k < kSpectrumSamples; ++k) EXPECT_NEAR(u[k], 3 * u1[k], 1e-4f * (1 + u[k]));
    }
}

}  // namespace
}  // namespace pathlab::spectral
