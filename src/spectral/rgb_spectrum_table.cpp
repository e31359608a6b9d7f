#include "spectral/rgb_spectrum_table.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <mutex>

#include "core/paths.h"
#include "spectral/sigmoid_fitter.h"

namespace pathlab::spectral {
namespace {

double smoothstep(double x) {
    return x * x * (3 - 2 * x);
}

// One (l, x, y) column: continuation along z from k = n/5 up, then down.
void solveColumn(const SigmoidFitter& fitter, RgbToSpectrumTable& t, int l, int xi, int yi,
                 float& worst) {
    const int n = t.resolution, start = n / 5;
    const double x = double(xi) / (n - 1), y = double(yi) / (n - 1);
    auto solve = [&](int k, SigmoidCoefficients& c) {
        const double z = t.zNodes[size_t(k)];
        Vec3d rgb{};
        rgb[size_t(l)] = z;
        rgb[size_t((l + 1) % 3)] = x * z;
        rgb[size_t((l + 2) % 3)] = y * z;
        worst = std::max(worst, float(fitter.fit(rgb, c)));
        const SigmoidPolynomial p = toNanometres(c);
        float* out = &t.coefficients[t.index(l, k, yi, xi)];
        out[0] = p.c0, out[1] = p.c1, out[2] = p.c2;
    };
    SigmoidCoefficients c{};
    for (int k = start; k < n; ++k) solve(k, c);
    c = {};
    for (int k = start; k >= 0; --k) solve(k, c);
}

}  // namespace

RgbToSpectrumTable makeRgbToSpectrumTable(int resolution) {
    RgbToSpectrumTable t;
    t.resolution = std::max(resolution, 3);
    const int n = t.resolution;
    for (int k = 0; k < n; ++k)
        t.zNodes.push_back(float(smoothstep(smoothstep(k / double(n - 1)))));
    t.coefficients.assign(size_t(3) * n * n * n * 3, 0.f);
    const SigmoidFitter fitter(linearSrgb());
    std::vector<float> worstPerColumn(size_t(3) * n * n, 0.f);
    tbb::parallel_for(0, 3 * n * n, [&](int column) {
        solveColumn(fitter, t, column / (n * n), column % n, (column / n) % n,
                    worstPerColumn[size_t(column)]);
    });
    t.worstDeltaE = *std::max_element(worstPerColumn.begin(), worstPerColumn.end());
    return t;
}

SigmoidPolynomial RgbToSpectrumTable::lookup(Vec3f rgb) const {
    // Greys are constant spectra, exactly: S(c₂) = v for c₂ = (v − ½)/√(v(1 − v)).
    if (rgb.x == rgb.y && rgb.y == rgb.z) {
        const float v = rgb.x;
        if (v <= 0) return {0, 0, -std::numeric_limits<float>::infinity()};
        if (v >= 1) return {0, 0, std::numeric_limits<float>::infinity()};
        return {0, 0, (v - 0.5f) / std::sqrt(v * (1 - v))};
    }
    const int l = rgb.x >= rgb.y ? (rgb.x >= rgb.z ? 0 : 2) : (rgb.y >= rgb.z ? 1 : 2);
    const float z = rgb[l], n1 = float(resolution - 1);
    const float x = rgb[(l + 1) % 3] / z * n1, y = rgb[(l + 2) % 3] / z * n1;
    const int xi = std::min(int(x), resolution - 2), yi = std::min(int(y), resolution - 2);
    const int zi =
        int(std::upper_bound(zNodes.begin() + 1, zNodes.end() - 1, z) - zNodes.begin()) - 1;
    const float dx = x - xi, dy = y - yi,
                dz = (z - zNodes[size_t(zi)]) / (zNodes[size_t(zi) + 1] - zNodes[size_t(zi)]);
    float c[3] = {0, 0, 0};
    for (int corner = 0; corner < 8; ++corner) {
        const int ox = corner & 1, oy = (corner >> 1) & 1, oz = corner >> 2;
        const float w = (ox ? dx : 1 - dx) * (oy ? dy : 1 - dy) * (oz ? dz : 1 - dz);
        const float* p = &coefficients[index(l, zi + oz, yi + oy, xi + ox)];
        for (int j = 0; j < 3; ++j) c[j] += w * p[j];
    }
    return {c[0], c[1], c[2]};
}

const RgbToSpectrumTable& defaultRgbToSpectrumTable() {
    static std::shared_ptr<const RgbToSpectrumTable> table;
    static std::once_flag once;
    std::call_once(once, [] {
        table = loadOrCreateRgbToSpectrumTable(
            cacheDirectory() /
                ("rgb-to-spectrum-srgb-" + std::to_string(kRgbToSpectrumResolution) + ".bin"),
            kRgbToSpectrumResolution);
    });
    return *table;
}

}  // namespace pathlab::spectral
