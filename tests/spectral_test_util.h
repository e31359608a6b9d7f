// Helpers for the spectral-mode tests: a pbrt-v4 material, a sphere in a
// white furnace, and each channel's image mean with its standard error, to
// compare renders within their noise.
#pragma once

#include <cmath>

#include "render/renderer.h"
#include "scene/pbrt/importer.h"

namespace pathlab::test {

// A sphere of material m in a furnace (a sky of radiance 1), filling about
// half of the image.
inline SceneDescription sphereInFurnace(const Material& m) {
    SceneDescription s;
    s.materials.push_back(m);
    s.spheres.push_back({Vec3f(0, 0, 0), 0.8f, 0});
    s.environment = Vec3f(1.0f);
    s.camera = Camera{{0, 0, 4}, {0, 0, 0}, {0, 1, 0}, 30};
    s.resolution = {12, 12};
    return s;
}

// The material a pbrt-v4 Material directive makes (on one triangle).
inline Material pbrtMaterial(const std::string& material) {
    const pbrt::ImportResult r =
        pbrt::importPbrtText("WorldBegin\n" + material +
                                 "\nShape \"trianglemesh\" \"point3 P\" [0 0 0  1 0 0  0 1 0] "
                                 "\"integer indices\" [0 1 2]\n",
                             "test.pbrt", ".", {});
    return r.scene.materials[size_t(r.scene.meshes[0].material)];
}

// Each channel's image mean and the standard error of that mean (the pixels'
// estimates are independent).
struct ChannelMeans {
    double mean[3] = {}, standardError[3] = {};
};
inline ChannelMeans channelMeans(const RenderOutput& out) {
    ChannelMeans m;
    const size_t pixels = size_t(out.image.width) * size_t(out.image.height);
    for (int c = 0; c < 3; ++c) {
        double sum = 0, var = 0;
        for (size_t i = 0; i < pixels; ++i)
            sum += out.image.rgb[3 * i + size_t(c)],
                var += out.varianceOfMean.rgb[3 * i + size_t(c)];
        m.mean[c] = sum / double(pixels);
        m.standardError[c] = std::sqrt(var) / double(pixels);
    }
    return m;
}

}  // namespace pathlab::test
