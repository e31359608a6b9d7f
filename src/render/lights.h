// The scene's lights for next-event estimation: triangle and parallelogram area
// lights (a mesh with emission; two triangles forming a parallelogram are merged
// into one quad light so a 2D sample maps onto it without a seam) and a
// constant environment. One light is chosen per estimate: area lights in
// proportion to their emitted power (pbrt-v4's PowerLightSampler). An
// environment has no finite power (pbrt-v4 substitutes π·r²·4π·L for a scene
// of radius r, which lets a wide floor hand it nearly every sample); here it
// gets the share of the irradiance it delivers at the scene's focus point (the
// camera's target) next to the area lights' unoccluded irradiance there.
#pragma once

#include <optional>
#include <vector>

#include "core/math.h"
#include "scene/scene.h"

namespace pathlab {

struct AreaLight {
    Vec3f p0, e1, e2;  // triangle p0, p0+e1, p0+e2 — or parallelogram p0 + u·e1 + v·e2
    Vec3f n;           // unit normal, e1 × e2 direction: the emitting side
    float area = 0;
    Vec3f radiance;
    bool twoSided = false;
    bool parallelogram = false;
    float power() const;
    // A uniformly distributed point on the light for u in [0,1)².
    Vec3f samplePoint(Vec2f u) const;
    // Emitted radiance towards direction w (pointing away from the light).
    Vec3f emitted(Vec3f w) const;
};

struct LightSample {
    Vec3f wi;        // unit direction from the shading point towards the light
    float distance;  // to the light point; infinity for the environment
    Vec3f radiance;  // arriving along −wi
    float pdf;       // solid-angle density, including the light-choice probability
};

class LightSet {
public:
    // `focus` is where the environment's share of light choices is judged.
    LightSet(const SceneDescription& scene, Vec3f focus);

    bool empty() const { return cdf_.empty(); }
    size_t areaLightCount() const { return lights_.size(); }
    const AreaLight& areaLight(int i) const { return lights_[size_t(i)]; }
    // The light a triangle belongs to, or −1.
    int lightOfTriangle(unsigned mesh, unsigned triangle) const;

    std::optional<LightSample> sample(Vec3f ref, float uChoice, Vec2f u) const;
    // Solid-angle pdf (with choice probability) of reaching point p with normal
    // on light `light` from ref — for MIS when a BSDF sample hits the light.
    float pdfAreaLight(int light, Vec3f ref, Vec3f p) const;
    float pdfEnvironment() const;
    Vec3f environment() const { return environment_; }

private:
    float pmf(size_t i) const;
    void buildDistribution(Vec3f focus);
    std::vector<AreaLight> lights_;
    std::vector<std::vector<int>> triangleLight_;  // per mesh, per triangle
    Vec3f environment_;
    std::vector<float> cdf_;  // over area lights, then the environment if present
};

}  // namespace pathlab
