// The scene's lights for next-event estimation: triangle and parallelogram area
// lights (a mesh with emission; two triangles forming a parallelogram are merged
// into one quad light so a 2D sample maps onto it without a seam) and a
// constant environment. One light is chosen per estimate: area lights in
// proportion to their emitted power (pbrt-v4's PowerLightSampler). An
// environment has no finite power (pbrt-v4 substitutes π·r²·4π·L for a scene
// of radius r, which lets a wide floor hand it nearly every sample); here it
// gets the share of the irradiance it delivers at the scene's focus point (the
// camera's target) next to the area lights' unoccluded irradiance there.
// Point, spot and distant lights (punctual_lights.h) join the choice: point
// and spot lights by their power, distant lights, which have no finite power
// either, by their irradiance at the focus point as the environment. An image
// environment map (environment_light.h) is one more such light, after the
// constant environment. That is the `power` light selection, the default; the
// choice can also be uniform or made by a light BVH (light_sampling/).
//
// An emitting sphere is one more area light, sampled as pbrt-v4 samples it:
// uniformly in the cone of directions it subtends at a receiver outside it,
// uniformly by area from inside (render/sphere_light.h) — unless
// LightSampling::UniformArea asks for area sampling everywhere, which is there
// to be compared.
//
// Triangles and parallelograms are sampled uniformly by area unless
// LightSampling::SolidAngle is asked for. Then a point on a rectangular light is sampled by the
// solid angle it subtends at the receiver (Ureña, Fajardo & King 2013), the 2D sample first warped
// by a bilinear fit of the receiver's cosine at the rectangle's corners (as pbrt-v4's
// BilinearPatch::Sample); other lights, and rectangles seen at a tiny solid
// angle or from (nearly) their own plane, are sampled uniformly by area. Which
// strategy is used depends only on the receiver's position, so the density
// reported for a sample and pdfAreaLight agree exactly. Area sampling is the
// default because on the Cornell box solid-angle sampling lowers the MSE of the
// best samplers by about 1.5% (docs/rendering.md) while a frame takes about
// 1.5 times as long: the better image per second comes from area sampling.
#pragma once

#include <optional>
#include <vector>

#include "core/math.h"
#include "render/environment_light.h"
#include "render/light_sampling/light_chooser.h"
#include "render/punctual_lights.h"
#include "render/sampling_routines.h"
#include "scene/scene.h"

namespace pathlab {

// Area: triangles and parallelograms by area, spheres by their cone (the
// default). SolidAngle: rectangles by solid angle too. UniformArea: every
// light by area, spheres too.
enum class LightSampling { Area, SolidAngle, UniformArea };

struct AreaLight {
    Vec3f p0, e1, e2;  // triangle p0, p0+e1, p0+e2 — or parallelogram p0 + u·e1 + v·e2
    Vec3f n;           // unit normal, e1 × e2 direction: the emitting side
    float area = 0;
    Vec3f radiance;
    bool twoSided = false;
    bool parallelogram = false;
    // A parallelogram with perpendicular edges: then xAxis = e1/|e1|, yAxis =
    // n × xAxis, and the rectangle is p0 + [0, width]·xAxis + [0, height]·yAxis.
    bool rectangle = false;
    bool solidAngleSampling = false;  // sample the rectangle (sphere) by solid angle
    // An emitting sphere (Sphere::emission): centre and radius; p0, e1, e2 and
    // n are unused, area is 4πr².
    bool sphere = false;
    Vec3f center;
    float radius = 0;
    Vec3f xAxis, yAxis;
    float width = 0, height = 0;
    float power() const;
    // A uniformly distributed point on the light for u in [0,1)².
    Vec3f samplePoint(Vec2f u) const {
        if (parallelogram) return p0 + e1 * u.x + e2 * u.y;
        const Vec2f b = sampleUniformTriangle(u);
        // Barycentrics (b0, b1, b2) of (p0, p0+e1, p0+e2).
        return p0 + e1 * b.y + e2 * (1 - b.x - b.y);
    }
    // A point on the light for next-event estimation at `ref`, whose shading
    // normal is `ns` (zero: unknown, no cosine warp), with its density per unit
    // solid angle at ref. Nothing when ref sees only the back of a one-sided
    // light or the point coincides with ref.
    struct DirectionSample {
        Vec3f p;
        float pdf;
    };
    std::optional<DirectionSample> sampleFrom(Vec3f ref, Vec3f ns, Vec2f u) const;
    // The solid-angle density with which sampleFrom(ref, ns, ·) produces point p
    // (p on the light, seen from ref on its emitting side).
    float pdfFrom(Vec3f ref, Vec3f ns, Vec3f p) const;
    // Emitted radiance towards direction w (pointing away from the light).
    // Not for spheres, whose normal depends on the point: emittedAt.
    Vec3f emitted(Vec3f w) const { return (twoSided || dot(n, w) > 0) ? radiance : Vec3f(0.0f); }
    // Emitted radiance from point p of the light towards w.
    Vec3f emittedAt(Vec3f p, Vec3f w) const {
        if (sphere) [[unlikely]]
            return (twoSided || dot(p - center, w) > 0) ? radiance : Vec3f(0.0f);
        return emitted(w);
    }
};

struct LightSample {
    Vec3f wi;        // unit direction from the shading point towards the light
    float distance;  // to the light point; infinity for the environment
    Vec3f radiance;  // arriving along −wi
    float pdf;       // solid-angle density, including the light-choice probability
    // A point, spot or distant light: `pdf` is the choice probability alone,
    // and no BSDF sample competes with the sample (MIS weight 1).
    bool delta = false;
};

// Uniform area sampling, the default: the same arithmetic as sampleFrom followed
// by the direction and distance (so the same bits), with the distance's square
// root taken once instead of twice. Next-event estimation calls this at every
// diffuse vertex, and the two dependent roots and divisions were a latency
// chain in every path.
inline std::optional<LightSample> sampleByArea(const AreaLight& light, Vec3f ref, Vec2f u,
                                               float choicePmf) {
    if (!light.twoSided && dot(ref - light.p0, light.n) <= 0) return std::nullopt;
    const Vec3f d = light.samplePoint(u) - ref;
    const float dist2 = dot(d, d);
    const float dist = std::sqrt(dist2);
    const float cosLight = std::abs(dot(light.n, d)) / dist;
    if (!(cosLight > 0)) return std::nullopt;
    const float pdf = dist2 / (light.area * cosLight);  // areaDensity
    if (!(pdf > 0) || !(dist2 > 0) || std::isinf(pdf)) return std::nullopt;
    const Vec3f wi = d / dist;
    const Vec3f Le = light.emitted(-wi);
    if (isBlack(Le)) return std::nullopt;
    return LightSample{wi, dist, Le, choicePmf * pdf};
}

class LightSet {
  public:
    // `focus` is where the environment's share of light choices is judged.
    LightSet(const SceneDescription& scene, Vec3f focus,
             LightSampling strategy = LightSampling::Area,
             LightSelection selection = LightSelection::Power);

    bool empty() const { return chooser_.size() == 0; }
    // All lights: area lights, then punctual lights, then the environment if
    // present, then the environment map if present — the chooser's indices.
    size_t lightCount() const { return chooser_.size(); }
    const LightChooser& chooser() const { return chooser_; }
    size_t areaLightCount() const { return lights_.size(); }
    const AreaLight& areaLight(int i) const { return lights_[size_t(i)]; }
    size_t punctualLightCount() const { return punctual_.size(); }
    // The light a triangle belongs to, or −1.
    int lightOfTriangle(unsigned mesh, unsigned triangle) const;
    // The light of SceneDescription::spheres[sphere], or −1 when it does not emit.
    int lightOfSphere(unsigned sphere) const { return sphereLight_[sphere]; }
    // lightOfTriangle of all the mesh's triangles, by triangle.
    const int* trianglesLights(unsigned mesh) const { return triangleLight_[mesh].data(); }

    // A light sample for the receiver at `ref` with shading normal `ns` (the zero
    // vector when there is none). uChoice picks the light.
    // A scene lit by one area light sampled by area (the Cornell box; the wolf
    // adds an environment) takes it without the choice: its probability is
    // probability 1 exactly whatever the selection, so the same bits, and the whole sample is
    // inline in the integrator, where next-event estimation calls it at every vertex.
    std::optional<LightSample> sample(Vec3f ref, Vec3f ns, float uChoice, Vec2f u) const {
        if (onlyAreaLight_) return sampleByArea(lights_[0], ref, u, 1.0f);
        return sampleChosen(ref, ns, uChoice, u);
    }
    // The scene's only light, an area light sampled by area; null otherwise.
    const AreaLight* onlyAreaLight() const { return onlyAreaLight_ ? &lights_[0] : nullptr; }
    // False when there is at most one light to choose: uChoice is then never read.
    bool choiceUsesSample() const { return chooser_.size() > 1; }
    // Solid-angle pdf (with choice probability) with which sample(ref, ns, …)
    // reaches point p of light `light` — for MIS when a BSDF sample hits the
    // light. ref and ns must be those the light sample would have used.
    float pdfAreaLight(int light, Vec3f ref, Vec3f ns, Vec3f p) const;
    float pdfEnvironment() const;
    Vec3f environment() const { return environment_; }
    // The image environment map, when the scene has one: its radiance from
    // direction dir and the solid-angle pdf (with choice probability) with
    // which sample() reaches dir through it.
    bool hasEnvironmentMap() const { return environmentMap_.has_value(); }
    Vec3f environmentMapRadiance(Vec3f dir) const { return environmentMap_->radiance(dir); }
    float pdfEnvironmentMap(Vec3f dir) const;

  private:
    std::optional<LightSample> sampleChosen(Vec3f ref, Vec3f ns, float uChoice, Vec2f u) const;
    std::optional<LightSample> samplePunctual(size_t i, Vec3f ref, float choicePmf) const;
    std::vector<double> powerWeights(Vec3f focus) const;
    std::vector<std::optional<LightBounds>> lightBounds() const;
    std::vector<AreaLight> lights_;
    std::vector<std::vector<int>> triangleLight_;  // per mesh, per triangle
    std::vector<int> sphereLight_;                 // per sphere
    std::vector<PunctualLight> punctual_;
    std::optional<EnvironmentLight> environmentMap_;
    size_t environmentMapIndex() const;  // in chooser_
    Vec3f environment_;
    LightChooser chooser_;
    bool onlyAreaLight_ = false;  // lights_[0] is the only light, a polygon sampled by area
};

}  // namespace pathlab
