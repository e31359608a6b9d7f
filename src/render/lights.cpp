#include "render/lights.h"

#include <algorithm>
#include <limits>

#include "render/sampling_routines.h"

namespace pathlab {
namespace {

// Two consecutive triangles (a,b,c), (a,c,d) form a parallelogram when
// a + c = b + d; tolerance relative to the edge length.
bool formsParallelogram(Vec3f a, Vec3f b, Vec3f c, Vec3f d) {
    const Vec3f diff = (a + c) - (b + d);
    const float scale = std::max(length(b - a), length(d - a));
    return length(diff) <= 1e-5f * scale;
}

AreaLight makeLight(Vec3f p0, Vec3f e1, Vec3f e2, bool parallelogram, const Mesh& mesh) {
    AreaLight l;
    l.p0 = p0, l.e1 = e1, l.e2 = e2;
    const Vec3f c = cross(e1, e2);
    const float len = length(c);
    l.n = c / len;
    l.area = parallelogram ? len : len / 2;
    l.radiance = mesh.emission;
    l.twoSided = mesh.twoSided;
    l.parallelogram = parallelogram;
    return l;
}

}  // namespace

float AreaLight::power() const { return luminance(radiance) * area * kPi * (twoSided ? 2 : 1); }

Vec3f AreaLight::samplePoint(Vec2f u) const {
    if (parallelogram) return p0 + e1 * u.x + e2 * u.y;
    const Vec2f b = sampleUniformTriangle(u);
    // Barycentrics (b0, b1, b2) of (p0, p0+e1, p0+e2).
    return p0 + e1 * b.y + e2 * (1 - b.x - b.y);
}

Vec3f AreaLight::emitted(Vec3f w) const {
    return (twoSided || dot(n, w) > 0) ? radiance : Vec3f(0.0f);
}

LightSet::LightSet(const SceneDescription& scene, Vec3f focus)
    : environment_(scene.environment) {
    triangleLight_.resize(scene.meshes.size());
    for (size_t m = 0; m < scene.meshes.size(); ++m) {
        const Mesh& mesh = scene.meshes[m];
        triangleLight_[m].assign(mesh.triangleCount(), -1);
        if (isBlack(mesh.emission)) continue;
        auto P = [&](size_t t, int k) { return mesh.positions[mesh.indices[3 * t + size_t(k)]]; };
        for (size_t t = 0; t < mesh.triangleCount(); ++t) {
            const Vec3f a = P(t, 0), b = P(t, 1), c = P(t, 2);
            const bool pair = t + 1 < mesh.triangleCount() &&
                              mesh.indices[3 * t] == mesh.indices[3 * (t + 1)] &&
                              mesh.indices[3 * t + 2] == mesh.indices[3 * (t + 1) + 1] &&
                              formsParallelogram(a, b, c, P(t + 1, 2));
            triangleLight_[m][t] = int(lights_.size());
            if (pair) {
                lights_.push_back(makeLight(a, b - a, P(t + 1, 2) - a, true, mesh));
                triangleLight_[m][++t] = int(lights_.size()) - 1;
            } else {
                lights_.push_back(makeLight(a, b - a, c - a, false, mesh));
            }
        }
    }
    buildDistribution(focus);
}

// Irradiance at `x` from light `l` if nothing blocked it, treating the light as
// a point at its centroid (receiver orientation unknown: no receiver cosine).
static double irradianceAt(const AreaLight& l, Vec3f x) {
    const Vec3f centroid = l.p0 + (l.e1 + l.e2) * (l.parallelogram ? 0.5f : 1.0f / 3.0f);
    const Vec3f d = x - centroid;
    const float dist2 = std::max(dot(d, d), 1e-12f);
    const float cosLight = l.twoSided ? std::abs(dot(l.n, d)) : std::max(0.0f, dot(l.n, d));
    return double(luminance(l.radiance)) * l.area * cosLight / std::sqrt(dist2) / dist2;
}

void LightSet::buildDistribution(Vec3f focus) {
    std::vector<double> weight;
    double areaPower = 0, areaIrradiance = 0;
    for (const AreaLight& l : lights_) {
        weight.push_back(l.power());
        areaPower += l.power();
        areaIrradiance += irradianceAt(l, focus);
    }
    if (!isBlack(environment_)) {
        // A uniform environment delivers π·L onto a surface facing any way.
        const double envIrradiance = kPi * double(luminance(environment_));
        const double share = areaPower > 0 && areaIrradiance > 0
                                 ? envIrradiance / (envIrradiance + areaIrradiance)
                                 : 1.0;
        weight.push_back(share >= 1 ? 1.0 : areaPower * share / (1 - share));
    }
    double total = 0;
    for (double w : weight) total += w;
    if (total <= 0) return;
    double running = 0;
    for (double w : weight) cdf_.push_back(float((running += w) / total));
    cdf_.back() = 1.0f;
}

int LightSet::lightOfTriangle(unsigned mesh, unsigned triangle) const {
    return triangleLight_[mesh][triangle];
}

float LightSet::pmf(size_t i) const { return cdf_[i] - (i == 0 ? 0.0f : cdf_[i - 1]); }

std::optional<LightSample> LightSet::sample(Vec3f ref, float uChoice, Vec2f u) const {
    if (cdf_.empty()) return std::nullopt;
    const size_t i = std::min(size_t(std::upper_bound(cdf_.begin(), cdf_.end(), uChoice) -
                                     cdf_.begin()),
                              cdf_.size() - 1);
    const float choicePmf = pmf(i);
    if (choicePmf <= 0) return std::nullopt;
    if (i == lights_.size()) {  // the environment: uniform directions
        return LightSample{sampleUniformSphere(u), std::numeric_limits<float>::infinity(),
                           environment_, choicePmf * uniformSpherePdf()};
    }
    const AreaLight& light = lights_[i];
    const Vec3f p = light.samplePoint(u);
    const Vec3f d = p - ref;
    const float dist2 = dot(d, d);
    if (dist2 <= 0) return std::nullopt;
    const float dist = std::sqrt(dist2);
    const Vec3f wi = d / dist;
    const float cosLight = std::abs(dot(light.n, wi));
    const Vec3f Le = light.emitted(-wi);
    if (cosLight <= 0 || isBlack(Le)) return std::nullopt;
    // Area density 1/A converted to solid angle: dist² / (A cosθ_light).
    return LightSample{wi, dist, Le, choicePmf * dist2 / (light.area * cosLight)};
}

float LightSet::pdfAreaLight(int light, Vec3f ref, Vec3f p) const {
    const AreaLight& l = lights_[size_t(light)];
    const Vec3f d = p - ref;
    const float dist2 = dot(d, d);
    const float cosLight = std::abs(dot(l.n, d)) / std::sqrt(dist2);
    if (cosLight <= 0) return 0;
    return pmf(size_t(light)) * dist2 / (l.area * cosLight);
}

float LightSet::pdfEnvironment() const {
    if (cdf_.empty() || isBlack(environment_)) return 0;
    return pmf(lights_.size()) * uniformSpherePdf();
}

}  // namespace pathlab
