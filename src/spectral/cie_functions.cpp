#include "spectral/cie_functions.h"

#include <algorithm>
#include <cmath>

#include "spectral/cie_data.h"

namespace pathlab::spectral {
namespace {

double interpolateCmf(const double* table, double lambdaNm) {
    const double x = (lambdaNm - cie_data::kCmfFirst) / cie_data::kCmfStep;
    if (!(x >= 0) || x > cie_data::kCmfCount - 1) return 0;
    const int i = std::min(int(x), cie_data::kCmfCount - 2);
    const double t = x - i;
    return (1 - t) * table[i] + t * table[i + 1];
}

// Composite rule over [360, 830]: `panels` panels, each with the interior
// nodes and weights of `rule` (fractions of the panel and of its width).
template <size_t N>
Quadrature compositeRule(int panels, const double (&fraction)[N], const double (&weight)[N]) {
    Quadrature q;
    const double width = (830.0 - 360.0) / panels;
    for (int p = 0; p < panels; ++p)
        for (size_t k = 0; k < N; ++k) {
            if (p > 0 && k == 0) {  // shared with the previous panel's last node
                q.weight.back() += weight[0] * width;
                continue;
            }
            q.lambda.push_back(360.0 + (p + fraction[k]) * width);
            q.weight.push_back(weight[k] * width);
        }
    return q;
}

}  // namespace

double cieX(double lambdaNm) {
    return interpolateCmf(cie_data::kCmfX, lambdaNm);
}
double cieY(double lambdaNm) {
    return interpolateCmf(cie_data::kCmfY, lambdaNm);
}
double cieZ(double lambdaNm) {
    return interpolateCmf(cie_data::kCmfZ, lambdaNm);
}

Vec3f cieXyzMatching(float lambdaNm) {
    // interpolateCmf's arithmetic for the three tables, the interval and its
    // fraction found once (the film converts every path's four wavelengths).
    const double x = (lambdaNm - cie_data::kCmfFirst) / cie_data::kCmfStep;
    if (!(x >= 0) || x > cie_data::kCmfCount - 1) return {};
    const int i = std::min(int(x), cie_data::kCmfCount - 2);
    const double t = x - i;
    auto at = [&](const double* table) { return float((1 - t) * table[i] + t * table[i + 1]); };
    return {at(cie_data::kCmfX), at(cie_data::kCmfY), at(cie_data::kCmfZ)};
}

double cieYIntegral() {
    static const double integral = [] {
        double sum = 0;
        for (int i = 0; i + 1 < cie_data::kCmfCount; ++i)
            sum += 0.5 * (cie_data::kCmfY[i] + cie_data::kCmfY[i + 1]) * cie_data::kCmfStep;
        return sum;
    }();
    return integral;
}

const Quadrature& fineQuadrature() {
    static const Quadrature q = compositeRule(470, {0.0, 0.5, 1.0}, {1 / 6.0, 4 / 6.0, 1 / 6.0});
    return q;
}

const Quadrature& coarseQuadrature() {
    static const Quadrature q =
        compositeRule(94, {0.0, 1 / 3.0, 2 / 3.0, 1.0}, {1 / 8.0, 3 / 8.0, 3 / 8.0, 1 / 8.0});
    return q;
}

}  // namespace pathlab::spectral
