#include "sampling/spectrum.h"

#include <cmath>
#include <complex>

#include "metrics/power_spectrum.h"

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
    // The FFT periodogram of metrics/power_spectrum.h, over the variance.
    const RadialPowerSpectrum s = radialPeriodogram(image, w, h);
    const double variance = s.totalPower > 0 ? s.totalPower : 1.0;
    std::vector<double> out(s.power.size(), 0.0);
    for (size_t r = 1; r < out.size(); ++r) out[r] = s.power[r] / variance;
    return out;
}

}  // namespace pathlab
