#include "render/pixel_filter.h"

#include <cmath>
#include <string>

#include "core/error.h"

namespace pathlab {
namespace {

// pbrt-v4's Lerp(t, a, b) = (1 − t)·a + t·b, in that order of operations.
float lerp1(float t, float a, float b) {
    return (1 - t) * a + t * b;
}

// The normal density N(0, σ²) at x (pbrt-v4's Gaussian).
float gaussian(float x, float sigma) {
    return 1 / std::sqrt(2 * kPi * sigma * sigma) * std::exp(-(x * x) / (2 * sigma * sigma));
}

// Mitchell & Netravali's cubic (SIGGRAPH 1988) on [−2, 2], as pbrt-v4's Mitchell1D.
float mitchell1D(float x, float b, float c) {
    x = std::abs(x);
    if (x <= 1)
        return ((12 - 9 * b - 6 * c) * x * x * x + (-18 + 12 * b + 6 * c) * x * x + (6 - 2 * b)) *
               (1.f / 6.f);
    if (x <= 2)
        return ((-b - 6 * c) * x * x * x + (6 * b + 30 * c) * x * x + (-12 * b - 48 * c) * x +
                (8 * b + 24 * c)) *
               (1.f / 6.f);
    return 0;
}

// sin(πx)/(πx), 1 where 1 + (πx)² rounds to 1 (pbrt-v4's Sinc via SinXOverX).
float sinc(float x) {
    const float px = kPi * x;
    if (1 + px * px == 1) return 1;
    return std::sin(px) / px;
}

// The sinc windowed by a wider sinc (Lanczos), zero beyond the radius.
float windowedSinc(float x, float radius, float tau) {
    if (std::abs(x) > radius) return 0;
    return sinc(x) * sinc(x / tau);
}

// pbrt-v4's SampleLinear: x in [0, 1) with density ∝ lerp(x, a, b).
float sampleLinear(float u, float a, float b) {
    if (u == 0 && a == 0) return 0;
    const float x = u * (a + b) / (a + std::sqrt(lerp1(u, a * a, b * b)));
    return std::min(x, kOneMinusEpsilon);
}

// The last i in [0, n − 1) with cdf[i] ≤ u (pbrt-v4's FindInterval over the
// n = cdf.size() entries): the cell u falls in.
int findInterval(const std::vector<float>& cdf, float u) {
    int lo = 0, hi = int(cdf.size()) - 1;  // cdf[lo] ≤ u is assumed, as cdf[0] = 0
    while (hi - lo > 1) {
        const int mid = (lo + hi) / 2;
        if (cdf[size_t(mid)] <= u)
            lo = mid;
        else
            hi = mid;
    }
    return std::min(lo, int(cdf.size()) - 2);
}

void requireRadius(const PixelFilter& f) {
    const auto ok = [](float r) { return std::isfinite(r) && r > 0 && r <= 64; };
    if (!ok(f.radius.x) || !ok(f.radius.y))
        throw InputError("pixel filter radius must be in (0, 64], got " +
                         std::to_string(f.radius.x) + " x " + std::to_string(f.radius.y));
    if (f.type == FilterType::Gaussian && !(f.sigma > 0 && std::isfinite(f.sigma)))
        throw InputError("gaussian filter sigma must be positive, got " + std::to_string(f.sigma));
    if (f.type == FilterType::Lanczos && !(f.tau > 0 && std::isfinite(f.tau)))
        throw InputError("sinc filter tau must be positive, got " + std::to_string(f.tau));
}

}  // namespace

PixelFilter defaultPixelFilter(FilterType type) {
    PixelFilter f;
    f.type = type;
    switch (type) {
        case FilterType::Box:
            f.radius = {0.5f, 0.5f};
            break;
        case FilterType::Gaussian:
            f.radius = {1.5f, 1.5f};
            break;
        case FilterType::Mitchell:
        case FilterType::Triangle:
            f.radius = {2, 2};
            break;
        case FilterType::Lanczos:
            f.radius = {4, 4};
            break;
    }
    return f;
}

float evaluateFilter(const PixelFilter& f, Vec2f p) {
    switch (f.type) {
        case FilterType::Box:
            return std::abs(p.x) <= f.radius.x && std::abs(p.y) <= f.radius.y ? 1.0f : 0.0f;
        case FilterType::Gaussian:
            // Shifted down by its value at the radius, so that it meets zero there.
            return std::max(0.0f, gaussian(p.x, f.sigma) - gaussian(f.radius.x, f.sigma)) *
                   std::max(0.0f, gaussian(p.y, f.sigma) - gaussian(f.radius.y, f.sigma));
        case FilterType::Mitchell:
            return mitchell1D(2 * p.x / f.radius.x, f.b, f.c) *
                   mitchell1D(2 * p.y / f.radius.y, f.b, f.c);
        case FilterType::Lanczos:
            return windowedSinc(p.x, f.radius.x, f.tau) * windowedSinc(p.y, f.radius.y, f.tau);
        case FilterType::Triangle:
            return std::max(0.0f, f.radius.x - std::abs(p.x)) *
                   std::max(0.0f, f.radius.y - std::abs(p.y));
    }
    return 0;
}

float sampleTent(float u, float radius) {
    // pbrt-v4 picks the side with SampleDiscrete({½, ½}) and reuses u, rescaled.
    if (u < 0.5f)
        return -radius + radius * sampleLinear(std::min(u / 0.5f, kOneMinusEpsilon), 0, 1);
    return radius * sampleLinear(std::min((u - 0.5f) / 0.5f, kOneMinusEpsilon), 1, 0);
}

PiecewiseConstant2D::Distribution1D::Distribution1D(const float* f, int n, float lo_, float hi_)
    : func(f, f + n), cdf(size_t(n) + 1), lo(lo_), hi(hi_) {
    for (float& v : func) v = std::abs(v);
    cdf[0] = 0;
    for (size_t i = 1; i <= size_t(n); ++i)
        cdf[i] = cdf[i - 1] + func[i - 1] * (hi - lo) / float(n);
    integral = cdf[size_t(n)];
    for (size_t i = 1; i <= size_t(n); ++i)
        cdf[i] = integral == 0 ? float(i) / float(n) : cdf[i] / integral;
}

float PiecewiseConstant2D::Distribution1D::sample(float u, float* pdf, int* cell) const {
    const int o = findInterval(cdf, u);
    float du = u - cdf[size_t(o)];
    if (cdf[size_t(o) + 1] - cdf[size_t(o)] > 0) du /= cdf[size_t(o) + 1] - cdf[size_t(o)];
    *pdf = integral > 0 ? func[size_t(o)] / integral : 0;
    *cell = o;
    return lerp1((float(o) + du) / float(func.size()), lo, hi);
}

PiecewiseConstant2D::PiecewiseConstant2D(const std::vector<float>& values, int nx, int ny, Vec2f lo,
                                         Vec2f hi)
    : lo_(lo), hi_(hi) {
    rows_.reserve(size_t(ny));
    std::vector<float> rowIntegrals(static_cast<size_t>(ny));
    for (int y = 0; y < ny; ++y) {
        rows_.emplace_back(values.data() + size_t(y) * size_t(nx), nx, lo.x, hi.x);
        rowIntegrals[size_t(y)] = rows_.back().integral;
    }
    marginal_ = Distribution1D(rowIntegrals.data(), ny, lo.y, hi.y);
}

PiecewiseConstant2D::Sample PiecewiseConstant2D::sample(Vec2f u) const {
    Sample s;
    float pdfY, pdfX;
    s.p.y = marginal_.sample(u.y, &pdfY, &s.cy);
    s.p.x = rows_[size_t(s.cy)].sample(u.x, &pdfX, &s.cx);
    s.pdf = pdfX * pdfY;
    return s;
}

float PiecewiseConstant2D::pdf(Vec2f p) const {
    const int nx = int(rows_[0].func.size()), ny = int(rows_.size());
    const int cx = std::clamp(int((p.x - lo_.x) / (hi_.x - lo_.x) * float(nx)), 0, nx - 1);
    const int cy = std::clamp(int((p.y - lo_.y) / (hi_.y - lo_.y) * float(ny)), 0, ny - 1);
    return rows_[size_t(cy)].func[size_t(cx)] / marginal_.integral;
}

FilterSampler::FilterSampler(const PixelFilter& filter) : filter_(filter) {
    requireRadius(filter);
    unitBox_ = filter.type == FilterType::Box && filter.radius.x == 0.5f && filter.radius.y == 0.5f;
    if (constantWeight()) return;
    // pbrt-v4's FilterSampler: f at the centres of 32 cells per unit of
    // radius over [−r, r]², sampled as a piecewise-constant density.
    tabulated_ = true;
    nx_ = std::max(1, int(32 * filter.radius.x));
    ny_ = std::max(1, int(32 * filter.radius.y));
    values_.resize(size_t(nx_) * size_t(ny_));
    const Vec2f lo{-filter.radius.x, -filter.radius.y}, hi = filter.radius;
    for (int y = 0; y < ny_; ++y)
        for (int x = 0; x < nx_; ++x) {
            const Vec2f p{lerp1((float(x) + 0.5f) / float(nx_), lo.x, hi.x),
                          lerp1((float(y) + 0.5f) / float(ny_), lo.y, hi.y)};
            values_[size_t(y) * size_t(nx_) + size_t(x)] = evaluateFilter(filter, p);
        }
    distribution_ = PiecewiseConstant2D(values_, nx_, ny_, lo, hi);
    if (!(distribution_.integral() > 0))
        throw InputError("pixel filter is zero everywhere at its resolution");
}

FilterSample FilterSampler::sample(Vec2f u) const {
    switch (filter_.type) {
        case FilterType::Box:
            return {{lerp1(u.x, -filter_.radius.x, filter_.radius.x),
                     lerp1(u.y, -filter_.radius.y, filter_.radius.y)},
                    1.0f};
        case FilterType::Triangle:
            return {{sampleTent(u.x, filter_.radius.x), sampleTent(u.y, filter_.radius.y)}, 1.0f};
        default: {
            const PiecewiseConstant2D::Sample s = distribution_.sample(u);
            const float f = values_[size_t(s.cy) * size_t(nx_) + size_t(s.cx)];
            // A cell of density 0 is only reached on a CDF plateau's edge;
            // it contributes nothing rather than f/0.
            return {s.p, s.pdf > 0 ? f / s.pdf : 0.0f};
        }
    }
}

float FilterSampler::pdf(Vec2f p) const {
    const Vec2f r = filter_.radius;
    if (std::abs(p.x) > r.x || std::abs(p.y) > r.y) return 0;
    switch (filter_.type) {
        case FilterType::Box:
            return 1 / (4 * r.x * r.y);
        case FilterType::Triangle: {
            const auto tent = [](float x, float radius) {
                return std::max(0.0f, 1 / radius - std::abs(x) / (radius * radius));
            };
            return tent(p.x, r.x) * tent(p.y, r.y);
        }
        default:
            return distribution_.pdf(p);
    }
}

float FilterSampler::tabulatedValue(Vec2f p) const {
    if (!tabulated_) return evaluateFilter(filter_, p);
    const Vec2f r = filter_.radius;
    const int cx = std::clamp(int((p.x + r.x) / (2 * r.x) * float(nx_)), 0, nx_ - 1);
    const int cy = std::clamp(int((p.y + r.y) / (2 * r.y) * float(ny_)), 0, ny_ - 1);
    return values_[size_t(cy) * size_t(nx_) + size_t(cx)];
}

}  // namespace pathlab
