// The error spectrum (metrics/error_spectrum.h): normalisation, rings,
// Parseval and the low-frequency fraction, on synthetic errors whose spectra
// are known.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <sstream>
#include <thread>

#include "metrics/error_spectrum.h"

namespace pathlab {
namespace {

// A reference of zeros and a test holding `error` in all three channels.
Image errorImage(const std::vector<double>& error, int w, int h) {
    Image img(w, h);
    for (size_t i = 0; i < error.size(); ++i)
        for (int c = 0; c < 3; ++c) img.rgb[3 * i + c] = float(error[i]);
    return img;
}

std::vector<double> gaussianNoise(int w, int h, double sigma, uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> normal(0.0, sigma);
    std::vector<double> v(size_t(w) * h);
    for (double& x : v) x = normal(rng);
    return v;
}

double populationVariance(const std::vector<double>& v) {
    double mean = 0, sq = 0;
    for (double x : v) mean += x;
    mean /= double(v.size());
    for (double x : v) sq += (x - mean) * (x - mean);
    return sq / double(v.size());
}

// White noise of variance σ² in each channel, independent across channels:
// the channel mean has variance σ²/3, and every ring's mean power estimates
// it. A ring of c frequencies holds about c/2 independent periodogram values
// (P(k) = P(−k)), each σ²/3 times an Exp(1) variable (a χ² with 2 degrees of
// freedom over 2), so its mean has relative standard deviation √(2/c); five of
// those bound each of the 48 rings (a false alarm about once in 10⁴ runs; the
// seed is fixed).
TEST(ErrorSpectrum, WhiteNoiseIsFlatAtItsVariance) {
    const int w = 128, h = 96;
    const double sigma = 0.3;
    Image ref(w, h), test(w, h);
    std::mt19937_64 rng(11);
    std::normal_distribution<double> normal(0.0, sigma);
    for (float& v : test.rgb) v = float(normal(rng));
    const RadialPowerSpectrum s = errorSpectrum(ref, test);
    ASSERT_EQ(s.power.size(), size_t(h / 2 + 1));
    const double level = sigma * sigma / 3;
    for (size_t r = 1; r < s.power.size(); ++r) {
        EXPECT_NEAR(s.frequency[r], double(r) / h, 1e-15);
        const double bound = 5 * std::sqrt(2.0 / double(s.count[r]));
        EXPECT_NEAR(s.power[r] / level, 1.0, bound) << "ring " << r << " of " << s.count[r];
    }
    EXPECT_NEAR(s.totalPower / level, 1.0, 0.05);
}

// A 2×2 box-blurred noise is not flat: its response cos(πf_x)·cos(πf_y)
// keeps low frequencies and removes those near Nyquist.
TEST(ErrorSpectrum, BlurredNoiseIsNotFlat) {
    const int n = 64;
    const std::vector<double> white = gaussianNoise(n, n, 1.0, 3);
    std::vector<double> blurred(white.size());
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x)
            blurred[size_t(y) * n + x] =
                (white[size_t(y) * n + x] + white[size_t(y) * n + (x + 1) % n] +
                 white[size_t((y + 1) % n) * n + x] +
                 white[size_t((y + 1) % n) * n + (x + 1) % n]) /
                4;
    const RadialPowerSpectrum s = radialPeriodogram(blurred, n, n);
    const double level = populationVariance(blurred);
    EXPECT_GT(s.power[2] / level, 1.5);
    EXPECT_LT(s.power[n / 2] / level, 0.5);
}

// A cosine error of frequency 12/96 along x, or 8/64 along y, in a 96×64
// image: ring 8 either way (0.125 cycles per pixel), with all of the power.
TEST(ErrorSpectrum, SinusoidPutsItsPowerInItsRing) {
    const int w = 96, h = 64;
    for (bool alongX : {true, false}) {
        std::vector<double> e(size_t(w) * h);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x)
                e[size_t(y) * w + x] = 0.4 * (alongX ? std::cos(2 * M_PI * 12 * x / w)
                                                     : std::cos(2 * M_PI * 8 * y / h));
        const RadialPowerSpectrum s = errorSpectrum(Image(w, h), errorImage(e, w, h));
        size_t peak = 1;
        for (size_t r = 1; r < s.power.size(); ++r)
            if (s.power[r] > s.power[peak]) peak = r;
        EXPECT_EQ(peak, 8u);
        EXPECT_DOUBLE_EQ(s.frequency[peak], 0.125);
        // The cosine's variance 0.4²/2 sits on its two frequencies ±k.
        EXPECT_NEAR(s.totalPower, 0.08, 1e-6);
        EXPECT_NEAR(s.power[8] * double(s.count[8]), 0.08 * w * h, 1e-3);
        // 0.125 is not below a quarter of Nyquist.
        EXPECT_NEAR(s.lowFrequencyFraction(), 0.0, 1e-9);
    }
}

TEST(ErrorSpectrum, LowFrequencyBandEndsAtAQuarterOfNyquist) {
    const int w = 96, h = 64;
    std::vector<double> e(size_t(w) * h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) e[size_t(y) * w + x] = std::sin(2 * M_PI * 11 * x / w);
    EXPECT_NEAR(radialPeriodogram(e, w, h).lowFrequencyFraction(), 1.0, 1e-9);
}

// Parseval: the total power is the variance, the DC term w·h·mean², on odd,
// non-square sizes, and every frequency is in a ring, the DC or a corner.
TEST(ErrorSpectrum, ParsevalOnOddNonSquareSizes) {
    for (auto [w, h] : {std::pair{37, 23}, {23, 37}, {1, 9}, {50, 1}, {17, 17}}) {
        std::vector<double> e = gaussianNoise(w, h, 0.7, uint64_t(w * 100 + h));
        for (double& v : e) v += 0.2;
        const RadialPowerSpectrum s = radialPeriodogram(e, w, h);
        const double var = populationVariance(e);
        double mean = 0;
        for (double v : e) mean += v;
        mean /= double(e.size());
        EXPECT_NEAR(s.totalPower, var, 1e-12 * var) << w << "x" << h;
        EXPECT_NEAR(s.power[0], double(w) * h * mean * mean, 1e-9) << w << "x" << h;
        ASSERT_EQ(s.power.size(), size_t(std::min(w, h) / 2 + 1));
        int64_t inRings = 0;
        double ringPower = 0;
        for (size_t r = 1; r < s.power.size(); ++r)
            inRings += s.count[r], ringPower += s.power[r] * double(s.count[r]);
        EXPECT_LE(inRings, int64_t(w) * h - 1);
        EXPECT_LE(ringPower, s.totalPower * w * h * (1 + 1e-12));
        if (w == h) {
            EXPECT_GT(inRings, int64_t(0.75 * w * h));  // all but the corners
        }
    }
}

// White noise's low-frequency fraction is the area of the disc |f| < 1/8 in
// the square of frequencies, π/64 ≈ 0.0491. Over 128² the fraction, a ratio
// of sums of 8192 independent exponentials, has a standard deviation of about
// √(0.049/8192) ≈ 0.0025; the bound is four of those.
TEST(ErrorSpectrum, WhiteNoiseLowFrequencyFractionIsTheAreaRatio) {
    const int n = 128;
    const std::vector<double> e = gaussianNoise(n, n, 1.0, 5);
    const double fraction = lowFrequencyErrorFraction(Image(n, n), errorImage(e, n, n));
    EXPECT_NEAR(fraction, M_PI / 64, 0.01);
    // A high-pass error (each pixel minus its right neighbour) is bluer.
    std::vector<double> blue(e.size());
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x)
            blue[size_t(y) * n + x] = e[size_t(y) * n + x] - e[size_t(y) * n + (x + 1) % n];
    EXPECT_LT(radialPeriodogram(blue, n, n).lowFrequencyFraction(), fraction / 2);
}

TEST(ErrorSpectrum, ConstantErrorHasNoFraction) {
    const RadialPowerSpectrum s = radialPeriodogram(std::vector<double>(64, 0.5), 8, 8);
    EXPECT_NEAR(s.power[0], 64 * 0.25, 1e-12);
    EXPECT_EQ(s.totalPower, 0.0);
    EXPECT_TRUE(std::isnan(s.lowFrequencyFraction()));
}

// Many threads planning and running transforms at once get the bits one
// thread gets (FFTW's planner is serialised, its plans are deterministic).
TEST(ErrorSpectrum, SameBitsFromConcurrentThreads) {
    const int w = 60, h = 44;
    const std::vector<double> e = gaussianNoise(w, h, 1.0, 9);
    const RadialPowerSpectrum alone = radialPeriodogram(e, w, h);
    std::vector<RadialPowerSpectrum> results(4);
    std::vector<std::thread> threads;
    for (auto& r : results)
        threads.emplace_back([&r, &e] {
            for (int k = 0; k < 5; ++k) r = radialPeriodogram(e, w, h);
        });
    for (auto& t : threads) t.join();
    for (const auto& r : results) {
        EXPECT_EQ(r.power, alone.power);
        EXPECT_EQ(r.totalPower, alone.totalPower);
        EXPECT_EQ(r.lowFrequencyPower, alone.lowFrequencyPower);
    }
}

TEST(ErrorSpectrum, CsvHasOneRowPerRingThatReadsBackExactly) {
    const std::vector<double> e = gaussianNoise(20, 12, 1.0, 2);
    const RadialPowerSpectrum s = radialPeriodogram(e, 20, 12);
    const std::string csv = errorSpectrumCsv(s);
    ASSERT_EQ(csv.rfind("frequency,power\n", 0), 0u);
    std::istringstream in(csv.substr(16));
    std::string line;
    size_t r = 0;
    while (std::getline(in, line)) {
        const size_t comma = line.find(',');
        ASSERT_NE(comma, std::string::npos);
        EXPECT_EQ(std::stod(line.substr(0, comma)), s.frequency[r]);
        EXPECT_EQ(std::stod(line.substr(comma + 1)), s.power[r]);
        ++r;
    }
    EXPECT_EQ(r, s.power.size());
}

}  // namespace
}  // namespace pathlab
