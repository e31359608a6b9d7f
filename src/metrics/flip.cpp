#include "metrics/flip.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/error.h"
#include "metrics/flip_color.h"

namespace pathlab::flip {
namespace {

// Constants of [HPG20]: q_c (colour-difference exponent), p_c and p_t (the
// knee of the colour-difference remapping), w (feature width in degrees) and
// q_f (feature-difference exponent).
constexpr float kColorExponent = 0.7f;
constexpr float kColorKnee = 0.4f;
constexpr float kColorKneeTarget = 0.95f;
constexpr float kFeatureWidthDegrees = 0.082f;
constexpr float kFeatureExponent = 0.5f;

// The CSF Gaussians of [HPG20] in the spatial domain, a·sqrt(π/b)·exp(−π²x²/b)
// with x in degrees: Yy (a=1, b=0.0047), Cx (a=1, b=0.0053), and Cz the sum of
// (a=34.1, b=0.04) and (a=13.5, b=0.025).
constexpr float kPi = 3.14159265358979f;
constexpr float kAchromaticB = 0.0047f, kRedGreenB = 0.0053f;
constexpr float kBlueYellowA1 = 34.1f, kBlueYellowB1 = 0.04f;
constexpr float kBlueYellowA2 = 13.5f, kBlueYellowB2 = 0.025f;

float csfGaussian(float x2, float a, float b) {
    return a * std::sqrt(kPi / b) * std::exp(-(kPi * kPi) * x2 / b);
}

// The 1-D factor g whose outer product g(x)g(y) is the 2-D Gaussian above:
// sqrt(a·sqrt(π/b))·exp(−π²x²/b).
float csfGaussianFactor(float x2, float a, float b) {
    return std::sqrt(a * std::sqrt(kPi / b)) * std::exp(-(kPi * kPi) * x2 / b);
}

// A single-channel image plane.
struct Plane {
    int width = 0, height = 0;
    std::vector<float> values;
    Plane() = default;
    Plane(int w, int h) : width(w), height(h), values(size_t(w) * size_t(h)) {}
    float* row(int y) { return values.data() + size_t(y) * width; }
    const float* row(int y) const { return values.data() + size_t(y) * width; }
};

struct YcxczPlanes {
    Plane y, cx, cz;
};

// Runs body(y) for every row, in parallel; each row is computed independently
// so the result does not depend on the number of threads.
template <typename Body>
void forEachRow(int height, const Body& body) {
    tbb::parallel_for(tbb::blocked_range<int>(0, height), [&](const tbb::blocked_range<int>& r) {
        for (int y = r.begin(); y != r.end(); ++y) body(y);
    });
}

// Copies a row into `padded` with `radius` clamped-edge samples on each side,
// so the horizontal convolutions need no bounds checks.
void padRow(const float* in, int width, int radius, std::vector<float>& padded) {
    padded.resize(size_t(width) + 2 * size_t(radius));
    for (int i = 0; i < radius; ++i) padded[i] = in[0];
    std::copy(in, in + width, padded.begin() + radius);
    for (int i = 0; i < radius; ++i) padded[size_t(radius) + width + i] = in[width - 1];
}

// out[x] = Σ_k w[k]·sources[k][x], taps accumulated in ascending k for every
// pixel. Pixels are processed in blocks whose sums stay in registers; the
// per-pixel order of operations is the same as a plain loop over k.
void weightedSum(const std::vector<const float*>& sources, const std::vector<float>& weights,
                 int width, float* __restrict out) {
    constexpr int kBlock = 16;
    const size_t taps = weights.size();
    int x0 = 0;
    for (; x0 + kBlock <= width; x0 += kBlock) {
        float sum[kBlock] = {};
        for (size_t k = 0; k < taps; ++k) {
            const float w = weights[k];
            const float* __restrict src = sources[k] + x0;
            for (int i = 0; i < kBlock; ++i) sum[i] += w * src[i];
        }
        std::copy(sum, sum + kBlock, out + x0);
    }
    for (int x = x0; x < width; ++x) {
        float sum = 0.0f;
        for (size_t k = 0; k < taps; ++k) sum += weights[k] * sources[k][x];
        out[x] = sum;
    }
}

// Horizontal convolution of a padded row: out[x] = Σ_k w[k]·padded[x+k].
void convolveRow(const std::vector<float>& padded, const std::vector<float>& weights, int width,
                 float* out) {
    std::vector<const float*> sources(weights.size());
    for (size_t k = 0; k < weights.size(); ++k) sources[k] = padded.data() + k;
    weightedSum(sources, weights, width, out);
}

// Vertical convolution: out[x] = Σ_k w[k]·in(x, clamp(y+k−r)).
void convolveColumn(const Plane& in, int y, const std::vector<float>& weights, float* out) {
    const int radius = int(weights.size() / 2);
    std::vector<const float*> sources(weights.size());
    for (size_t k = 0; k < weights.size(); ++k)
        sources[k] = in.row(std::clamp(y + int(k) - radius, 0, in.height - 1));
    weightedSum(sources, weights, in.width, out);
}

YcxczPlanes toYcxcz(const Image& image) {
    YcxczPlanes p{Plane(image.width, image.height), Plane(image.width, image.height),
                  Plane(image.width, image.height)};
    forEachRow(image.height, [&](int y) {
        const float* rgb = &image.rgb[size_t(y) * image.width * 3];
        for (int x = 0; x < image.width; ++x) {
            const Color c = linearRgbToYcxcz({rgb[3 * x], rgb[3 * x + 1], rgb[3 * x + 2]});
            p.y.row(y)[x] = c.x, p.cx.row(y)[x] = c.y, p.cz.row(y)[x] = c.z;
        }
    });
    return p;
}

// The horizontal half of the CSF filtering of one image: four planes
// (Yy, Cx, and Cz through each of the two blue–yellow factors).
struct CsfHalf {
    Plane y, cx, cz1, cz2;
};

CsfHalf filterCsfHorizontally(const YcxczPlanes& in, const CsfFilters& f) {
    const int w = in.y.width, h = in.y.height;
    CsfHalf out{Plane(w, h), Plane(w, h), Plane(w, h), Plane(w, h)};
    forEachRow(h, [&](int y) {
        std::vector<float> padded;
        padRow(in.y.row(y), w, f.radius, padded);
        convolveRow(padded, f.achromatic, w, out.y.row(y));
        padRow(in.cx.row(y), w, f.radius, padded);
        convolveRow(padded, f.redGreen, w, out.cx.row(y));
        padRow(in.cz.row(y), w, f.radius, padded);
        convolveRow(padded, f.blueYellow1, w, out.cz1.row(y));
        convolveRow(padded, f.blueYellow2, w, out.cz2.row(y));
    });
    return out;
}

// Filtered YCxCz of one row → Hunt-adjusted L*a*b*, after clamping to the
// displayable [0,1] linear RGB range ([HPG20], colour pipeline).
struct RowBuffers {
    std::vector<float> y, cx, cz1, cz2;
    explicit RowBuffers(int w) : y(w), cx(w), cz1(w), cz2(w) {}
};

void filterCsfVertically(const CsfHalf& in, const CsfFilters& f, int y, RowBuffers& out) {
    convolveColumn(in.y, y, f.achromatic, out.y.data());
    convolveColumn(in.cx, y, f.redGreen, out.cx.data());
    convolveColumn(in.cz1, y, f.blueYellow1, out.cz1.data());
    convolveColumn(in.cz2, y, f.blueYellow2, out.cz2.data());
}

Color filteredToHuntLab(const RowBuffers& row, int x) {
    const Color ycxcz{row.y[x], row.cx[x], row.cz1[x] + row.cz2[x]};
    Color rgb = xyzToLinearRgb(ycxczToXyz(ycxcz));
    rgb = {std::clamp(rgb.x, 0.0f, 1.0f), std::clamp(rgb.y, 0.0f, 1.0f),
           std::clamp(rgb.z, 0.0f, 1.0f)};
    return huntAdjust(linearRgbToLab(rgb));
}

// Horizontal half of the feature filtering of the achromatic channel
// normalised to [0,1]: x-derivatives and the x-Gaussian.
struct FeatureHalf {
    Plane dx, ddx, gauss;
};

FeatureHalf filterFeaturesHorizontally(const Plane& achromatic, const FeatureFilters& f) {
    const int w = achromatic.width, h = achromatic.height;
    FeatureHalf out{Plane(w, h), Plane(w, h), Plane(w, h)};
    forEachRow(h, [&](int y) {
        std::vector<float> padded;
        padRow(achromatic.row(y), w, f.radius, padded);
        convolveRow(padded, f.firstDerivative, w, out.dx.row(y));
        convolveRow(padded, f.secondDerivative, w, out.ddx.row(y));
        convolveRow(padded, f.gaussian, w, out.gauss.row(y));
    });
    return out;
}

// Yy of YCxCz back to [0,1] ((Yy + 16)/116, i.e. relative luminance), the
// input of the feature detectors ([HPG20], feature pipeline).
Plane normalizedAchromatic(const Plane& yy) {
    Plane out(yy.width, yy.height);
    forEachRow(yy.height, [&](int y) {
        for (int x = 0; x < yy.width; ++x)
            out.row(y)[x] = yy.row(y)[x] * (1.0f / 116.0f) + 16.0f / 116.0f;
    });
    return out;
}

// Edge and point magnitudes of one row: |∇(G*Y)| and |(∂²x, ∂²y)(G*Y)|.
struct FeatureRow {
    std::vector<float> edge, point;
};

FeatureRow featureMagnitudes(const FeatureHalf& half, const FeatureFilters& f, int y) {
    const int w = half.dx.width;
    std::vector<float> dx(w), ddx(w), dy(w), ddy(w);
    convolveColumn(half.dx, y, f.gaussian, dx.data());
    convolveColumn(half.ddx, y, f.gaussian, ddx.data());
    convolveColumn(half.gauss, y, f.firstDerivative, dy.data());
    convolveColumn(half.gauss, y, f.secondDerivative, ddy.data());
    FeatureRow row{std::vector<float>(w), std::vector<float>(w)};
    for (int x = 0; x < w; ++x) {
        row.edge[x] = std::sqrt(dx[x] * dx[x] + dy[x] * dy[x]);
        row.point[x] = std::sqrt(ddx[x] * ddx[x] + ddy[x] * ddy[x]);
    }
    return row;
}

}  // namespace

// One image's half of LDR-FLIP, everything that does not depend on the other
// image: its CSF-filtered colours in Hunt-adjusted L*a*b* ([HPG20], colour
// pipeline) and its edge and point magnitudes (feature pipeline).
struct LdrSide {
    int width = 0, height = 0;
    std::vector<Color> lab;
    std::vector<float> edge, point;
};

namespace {

LdrSide prepareLdrSide(const Image& image, float ppd) {
    const YcxczPlanes planes = toYcxcz(image);
    const int w = image.width, h = image.height;
    LdrSide side{w, h, std::vector<Color>(image.pixelCount()),
                 std::vector<float>(image.pixelCount()), std::vector<float>(image.pixelCount())};
    const CsfFilters csf = makeCsfFilters(ppd);
    const CsfHalf csfHalf = filterCsfHorizontally(planes, csf);
    const FeatureFilters features = makeFeatureFilters(ppd);
    const FeatureHalf featureHalf =
        filterFeaturesHorizontally(normalizedAchromatic(planes.y), features);
    forEachRow(h, [&](int y) {
        RowBuffers row(w);
        filterCsfVertically(csfHalf, csf, y, row);
        const FeatureRow magnitudes = featureMagnitudes(featureHalf, features, y);
        const size_t begin = size_t(y) * size_t(w);
        for (int x = 0; x < w; ++x) side.lab[begin + size_t(x)] = filteredToHuntLab(row, x);
        std::copy(magnitudes.edge.begin(), magnitudes.edge.end(), side.edge.begin() + begin);
        std::copy(magnitudes.point.begin(), magnitudes.point.end(), side.point.begin() + begin);
    });
    return side;
}

// LDR-FLIP from the two sides: the colour difference ΔE_c in [0,1], then
// ΔE = ΔE_c^(1 − ΔE_f) with ΔE_f = (max(|Δedge|, |Δpoint|)/√2)^q_f ([HPG20],
// final difference map).
std::vector<float> ldrFlipErrorMap(const LdrSide& ref, const LdrSide& test) {
    const float cmax = maxColorDistance();
    const float inverseSqrt2 = 1.0f / std::sqrt(2.0f);
    std::vector<float> error(ref.lab.size());
    forEachRow(ref.height, [&](int y) {
        const size_t begin = size_t(y) * size_t(ref.width), end = begin + size_t(ref.width);
        for (size_t i = begin; i < end; ++i) {
            const float distance = hyab(ref.lab[i], test.lab[i]);
            const float color = remapColorDifference(std::pow(distance, kColorExponent), cmax);
            const float edge = std::fabs(ref.edge[i] - test.edge[i]);
            const float point = std::fabs(ref.point[i] - test.point[i]);
            const float feature = std::pow(inverseSqrt2 * std::max(edge, point), kFeatureExponent);
            error[i] = std::pow(color, 1.0f - feature);
        }
    });
    return error;
}

// ACES fit coefficients: (a·x² + b·x + c) / (d·x² + e·x + f).
struct ToneCurve {
    float a, b, c, d, e, f;
};
constexpr ToneCurve kAces{0.6f * 0.6f * 2.51f, 0.6f * 0.03f, 0.0f,
                          0.6f * 0.6f * 2.43f, 0.6f * 0.59f, 0.14f};

Image exposeAndToneMap(const Image& image, float exposure) {
    const float scale = std::pow(2.0f, exposure);
    Image out(image.width, image.height);
    forEachRow(image.height, [&](int y) {
        const size_t begin = size_t(y) * image.width * 3, end = begin + size_t(image.width) * 3;
        for (size_t i = begin; i < end; ++i)
            out.rgb[i] = std::clamp(acesToneMap(image.rgb[i] * scale), 0.0f, 1.0f);
    });
    return out;
}

// The test image must have the reference's size (width × height).
void requireSize(int width, int height, const Image& test) {
    if (width != test.width || height != test.height)
        throw InputError("images differ in size: reference " + std::to_string(width) + "x" +
                         std::to_string(height) + ", test " + std::to_string(test.width) + "x" +
                         std::to_string(test.height));
}

void requireSameSize(const Image& reference, const Image& test) {
    requireSize(reference.width, reference.height, test);
    if (reference.pixelCount() == 0) throw InputError("images are empty");
}

Image clampedToUnit(const Image& image) {
    Image out = image;
    for (float& v : out.rgb) v = std::clamp(v, 0.0f, 1.0f);
    return out;
}

ExposureRange resolveExposures(const Image& reference, const Options& options) {
    ExposureRange range;
    if (!options.startExposure || !options.stopExposure) range = automaticExposureRange(reference);
    if (options.startExposure) range.start = *options.startExposure;
    if (options.stopExposure) range.stop = *options.stopExposure;
    if (!(range.start <= range.stop))
        throw InputError("start exposure must not exceed stop exposure");
    range.count = options.exposureCount ? *options.exposureCount
                                        : int(std::max(2.0f, std::ceil(range.stop - range.start)));
    if (range.count < 2) throw InputError("HDR-FLIP needs at least 2 exposures");
    return range;
}

// The weighted p-quantiles (ascending fractions) of errors in [0,1] without a
// full sort: errors are binned by value, so bins in order are the sorted
// order; only the bin where a running sum crosses p·total is sorted.
std::vector<double> weightedPercentiles(const std::vector<float>& errors,
                                        const std::vector<double>& fractions) {
    constexpr int kBins = 4096;
    auto binOf = [](float e) { return std::clamp(int(e * float(kBins)), 0, kBins - 1); };
    std::vector<double> binSums(kBins, 0.0);
    double total = 0;
    for (float e : errors) binSums[binOf(e)] += e, total += e;
    std::vector<double> result(fractions.size(), 0.0);
    size_t next = 0;
    double running = 0;
    for (int b = 0; b < kBins && next < fractions.size(); ++b) {
        if (!(running + binSums[b] > fractions[next] * total)) {
            running += binSums[b];
            continue;
        }
        std::vector<float> bin;
        for (float e : errors)
            if (binOf(e) == b) bin.push_back(e);
        std::sort(bin.begin(), bin.end());
        for (float e : bin) {
            running += e;
            while (next < fractions.size() && running > fractions[next] * total) result[next++] = e;
        }
    }
    return result;
}

}  // namespace

float pixelsPerDegree(float distanceMeters, float displayWidthMeters, float displayWidthPixels) {
    return distanceMeters * (displayWidthPixels / displayWidthMeters) * (kPi / 180.0f);
}

float defaultPixelsPerDegree() {
    return pixelsPerDegree(0.7f, 0.7f, 3840.0f);
}

CsfFilters makeCsfFilters(float ppd) {
    // Radius: three standard deviations of the widest Gaussian; b = 2π²σ².
    const float widestB = std::max({kAchromaticB, kRedGreenB, kBlueYellowB1, kBlueYellowB2});
    CsfFilters f;
    f.radius = int(std::ceil(3.0f * std::sqrt(widestB / (2.0f * kPi * kPi)) * ppd));
    const int width = 2 * f.radius + 1;
    f.achromatic.resize(width), f.redGreen.resize(width);
    f.blueYellow1.resize(width), f.blueYellow2.resize(width);
    float sumY = 0, sumCx = 0, sumCz1 = 0, sumCz2 = 0;
    for (int i = 0; i < width; ++i) {
        const float degrees = float(i - f.radius) * (1.0f / ppd);
        const float x2 = degrees * degrees;
        sumY += f.achromatic[i] = csfGaussian(x2, 1.0f, kAchromaticB);
        sumCx += f.redGreen[i] = csfGaussian(x2, 1.0f, kRedGreenB);
        sumCz1 += f.blueYellow1[i] = csfGaussianFactor(x2, kBlueYellowA1, kBlueYellowB1);
        sumCz2 += f.blueYellow2[i] = csfGaussianFactor(x2, kBlueYellowA2, kBlueYellowB2);
    }
    // The 2-D blue–yellow kernel g1⊗g1 + g2⊗g2 sums to S1² + S2².
    const float czScale = 1.0f / std::sqrt(sumCz1 * sumCz1 + sumCz2 * sumCz2);
    for (int i = 0; i < width; ++i) {
        f.achromatic[i] *= 1.0f / sumY;
        f.redGreen[i] *= 1.0f / sumCx;
        f.blueYellow1[i] *= czScale;
        f.blueYellow2[i] *= czScale;
    }
    return f;
}

FeatureFilters makeFeatureFilters(float ppd) {
    const float sigma = 0.5f * kFeatureWidthDegrees * ppd;
    FeatureFilters f;
    f.radius = int(std::ceil(3.0f * sigma));
    const int width = 2 * f.radius + 1;
    f.gaussian.resize(width), f.firstDerivative.resize(width), f.secondDerivative.resize(width);
    float sumG = 0, sumD1Pos = 0, sumD1Neg = 0, sumD2Pos = 0, sumD2Neg = 0;
    for (int i = 0; i < width; ++i) {
        const float x = float(i - f.radius);
        const float g = std::exp(-(x * x) / (2.0f * sigma * sigma));
        const float d1 = -x * g;                                // ∝ dG/dx
        const float d2 = (x * x / (sigma * sigma) - 1.0f) * g;  // ∝ d²G/dx²
        f.gaussian[i] = g, f.firstDerivative[i] = d1, f.secondDerivative[i] = d2;
        sumG += g;
        (d1 > 0 ? sumD1Pos : sumD1Neg) += std::fabs(d1);
        (d2 > 0 ? sumD2Pos : sumD2Neg) += std::fabs(d2);
    }
    for (int i = 0; i < width; ++i) {
        f.gaussian[i] /= sumG;
        float& d1 = f.firstDerivative[i];
        d1 /= d1 > 0 ? sumD1Pos : sumD1Neg;
        float& d2 = f.secondDerivative[i];
        d2 /= d2 > 0 ? sumD2Pos : sumD2Neg;
    }
    return f;
}

FeatureMaps detectFeatures(const std::vector<float>& achromatic, int width, int height, float ppd) {
    if (achromatic.size() != size_t(width) * size_t(height))
        throw std::invalid_argument("detectFeatures: image size does not match its dimensions");
    Plane in(width, height);
    in.values = achromatic;
    const FeatureFilters filters = makeFeatureFilters(ppd);
    const FeatureHalf half = filterFeaturesHorizontally(in, filters);
    FeatureMaps maps{std::vector<float>(in.values.size()), std::vector<float>(in.values.size())};
    forEachRow(height, [&](int y) {
        const FeatureRow row = featureMagnitudes(half, filters, y);
        std::copy(row.edge.begin(), row.edge.end(), maps.edge.begin() + size_t(y) * width);
        std::copy(row.point.begin(), row.point.end(), maps.point.begin() + size_t(y) * width);
    });
    return maps;
}

float maxColorDistance() {
    const Color green = huntAdjust(linearRgbToLab({0.0f, 1.0f, 0.0f}));
    const Color blue = huntAdjust(linearRgbToLab({0.0f, 0.0f, 1.0f}));
    return std::pow(hyab(green, blue), kColorExponent);
}

float remapColorDifference(float poweredDistance, float cmax) {
    const float knee = kColorKnee * cmax;
    if (poweredDistance < knee) return poweredDistance * (kColorKneeTarget / knee);
    return kColorKneeTarget +
           ((poweredDistance - knee) / (cmax - knee)) * (1.0f - kColorKneeTarget);
}

float acesToneMap(float v) {
    const ToneCurve& t = kAces;
    return ((v * v) * t.a + v * t.b + t.c) / ((v * v) * t.d + v * t.e + t.f);
}

std::vector<float> ldrFlipErrorMap(const Image& reference, const Image& test, float ppd) {
    requireSameSize(reference, test);
    return ldrFlipErrorMap(prepareLdrSide(reference, ppd), prepareLdrSide(test, ppd));
}

ExposureRange automaticExposureRange(const Image& reference) {
    // x where the tone curve reaches 0.85: (a − t·d)x² + (b − t·e)x + (c − t·f) = 0.
    const float t = 0.85f;
    const float qa = kAces.a - t * kAces.d, qb = kAces.b - t * kAces.e, qc = kAces.c - t * kAces.f;
    const float half = -0.5f * (qb / qa);
    const float knee = half + std::sqrt(half * half - qc / qa);

    std::vector<float> luminances(reference.pixelCount());
    float largest = 0, smallestPositive = INFINITY;
    for (size_t i = 0; i < luminances.size(); ++i) {
        const float* p = &reference.rgb[3 * i];
        const float l = 0.2126f * p[0] + 0.7152f * p[1] + 0.0722f * p[2];
        luminances[i] = l;
        largest = std::max(largest, l);
        if (l > 0) smallestPositive = std::min(smallestPositive, l);
    }
    if (!(largest > 0)) return {0.0f, 0.0f, 2};  // black reference: nothing to expose
    auto middle = luminances.begin() + luminances.size() / 2;
    std::nth_element(luminances.begin(), middle, luminances.end());
    // A black median would give an infinite stop exposure; fall back to the
    // darkest non-black pixel.
    const float median = *middle > 0 ? *middle : smallestPositive;
    ExposureRange range{std::log2(knee / largest), std::log2(knee / median), 0};
    range.count = int(std::max(2.0f, std::ceil(range.stop - range.start)));
    return range;
}

std::vector<float> hdrFlipErrorMap(const Image& reference, const Image& test, float ppd,
                                   const ExposureRange& exposures) {
    requireSameSize(reference, test);
    Options options;
    options.mode = Mode::Hdr;
    options.ppd = ppd;
    options.startExposure = exposures.start;
    options.stopExposure = exposures.stop;
    options.exposureCount = exposures.count;
    return PreparedReference(reference, options).errorMap(test);
}

double weightedPercentile(std::vector<float> errors, double p) {
    return weightedPercentiles(errors, {p})[0];
}

Statistics poolErrors(const std::vector<float>& errors) {
    Statistics s;
    if (errors.empty()) return s;
    double total = 0;
    float lo = errors[0], hi = errors[0];
    for (float e : errors) total += e, lo = std::min(lo, e), hi = std::max(hi, e);
    s.mean = total / double(errors.size());
    s.min = lo, s.max = hi;
    const std::vector<double> q = weightedPercentiles(errors, {0.25, 0.5, 0.75});
    s.q1 = q[0], s.weightedMedian = q[1], s.q3 = q[2];
    return s;
}

namespace {

// Exposure i of the range: start + i·(stop − start)/(count − 1) ([EG21]).
float exposureAt(const ExposureRange& range, int i) {
    const float step = (range.stop - range.start) / float(range.count - 1);
    return range.start + float(i) * step;
}

}  // namespace

PreparedReference::PreparedReference(const Image& reference, const Options& options)
    : width_(reference.width), height_(reference.height), mode_(options.mode), ppd_(options.ppd) {
    if (reference.pixelCount() == 0) throw InputError("images are empty");
    if (!(options.ppd > 0)) throw InputError("pixels per degree must be positive");
    if (options.mode == Mode::Ldr) {
        sides_.push_back(prepareLdrSide(clampedToUnit(reference), ppd_));
        return;
    }
    exposures_ = resolveExposures(reference, options);
    for (int i = 0; i < exposures_.count; ++i)
        sides_.push_back(
            prepareLdrSide(exposeAndToneMap(reference, exposureAt(exposures_, i)), ppd_));
}

PreparedReference::~PreparedReference() = default;

std::vector<float> PreparedReference::errorMap(const Image& test) const {
    requireSize(width_, height_, test);
    if (mode_ == Mode::Ldr)
        return ldrFlipErrorMap(sides_[0], prepareLdrSide(clampedToUnit(test), ppd_));
    std::vector<float> maximum(test.pixelCount(), 0.0f);
    for (int i = 0; i < exposures_.count; ++i) {
        const std::vector<float> error = ldrFlipErrorMap(
            sides_[size_t(i)],
            prepareLdrSide(exposeAndToneMap(test, exposureAt(exposures_, i)), ppd_));
        for (size_t p = 0; p < maximum.size(); ++p) maximum[p] = std::max(maximum[p], error[p]);
    }
    return maximum;
}

Result PreparedReference::evaluate(const Image& test) const {
    Result r;
    r.width = width_, r.height = height_;
    r.mode = mode_, r.ppd = ppd_;
    if (mode_ == Mode::Hdr) r.exposures = exposures_;
    r.errorMap = errorMap(test);
    r.stats = poolErrors(r.errorMap);
    return r;
}

Result evaluate(const Image& reference, const Image& test, const Options& options) {
    requireSameSize(reference, test);
    return PreparedReference(reference, options).evaluate(test);
}

}  // namespace pathlab::flip
