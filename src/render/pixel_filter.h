// Pixel reconstruction filters, sampled by filter importance sampling as
// pbrt-v4 does (filters.h, filters.cpp; Ernst, Stamminger & Greiner, "Filter
// Importance Sampling", IEEE RT 2006): instead of splatting every sample onto
// the pixels its filter covers, each sample is drawn at an offset p from its
// pixel's centre with a density close to |f|, and carries the weight
// f(p)/pdf(p); the film keeps Σ w·L / Σ w per pixel (pbrt-v4's RGBFilm).
//
// Box and triangle are sampled exactly (weight 1). Gaussian, Mitchell and
// Lanczos are tabulated, like pbrt-v4's FilterSampler, as a piecewise-constant
// 2D distribution of 32 cells per unit of radius: the weight is the cell's
// tabulated f over its density, so it is ±∫|f̃| — the same magnitude for every
// sample, negative where the filter is (Mitchell's and Lanczos' lobes).
#pragma once

#include <vector>

#include "core/math.h"
#include "scene/scene.h"

namespace pathlab {

// pbrt-v4's parameters for a filter named in a scene without any (the
// *Filter::Create functions of filters.cpp): box radius 0.5; gaussian radius
// 1.5, sigma 0.5; mitchell radius 2, B = C = 1/3; sinc (Lanczos) radius 4,
// tau 3; triangle radius 2.
PixelFilter defaultPixelFilter(FilterType type);

// The filter's value at offset p from the pixel centre (pbrt-v4's
// Filter::Evaluate); zero outside [−radius, radius].
float evaluateFilter(const PixelFilter& filter, Vec2f p);

// pbrt-v4's SampleTent: x in [−radius, radius] with density
// max(0, 1/r − |x|/r²), one half of u's range for each side.
float sampleTent(float u, float radius);

// A piecewise-constant density over a rectangle, proportional to |values|
// of an nx × ny grid of equal cells (row-major, x fastest): pbrt-v4's
// PiecewiseConstant2D, sampled by inversion, the marginal in y first and then
// x within the chosen row.
class PiecewiseConstant2D {
  public:
    PiecewiseConstant2D() = default;
    PiecewiseConstant2D(const std::vector<float>& values, int nx, int ny, Vec2f lo, Vec2f hi);
    struct Sample {
        Vec2f p;
        float pdf;   // with respect to area in the rectangle
        int cx, cy;  // the cell
    };
    Sample sample(Vec2f u) const;
    float pdf(Vec2f p) const;
    float integral() const { return marginal_.integral; }

  private:
    // pbrt-v4's PiecewiseConstant1D over [lo, hi]: |f| and its normalised CDF.
    struct Distribution1D {
        std::vector<float> func, cdf;
        float lo = 0, hi = 1, integral = 0;
        Distribution1D() = default;
        Distribution1D(const float* f, int n, float lo, float hi);
        // x and its cell; pdf is func[cell] / integral (0 for a zero function).
        float sample(float u, float* pdf, int* cell) const;
    };
    std::vector<Distribution1D> rows_;  // x given y, one per row
    Distribution1D marginal_;           // y
    Vec2f lo_{0, 0}, hi_{1, 1};
};

struct FilterSample {
    Vec2f p;       // offset from the pixel centre, in pixels
    float weight;  // f/pdf
};

// Draws a pixel sample's offset for a filter. Immutable once built; shared
// by every rendering thread.
class FilterSampler {
  public:
    // Throws InputError when a radius is not in (0, 64] or a parameter
    // makes the filter meaningless (sigma or tau not positive).
    explicit FilterSampler(const PixelFilter& filter);

    FilterSample sample(Vec2f u) const;
    // The density of sample()'s offsets at p.
    float pdf(Vec2f p) const;
    const PixelFilter& filter() const { return filter_; }
    // Box of radius ½: the offset is u − ½ (the renderer places the sample at
    // pixel + u and keeps the plain mean, as before filters existed).
    bool unitBox() const { return unitBox_; }
    // Every weight is 1 (box, triangle): the film's Σ w·L / Σ w is the plain mean.
    bool constantWeight() const {
        return filter_.type == FilterType::Box || filter_.type == FilterType::Triangle;
    }
    // The tabulated filter (gaussian, mitchell, lanczos); null otherwise.
    const PiecewiseConstant2D* table() const { return tabulated_ ? &distribution_ : nullptr; }
    // The tabulated value of the cell holding p (pbrt-v4's f[pi]).
    float tabulatedValue(Vec2f p) const;

  private:
    PixelFilter filter_;
    bool unitBox_ = false, tabulated_ = false;
    int nx_ = 0, ny_ = 0;
    std::vector<float> values_;  // the filter at the cell centres, signed
    PiecewiseConstant2D distribution_;
};

}  // namespace pathlab
