#include "render/lights.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "render/sampling_routines.h"
#include "render/sphere_light.h"

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
    const float l1 = length(e1), l2 = length(e2);
    l.rectangle = parallelogram && std::abs(dot(e1, e2)) <= 1e-5f * l1 * l2;
    if (l.rectangle) {
        l.xAxis = e1 / l1;
        l.yAxis = cross(l.n, l.xAxis);  // = e2/|e2| up to the tolerance above
        l.width = l1;
        l.height = dot(e2, l.yAxis);
    }
    return l;
}

// Below this solid angle (steradians) a rectangle is sampled by area: the
// spherical construction loses precision, and the two densities nearly agree
// anyway (pbrt-v4 uses the same bound for bilinear patches).
constexpr double kMinSphericalSolidAngle = 1e-4;
// Receivers closer to a rectangle's plane than this fraction of its longer
// edge sample it by area too: the construction divides by that distance.
constexpr double kMinRelativePlaneDistance = 1e-4;

// Solid angle of the rectangle [x0,x1]×[y0,y1] in the plane at distance h > 0,
// seen from the point above the origin. A rectangle [0,x]×[0,y] with a corner at
// the foot point subtends atan(xy / (h·r)), r = √(x²+y²+h²) the corner's distance
// (e.g. Mathar 2014, "Solid Angle of a Rectangular Plate"); that is odd in x and
// in y, so any rectangle is the signed sum over its four corners. The four
// arctangents are added as the argument of a product of complex numbers
// 1 ± i·a — one atan2 — with no cancellation against 2π as in the angle-sum
// formula Σγ − 2π. rXY is the distance to corner (xX, yY).
double rectangleSolidAngle(double x0, double x1, double y0, double y1, double h, double r00,
                           double r10, double r01, double r11) {
    const double a00 = x0 * y0 / (h * r00), a10 = x1 * y0 / (h * r10);
    const double a01 = x0 * y1 / (h * r01), a11 = x1 * y1 / (h * r11);
    // (1 + i·a11)(1 − i·a01): the strip at y1; (1 + i·a00)(1 − i·a10): at y0.
    const double pr = 1 + a11 * a01, pi = a11 - a01;
    const double qr = 1 + a00 * a10, qi = a00 - a10;
    // (Single precision suffices here: atan2's error is relative to its result.)
    const double raw = std::atan2(float(pr * qi + pi * qr), float(pr * qr - pi * qi));
    // Ω < 2π always, and Ω < π when the foot point is outside the rectangle
    // (the rectangle then lies in a half-plane): that fixes the branch. With the
    // foot inside, every factor has a non-negative imaginary part, so a tiny Ω
    // cannot round to a negative argument.
    if (x0 <= 0 && x1 >= 0 && y0 <= 0 && y1 >= 0) return raw < 0 ? raw + 2 * M_PI : raw;
    return raw < -M_PI / 2 ? raw + 2 * M_PI : std::max(raw, 0.0);
}

// A rectangular light seen from a reference point, in the local frame of
// Ureña, Fajardo & King 2013, "An Area-Preserving Parametrization for
// Spherical Rectangles", §3: the reference point at the origin, the rectangle
// [x0,x1]×[y0,y1] in the plane z = z0 = −h < 0 (the frame's z is flipped when
// the point lies on the other side), edges along the light's xAxis and yAxis.
struct SphericalRectangle {
    double x0, x1, y0, y1, h;
    double signedDistance;      // (p0 − ref)·n: world z of the plane seen from ref
    double r00, r10, r01, r11;  // distances to the corners
    double solidAngle;

    SphericalRectangle(const AreaLight& l, Vec3f ref) {
        const Vec3f d = l.p0 - ref;
        x0 = dot(d, l.xAxis);
        y0 = dot(d, l.yAxis);
        signedDistance = dot(d, l.n);
        h = std::abs(signedDistance);
        x1 = x0 + l.width;
        y1 = y0 + l.height;
        const double hh = h * h;
        r00 = std::sqrt(x0 * x0 + y0 * y0 + hh), r10 = std::sqrt(x1 * x1 + y0 * y0 + hh);
        r01 = std::sqrt(x0 * x0 + y1 * y1 + hh), r11 = std::sqrt(x1 * x1 + y1 * y1 + hh);
        solidAngle = h > 0 ? rectangleSolidAngle(x0, x1, y0, y1, h, r00, r10, r01, r11) : 0;
    }

    bool usable(const AreaLight& l) const {
        return solidAngle >= kMinSphericalSolidAngle &&
               h >= kMinRelativePlaneDistance * std::max(l.width, l.height);
    }

    // The paper's Algorithm 1: u.x picks the abscissa xu at which the strip
    // [x0,xu]×[y0,y1] subtends u.x·Ω; u.y then moves linearly in
    // hv = y/√(xu²+z0²+y²), the sine of the elevation, which is uniform in solid
    // angle along the segment x = xu. Returns (xu, yv) in the rectangle's plane.
    std::pair<double, double> sample(Vec2f u) const {
        const double hh = h * h;
        const double rx0 = std::sqrt(hh + x0 * x0);
        const double ry0 = std::sqrt(hh + y0 * y0), ry1 = std::sqrt(hh + y1 * y1);
        // The planes through the origin and the edges v00v10 and v11v01 have
        // normals n0 = (0, z0, −y0)/ry0 and n2 = (0, −z0, y1)/ry1 (§3); b0, b1
        // are their z components.
        const double b0 = -y0 / ry0, b1 = y1 / ry1;
        // The internal angles γ2, γ3 at corners v01 and v00 are acos(−n2·n3) and
        // acos(−n3·n0), n3 = (z0, 0, −x0)/rx0. Their cosines and sines in closed
        // form (1 − cos² simplifies to h²r²/(…), no cancellation) give γ2 + γ3
        // without inverse trigonometry.
        const double c2 = x0 * y1 / (ry1 * rx0), s2 = h * r01 / (ry1 * rx0);
        const double c3 = -x0 * y0 / (rx0 * ry0), s3 = h * r00 / (rx0 * ry0);
        const double c23 = c2 * c3 - s2 * s3, s23 = s2 * c3 + c2 * s3;
        // au = u.x·Ω + k with k = 2π − γ2 − γ3 (paper eq. 8); the 2π drops out
        // of its sine and cosine.
        const float uOmega = float(double(u.x) * solidAngle);
        const double cw = std::cos(uOmega), sw = std::sin(uOmega);
        const double cosAu = cw * c23 + sw * s23, sinAu = sw * c23 - cw * s23;
        // The cosine cu of the angle between the x axis and the plane through
        // the origin and x = xu (eqs. 9–10), from which xu follows.
        const double fu = (cosAu * b0 - b1) / sinAu;
        double cu = std::copysign(1.0, fu) / std::sqrt(fu * fu + b0 * b0);
        cu = std::clamp(cu, -1 + 1e-12, 1 - 1e-12);
        const double xu = std::clamp(cu * h / std::sqrt(1 - cu * cu), x0, x1);
        // The segment x = xu: uniform in hv between its endpoints (eqs. 11–12).
        const double dd2 = xu * xu + hh;
        const double h0 = y0 / std::sqrt(dd2 + y0 * y0), h1 = y1 / std::sqrt(dd2 + y1 * y1);
        const double hv = h0 + double(u.y) * (h1 - h0), hv2 = hv * hv;
        const double yv =
            hv2 < 1 - 1e-12 ? std::clamp(hv * std::sqrt(dd2 / (1 - hv2)), y0, y1) : y1;
        return {xu, yv};
    }

    // The inverse: the u with sample(u) = (xu, yv), from the same two facts.
    Vec2f invert(double xu, double yv) const {
        xu = std::clamp(xu, x0, x1);
        yv = std::clamp(yv, y0, y1);
        const double hh = h * h;
        const double ru0 = std::sqrt(xu * xu + y0 * y0 + hh);
        const double ru1 = std::sqrt(xu * xu + y1 * y1 + hh);
        const double strip = rectangleSolidAngle(x0, xu, y0, y1, h, r00, ru0, r01, ru1);
        const double dd2 = xu * xu + hh;
        const double h0 = y0 / ru0, h1 = y1 / ru1;
        const double hv = yv / std::sqrt(dd2 + yv * yv);
        const double ux = strip / solidAngle;
        const double uy = h1 > h0 ? (hv - h0) / (h1 - h0) : 0.5;
        return {float(std::clamp(ux, 0.0, 1.0)), float(std::clamp(uy, 0.0, 1.0))};
    }

    // pbrt-v4's warp for the cosine at the receiver: the receiver's |cosθ|
    // towards the corners (floored at 0.01, so no part of the light gets zero
    // density), in sampleBilinear's corner order (0,0), (1,0), (0,1), (1,1) of
    // the (u.x along xAxis, u.y along yAxis) square.
    void cornerCosines(const AreaLight& l, Vec3f ns, float (&w)[4]) const {
        const double nx = dot(ns, l.xAxis), ny = dot(ns, l.yAxis);
        const double nz = double(dot(ns, l.n)) * signedDistance;
        w[0] = float(std::max(0.01, std::abs(nx * x0 + ny * y0 + nz) / r00));
        w[1] = float(std::max(0.01, std::abs(nx * x1 + ny * y0 + nz) / r10));
        w[2] = float(std::max(0.01, std::abs(nx * x0 + ny * y1 + nz) / r01));
        w[3] = float(std::max(0.01, std::abs(nx * x1 + ny * y1 + nz) / r11));
    }
};

bool hasNormal(Vec3f ns) {
    return ns.x != 0 || ns.y != 0 || ns.z != 0;
}

// The light as a spherical rectangle seen from ref, when it is sampled by solid
// angle there; nothing when area sampling applies.
// Callers test l.solidAngleSampling first, so that area sampling (the default)
// makes no call and builds no optional rectangle per light sample.
std::optional<SphericalRectangle> solidAngleView(const AreaLight& l, Vec3f ref) {
    const SphericalRectangle rect(l, ref);
    if (!rect.usable(l)) return std::nullopt;
    return rect;
}

AreaLight makeSphereLight(const Sphere& s) {
    AreaLight l;
    l.sphere = true;
    l.center = s.center;
    l.radius = s.radius;
    l.area = 4 * kPi * s.radius * s.radius;
    l.radiance = s.emission;
    l.twoSided = s.twoSided;
    return l;
}

// A sphere light's point for a receiver at ref: by its cone where the
// receiver is outside and cone sampling is on, else by area.
std::optional<AreaLight::DirectionSample> sampleSphereFrom(const AreaLight& l, Vec3f ref, Vec2f u) {
    if (l.solidAngleSampling && sphereConeExists(l.center, l.radius, ref)) {
        const SpherePoint s = sampleSphereCone(l.center, l.radius, ref, u);
        return AreaLight::DirectionSample{s.p, s.pdf};
    }
    const auto s = sampleSphereArea(l.center, l.radius, ref, u);
    if (!s) return std::nullopt;
    return AreaLight::DirectionSample{s->p, s->pdf};
}

// Uniform area density 1/A per unit solid angle at ref: dist² / (A |cosθ_light|);
// 0 when p is ref itself or lies edge-on.
float areaDensity(const AreaLight& l, Vec3f ref, Vec3f p) {
    const Vec3f d = p - ref;
    const float dist2 = dot(d, d);
    const float cosLight = std::abs(dot(l.n, d)) / std::sqrt(dist2);
    if (!(cosLight > 0)) return 0;
    return dist2 / (l.area * cosLight);
}

}  // namespace

float AreaLight::power() const {
    return luminance(radiance) * area * kPi * (twoSided ? 2 : 1);
}

std::optional<AreaLight::DirectionSample> AreaLight::sampleFrom(Vec3f ref, Vec3f ns,
                                                                Vec2f u) const {
    if (sphere) [[unlikely]]
        return sampleSphereFrom(*this, ref, u);
    if (!twoSided && dot(ref - p0, n) <= 0) return std::nullopt;  // sees the back only
    if (const auto rect = solidAngleSampling ? solidAngleView(*this, ref) : std::nullopt) {
        float pdf = float(1 / rect->solidAngle);
        if (hasNormal(ns)) {
            float w[4];
            rect->cornerCosines(*this, ns, w);
            u = sampleBilinear(u, w);
            pdf *= bilinearPdf(u, w);
        }
        const auto [xu, yv] = rect->sample(u);
        // (xu, yv) are relative to the reference point's foot; p0 sits at (x0, y0).
        const Vec3f p = p0 + xAxis * float(xu - rect->x0) + yAxis * float(yv - rect->y0);
        return DirectionSample{p, pdf};
    }
    const Vec3f p = samplePoint(u);
    const float pdf = areaDensity(*this, ref, p);
    if (pdf <= 0) return std::nullopt;
    return DirectionSample{p, pdf};
}

float AreaLight::pdfFrom(Vec3f ref, Vec3f ns, Vec3f p) const {
    if (sphere) [[unlikely]] {
        // Constant over the cone: p is where the ray towards it first meets
        // the sphere, on the cap the cone covers.
        if (solidAngleSampling && sphereConeExists(center, radius, ref))
            return sphereConePdf(center, radius, ref);
        return sphereAreaPdf(center, radius, ref, p);
    }
    if (!twoSided && dot(ref - p0, n) <= 0) return 0;
    if (const auto rect = solidAngleSampling ? solidAngleView(*this, ref) : std::nullopt) {
        float pdf = float(1 / rect->solidAngle);
        if (hasNormal(ns)) {
            float w[4];
            rect->cornerCosines(*this, ns, w);
            const Vec3f q = p - p0;
            pdf *= bilinearPdf(rect->invert(rect->x0 + dot(q, xAxis), rect->y0 + dot(q, yAxis)), w);
        }
        return pdf;
    }
    return areaDensity(*this, ref, p);
}

LightSet::LightSet(const SceneDescription& scene, Vec3f focus, LightSampling strategy,
                   LightSelection selection)
    : punctual_(scene.punctualLights), environment_(scene.environment) {
    if (!scene.environmentMap.empty()) environmentMap_.emplace(scene.environmentMap);
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
    for (AreaLight& l : lights_)
        l.solidAngleSampling = l.rectangle && strategy == LightSampling::SolidAngle;
    sphereLight_.assign(scene.spheres.size(), -1);
    for (size_t i = 0; i < scene.spheres.size(); ++i) {
        if (isBlack(scene.spheres[i].emission)) continue;
        sphereLight_[i] = int(lights_.size());
        lights_.push_back(makeSphereLight(scene.spheres[i]));
        lights_.back().solidAngleSampling = strategy != LightSampling::UniformArea;
    }
    chooser_ = LightChooser(selection, powerWeights(focus), lightBounds());
    onlyAreaLight_ = chooser_.size() == 1 && lights_.size() == 1 &&
                     !lights_[0].solidAngleSampling && !lights_[0].sphere;
}

// Irradiance at `x` from light `l` if nothing blocked it, treating the light as
// a point at its centroid (receiver orientation unknown: no receiver cosine).
static double irradianceAt(const AreaLight& l, Vec3f x) {
    if (l.sphere) {
        // A sphere facing x delivers π L sin²θmax = π L r² / d² (d ≥ r).
        const Vec3f d = x - l.center;
        const float r2 = l.radius * l.radius;
        return double(luminance(l.radiance)) * kPi * r2 / std::max(dot(d, d), r2);
    }
    const Vec3f centroid = l.p0 + (l.e1 + l.e2) * (l.parallelogram ? 0.5f : 1.0f / 3.0f);
    const Vec3f d = x - centroid;
    const float dist2 = std::max(dot(d, d), 1e-12f);
    const float cosLight = l.twoSided ? std::abs(dot(l.n, d)) : std::max(0.0f, dot(l.n, d));
    return double(luminance(l.radiance)) * l.area * cosLight / std::sqrt(dist2) / dist2;
}

// The power selection's weight of each light, in the chooser's order.
std::vector<double> LightSet::powerWeights(Vec3f focus) const {
    std::vector<double> weight;
    double finitePower = 0, finiteIrradiance = 0;
    for (const AreaLight& l : lights_) {
        weight.push_back(l.power());
        finitePower += l.power();
        finiteIrradiance += irradianceAt(l, focus);
    }
    // Lights without finite power (distant lights, the environment): their
    // share of the choices is their share of the irradiance at the focus.
    std::vector<size_t> infinite;
    std::vector<double> infiniteIrradiance;
    for (const PunctualLight& l : punctual_) {
        if (l.type == PunctualLightType::Distant) {
            infinite.push_back(weight.size());
            infiniteIrradiance.push_back(punctualIrradianceAt(l, focus));
            weight.push_back(0);
            continue;
        }
        weight.push_back(punctualPower(l));
        finitePower += punctualPower(l);
        finiteIrradiance += punctualIrradianceAt(l, focus);
    }
    if (!isBlack(environment_)) {
        // A uniform environment delivers π·L onto a surface facing any way.
        infinite.push_back(weight.size());
        infiniteIrradiance.push_back(kPi * double(luminance(environment_)));
        weight.push_back(0);
    }
    if (environmentMap_) {
        infinite.push_back(weight.size());
        infiniteIrradiance.push_back(environmentMap_->meanIrradiance());
        weight.push_back(0);
    }
    double infiniteTotal = 0;
    for (double e : infiniteIrradiance) infiniteTotal += e;
    if (infiniteTotal > 0) {
        const double share = finitePower > 0 && finiteIrradiance > 0
                                 ? infiniteTotal / (infiniteTotal + finiteIrradiance)
                                 : 1.0;
        const double infiniteWeight = share >= 1 ? 1.0 : finitePower * share / (1 - share);
        for (size_t j = 0; j < infinite.size(); ++j)
            weight[infinite[j]] = infiniteWeight * (infiniteIrradiance[j] / infiniteTotal);
    }
    return weight;
}

// What the light BVH knows of each light (PBRT 4th ed., §12.6.3): an area
// light's box, its power and its normal (θo = 0, or its two sides), emitting
// over a hemisphere (θe = π/2); a point light in every direction (θo = π);
// a spot light within its outer cone (θo the full-intensity cone, θe the
// falloff band). Their phi is 4π·I as pbrt-v4's, so that Importance's
// phi/d² is in proportion to the intensity. Distant lights and environments
// have no position: nothing (the chooser samples them beside the tree).
std::vector<std::optional<LightBounds>> LightSet::lightBounds() const {
    std::vector<std::optional<LightBounds>> bounds;
    for (const AreaLight& l : lights_) {
        LightBounds b;
        if (l.sphere) {
            // Normals in every direction, as pbrt-v4's Sphere::NormalBounds.
            b.bounds.extend(l.center - Vec3f(l.radius)),
                b.bounds.extend(l.center + Vec3f(l.radius));
            b.phi = l.power();
            b.normals = DirectionCone::entireSphere();
            b.twoSided = l.twoSided;
            bounds.push_back(b);
            continue;
        }
        b.bounds.extend(l.p0), b.bounds.extend(l.p0 + l.e1), b.bounds.extend(l.p0 + l.e2);
        if (l.parallelogram) b.bounds.extend(l.p0 + l.e1 + l.e2);
        b.phi = l.power();
        b.normals = {l.n, 1};
        b.twoSided = l.twoSided;
        bounds.push_back(b);
    }
    for (const PunctualLight& l : punctual_) {
        if (l.type == PunctualLightType::Distant) {
            bounds.emplace_back();
            continue;
        }
        LightBounds b;
        b.bounds.extend(l.position);
        b.phi = 4 * kPi * luminance(l.intensity);
        b.normals = DirectionCone::entireSphere();
        if (l.type == PunctualLightType::Spot) {
            b.normals = {l.direction, l.cosFalloffStart};
            b.cosThetaE = std::cos(std::acos(std::clamp(l.cosFalloffEnd, -1.0f, 1.0f)) -
                                   std::acos(std::clamp(l.cosFalloffStart, -1.0f, 1.0f)));
        }
        bounds.push_back(b);
    }
    while (bounds.size() < lights_.size() + punctual_.size() + (isBlack(environment_) ? 0 : 1) +
                               (environmentMap_ ? 1 : 0))
        bounds.emplace_back();
    return bounds;
}

int LightSet::lightOfTriangle(unsigned mesh, unsigned triangle) const {
    return triangleLight_[mesh][triangle];
}

std::optional<LightSample> LightSet::sampleChosen(Vec3f ref, Vec3f ns, float uChoice,
                                                  Vec2f u) const {
    const auto chosen = chooser_.choose(ref, ns, uChoice);
    if (!chosen || !(chosen->pmf > 0)) return std::nullopt;
    const size_t i = size_t(chosen->light);
    const float choicePmf = chosen->pmf;
    if (i >= lights_.size() && i < lights_.size() + punctual_.size())
        return samplePunctual(i - lights_.size(), ref, choicePmf);
    if (environmentMap_ && i == environmentMapIndex()) {
        const auto s = environmentMap_->sample(u);
        if (!s || !(s->pdf > 0) || isBlack(s->radiance)) return std::nullopt;
        return LightSample{s->wi, std::numeric_limits<float>::infinity(), s->radiance,
                           choicePmf * s->pdf};
    }
    if (i == lights_.size() + punctual_.size()) {  // the environment: uniform directions
        return LightSample{sampleUniformSphere(u), std::numeric_limits<float>::infinity(),
                           environment_, choicePmf * uniformSpherePdf()};
    }
    const AreaLight& light = lights_[i];
    if (!light.solidAngleSampling && !light.sphere) return sampleByArea(light, ref, u, choicePmf);
    const auto s = light.sampleFrom(ref, ns, u);
    if (!s) return std::nullopt;
    const Vec3f d = s->p - ref;
    const float dist2 = dot(d, d);
    if (!(dist2 > 0) || !(s->pdf > 0) || std::isinf(s->pdf)) return std::nullopt;
    const float dist = std::sqrt(dist2);
    const Vec3f wi = d / dist;
    const Vec3f Le = light.emittedAt(s->p, -wi);
    if (isBlack(Le)) return std::nullopt;
    return LightSample{wi, dist, Le, choicePmf * s->pdf};
}

// pbrt-v4's PointLight / SpotLight::SampleLi (I / r² towards the light) and
// DistantLight::SampleLi (L from −direction, unbounded shadow ray).
std::optional<LightSample> LightSet::samplePunctual(size_t i, Vec3f ref, float choicePmf) const {
    const PunctualLight& l = punctual_[i];
    if (l.type == PunctualLightType::Distant)
        return LightSample{-l.direction, std::numeric_limits<float>::infinity(), l.radiance,
                           choicePmf, true};
    const Vec3f d = l.position - ref;
    const float dist2 = dot(d, d);
    if (!(dist2 > 0)) return std::nullopt;
    const float dist = std::sqrt(dist2);
    const Vec3f wi = d / dist;
    const Vec3f I = l.type == PunctualLightType::Spot ? spotIntensity(l, -wi) : l.intensity;
    if (isBlack(I)) return std::nullopt;
    return LightSample{wi, dist, I / dist2, choicePmf, true};
}

float LightSet::pdfAreaLight(int light, Vec3f ref, Vec3f ns, Vec3f p) const {
    return chooser_.pmf(ref, ns, size_t(light)) * lights_[size_t(light)].pdfFrom(ref, ns, p);
}

size_t LightSet::environmentMapIndex() const {
    return lights_.size() + punctual_.size() + (isBlack(environment_) ? 0 : 1);
}

float LightSet::pdfEnvironmentMap(Vec3f dir) const {
    if (!environmentMap_ || empty()) return 0;
    // Lights without a position: their choice does not depend on the receiver.
    return chooser_.pmf({}, {}, environmentMapIndex()) * environmentMap_->pdf(dir);
}

float LightSet::pdfEnvironment() const {
    if (empty() || isBlack(environment_)) return 0;
    return chooser_.pmf({}, {}, lights_.size() + punctual_.size()) * uniformSpherePdf();
}

}  // namespace pathlab
