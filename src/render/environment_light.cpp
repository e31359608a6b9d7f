#include "render/environment_light.h"

#include <algorithm>
#include <cmath>

#include "core/equal_area.h"
#include "render/sampling_routines.h"

namespace pathlab {

namespace {

std::vector<float> texelLuminances(const EnvironmentImage& image) {
    std::vector<float> lum(image.texels.size());
    for (size_t i = 0; i < lum.size(); ++i) lum[i] = std::max(0.0f, luminance(image.texels[i]));
    return lum;
}

Vec3f apply(const Vec3f (&m)[3], Vec3f v) {
    return m[0] * v.x + m[1] * v.y + m[2] * v.z;
}

}  // namespace

EnvironmentLight::EnvironmentLight(EnvironmentImage image)
    : image_(std::move(image)),
      distribution_(texelLuminances(image_), image_.width, image_.height, {0, 0}, {1, 1}) {
    double sum = 0;
    for (const Vec3f& t : image_.texels) sum += double(luminance(t));
    meanIrradiance_ = kPi * sum / double(std::max<size_t>(1, image_.texels.size()));
}

Vec2f EnvironmentLight::toSquare(Vec3f w) const {
    return equalAreaSphereToSquare(normalize(apply(image_.toLight, w)));
}

// pbrt-v4's ImageLe: the nearest texel.
Vec3f EnvironmentLight::texel(Vec2f uv) const {
    const int x = std::clamp(int(uv.x * float(image_.width)), 0, image_.width - 1);
    const int y = std::clamp(int(uv.y * float(image_.height)), 0, image_.height - 1);
    return image_.texels[size_t(y) * size_t(image_.width) + size_t(x)];
}

Vec3f EnvironmentLight::radiance(Vec3f w) const {
    return texel(toSquare(w));
}

std::optional<EnvironmentLight::Sample> EnvironmentLight::sample(Vec2f u) const {
    if (image_.uniformSampling) {
        const Vec3f w = sampleUniformSphere(u);
        return Sample{w, radiance(w), uniformSpherePdf()};
    }
    const PiecewiseConstant2D::Sample m = distribution_.sample(u);
    const Vec2f uv = m.p;
    const float mapPdf = m.pdf;
    if (!(mapPdf > 0)) return std::nullopt;
    const Vec3f w = normalize(apply(image_.toWorld, equalAreaSquareToSphere(uv)));
    // The texel the direction was drawn in, as pbrt-v4's SampleLi looks it up.
    return Sample{w, texel(uv), mapPdf / float(4 * kPi)};
}

float EnvironmentLight::pdf(Vec3f w) const {
    if (image_.uniformSampling) return uniformSpherePdf();
    return distribution_.pdf(toSquare(w)) / float(4 * kPi);
}

}  // namespace pathlab
