#include "metrics/error_spectrum_plot.h"

#include <algorithm>
#include <cmath>

namespace pathlab {
namespace {

constexpr int kWidth = 480, kHeight = 320, kMargin = 20;
constexpr int kPlotW = kWidth - 2 * kMargin, kPlotH = kHeight - 2 * kMargin;

class Canvas {
  public:
    Canvas() : image_(kWidth, kHeight) { std::fill(image_.rgb.begin(), image_.rgb.end(), 1.0f); }

    void dot(int x, int y, Vec3f colour) {
        if (x >= 0 && y >= 0 && x < kWidth && y < kHeight) image_.set(x, y, colour);
    }
    // Every `period` pixels draws `on` of them (1, 1: a solid line).
    void horizontal(int y, Vec3f colour, int period = 1, int on = 1) {
        for (int i = 0; i <= kPlotW; ++i)
            if (i % period < on) dot(kMargin + i, y, colour);
    }
    void vertical(int x, Vec3f colour, int period = 1, int on = 1) {
        for (int i = 0; i <= kPlotH; ++i)
            if (i % period < on) dot(x, kMargin + i, colour);
    }
    // A segment two pixels thick, sampled densely enough to leave no gaps.
    void segment(double x0, double y0, double x1, double y1, Vec3f colour) {
        const int steps = int(std::max(std::abs(x1 - x0), std::abs(y1 - y0))) * 2 + 1;
        for (int t = 0; t <= steps; ++t) {
            const double a = double(t) / steps;
            const int x = int(std::lround(x0 + a * (x1 - x0)));
            const int y = int(std::lround(y0 + a * (y1 - y0)));
            dot(x, y, colour), dot(x, y + 1, colour);
        }
    }
    Image take() { return std::move(image_); }

  private:
    Image image_;
};

// Whole decades [lo, hi] holding the positive powers of rings 1.. and the total.
std::pair<int, int> decadeRange(const RadialPowerSpectrum& s) {
    double lo = s.totalPower > 0 ? s.totalPower : HUGE_VAL, hi = s.totalPower;
    for (size_t r = 1; r < s.power.size(); ++r)
        if (s.power[r] > 0) lo = std::min(lo, s.power[r]), hi = std::max(hi, s.power[r]);
    if (!(hi > 0)) return {-1, 0};
    const int a = int(std::floor(std::log10(lo))), b = int(std::ceil(std::log10(hi)));
    return {a, std::max(b, a + 1)};
}

}  // namespace

Image errorSpectrumPlot(const RadialPowerSpectrum& s) {
    Canvas canvas;
    const auto [lo, hi] = decadeRange(s);
    const auto px = [](double f) { return kMargin + f / 0.5 * kPlotW; };
    const auto py = [lo = lo, hi = hi](double p) {
        const double v = p > 0 ? std::clamp(std::log10(p), double(lo), double(hi)) : double(lo);
        return kMargin + (hi - v) / (hi - lo) * kPlotH;
    };
    const Vec3f frame(0.55f), faint(0.88f), grey(0.5f), blue(0.02f, 0.12f, 0.55f);
    for (int d = lo + 1; d < hi; ++d)
        canvas.horizontal(int(std::lround(py(std::pow(10.0, d)))), faint);
    canvas.horizontal(kMargin, frame), canvas.horizontal(kMargin + kPlotH, frame);
    canvas.vertical(kMargin, frame), canvas.vertical(kMargin + kPlotW, frame);
    canvas.vertical(int(std::lround(px(kLowFrequencyLimit))), grey, 4, 1);
    if (s.totalPower > 0) canvas.horizontal(int(std::lround(py(s.totalPower))), grey, 8, 4);
    for (size_t r = 1; r + 1 < s.power.size(); ++r)
        canvas.segment(px(s.frequency[r]), py(s.power[r]), px(s.frequency[r + 1]),
                       py(s.power[r + 1]), blue);
    return canvas.take();
}

}  // namespace pathlab
