#include "sampling/spectrum.h"

#include <cmath>
#include <complex>

namespace pathlab {
namespace {

using Complex = std::complex<double>;

std::vector<double> ringAverage(const std::vector<double>& power, int nx, int ny, int cx, int cy,
                                int maxRadius) {
    std::vector<double> sum(size_t(maxRadius) + 1, 0.0);
    std::vector<int> count(sum.size(), 0);
    for (int y = 0; y < ny; ++y)
        for (int x = 0; x < nx; ++x) {
            const double fx = x - cx, fy = y - cy;
            const auto r = static_cast<int>(std::lround(std::sqrt(fx * fx + fy * fy)));
            if (r > maxRadius) continue;
            sum[r] += power[size_t(y) * nx + x];
            ++count[r];
        }
    for (size_t r = 0; r < sum.size(); ++r) sum[r] = count[r] ? sum[r] / count[r] : 0.0;
    return sum;
}

}  // namespace

std::vector<double> powerSpectrum(const std::vector<Vec2f>& points, int maxFrequency) {
    const int side = 2 * maxFrequency + 1;
    std::vector<Complex> sums(size_t(side) * side, Complex(0, 0));
    std::vector<Complex> ex(side), ey(side);
    for (const Vec2f& p : points) {
        // exp(−2πi f x) for f = −F..F by repeated multiplication (separable DFT).
        const Complex stepX = std::polar(1.0, -2 * M_PI * p.x);
        const Complex stepY = std::polar(1.0, -2 * M_PI * p.y);
        ex[maxFrequency] = ey[maxFrequency] = 1.0;
        for (int f = 1; f <= maxFrequency; ++f) {
            ex[maxFrequency + f] = ex[maxFrequency + f - 1] * stepX;
            ey[maxFrequency + f] = ey[maxFrequency + f - 1] * stepY;
            ex[maxFrequency - f] = std::conj(ex[maxFrequency + f]);
            ey[maxFrequency - f] = std::conj(ey[maxFrequency + f]);
        }
        for (int y = 0; y < side; ++y) {
            Complex* row = &sums[size_t(y) * side];
            for (int x = 0; x < side; ++x) row[x] += ex[x] * ey[y];
        }
    }
    std::vector<double> power(sums.size());
    const double n = points.empty() ? 1.0 : double(points.size());
    for (size_t i = 0; i < sums.size(); ++i) power[i] = std::norm(sums[i]) / n;
    return power;
}

std::vector<double> radialAverage(const std::vector<double>& power, int maxFrequency) {
    const int side = 2 * maxFrequency + 1;
    return ringAverage(power, side, side, maxFrequency, maxFrequency, maxFrequency);
}

std::vector<double> radialPowerSpectrum(const std::vector<Vec2f>& points, int maxFrequency) {
    return radialAverage(powerSpectrum(points, maxFrequency), maxFrequency);
}

std::vector<double> radialPowerSpectrum(const std::vector<double>& image, int w, int h) {
    const size_t n = size_t(w) * h;
    double mean = 0;
    for (double v : image) mean += v;
    mean /= double(n);
    double variance = 0;
    for (double v : image) variance += (v - mean) * (v - mean);
    variance /= double(n);
    // Row DFTs then column DFTs (O(w·h·(w+h)), plenty for textures ≤ 256²).
    std::vector<Complex> rows(n);
    for (int y = 0; y < h; ++y)
        for (int fx = 0; fx < w; ++fx) {
            Complex s(0, 0);
            for (int x = 0; x < w; ++x)
                s += (image[size_t(y) * w + x] - mean) * std::polar(1.0, -2 * M_PI * fx * x / w);
            rows[size_t(y) * w + fx] = s;
        }
    std::vector<double> power(n);
    for (int fx = 0; fx < w; ++fx)
        for (int fy = 0; fy < h; ++fy) {
            Complex s(0, 0);
            for (int y = 0; y < h; ++y)
                s += rows[size_t(y) * w + fx] * std::polar(1.0, -2 * M_PI * fy * y / h);
            // Shift so the zero frequency sits at (w/2, h/2).
            const int sx = (fx + w / 2) % w, sy = (fy + h / 2) % h;
            power[size_t(sy) * w + sx] = std::norm(s) / (double(n) * (variance > 0 ? variance : 1));
        }
    return ringAverage(power, w, h, w / 2, h / 2, std::min(w, h) / 2);
}

}  // namespace pathlab
