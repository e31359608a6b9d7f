#include "spectral/sigmoid_fitter.h"

#include <cmath>

#include "spectral/cie_functions.h"

namespace pathlab::spectral {
namespace {

constexpr double kRange = double(kLambdaMax) - double(kLambdaMin);
constexpr int kMaxIterations = 15;
constexpr double kConverged = 1e-6, kSmallestStep = 1e-3;
// Coefficients beyond this make the sigmoid a step the quadrature cannot
// resolve; the paper's implementation bounds them the same way.
constexpr double kMaxCoefficient = 200;

// L*a*b* of xyz and its derivatives with respect to X, Y, Z.
Vec3d labWithJacobian(const Vec3d& xyz, const Vec3d& white, Mat3d& jacobian) {
    constexpr double delta = 6.0 / 29.0, delta3 = delta * delta * delta;
    double f[3], df[3];
    for (int i = 0; i < 3; ++i) {
        const double t = xyz[i] / white[i];
        if (t > delta3) {
            f[i] = std::cbrt(t);
            df[i] = 1 / (3 * f[i] * f[i] * white[i]);
        } else {
            f[i] = t / (3 * delta * delta) + 4.0 / 29.0;
            df[i] = 1 / (3 * delta * delta * white[i]);
        }
    }
    jacobian = {
        {{0, 116 * df[1], 0}, {500 * df[0], -500 * df[1], 0}, {0, 200 * df[1], -200 * df[2]}}};
    return {116 * f[1] - 16, 500 * (f[0] - f[1]), 200 * (f[1] - f[2])};
}

// Solves m·x = b by Cramer's rule; false when m is singular.
bool solve3(const Mat3d& m, const Vec3d& b, Vec3d& x) {
    const double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                       m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                       m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    if (!(std::abs(det) > 1e-30)) return false;
    for (int c = 0; c < 3; ++c) {
        Mat3d mc = m;
        for (int r = 0; r < 3; ++r) mc[r][c] = b[r];
        x[c] = (mc[0][0] * (mc[1][1] * mc[2][2] - mc[1][2] * mc[2][1]) -
                mc[0][1] * (mc[1][0] * mc[2][2] - mc[1][2] * mc[2][0]) +
                mc[0][2] * (mc[1][0] * mc[2][1] - mc[1][1] * mc[2][0])) /
               det;
    }
    return true;
}

}  // namespace

SigmoidFitter::SigmoidFitter(const RgbColourSpace& space)
    : rgbToXyz_(space.rgbToXyz), whiteXyz_(space.whiteXyz) {
    const Quadrature& q = coarseQuadrature();
    for (size_t k = 0; k < q.lambda.size(); ++k) {
        const double l = q.lambda[k];
        const double w = q.weight[k] * (*space.illuminant)(l) / cieYIntegral();
        x_.push_back((l - kLambdaMin) / kRange);
        basis_.push_back(multiply(space.xyzToRgb, Vec3d{w * cieX(l), w * cieY(l), w * cieZ(l)}));
    }
}

Vec3d SigmoidFitter::rgbOf(const SigmoidCoefficients& c, Mat3d* jacobian) const {
    Vec3d rgb{};
    if (jacobian) *jacobian = {};
    for (size_t k = 0; k < x_.size(); ++k) {
        const double x = x_[k], p = (c[0] * x + c[1]) * x + c[2];
        const double root = std::sqrt(1 + p * p);
        const double s = 0.5 + p / (2 * root);
        for (int i = 0; i < 3; ++i) rgb[i] += s * basis_[k][i];
        if (!jacobian) continue;
        // dS/dp = 1 / (2 (1 + p²)^{3/2}); dp/dc = (x², x, 1).
        const double ds = 1 / (2 * root * root * root), dp[3] = {x * x, x, 1};
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) (*jacobian)[i][j] += ds * dp[j] * basis_[k][i];
    }
    return rgb;
}

double SigmoidFitter::fit(const Vec3d& rgb, SigmoidCoefficients& c) const {
    Mat3d unused;
    const Vec3d targetLab = labWithJacobian(multiply(rgbToXyz_, rgb), whiteXyz_, unused);
    // The L*a*b* residual at x and its Jacobian with respect to x.
    auto residual = [&](const SigmoidCoefficients& x, Mat3d& jacobian) {
        Mat3d dRgb, dLab;
        const Vec3d lab = labWithJacobian(multiply(rgbToXyz_, rgbOf(x, &dRgb)), whiteXyz_, dLab);
        jacobian = multiply(multiply(dLab, rgbToXyz_), dRgb);
        return Vec3d{lab[0] - targetLab[0], lab[1] - targetLab[1], lab[2] - targetLab[2]};
    };
    auto norm = [](const Vec3d& r) { return std::sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]); };
    Mat3d jacobian;
    Vec3d r = residual(c, jacobian);
    double error = norm(r);
    for (int iteration = 0; iteration < kMaxIterations && error >= kConverged; ++iteration) {
        Vec3d step;
        if (!solve3(jacobian, r, step)) break;
        // Backtracking: far from the solution the full Gauss–Newton step can
        // overshoot into the sigmoid's flat tails, where it never returns;
        // halve it until the error falls. No fall at all: stalled (a colour
        // the bounded sigmoids cannot reach).
        bool improved = false;
        for (double t = 1; t > kSmallestStep && !improved; t *= 0.5) {
            SigmoidCoefficients trial;
            double largest = 0;
            for (int j = 0; j < 3; ++j) {
                trial[j] = c[j] - t * step[j];
                largest = std::max(largest, std::abs(trial[j]));
            }
            if (largest > kMaxCoefficient)
                for (double& x : trial) x *= kMaxCoefficient / largest;
            Mat3d trialJacobian;
            const Vec3d trialR = residual(trial, trialJacobian);
            if (norm(trialR) < error) {
                c = trial, r = trialR, jacobian = trialJacobian, error = norm(trialR);
                improved = true;
            }
        }
        if (!improved) break;
    }
    return error;
}

SigmoidPolynomial toNanometres(const SigmoidCoefficients& c) {
    // c₀x² + c₁x + c₂ with x = (λ − a)·s, expanded in powers of λ.
    const double a = kLambdaMin, s = 1 / kRange;
    return {float(c[0] * s * s), float(c[1] * s - 2 * c[0] * s * s * a),
            float(c[0] * s * s * a * a - c[1] * s * a + c[2])};
}

}  // namespace pathlab::spectral
